// SPDX-License-Identifier: MIT
// sample_fixed8_impl.h — llvmpipe's 8-bit fixed-point ("AoS") filtering path.
//
//  - NEAREST: i = floor(s * N), clamped to [0, N-1] (or & (N-1) for repeat).
//  - LINEAR: S = RNE(s * (N * 256)) - 128, i0 = S >> 8, 8-bit weight S & 255 (meaning w/256);
//    clamp-to-edge collapses an out-of-range footprint onto one texel, repeat wraps with & (N-1).
//  - lerp8(w, a, b) = a + floor((w * (b - a) + 128) / 256): x first on both rows, each row
//    rounded to 8 bits, then y.
//  - MIP: weight trunc(frac * 256), lerp8 between the two levels' 8-bit results.
//  - The 8-bit result becomes float as c * fl(1/255).
// Cubes reach this path with their face coordinates and clamp-to-edge per face (no seams).
#pragma once
#include <algorithm>

#include "raster/numeric.h"
#include "raster/sampler_paths.h"

namespace pem::raster::isa {
namespace {

struct Axis8 {
    int i0 = 0, i1 = 0, w = 0;  // w in 0..255 (weight of i1, /256)
};

int32_t WrapSub(int32_t a, int32_t b) {
    return static_cast<int32_t>(static_cast<uint32_t>(a) - static_cast<uint32_t>(b));
}

Axis8 Linear8(float s, int n, Wrap wrap) {
    const float scale = static_cast<float>(n << 8);
    const int32_t S = WrapSub(RoundHalfEvenI32(s * scale), 128);
    Axis8 a;
    a.w = S & 255;
    const int32_t i0 = S >> 8;
    if (wrap == Wrap::Repeat) {
        a.i0 = i0 & (n - 1);
        a.i1 = a.i0 != n - 1 ? a.i0 + 1 : 0;
    } else {  // clamp to edge
        const bool lo = i0 >= 0, hi = i0 < n - 1;
        a.i0 = lo ? (hi ? i0 : n - 1) : 0;
        a.i1 = a.i0 + (lo && hi ? 1 : 0);
    }
    return a;
}

int Nearest8(float s, int n, Wrap wrap) {
    const int32_t i = FloorI32(s * static_cast<float>(n));
    if (wrap == Wrap::Repeat) return i & (n - 1);
    return std::clamp(i, 0, n - 1);
}

struct Level8 {
    const uint8_t* texels;
    int w, h;
    uint32_t base;
};

const uint8_t* Texel(const Level8& lv, int face, int i, int j) {
    return lv.texels + 4 * ((static_cast<size_t>(face) * lv.h + j) * lv.w + i);
}
uint32_t TexelIndex(const Level8& lv, int face, int i, int j) {
    return lv.base + static_cast<uint32_t>((face * lv.h + j) * lv.w + i);
}

// Filters one level in 8 bits, adding taps scaled by `scale`.
Rgba8 FilterLevel(const Level8& lv, Filter filter, Wrap ws, Wrap wt, float s, float t, int face,
                  float scale, PixelTaps* taps) {
    Rgba8 out;
    if (filter == Filter::Nearest) {
        const int i = Nearest8(s, lv.w, ws), j = Nearest8(t, lv.h, wt);
        const uint8_t* p = Texel(lv, face, i, j);
        for (int c = 0; c < 4; ++c) out[c] = p[c];
        if (taps) taps->Add(TexelIndex(lv, face, i, j), scale);
        return out;
    }
    const Axis8 x = Linear8(s, lv.w, ws), y = Linear8(t, lv.h, wt);
    const uint8_t* t00 = Texel(lv, face, x.i0, y.i0);
    const uint8_t* t01 = Texel(lv, face, x.i1, y.i0);
    const uint8_t* t10 = Texel(lv, face, x.i0, y.i1);
    const uint8_t* t11 = Texel(lv, face, x.i1, y.i1);
    for (int c = 0; c < 4; ++c) {
        const uint8_t r0 = Lerp8(x.w, t00[c], t01[c]);
        const uint8_t r1 = Lerp8(x.w, t10[c], t11[c]);
        out[c] = Lerp8(y.w, r0, r1);
    }
    if (taps) {
        const float a = static_cast<float>(x.w) / 256.0f, b = static_cast<float>(y.w) / 256.0f;
        const float w[4] = {(1.0f - a) * (1.0f - b), a * (1.0f - b), (1.0f - a) * b, a * b};
        const int is[4] = {x.i0, x.i1, x.i0, x.i1}, js[4] = {y.i0, y.i0, y.i1, y.i1};
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0.0f) taps->Add(TexelIndex(lv, face, is[k], js[k]), w[k] * scale);
    }
    return out;
}

void FilterFixed8(const PreparedFrame& frame, const Texture& tex, const PreparedTexture& /*pt*/,
                  const LaneSample& ls, std::array<RgbaF, kLanes>* colour,
                  std::array<PixelTaps, kLanes>* taps) {
    const SamplerState& s = tex.sampler;
    const bool cube = tex.kind == TextureKind::Cube;
    const Wrap ws = cube ? Wrap::ClampToEdge : s.wrapS;
    const Wrap wt = cube ? Wrap::ClampToEdge : s.wrapT;
    auto level = [&](int l) {
        return Level8{tex.levels[static_cast<size_t>(l)].data(), tex.LevelWidth(l),
                      tex.LevelHeight(l), frame.indexer().LevelBase(ls.texture, l)};
    };
    for (int l = 0; l < kLanes; ++l) {
        if (!(ls.live & (1u << l))) continue;
        const LodResult& lod = ls.lod[l];
        const bool mag = lod.magnify && s.minFilter != s.magFilter;
        const Filter filter = mag ? s.magFilter : s.minFilter;
        const bool twoLevels = !mag && s.mipFilter == MipFilter::Linear;
        // MIP weight: truncation of frac * 256.
        const int wl = twoLevels ? std::max(TruncI32(lod.frac * 256.0f), 0) : 0;
        const float w1 = static_cast<float>(wl) / 256.0f;
        PixelTaps* tp = taps ? &(*taps)[l] : nullptr;
        const int level0 = mag ? 0 : lod.level0;
        Rgba8 c =
            FilterLevel(level(level0), filter, ws, wt, ls.s[l], ls.t[l], ls.face[l], 1.0f - w1, tp);
        if (wl > 0) {
            const Rgba8 c1 = FilterLevel(level(lod.level1), filter, ws, wt, ls.s[l], ls.t[l],
                                         ls.face[l], w1, tp);
            for (int k = 0; k < 4; ++k) c[k] = Lerp8(wl & 255, c[k], c1[k]);
        }
        for (int k = 0; k < 4; ++k) (*colour)[l][k] = FloatFromUnorm8(c[k]);
    }
}

}  // namespace
}  // namespace pem::raster::isa
