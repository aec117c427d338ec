// SPDX-License-Identifier: MIT
// viewpoints.cpp — viewpoint samples (viewpoints.h).
#include "pipeline/viewpoints.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "base/input_error.h"

namespace pem::pipeline {

std::vector<raster::Camera> SampleViews(const trace::Scene& scene, const std::string& spec,
                                        int width, int height) {
    if (!scene.camera) throw base::InputError(scene.path, "no camera node (needed by --views)");
    const raster::Camera cam = trace::CameraForSize(*scene.camera, width, height);
    if (spec == "camera") return {cam};
    int n = 0;
    double step = 0.0;
    char extra = 0;
    if (std::sscanf(spec.c_str(), "circle:%d:%lf%c", &n, &step, &extra) != 2 || n < 1 ||
        n > 100000 || !std::isfinite(step))
        throw base::InputError("--views " + spec, "expected camera or circle:N:STEP_DEG");
    return CircleViews(cam, trace::LensCentre(scene), n, step);
}

std::vector<raster::Camera> CircleViews(const raster::Camera& camera, const glm::vec3& centre,
                                        int n, double stepDeg) {
    std::vector<raster::Camera> views;
    const glm::dvec3 c(centre), e(camera.eye);
    const glm::dvec2 offset(e.x - c.x, e.z - c.z);
    for (int i = 0; i < n; ++i) {
        const double a = i * stepDeg * std::numbers::pi / 180.0;
        const double ca = std::cos(a), sa = std::sin(a);
        raster::Camera cam = camera;
        // Rotation about +Y: (x, z) -> (x cos a + z sin a, −x sin a + z cos a).
        cam.eye = glm::vec3(glm::dvec3(c.x + offset.x * ca + offset.y * sa, e.y,
                                       c.z - offset.x * sa + offset.y * ca));
        cam.target = centre;
        cam.up = {0.0f, 1.0f, 0.0f};
        views.push_back(cam);
    }
    return views;
}

}  // namespace pem::pipeline
