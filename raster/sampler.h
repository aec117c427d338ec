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
// seamless cube corner's missing texel spread over the other three, or an anisotropic
// footprint's table weights over their sum (aniso.h). They are exact for the float filtering
// paths; for the 8-bit fixed-point paths they are the ideal weights that path rounds (see
// docs/raster-model.md for the bound).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/blend.h"
#include "raster/frame.h"
#include "raster/render.h"

namespace pem::raster {

struct Tap {
    uint32_t texel;  // global texel index (texel_index.h)
    float weight;
};

constexpr int kMaxTaps = 8;  // bilinear paths: two levels x four texels

// A pixel's taps: up to kMaxTaps inline (the bilinear paths, merged per texel) and, for an
// anisotropic footprint (one entry per texel), the rest in `more`: storage the anisotropic path
// owns per thread, valid until that thread samples again. A plain aggregate, so the shading
// loop's per-group array costs nothing when it is not used: value-initialise it (PixelTaps{})
// before use.
struct PixelTaps {
    int count;  // entries of `tap` in use
    std::array<Tap, kMaxTaps> tap;
    std::vector<Tap>* more;  // null: none beyond `tap`

    int Count() const { return count + (more ? static_cast<int>(more->size()) : 0); }
    const Tap& At(int k) const {
        return k < kMaxTaps ? tap[static_cast<size_t>(k)]
                            : (*more)[static_cast<size_t>(k - kMaxTaps)];
    }
    // Adds to the texel's inline entry, or makes one (the bilinear paths: <= kMaxTaps texels).
    void Add(uint32_t texel, float weight) {
        for (int k = 0; k < count; ++k)
            if (tap[static_cast<size_t>(k)].texel == texel) {
                tap[static_cast<size_t>(k)].weight += weight;
                return;
            }
        if (count < kMaxTaps) tap[static_cast<size_t>(count++)] = {texel, weight};
    }
    // Appends an entry for a texel not yet present; beyond kMaxTaps into *overflow (emptied on
    // first use).
    void Append(uint32_t texel, float weight, std::vector<Tap>* overflow) {
        if (count < kMaxTaps) {
            tap[static_cast<size_t>(count++)] = {texel, weight};
            return;
        }
        if (!more) {
            more = overflow;
            more->clear();
        }
        more->push_back({texel, weight});
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
