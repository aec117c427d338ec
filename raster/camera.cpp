// SPDX-License-Identifier: MIT
// camera.cpp — ViewMatrix / ProjectionMatrix (GLM's GL conventions) and the pixel-centre ray.
// The camera basis is computed exactly as glm::lookAt does, so PixelRay and ViewMatrix agree.
// Not here: clipping or any rasterization (raster/render.h).
#include "raster/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace pem::raster {

namespace {

// The orthonormal camera frame of glm::lookAt: s (right), u (up), f (forward).
struct Basis {
    glm::vec3 s, u, f;
};

Basis CameraBasis(const Camera& c) {
    const glm::vec3 f = glm::normalize(c.target - c.eye);
    const glm::vec3 s = glm::normalize(glm::cross(f, c.up));
    return {s, glm::cross(s, f), f};
}

}  // namespace

glm::mat4 ViewMatrix(const Camera& camera) {
    return glm::lookAt(camera.eye, camera.target, camera.up);
}

glm::mat4 ProjectionMatrix(const Camera& camera, float zNear, float zFar) {
    return glm::perspective(camera.fovYRadians, camera.Aspect(), zNear, zFar);
}

glm::mat4 ViewProjection(const Camera& camera, float zNear, float zFar) {
    return ProjectionMatrix(camera, zNear, zFar) * ViewMatrix(camera);
}

PixelRays::PixelRays(const Camera& camera)
    : eye_(camera.eye),
      width_(static_cast<float>(camera.width)),
      height_(static_cast<float>(camera.height)),
      tanHalf_(std::tan(0.5f * camera.fovYRadians)),
      aspect_(camera.Aspect()) {
    const Basis b = CameraBasis(camera);
    s_ = b.s, u_ = b.u, f_ = b.f;
}

Ray PixelRays::operator()(float px, float py) const {
    // Step 1: image point → NDC (y flips: row 0 is the top, NDC +1).
    const float ndcX = 2.0f * px / width_ - 1.0f;
    const float ndcY = 1.0f - 2.0f * py / height_;
    // Step 2: NDC → camera-space direction on the plane z = -1.
    const float x = ndcX * tanHalf_ * aspect_;
    const float y = ndcY * tanHalf_;
    // Step 3: camera → world with the lookAt basis.
    return {eye_, glm::normalize(x * s_ + y * u_ + f_)};
}

Ray PixelRay(const Camera& camera, float px, float py) {
    return PixelRays(camera)(px, py);
}

ImageProjection::ImageProjection(const Camera& camera)
    : eye_(camera.eye),
      width_(static_cast<float>(camera.width)),
      height_(static_cast<float>(camera.height)),
      tanHalf_(std::tan(0.5f * camera.fovYRadians)),
      aspect_(camera.Aspect()) {
    const Basis b = CameraBasis(camera);
    s_ = b.s, u_ = b.u, f_ = b.f;
}

glm::vec2 ImageProjection::operator()(const glm::vec3& p, float* depth) const {
    const glm::vec3 d = p - eye_;
    const float z = glm::dot(d, f_);  // distance along the view axis
    if (depth) *depth = z;
    const float ndcX = glm::dot(d, s_) / (z * tanHalf_ * aspect_);
    const float ndcY = glm::dot(d, u_) / (z * tanHalf_);
    return {(ndcX + 1.0f) * 0.5f * width_, (1.0f - ndcY) * 0.5f * height_};
}

glm::vec2 ProjectToImage(const Camera& camera, const glm::vec3& p, float* depth) {
    return ImageProjection(camera)(p, depth);
}

}  // namespace pem::raster
