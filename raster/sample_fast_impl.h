// SPDX-License-Identifier: MIT
// sample_fast_impl.h — the hot case of the llvmpipe profile, written lane-parallel: a seamless
// cube, GL_LINEAR_MIPMAP_LINEAR with mag LINEAR, no taps. Every loop runs over
// the eight lanes with selects instead of branches so the compiler can vectorise it; the
// arithmetic per lane is exactly that of cube_lookup_impl.h, lod_impl.h and
// sample_float_impl.h (the conformance suite checks both against llvmpipe). Lanes whose
// footprint crosses a face edge are finished by the general SeamlessLinear.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX2__) || defined(__FMA__)
#include <immintrin.h>
#endif

#include "raster/numeric.h"
#include "raster/sample_float_impl.h"
#include "raster/sampler.h"

namespace pem::raster::isa {
namespace {

// Face selection, projection and squared scale factor of all eight lanes, as branch-free
// loops over lanes (bit-pattern selects) so the compiler vectorises them. Per lane this is
// exactly cube_lookup_impl.h's CubeLookup followed by llvmpipe's rho^2 (Inf/NaN -> 0); without
// derivatives the projection uses 0.5/|ma| (0 for ma == 0) and rho^2 is 0.
void CubeLanes(const LaneCoords& c, bool withDerivs, float n, int32_t* face, float* s, float* t,
               float* rho2) {
    // Directions and fine quad differences (right - left in the row, bottom - top).
    alignas(32) float d[3][kLanes], dx[3][kLanes], dy[3][kLanes];
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < kLanes; ++l) d[k][l] = c.c[l][k];
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < kLanes; ++l) {
            const int q = l & ~3, p = l & 3, left = q + (p & 2), top = q + (p & 1);
            dx[k][l] = withDerivs ? d[k][left + 1] - d[k][left] : 0.0f;
            dy[k][l] = withDerivs ? d[k][top + 2] - d[k][top] : 0.0f;
        }
    for (int l = 0; l < kLanes; ++l) {
        const float x = d[0][l], y = d[1][l], z = d[2][l];
        const float as = std::fabs(x), at = std::fabs(y), ar = std::fabs(z);
        const bool isZ = !(ar < (as > at ? as : at));  // unordered compares (NaN: true)
        const bool isX = !isZ & !(as <= at);
        const bool isY = !isX & !isZ;
        const uint32_t mX = 0u - static_cast<uint32_t>(isX), mY = 0u - static_cast<uint32_t>(isY);
        const uint32_t mZ = 0u - static_cast<uint32_t>(isZ);
        auto pick = [&](uint32_t bx, uint32_t by, uint32_t bz) {
            return BitsFloat((bx & mX) | (by & mY) | (bz & mZ));
        };
        const uint32_t neg = 0x80000000u;
        const float ma = pick(FloatBits(x), FloatBits(y), FloatBits(z));
        const uint32_t sign = FloatBits(ma) & neg;
        face[l] = static_cast<int32_t>((4u & mZ) | (2u & mY)) + static_cast<int32_t>(sign >> 31);
        // (sc, tc): X: (-z ^ sign, -y); Y: (x, z ^ sign); Z: (x ^ sign, -y).
        auto minorS = [&](float vx, float vz) {
            return pick(FloatBits(vz) ^ neg ^ sign, FloatBits(vx), FloatBits(vx) ^ sign);
        };
        auto minorT = [&](float vy, float vz) {
            return pick(FloatBits(vy) ^ neg, FloatBits(vz) ^ sign, FloatBits(vy) ^ neg);
        };
        const float sc = minorS(x, z), tc = minorT(y, z);
        // With derivatives: the quotient rule through 1/ma (signed); the projection uses
        // |0.5 * (1/ma)|, which equals 0.5/|ma| except for ma == 0 (then NaN, as llvmpipe).
        const float scdx = minorS(dx[0][l], dx[2][l]), tcdx = minorT(dx[1][l], dx[2][l]);
        const float scdy = minorS(dy[0][l], dy[2][l]), tcdy = minorT(dy[1][l], dy[2][l]);
        const float madx = pick(FloatBits(dx[0][l]), FloatBits(dx[1][l]), FloatBits(dx[2][l]));
        const float mady = pick(FloatBits(dy[0][l]), FloatBits(dy[1][l]), FloatBits(dy[2][l]));
        const float ima = 1.0f / ma;
        const float imaHalf = 0.5f * ima;
        const float qx = madx * ima, qy = mady * ima;
        const float xs = n * ((scdx - qx * sc) * imaHalf), xt = n * ((tcdx - qx * tc) * imaHalf);
        const float ys = n * ((scdy - qy * sc) * imaHalf), yt = n * ((tcdy - qy * tc) * imaHalf);
        const float rx = xs * xs + xt * xt, ry = ys * ys + yt * yt;
        const float rho = rx > ry ? rx : ry;
        const uint32_t rb = FloatBits(rho);
        const uint32_t finite = 0u - static_cast<uint32_t>((rb & 0x7f800000u) != 0x7f800000u);
        // Without derivatives: 0.5/|ma|, guarded against 0 (unordered: NaN stays NaN).
        const float am = std::fabs(ma);
        const bool amPositive = !(am <= 0.0f);
        const float plain = 0.5f / (amPositive ? am : 1.0f);
        const float imaHalfPos = withDerivs ? std::fabs(imaHalf) : (amPositive ? plain : 0.0f);
        rho2[l] = withDerivs ? BitsFloat(rb & finite) : 0.0f;
        s[l] = sc * imaHalfPos + 0.5f;
        t[l] = tc * imaHalfPos + 0.5f;
    }
}

// True when SampleFastSeamless handles this sampler (and the caller wants no taps).
bool FastSeamlessApplies(const Texture& t, const PipeLodState& st, const RenderOptions& o) {
    const SamplerState& s = t.sampler;
    return o.profile == Profile::Llvmpipe && o.cubeLod == CubeLod::Llvmpipe &&
           t.kind == TextureKind::Cube && s.seamless && s.minFilter == Filter::Linear &&
           s.magFilter == Filter::Linear && s.mipFilter == MipFilter::Linear && !st.minMaxEqual;
}

// cvttps2dq without undefined behaviour and without a branch: INT32_MIN for NaN and |x| >= 2^31.
inline int32_t TruncOrMin(float x) {
    const bool inRange = std::fabs(x) < 2147483648.0f;
    const int32_t i = static_cast<int32_t>(inRange ? x : 0.0f);
    return inRange ? i : INT32_MIN;
}

// MIP levels of eight lanes for GL_*_MIPMAP_LINEAR: lambda = 0.5 * FastLog2(rho^2) (+ bias,
// clamps), floor and fraction, levels clamped to [0, last] with the fraction zeroed at both ends
// (lod_impl.h's LambdaFromRhoSquared and LevelsFor, lane-parallel).
void LodLanes(const PipeLodState& st, const float* rho2, int last, int32_t* level0, int32_t* level1,
              float* frac) {
    alignas(32) float lambda[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        const uint32_t bits = FloatBits(rho2[l]);
        const float e = static_cast<float>(static_cast<int32_t>((bits >> 23) & 255u) - 128);
        lambda[l] = (e + BitsFloat((bits & 0x007fffffu) | 0x3f800000u)) * 0.5f;
    }
    if (st.biasNonZero)
        for (int l = 0; l < kLanes; ++l) lambda[l] = lambda[l] + st.lodBias;
    if (st.applyMaxLod)
        for (int l = 0; l < kLanes; ++l) lambda[l] = lambda[l] < st.maxLod ? lambda[l] : st.maxLod;
    if (st.applyMinLod)
        for (int l = 0; l < kLanes; ++l) lambda[l] = lambda[l] > st.minLod ? lambda[l] : st.minLod;
    for (int l = 0; l < kLanes; ++l) {
        const float fl = std::floor(lambda[l]);
        float f = lambda[l] - fl;
        const int32_t l0Raw = TruncOrMin(fl);
        const bool below = l0Raw < 0, above = l0Raw >= last;
        level0[l] = below ? 0 : (above ? last : l0Raw);
        level1[l] = below ? 0 : (above ? last : l0Raw + 1);
        f = below ? 0.0f : f;
        frac[l] = above ? 0.0f : f;
    }
}

// The filter footprints of eight lanes on a texture shape (size, levels, sampler): level pair,
// MIP fraction, texel positions, bilinear fractions and seamless edge footprints per slot. They
// depend on the coordinates and the shape only, so textures of one shape share them. The
// general footprint of a lane whose bilinear footprint crosses a face edge (`fp`) is made for
// the lanes a draw reads (`fpLanes`); whether any lane's crosses a corner, a choice for the
// whole vector, is decided over all eight.
struct FastFootprints {
    const Texture* shape = nullptr;  // the texture they were computed for
    int slots = 1;
    alignas(32) int32_t face[kLanes], level[2][kLanes];
    alignas(32) float frac[kLanes], faceS[kLanes], faceT[kLanes];  // face coordinates
    alignas(32) int32_t x0[2][kLanes], y0[2][kLanes], size[2][kLanes], edge[2][kLanes];
    alignas(32) int32_t corner[2][kLanes];
    alignas(32) float a[2][kLanes], b[2][kLanes];
    std::array<Footprint, kLanes> fp[2];
    unsigned fpLanes[2] = {0, 0};
    bool anyCorner[2] = {false, false};

    // Whether footprints computed for `shape` serve texture t (same size, levels and sampler).
    bool Serves(const Texture& t) const {
        return shape && (shape == &t ||
                         (shape->kind == t.kind && shape->width == t.width &&
                          shape->NumLevels() == t.NumLevels() && shape->sampler == t.sampler));
    }
};

// Whether any of eight floats is > 0 / any of eight ints is not 0: one vector load of what a
// vector loop just stored (eight scalar loads of a vector store stall store forwarding).
inline bool AnyPositive(const float* v) {
#if defined(__AVX2__)
    const __m256 x = _mm256_load_ps(v);
    return _mm256_movemask_ps(_mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_GT_OQ)) != 0;
#else
    bool any = false;
    for (int l = 0; l < kLanes; ++l) any |= v[l] > 0.0f;
    return any;
#endif
}

inline bool AnyNonZero(const int32_t* v) {
#if defined(__AVX2__)
    const __m256i x = _mm256_load_si256(reinterpret_cast<const __m256i*>(v));
    return !_mm256_testz_si256(x, x);
#else
    bool any = false;
    for (int l = 0; l < kLanes; ++l) any |= v[l] != 0;
    return any;
#endif
}

// The general footprints of the edge lanes in `live` not made yet.
void EdgeFootprints(unsigned live, FastFootprints* f) {
    for (int slot = 0; slot < f->slots; ++slot) {
        for (unsigned set = live & ~f->fpLanes[slot]; set; set &= set - 1) {
            const int l = std::countr_zero(set);
            if (f->edge[slot][l])
                f->fp[slot][l] =
                    SeamlessLinear(f->faceS[l], f->faceT[l], f->face[l], f->size[slot][l]);
        }
        f->fpLanes[slot] |= live;
    }
}

void FastFootprintsOf(const PreparedTexture& pt, const LaneCoords& coords, unsigned live,
                      FastFootprints* f) {
    const Texture& tex = *pt.source;
    const PipeLodState& st = pt.lod;
    const int last = tex.NumLevels() - 1;
    const float n = static_cast<float>(tex.width);
    f->shape = &tex;

    // Face, projection and rho^2 per lane, then LOD.
    float* s = f->faceS;
    float* t = f->faceT;
    alignas(32) float rho2[kLanes];
    CubeLanes(coords, true, n, f->face, s, t, rho2);
    LodLanes(st, rho2, last, f->level[0], f->level[1], f->frac);

    f->slots = AnyPositive(f->frac) ? 2 : 1;
    for (int slot = 0; slot < f->slots; ++slot) {
        // Footprints: texel column/row, fractions and edge flags per lane.
        const int32_t* lev = f->level[slot];
        for (int l = 0; l < kLanes; ++l) {
            const int32_t sz = std::max(1, tex.width >> lev[l]);
            const float szf = static_cast<float>(sz);
            const float u = (s[l] > 0.0f ? s[l] : 0.0f) * szf - 0.5f;
            const float v = (t[l] > 0.0f ? t[l] : 0.0f) * szf - 0.5f;
            const float fu = std::floor(u), fv = std::floor(v);
            f->a[slot][l] = u - fu;
            f->b[slot][l] = v - fv;
            const int32_t ix = TruncOrMin(fu), iy = TruncOrMin(fv);
            f->x0[slot][l] = ix;
            f->y0[slot][l] = iy;
            f->size[slot][l] = sz;
            const int32_t offX = (ix < 0) | (ix + 1 > sz - 1), offY = (iy < 0) | (iy + 1 > sz - 1);
            f->edge[slot][l] = offX | offY;
            f->corner[slot][l] = offX & offY;  // SeamlessLinear's corner >= 0
        }
        f->anyCorner[slot] = AnyNonZero(f->corner[slot]);
        f->fpLanes[slot] = 0;
    }
    EdgeFootprints(live, f);
}

// A pixel's four channels as one vector (GCC/Clang vector extensions: SSE2 or NEON).
using F4 = float __attribute__((vector_size(16)));

// The two RGBA8 texels at p as floats, converted as PrepareTexture converts them (c * fl(1/255)):
// one 8-byte load, the bytes widened to 32-bit lanes, cvtdq2ps.
inline void Texels8(const uint8_t* p, F4* t0, F4* t1) {
    const auto k = static_cast<float>(1.0 / 255.0);
#if defined(__SSE2__)
    const __m128i b = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
    const __m128i z = _mm_setzero_si128(), w = _mm_unpacklo_epi8(b, z);
    *t0 = reinterpret_cast<F4>(_mm_cvtepi32_ps(_mm_unpacklo_epi16(w, z))) * k;
    *t1 = reinterpret_cast<F4>(_mm_cvtepi32_ps(_mm_unpackhi_epi16(w, z))) * k;
#else
    for (int c = 0; c < 4; ++c) {
        (*t0)[c] = static_cast<float>(p[c]) * k;
        (*t1)[c] = static_cast<float>(p[4 + c]) * k;
    }
#endif
}

// LerpF of four channels with one weight: fused per channel as LerpF is (one vfmadd in the
// AVX2/FMA build; the compilers keep the scalar form channel by channel).
inline F4 LerpF4(float w, F4 a, F4 b) {
#if defined(__FMA__)
    return _mm_fmadd_ps(_mm_set1_ps(w), b - a, a);
#else
    F4 r;
    for (int c = 0; c < 4; ++c) r[c] = LerpF(w, a[c], b[c]);
    return r;
#endif
}

inline F4 LoadF4(const float* p) {
    F4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

inline F4 ToF4(const RgbaF& c) {
    return LoadF4(c.data());
}

// The bilinear filter of one lane inside a face, as FilterFootprint computes it: rows
// (t00, t01) and (t10, t11) lerped along s with weight a, then along t with weight b.
inline F4 Bilinear(F4 t00, F4 t01, F4 t10, F4 t11, float a, float b) {
    return LerpF4(b, LerpF4(a, t00, t01), LerpF4(a, t10, t11));
}

// Filters the live lanes of texture `pt` (of the footprints' shape). An RGBA8 texture's lanes
// inside a face read its bytes, not the float copy: a quarter of the memory, so more of the
// levels a minified sphere reads stay in L2 (the raster benchmark frame 5 % faster at two
// threads; converting each byte through a table instead was 5 % slower). Not inlined: inside
// DrawBands its per-lane loop spilled and reloaded most of its values (the sky quad 1-2 %
// faster out of line).
__attribute__((noinline)) void FilterFast(const PreparedTexture& pt, const FastFootprints& f,
                                          unsigned live, std::array<RgbaF, kLanes>* colour) {
    const bool bytes = pt.source->format == TexelFormat::Rgba8 && !pt.source->levels[0].empty();
    const std::vector<float>* levelsF = pt.levelsF.data();
    const std::vector<uint8_t>* levels8 = pt.source->levels.data();
    for (int slot = 0; slot < f.slots; ++slot) {
        const bool anyCorner = f.anyCorner[slot];
        for (unsigned set = live; set; set &= set - 1) {  // the live lanes, no branch per lane
            const int l = std::countr_zero(set);
            if (slot == 1 && f.frac[l] == 0.0f) continue;
            const auto lv = static_cast<size_t>(f.level[slot][l]);
            const int32_t sz = f.size[slot][l];
            const int32_t base = (f.face[l] * sz + f.y0[slot][l]) * sz + f.x0[slot][l];
            F4 v;
            if (f.edge[slot][l]) {
                v = ToF4(FilterFootprint({levelsF[lv].data(), 0}, f.fp[slot][l], anyCorner, 1.0f,
                                         nullptr));
            } else if (anyCorner) {
                Footprint fp;
                fp.a = f.a[slot][l];
                fp.b = f.b[slot][l];
                fp.texel = {base, base + 1, base + sz, base + sz + 1};
                v = ToF4(FilterFootprint({levelsF[lv].data(), 0}, fp, true, 1.0f, nullptr));
            } else if (bytes) {  // the 8-bit texels: a quarter of the float copy's bytes
                const uint8_t* t00 = levels8[lv].data() + 4 * static_cast<size_t>(base);
                F4 t[4];
                Texels8(t00, &t[0], &t[1]);
                Texels8(t00 + 4 * static_cast<size_t>(sz), &t[2], &t[3]);
                v = Bilinear(t[0], t[1], t[2], t[3], f.a[slot][l], f.b[slot][l]);
            } else {
                const float* t00 = levelsF[lv].data() + 4 * static_cast<size_t>(base);
                const float* t10 = t00 + 4 * static_cast<size_t>(sz);
                v = Bilinear(LoadF4(t00), LoadF4(t00 + 4), LoadF4(t10), LoadF4(t10 + 4),
                             f.a[slot][l], f.b[slot][l]);
            }
            float* out = (*colour)[l].data();
            if (slot == 1) v = LerpF4(f.frac[l], LoadF4(out), v);
            std::memcpy(out, &v, sizeof v);
        }
    }
}

// The fast path of SampleLanes. `cache` (optional): footprints of an earlier texture; reused
// when they serve this one, else recomputed into it.
void SampleFastSeamless(const PreparedFrame& frame, int textureIndex, const LaneCoords& coords,
                        unsigned live, std::array<RgbaF, kLanes>* colour,
                        FastFootprints* cache = nullptr) {
    const PreparedTexture& pt = frame.texture(textureIndex);
    FastFootprints local;
    FastFootprints& f = cache ? *cache : local;
    if (!f.Serves(*pt.source))
        FastFootprintsOf(pt, coords, live, &f);
    else if (live & ~(f.fpLanes[0] & f.fpLanes[1]))
        EdgeFootprints(live, &f);
    FilterFast(pt, f, live, colour);
}

}  // namespace
}  // namespace pem::raster::isa
