// SPDX-License-Identifier: MIT
// sampler.h — texture lookups of one 2x2 quad with implicit derivatives, as llvmpipe computes
// them, returning every pixel's colour and, on request, its taps (texel, weight).
//
// Lanes: llvmpipe shades 8 pixels at a time (256-bit vectors: two 2x2 quads side by side, a
// 4x2 block at X % 4 == 0, Y % 2 == 0). Lane 4q + p is pixel p of quad q, with p: 0 = (0, 0),
// 1 = (1, 0), 2 = (0, 1), 3 = (1, 1) (raster space, y up = GL window y) and quad q at x + 2q.
// All lanes carry coordinates (uncovered "helper" pixels too): derivatives are differences
// inside a quad, and some of llvmpipe's choices (the seamless corner formula) are made once
// for all eight lanes.
//
// Taps are the linear weights of the filter: bilinear weights times the MIP weight, with a
// seamless cube corner's missing texel spread over the other three. They are exact for the
// float filtering paths; for the 8-bit fixed-point paths they are the ideal weights that path
// rounds (see docs/raster-model.md for the bound).
#pragma once

#include <array>
#include <cstdint>

#include "raster/blend.h"
#include "raster/frame.h"
#include "raster/render.h"

namespace pem::raster {

struct Tap {
    uint32_t texel;  // global texel index (texel_index.h)
    float weight;
};

constexpr int kMaxTaps = 8;  // two levels x four texels

struct PixelTaps {
    int count = 0;
    std::array<Tap, kMaxTaps> tap;
    void Add(uint32_t texel, float weight) {
        for (int k = 0; k < count; ++k)
            if (tap[k].texel == texel) {
                tap[k].weight += weight;
                return;
            }
        tap[count++] = {texel, weight};
    }
};

constexpr int kLanes = 8;

struct LaneCoords {
    std::array<std::array<float, 3>, kLanes> c;  // per lane: s, t, r (2D uses s, t)
};

// Samples texture `textureIndex` of the frame for the eight lanes. `taps` may be null. Only the
// lanes in `live` get a colour and taps (the others still take part in vector-wide choices).
void SampleLanes(const PreparedFrame& frame, int textureIndex, const RenderOptions& options,
                 const LaneCoords& coords, std::array<RgbaF, kLanes>* colour,
                 std::array<PixelTaps, kLanes>* taps, unsigned live = 0xFF);

}  // namespace pem::raster
