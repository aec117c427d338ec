// SPDX-License-Identifier: MIT
// infer_frames.h — frames for infer/'s tests: reflective spheres (whole, or only the grazing rim),
// screen quads over a small cube region (strong magnification) or at a constant minification
// (two MIP levels trading off), and a faint additive pass (texels seen only with tiny weights).
// All use one seamless trilinear cube map (texture 0) with every level; the clear colour is
// opaque black. The reflective sphere with the checker cube is test::BenchmarkFrame without
// its sky pass.
#pragma once

#include <glm/glm.hpp>

#include "raster/frame.h"

namespace pem::test {

// BenchmarkFrame(width, height, ...) minus the sky quad: a mirror sphere over the checker cube.
raster::Frame MirrorSphere(int width, int height, int cubeSize);

struct SphereSpec {
    int width = 96, height = 96, cubeSize = 16;
    glm::vec3 eye{0.2f, 0.5f, 3.0f};
    float radius = 1.0f;
    int rings = 24, segments = 32;
    float rimBand = 2.0f;  // keep quads with |n . view| < rimBand (2: the whole sphere)
    uint64_t seed = 1;     // random texels
};
raster::Frame RandomSphere(const SphereSpec& spec);

// A full-screen quad whose corner directions are (+-halfExtent, +-halfExtent, 1) around +Z
// (halfExtent 1 = the whole +Z face). Random texels.
raster::Frame FaceQuad(int width, int height, int cubeSize, float halfExtent, uint64_t seed);

// Adds an additive pass over the whole screen, colour `weight`, sampling around -Z.
void AddFaintPass(raster::Frame* frame, float weight);

}  // namespace pem::test
