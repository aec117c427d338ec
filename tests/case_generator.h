// SPDX-License-Identifier: MIT
// case_generator.h — the raster conformance corpus: deterministic frames that exercise every
// rule of the llvmpipe model (reflective spheres, cube edges and corners, minification and
// magnification, every filter and wrap mode, LOD bias and clamps, multi-pass blending, blend
// and conversion probes, tie directions, extreme magnitudes, clipping, two-texture passes, and
// depth buffers: every format and compare function, clears, writes, EQUAL multipass, near/far
// with and without depth clamp, steep slopes, extreme w; anisotropic filtering: 2D ground planes
// to the horizon, mirror spheres and a cylinder, a cube floor, every filter, GL values 1..100,
// LOD controls, non-square textures, receding walls, two units; the 2D parameterizations of
// runtime/parameterization.h: lat-long, sphere map, dual paraboloid and tennis ball spheres).
// Each case is small (<= 128x128) so the whole corpus renders through llvmpipe in seconds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raster/frame.h"
#include "runtime/parameterization.h"

namespace pem::test {

// splitmix64: the same stream as the case format's "random" texel generator.
struct Rng {
    uint64_t state;
    uint64_t Next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float Uniform(float a, float b) {
        const float u = static_cast<float>(Next() >> 40) * (1.0f / 16777216.0f);
        return a + (b - a) * u;
    }
    int Int(int n) { return static_cast<int>(Next() % static_cast<uint64_t>(n)); }
};

struct NamedCase {
    std::string name;
    raster::Frame frame;
};

std::vector<NamedCase> ConformanceCases();

// A 96x80 frame of a mirror sphere (rings x segments quads) reflecting a random map of layout
// `p` at `size` (runtime/parameterization.h), drawn with the layout's texgen.
raster::Frame LayoutSphere(runtime::Parameterization p, int size,
                           const raster::SamplerState& sampler, int rings, int segments,
                           uint64_t seed);

// The benchmark frame of bench/: width x height, a full-screen sky quad and a UV sphere of
// `rings` x `segments` quads with reflection vectors, one `cubeSize` cube, trilinear, seamless.
raster::Frame BenchmarkFrame(int width, int height, int rings, int segments, int cubeSize);

// The small-triangle frame of bench/: what the hybrid renderer's lens passes draw. A UV sphere
// of `rings` x `segments` quads (both faces; about two pixels a front triangle at 640x480) into
// an RGBA32F colour and a Z24 depth buffer: the outer layer replacing with depth LESS written,
// the inner layer premultiplied over with depth EQUAL, each from its own RGBA32F `cubeSize` cube
// (trilinear, seamless).
raster::Frame LensFrame(int width, int height, int rings, int segments, int cubeSize);

}  // namespace pem::test
