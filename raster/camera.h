// SPDX-License-Identifier: MIT
// camera.h — the one pinhole camera shared by raster/ (ViewMatrix, ProjectionMatrix) and trace/
// (PixelRay), so that rasterized and ray-traced pixels agree.
//
// Conventions:
//  - World space is right-handed; the camera looks from `eye` toward `target`, `up` is a hint
//    (need not be orthogonal to the view direction). ViewMatrix is glm::lookAt (camera looks
//    down its -Z), ProjectionMatrix is glm::perspective: GL clip space, z in [-w, w], the depth
//    range [0, 1] applied by raster/ (frame.h).
//  - Image coordinates (px, py) are continuous, x right, rows TOP-DOWN: (0, 0) is the top-left
//    corner of the image, (width, height) the bottom-right one, pixel (x, y) covers
//    [x, x+1) x [y, y+1) and its centre is (x + 0.5, y + 0.5). Row 0 is the top row, as in
//    raster's Image8; raster works in GL window space, whose y = height - py.
//  - So a world point p with ndc = (P·V·p).xyz / w lands at px = (ndc.x + 1)/2 · width,
//    py = (1 − ndc.y)/2 · height, and PixelRay(camera, px, py) passes through p.
//  - fovYRadians is the full vertical field of view; aspect = width / height.
// Not here: lens models, depth of field, orthographic cameras.
#pragma once

#include <glm/glm.hpp>

namespace pem::raster {

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 dir{0.0f, 0.0f, -1.0f};  // unit length when made by PixelRay
    bool operator==(const Ray&) const = default;
};

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 1.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYRadians = 0.785398163f;  // 45 degrees
    int width = 1, height = 1;
    bool operator==(const Camera&) const = default;

    float Aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
};

// World → camera (eye at the origin, looking down -Z, +Y up).
glm::mat4 ViewMatrix(const Camera& camera);

// Camera → GL clip space for the near/far planes zNear < zFar (both > 0).
glm::mat4 ProjectionMatrix(const Camera& camera, float zNear, float zFar);

// ProjectionMatrix · ViewMatrix.
glm::mat4 ViewProjection(const Camera& camera, float zNear, float zFar);

// The ray from the eye through the continuous image point (px, py) (rows top-down, pixel
// centres at +0.5). dir is unit length.
Ray PixelRay(const Camera& camera, float px, float py);

// The per-camera terms of PixelRay and ProjectToImage: the lookAt basis (s right, u up, f
// forward), tan(fovY/2), the aspect and the image size.
struct CameraTerms {
    explicit CameraTerms(const Camera& camera);
    glm::vec3 eye, s, u, f;
    float width, height, tanHalf, aspect;
};

// PixelRay for many image points of one camera: the per-camera terms computed once;
// operator() returns exactly PixelRay's ray (same bits: PixelRay is implemented with it).
class PixelRays {
  public:
    explicit PixelRays(const Camera& camera) : c_(camera) {}
    Ray operator()(float px, float py) const;

  private:
    CameraTerms c_;
};

// The continuous image point (rows top-down) where a world point projects; the inverse of
// PixelRay for points in front of the camera. `depth` receives the distance along the view axis.
glm::vec2 ProjectToImage(const Camera& camera, const glm::vec3& p, float* depth = nullptr);

// ProjectToImage for many points of one camera: the per-camera terms computed once; the same
// bits (ProjectToImage is implemented with it).
class ImageProjection {
  public:
    explicit ImageProjection(const Camera& camera) : c_(camera) {}
    glm::vec2 operator()(const glm::vec3& p, float* depth = nullptr) const;

  private:
    CameraTerms c_;
};

}  // namespace pem::raster
