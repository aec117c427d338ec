// SPDX-License-Identifier: MIT
// viewpoints.h — where the viewpoint samples are: `--views camera` (the scene camera) or
// `circle:N:STEP` (N cameras STEP degrees apart on the circle about the lens objects' centre,
// up = +Y), at the trace's image size. The cameras made here are stored whole in trace.json and
// used as they are by inference and every renderer.
//
//   std::vector<raster::Camera> v = SampleViews(scene, "circle:3:10", 640, 480);
//
// Errors: base::InputError naming the option and the cause.
#pragma once

#include <string>
#include <vector>

#include "raster/camera.h"
#include "trace/scene.h"

namespace pem::pipeline {

std::vector<raster::Camera> SampleViews(const trace::Scene& scene, const std::string& spec,
                                        int width, int height);

// n viewpoints stepDeg apart: the camera's eye rotated about the vertical axis through `centre`
// (height and horizontal distance kept, positive angles from +Z toward +X), looking at
// `centre`, up = +Y.
std::vector<raster::Camera> CircleViews(const raster::Camera& camera, const glm::vec3& centre,
                                        int n, double stepDeg);

}  // namespace pem::pipeline
