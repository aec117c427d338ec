// SPDX-License-Identifier: MIT
// camera.cpp — ViewMatrix / ProjectionMatrix (GLM's GL conventions) and the pixel-centre ray.
// The camera basis is computed exactly as glm::lookAt does, so PixelRay and ViewMatrix agree.
// Not here: clipping or any rasterization (raster/render.h).
#include "raster/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace pem::raster {

// The orthonormal camera frame of glm::lookAt: s (right), u (up), f (forward).
CameraTerms::CameraTerms(const Camera& c)
    : eye(c.eye),
      f(glm::normalize(c.target - c.eye)),
      width(static_cast<float>(c.width)),
      height(static_cast<float>(c.height)),
      tanHalf(std::tan(0.5f * c.fovYRadians)),
      aspect(c.Aspect()) {
    s = glm::normalize(glm::cross(f, c.up));
    u = glm::cross(s, f);
}

glm::mat4 ViewMatrix(const Camera& camera) {
    return glm::lookAt(camera.eye, camera.target, camera.up);
}

glm::mat4 ProjectionMatrix(const Camera& camera, float zNear, float zFar) {
    return glm::perspective(camera.fovYRadians, camera.Aspect(), zNear, zFar);
}

glm::mat4 ViewProjection(const Camera& camera, float zNear, float zFar) {
    return ProjectionMatrix(camera, zNear, zFar) * ViewMatrix(camera);
}

Ray PixelRays::operator()(float px, float py) const {
    // Step 1: image point → NDC (y flips: row 0 is the top, NDC +1).
    const float ndcX = 2.0f * px / c_.width - 1.0f;
    const float ndcY = 1.0f - 2.0f * py / c_.height;
    // Step 2: NDC → camera-space direction on the plane z = -1.
    const float x = ndcX * c_.tanHalf * c_.aspect;
    const float y = ndcY * c_.tanHalf;
    // Step 3: camera → world with the lookAt basis.
    return {c_.eye, glm::normalize(x * c_.s + y * c_.u + c_.f)};
}

Ray PixelRay(const Camera& camera, float px, float py) {
    return PixelRays(camera)(px, py);
}

glm::vec2 ImageProjection::operator()(const glm::vec3& p, float* depth) const {
    const glm::vec3 d = p - c_.eye;
    const float z = glm::dot(d, c_.f);  // distance along the view axis
    if (depth) *depth = z;
    const float ndcX = glm::dot(d, c_.s) / (z * c_.tanHalf * c_.aspect);
    const float ndcY = glm::dot(d, c_.u) / (z * c_.tanHalf);
    return {(ndcX + 1.0f) * 0.5f * c_.width, (1.0f - ndcY) * 0.5f * c_.height};
}

glm::vec2 ProjectToImage(const Camera& camera, const glm::vec3& p, float* depth) {
    return ImageProjection(camera)(p, depth);
}

}  // namespace pem::raster
