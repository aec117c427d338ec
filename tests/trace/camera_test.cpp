// SPDX-License-Identifier: MIT
// camera_test.cpp — raster/camera.h: the pixel convention (rows top-down, centres at +0.5), that
// PixelRay inverts ViewProjection, and that raster/ draws a point on the pixel whose centre ray
// hits it.
#include "raster/camera.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "raster/render.h"

namespace pem::raster {
namespace {

Camera TestCamera() {
    Camera c;
    c.eye = {0.25f, 1.4f, 3.3f};
    c.target = {0.25f, 0.45f, 0.0f};
    c.up = {0.0f, 1.0f, 0.0f};
    c.fovYRadians = glm::radians(40.0f);
    c.width = 64;
    c.height = 48;
    return c;
}

// The continuous image point of p through ViewProjection and GL's viewport (rows flipped).
glm::vec2 ProjectGl(const Camera& c, const glm::vec3& p) {
    const glm::vec4 clip = ViewProjection(c, 0.05f, 100.0f) * glm::vec4(p, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    const float windowY = (ndc.y + 1.0f) * 0.5f * static_cast<float>(c.height);
    return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(c.width),
            static_cast<float>(c.height) - windowY};
}

TEST(Camera, PixelRayPassesThroughProjectedPoint) {
    const Camera c = TestCamera();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> box(-1.5f, 1.5f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 p = c.target + glm::vec3(box(rng), box(rng), box(rng));
        const glm::vec2 px = ProjectGl(c, p);
        const Ray r = PixelRay(c, px.x, px.y);
        const glm::vec3 toP = glm::normalize(p - c.eye);
        EXPECT_GT(glm::dot(r.dir, toP), 1.0f - 1e-6f) << i;
        EXPECT_EQ(r.origin, c.eye);
        // ProjectToImage is the same mapping.
        const glm::vec2 q = ProjectToImage(c, p);
        EXPECT_NEAR(q.x, px.x, 2e-3f);
        EXPECT_NEAR(q.y, px.y, 2e-3f);
    }
}

TEST(Camera, RowZeroIsTheTop) {
    const Camera c = TestCamera();
    const Ray top = PixelRay(c, 32.0f, 0.5f), bottom = PixelRay(c, 32.0f, 47.5f);
    EXPECT_GT(top.dir.y, bottom.dir.y);
    // A point above the target lands in the upper half; +x (right of view) in the right half.
    EXPECT_LT(ProjectGl(c, c.target + glm::vec3(0.0f, 0.3f, 0.0f)).y, 24.0f);
    EXPECT_GT(ProjectGl(c, c.target + glm::vec3(0.3f, 0.0f, 0.0f)).x, 32.0f);
    // The image centre looks at the target.
    const Ray centre = PixelRay(c, 32.0f, 24.0f);
    EXPECT_GT(glm::dot(centre.dir, glm::normalize(c.target - c.eye)), 1.0f - 1e-6f);
}

TEST(Camera, FieldOfViewSpansTheImageEdges) {
    const Camera c = TestCamera();
    const glm::vec3 f = glm::normalize(c.target - c.eye);
    const float half = 0.5f * c.fovYRadians;
    EXPECT_NEAR(std::acos(glm::dot(PixelRay(c, 32.0f, 0.0f).dir, f)), half, 1e-5f);
    EXPECT_NEAR(std::acos(glm::dot(PixelRay(c, 32.0f, 48.0f).dir, f)), half, 1e-5f);
}

// raster/ draws a tiny triangle placed where pixel (x, y)'s centre ray goes onto exactly that
// pixel of the top-down Image8.
TEST(Camera, RasterDrawsOnThePixelOfTheCentreRay) {
    Camera c = TestCamera();
    c.width = 16;
    c.height = 12;
    const int px = 5, py = 2;  // upper-left area: a row flip would show
    const Ray r = PixelRay(c, px + 0.5f, py + 0.5f);
    const glm::vec3 hit = r.origin + 3.0f * r.dir;
    const glm::mat4 vp = ViewProjection(c, 0.05f, 100.0f);
    // A triangle of ~0.25 pixel around the hit point, built in the camera's image plane.
    const glm::vec3 right = glm::normalize(glm::cross(r.dir, c.up)), up = glm::cross(right, r.dir);
    const float s =
        0.25f * 3.0f * 2.0f * std::tan(0.5f * c.fovYRadians) / static_cast<float>(c.height);
    Pass pass;
    pass.numUnits = 0;
    for (const glm::vec3& p : {hit - s * right - s * up, hit + s * right - s * up, hit + s * up}) {
        Vertex v;
        v.pos = vp * glm::vec4(p, 1.0f);
        pass.vertices.push_back(v);
    }
    Frame frame;
    frame.width = c.width;
    frame.height = c.height;
    frame.passes.push_back(pass);
    const PreparedFrame prepared(frame);
    const Image8 img = Render(prepared, RenderOptions{}).image8;
    int covered = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x)
            if (img.rgba[static_cast<size_t>(4 * (y * c.width + x) + 3)] != 0) {
                ++covered;
                EXPECT_EQ(x, px);
                EXPECT_EQ(y, py);
            }
    EXPECT_EQ(covered, 1);
}

}  // namespace
}  // namespace pem::raster
