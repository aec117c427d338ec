// SPDX-License-Identifier: MIT
// sample_float_impl.h — llvmpipe's float ("SoA") filtering path, and the `linear` profile.
//
// Per MIP slot (level0, then level1 when some lane blends two levels):
//  - texel coordinates: u = wrap(s) * size - 0.5, i0 = floor(u), alpha = u - floor(u);
//    seamless cubes: s clamped below at 0 (NaN -> 0), neighbours across edges from the cube
//    adjacency, the missing corner texel replaced by the mean of the other three;
//  - bilinear: lerp(beta, lerp(alpha, t00, t01), lerp(alpha, t10, t11)) with fused lerps,
//    except when any of the eight lanes touches a cube corner: then every lane uses
//    w00*t00 + w01*t01 + w10*t10 + w11*t11 with the corner weight spread in thirds;
//  - MIP: lerp(frac, c0, c1).
#pragma once
#include <algorithm>
#include <cmath>

#include "raster/numeric.h"
#include "raster/sampler_paths.h"

namespace pem::raster::isa {
namespace {

float MaxNanToOther(float v, float other) {
    return std::isnan(v) ? other : std::max(v, other);
}
float MinNanToOther(float v, float other) {
    return std::isnan(v) ? other : std::min(v, other);
}

// gallivm's mirror: |2 * (x/2 - round_even(x/2))|, NaN -> 0.
float Mirror(float x) {
    const float h = x * 0.5f;
    const float f = h - std::nearbyint(h);
    return MaxNanToOther(std::fabs(f + f), 0.0f);
}

struct WrapAxis {
    int i0 = 0, i1 = 0;
    float w = 0;  // weight of i1
};

// Linear wrap of one 2D axis (lp_build_sample_wrap_linear, power-of-two sizes).
WrapAxis WrapLinear(float coord, int len, Wrap wrap) {
    const float lenf = static_cast<float>(len);
    WrapAxis a;
    float u;
    switch (wrap) {
        case Wrap::Repeat: {
            u = coord * lenf - 0.5f;
            const float fl = std::floor(u);
            a.w = u - fl;
            const int i = TruncI32(fl);
            a.i0 = i & (len - 1);
            a.i1 = (i + 1) & (len - 1);
            return a;
        }
        case Wrap::ClampToEdge: {
            u = MinNanToOther(coord * lenf, lenf) - 0.5f;
            u = u > 0.0f ? u : 0.0f;
            const float fl = std::floor(u);
            a.w = u - fl;
            a.i0 = TruncI32(fl);
            a.i1 = std::min(a.i0 + 1, len - 1);
            return a;
        }
        case Wrap::MirroredRepeat: {
            u = Mirror(coord) * lenf - 0.5f;
            const float fl = std::floor(u);
            a.w = u - fl;
            const int i = TruncI32(fl);
            a.i0 = std::max(i, 0);
            a.i1 = std::min(i + 1, len - 1);
            return a;
        }
    }
    return a;
}

// Nearest wrap of one axis (lp_build_sample_wrap_nearest).
int WrapNearest(float coord, int len, Wrap wrap) {
    const float lenf = static_cast<float>(len);
    switch (wrap) {
        case Wrap::Repeat:
            return FloorI32(coord * lenf) & (len - 1);
        case Wrap::ClampToEdge:
            return std::clamp(TruncI32(coord * lenf), 0, len - 1);
        case Wrap::MirroredRepeat:
            return std::min(TruncI32(Mirror(coord) * lenf), len - 1);
    }
    return 0;
}

// Cube adjacency (the GL face table): where texel (i, j) of `face` lands when it falls off an
// edge: 0 = i < 0, 1 = i > max, 2 = j < 0, 3 = j > max. For x fall-offs j is already clamped.
void CrossEdge(int face, int edge, int max, int* i, int* j) {
    const int oi = *i, oj = *j;
    int ni = 0, nj = 0;
    switch (edge) {
        case 0: {
            const int is[6] = {max, max, oj, max - oj, max, max};
            const int js[6] = {oj, oj, 0, max, oj, oj};
            ni = is[face];
            nj = js[face];
            break;
        }
        case 1: {
            const int is[6] = {0, 0, max - oj, oj, 0, 0};
            const int js[6] = {oj, oj, 0, max, oj, oj};
            ni = is[face];
            nj = js[face];
            break;
        }
        case 2: {
            const int is[6] = {max, 0, max - oi, oi, oi, max - oi};
            const int js[6] = {max - oi, oi, 0, max, max, 0};
            ni = is[face];
            nj = js[face];
            break;
        }
        default: {
            const int is[6] = {max, 0, oi, max - oi, oi, max - oi};
            const int js[6] = {oi, max - oi, 0, max, 0, max};
            ni = is[face];
            nj = js[face];
            break;
        }
    }
    *i = ni;
    *j = nj;
}

int NextFace(int face, int edge) {
    static const int kFace[4][6] = {
        {4, 5, 1, 1, 1, 0}, {5, 4, 0, 0, 0, 1}, {2, 2, 5, 4, 2, 2}, {3, 3, 4, 5, 3, 3}};
    return kFace[edge][face];
}

// The four texels and bilinear fractions of one lane at one level. A texel is its index inside
// the level (face-major: (face * h + j) * w + i).
struct Footprint {
    std::array<int32_t, 4> texel;  // order 00, 01, 10, 11 (x fastest)
    float a = 0, b = 0;            // weights of column 1 and row 1
    int corner = -1;               // index of the missing corner texel, or -1
    bool nearest = false;          // one texel (index 0)
};

int32_t TexelAt(int face, int i, int j, int w, int h) {
    return (face * h + j) * w + i;
}

Footprint SeamlessLinear(float s, float t, int face, int size) {
    Footprint f;
    const float sizef = static_cast<float>(size);
    const float u = MaxNanToOther(s, 0.0f) * sizef - 0.5f;
    const float v = MaxNanToOther(t, 0.0f) * sizef - 0.5f;
    const float fu = std::floor(u), fv = std::floor(v);
    f.a = u - fu;
    f.b = v - fv;
    // Under FTZ, s and t are NaN (then 0 here) or within [0, 1], so the floors lie in
    // [-1, size - 1]. Only the linear profile (no FTZ) reaches +Inf, from the projection of a
    // denormal major axis (1/ma overflows); its column and row stop at the far edge instead of
    // indexing past the face.
    const float last = sizef - 1.0f;
    const int x0 = TruncI32(fu < last ? fu : last), y0 = TruncI32(fv < last ? fv : last);
    const int x1 = x0 + 1, y1 = y0 + 1, max = size - 1;
    const bool offX0 = x0<0, offX1 = x1> max, offY0 = y0<0, offY1 = y1> max;
    const int y0c = std::max(y0, 0), y1c = std::min(y1, max);
    const int xs[4] = {x0, x1, x0, x1};
    const int ys[4] = {y0c, y0c, y1c, y1c};
    const bool offX[4] = {offX0, offX1, offX0, offX1};
    const bool offY[4] = {offY0, offY0, offY1, offY1};
    const int xEdge[4] = {0, 1, 0, 1}, yEdge[4] = {2, 2, 3, 3};
    for (int k = 0; k < 4; ++k) {
        int i = xs[k], j = ys[k], fc = face;
        if (offX[k]) {
            CrossEdge(face, xEdge[k], max, &i, &j);
            fc = NextFace(face, xEdge[k]);
        } else if (offY[k]) {
            CrossEdge(face, yEdge[k], max, &i, &j);
            fc = NextFace(face, yEdge[k]);
        }
        f.texel[k] = TexelAt(fc, i, j, size, size);
        if (offX[k] && offY[k]) f.corner = k;
    }
    return f;
}

Footprint PlainLinear(float s, float t, int face, int w, int h, Wrap ws, Wrap wt) {
    Footprint f;
    const WrapAxis x = WrapLinear(s, w, ws), y = WrapLinear(t, h, wt);
    f.a = x.w;
    f.b = y.w;
    const int xs[4] = {x.i0, x.i1, x.i0, x.i1}, ys[4] = {y.i0, y.i0, y.i1, y.i1};
    for (int k = 0; k < 4; ++k) f.texel[k] = TexelAt(face, xs[k], ys[k], w, h);
    return f;
}

Footprint PlainNearest(float s, float t, int face, int w, int h, Wrap ws, Wrap wt) {
    Footprint f;
    f.nearest = true;
    f.texel[0] = TexelAt(face, WrapNearest(s, w, ws), WrapNearest(t, h, wt), w, h);
    return f;
}

struct LevelView {
    const float* texels;  // RGBA floats of the level
    uint32_t base;        // global index of the level's first texel
};

const float* Fetch(const LevelView& lv, int32_t texel) {
    return lv.texels + 4 * static_cast<size_t>(texel);
}
uint32_t TexelOf(const LevelView& lv, int32_t texel) {
    return lv.base + static_cast<uint32_t>(texel);
}

// Bilinear weights of a footprint, the corner weight spread over the other three.
std::array<float, 4> Weights(const Footprint& f) {
    const float wx0 = 1.0f - f.a, wy0 = 1.0f - f.b;
    std::array<float, 4> w{wx0 * wy0, f.a * wy0, wx0 * f.b, f.a * f.b};
    float c = 0.0f;
    if (f.corner >= 0) c = w[f.corner] * (1.0f / 3.0f);
    for (int k = 0; k < 4; ++k) w[k] = (k == f.corner) ? 0.0f : w[k] + c;
    return w;
}

// Filters one footprint; `weighted` selects the explicit-weight formula.
RgbaF FilterFootprint(const LevelView& lv, const Footprint& f, bool weighted, float scale,
                      PixelTaps* taps) {
    if (f.nearest) {
        if (taps) taps->Add(TexelOf(lv, f.texel[0]), scale);
        const float* p = Fetch(lv, f.texel[0]);
        return {p[0], p[1], p[2], p[3]};
    }
    const float* t[4] = {Fetch(lv, f.texel[0]), Fetch(lv, f.texel[1]), Fetch(lv, f.texel[2]),
                         Fetch(lv, f.texel[3])};
    RgbaF out;
    if (!weighted && !taps) {
        for (int c = 0; c < 4; ++c) {
            const float r0 = LerpF(f.a, t[0][c], t[1][c]);
            const float r1 = LerpF(f.a, t[2][c], t[3][c]);
            out[c] = LerpF(f.b, r0, r1);
        }
        return out;
    }
    const std::array<float, 4> w = Weights(f);
    if (taps)
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0.0f) taps->Add(TexelOf(lv, f.texel[k]), w[k] * scale);
    for (int c = 0; c < 4; ++c) {
        if (weighted) {
            float v = w[0] * t[0][c];
            v = w[1] * t[1][c] + v;
            v = w[2] * t[2][c] + v;
            v = w[3] * t[3][c] + v;
            out[c] = v;
        } else {
            const float r0 = LerpF(f.a, t[0][c], t[1][c]);
            const float r1 = LerpF(f.a, t[2][c], t[3][c]);
            out[c] = LerpF(f.b, r0, r1);
        }
    }
    return out;
}

// Filters texture `tex` with sampler state `s` (its own, or the anisotropic path's bilinear
// fallback).
void FilterFloat(const PreparedFrame& frame, const Texture& tex, const SamplerState& s,
                 const PreparedTexture& pt, bool exactTexels, const LaneSample& ls,
                 std::array<RgbaF, kLanes>* colour, std::array<PixelTaps, kLanes>* taps) {
    const bool cube = tex.kind == TextureKind::Cube;
    const auto& levels = exactTexels ? pt.levelsExact : pt.levelsF;
    bool anyLerp = false;
    for (int l = 0; l < kLanes; ++l) anyLerp |= ls.lod[l].frac > 0.0f;
    const int slots = (s.mipFilter == MipFilter::Linear && anyLerp) ? 2 : 1;

    // With min != mag, a block whose lanes need both filters is sampled with LINEAR addressing
    // throughout (lp_build_sample_mipmap_both); otherwise each lane's own filter applies.
    bool anyLinear = false;
    for (int l = 0; l < kLanes; ++l)
        anyLinear |= (ls.lod[l].magnify ? s.magFilter : s.minFilter) == Filter::Linear;
    if (s.minFilter == s.magFilter) anyLinear = false;

    std::array<RgbaF, kLanes> slot0{};
    for (int slot = 0; slot < slots; ++slot) {
        // Footprints of all lanes, then the vector-wide corner decision.
        std::array<Footprint, kLanes> fp;
        std::array<LevelView, kLanes> lv;
        bool anyCorner = false;
        for (int l = 0; l < kLanes; ++l) {
            const LodResult& lod = ls.lod[l];
            const int level = slot == 0 ? lod.level0 : lod.level1;
            const int w = tex.LevelWidth(level), h = tex.LevelHeight(level);
            lv[l] = {levels[static_cast<size_t>(level)].data(),
                     frame.indexer().LevelBase(ls.texture, level)};
            const Filter filter = lod.magnify ? s.magFilter : s.minFilter;
            const Wrap ws = cube ? Wrap::ClampToEdge : s.wrapS;
            const Wrap wt = cube ? Wrap::ClampToEdge : s.wrapT;
            if (filter == Filter::Nearest && !anyLinear)
                fp[l] = PlainNearest(ls.s[l], ls.t[l], ls.face[l], w, h, ws, wt);
            else if (cube && s.seamless)
                fp[l] = SeamlessLinear(ls.s[l], ls.t[l], ls.face[l], w);
            else
                fp[l] = PlainLinear(ls.s[l], ls.t[l], ls.face[l], w, h, ws, wt);
            if (filter == Filter::Nearest && anyLinear) {
                // llvmpipe's mixed min/mag block: linear addressing, weights forced to 0 or 1.
                fp[l].a = fp[l].a > 0.5f ? 1.0f : 0.0f;
                fp[l].b = fp[l].b > 0.5f ? 1.0f : 0.0f;
            }
            anyCorner |= fp[l].corner >= 0;
        }
        for (int l = 0; l < kLanes; ++l) {
            const float frac = ls.lod[l].frac;
            // Lanes nobody reads, and second-level lookups with weight 0 (fma(0, d, c0) == c0),
            // need no texels.
            if (!(ls.live & (1u << l)) || (slot == 1 && frac == 0.0f)) continue;
            const float scale = slots == 1 ? 1.0f : (slot == 0 ? 1.0f - frac : frac);
            PixelTaps* tp = taps ? &(*taps)[l] : nullptr;
            if (tp && scale == 0.0f) tp = nullptr;
            const RgbaF v = FilterFootprint(lv[l], fp[l], anyCorner, scale, tp);
            if (slot == 0) {
                slot0[l] = v;
                (*colour)[l] = v;
            } else {
                for (int c = 0; c < 4; ++c) (*colour)[l][c] = LerpF(frac, slot0[l][c], v[c]);
            }
        }
    }
}

}  // namespace
}  // namespace pem::raster::isa
