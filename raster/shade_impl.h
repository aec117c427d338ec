// SPDX-License-Identifier: MIT
// shade_impl.h — the fragment stage's loop (fragment.h): 4x2 lane groups of a triangle, the
// early depth test (depth.h), per-lane interpolation (1/w interpolated, one division,
// attributes times it), texture units, the fragment colour texture(u0) * texture(u1) * colour,
// unorm8 conversion and 8-bit blending (or float blending into an RGBA32F colour buffer or the
// Linear profile's, or the rows of the rendering matrix).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <vector>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "raster/blend.h"
#include "raster/clip.h"
#include "raster/depth.h"
#include "raster/fragment.h"
#include "raster/matrix_rows.h"
#include "raster/numeric.h"
#include "raster/sampler_impl.h"

namespace pem::raster::isa {
namespace {

// Per-lane attribute values of a 4x2 lane group (sampler.h's lane order), attribute-major so
// the loops over lanes vectorise: the interpolated 1/w, one true division, each attribute
// times it.
struct LaneAttribs {
    alignas(32) float a[kMaxAttribs][kLanes];
};

constexpr int kLaneDx[kLanes] = {0, 1, 0, 1, 2, 3, 2, 3};
constexpr int kLaneDy[kLanes] = {0, 0, 1, 1, 0, 0, 1, 1};

// The lanes (bit l) of the columns in a set of the group's four columns (bit d: column gx + d).
constexpr std::array<unsigned, 16> kColumnLanes = [] {
    std::array<unsigned, 16> lanes{};
    for (unsigned columns = 0; columns < 16; ++columns)
        for (int l = 0; l < kLanes; ++l) lanes[columns] |= ((columns >> kLaneDx[l]) & 1u) << l;
    return lanes;
}();

void InterpolateLanes(const TriangleSetup& t, int gx, int gy, LaneAttribs* q) {
    alignas(32) float x[kLanes], y[kLanes], oow[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        x[l] = static_cast<float>(gx + kLaneDx[l]);
        y[l] = static_cast<float>(gy + kLaneDy[l]);
        oow[l] = 1.0f / EvalPlane(t.oow, x[l], y[l]);
    }
    for (int k = 0; k < t.numAttribs; ++k)
        for (int l = 0; l < kLanes; ++l) q->a[k][l] = EvalPlane(t.attr[k], x[l], y[l]) * oow[l];
}

// Edge values of four lanes (wrapping sums: unsigned) and their tests (-1: true, 0: false).
using U64x4 = uint64_t __attribute__((vector_size(32)));
using I64x4 = int64_t __attribute__((vector_size(32)));

// Bit l set where lane l's test (lanes 0-3 in v[0], 4-7 in v[1]) is true.
unsigned LaneBits(const I64x4 (&v)[2]) {
#if defined(__AVX2__)
    return static_cast<unsigned>(
        _mm256_movemask_pd(_mm256_castsi256_pd(reinterpret_cast<__m256i>(v[0]))) |
        _mm256_movemask_pd(_mm256_castsi256_pd(reinterpret_cast<__m256i>(v[1]))) << 4);
#else
    unsigned bits = 0;
    for (int l = 0; l < kLanes; ++l) bits |= static_cast<unsigned>(v[l / 4][l % 4] & 1) << l;
    return bits;
#endif
}

// Fragment depth of the eight lanes of a 4x2 group (computed once, shared by every draw).
struct LaneDepth {
    bool ready = false;
    alignas(32) float z[kLanes];
};

// The lanes of `mask` whose fragments pass `test` against the target's depth buffer, their
// values stored when the test writes. llvmpipe tests before shading (early depth: the shader
// neither discards nor writes depth) and skips a lane group none of whose lanes passes; failed
// lanes still carry coordinates for the others' derivatives, as uncovered lanes do.
unsigned DepthTestLanes(const FragmentTarget& tg, const DepthTest& test, const Plane& zPlane,
                        int gx, int gy, unsigned mask, LaneDepth* depth) {
    if (!depth->ready) {
        for (int l = 0; l < kLanes; ++l)
            depth->z[l] = FragmentDepth(zPlane, static_cast<float>(gx + kLaneDx[l]),
                                        static_cast<float>(gy + kLaneDy[l]));
        depth->ready = true;
    }
    const Frame& frame = tg.frame->frame();
    const DepthFormat format = frame.depth->format;
    unsigned passed = 0;
    for (unsigned set = mask; set; set &= set - 1) {  // the set lanes, no branch per lane
        const int l = std::countr_zero(set);
        const int x = gx + kLaneDx[l], y = gy + kLaneDy[l];
        uint32_t& stored = (*tg.depth)[tg.Index(x, y)];
        const uint32_t value = DepthFromFloat(format, depth->z[l]);
        if (!DepthPasses(test.func, format, value, stored)) continue;
        if (test.write) stored = value;
        passed |= 1u << l;
    }
    return passed;
}

// The fragment colour and its unorm8 conversion on F4 (sample_fast_impl.h): the same IEEE
// operations per channel as the scalar code, without the per-channel compares and selects (and
// their branches) the compilers emit for it. The colour is built in registers: four scalar
// stores read back as one vector stall.
using I4 = int32_t __attribute__((vector_size(16)));

RgbaF FromF4(F4 v) {
    RgbaF r;
    std::memcpy(r.data(), &v, sizeof v);
    return r;
}

// UnormFromFloatRne of four values (0 .. 255 in each int).
I4 UnormRne4(F4 x) {
    const I4 positive = x > 0.0f;  // ClampUnit: NaN -> 0, then at most 1
    const F4 low = reinterpret_cast<F4>(reinterpret_cast<I4>(x) & positive);
    const I4 below = low < 1.0f;
    const I4 one = reinterpret_cast<I4>(F4{1.0f, 1.0f, 1.0f, 1.0f});
    const F4 c = reinterpret_cast<F4>((reinterpret_cast<I4>(low) & below) | (one & ~below));
    constexpr float kShift = 12582912.0f;  // RoundEvenSmall
    const F4 rounded = (c * 255.0f + kShift) - kShift;
    return __builtin_convertvector(rounded, I4);
}

// The unorm8 bytes of a fragment colour packed little-endian (red in the low byte):
// UnormFromFloatRne or UnormFromFloatHalfUp per channel.
uint32_t PackUnorm(F4 x, UnormRounding r) {
    static_assert(std::endian::native == std::endian::little);
    if (r == UnormRounding::HalfEven) {
        using B16 = uint8_t __attribute__((vector_size(16)));
        const B16 bytes = reinterpret_cast<B16>(UnormRne4(x));
        const B16 low4 =
            __builtin_shufflevector(bytes, bytes, 0, 4, 8, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
        uint32_t packed;
        std::memcpy(&packed, &low4, sizeof packed);
        return packed;
    }
    uint32_t packed = 0;
    for (int c = 0; c < 4; ++c) packed |= uint32_t{UnormFromFloatHalfUp(x[c])} << (8 * c);
    return packed;
}

using LaneColours = std::array<std::array<RgbaF, kLanes>, kMaxUnits>;

// Writes a fully covered lane group of an unblended pass into an 8-bit target with RNE: the
// fragment colours of each pixel row's four lanes channel-major (a 4x4 transpose of their
// texture colours), converted together and stored as one 16-byte row: the same operations per
// channel as ShadeGroup's per-lane loop (the sky quad of the raster benchmark 4.2 -> 3.5 ms).
void StoreFullGroup8(const FragmentTarget& tg, const Pass& pass, const LaneAttribs& qa, int co,
                     const LaneColours& tex, int gx, int gy) {
    constexpr int kRowLanes[2][4] = {{0, 1, 4, 5}, {2, 3, 6, 7}};  // x = gx .. gx + 3
    auto channels = [](const std::array<RgbaF, kLanes>& t, const int* lanes, F4* ch) {
        const F4 a = ToF4(t[lanes[0]]), b = ToF4(t[lanes[1]]);
        const F4 c = ToF4(t[lanes[2]]), d = ToF4(t[lanes[3]]);
        const F4 ab0 = __builtin_shufflevector(a, b, 0, 4, 1, 5);  // a0 b0 a1 b1
        const F4 ab1 = __builtin_shufflevector(a, b, 2, 6, 3, 7);  // a2 b2 a3 b3
        const F4 cd0 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
        const F4 cd1 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
        ch[0] = __builtin_shufflevector(ab0, cd0, 0, 1, 4, 5);
        ch[1] = __builtin_shufflevector(ab0, cd0, 2, 3, 6, 7);
        ch[2] = __builtin_shufflevector(ab1, cd1, 0, 1, 4, 5);
        ch[3] = __builtin_shufflevector(ab1, cd1, 2, 3, 6, 7);
    };
    for (int row = 0; row < 2; ++row) {
        F4 t[4] = {}, t1[4];  // texture(u0) (* texture(u1)) per channel
        if (pass.numUnits >= 1) channels(tex[0], kRowLanes[row], t);
        if (pass.numUnits == 2) {
            channels(tex[1], kRowLanes[row], t1);
            for (int c = 0; c < 4; ++c) t[c] = t[c] * t1[c];
        }
        using U4 = uint32_t __attribute__((vector_size(16)));
        U4 packed = {0, 0, 0, 0};
        for (int c = 0; c < 4; ++c) {
            F4 lo, hi;
            std::memcpy(&lo, &qa.a[co + c][0], sizeof lo);
            std::memcpy(&hi, &qa.a[co + c][4], sizeof hi);
            const F4 col = row == 0 ? __builtin_shufflevector(lo, hi, 0, 1, 4, 5)
                                    : __builtin_shufflevector(lo, hi, 2, 3, 6, 7);
            const F4 v = pass.numUnits == 0 ? col : t[c] * col;  // left to right
            packed |= reinterpret_cast<U4>(UnormRne4(v)) << (8 * c);
        }
        std::memcpy(&tg.image8->rgba[4 * tg.Index(gx, gy + row)], &packed, sizeof packed);
    }
}

// Shades the covered lanes of one 4x2 group of one triangle with the interpolated attributes
// `qa` and writes them. `footprints` (one per unit) carry filter footprints from draw to draw.
void ShadeGroup(const FragmentTarget& tg, const Pass& pass, const LaneAttribs& qa, int gx, int gy,
                unsigned mask, std::array<FastFootprints, kMaxUnits>* footprints) {
    const Frame& frame = tg.frame->frame();
    const bool wantTaps = tg.rows != nullptr;

    // Texture units: the lanes of `mask` are written, and only they are read below (zeroing the
    // whole array, a rep stos per lane group, cost 4 % of the raster benchmark's frame).
    LaneColours tex;
    std::array<PixelTaps, kLanes> taps;  // matrix mode only (set up below)
    if (wantTaps) taps.fill(PixelTaps{});
    for (int u = 0; u < pass.numUnits; ++u) {
        LaneCoords lc;
        for (int l = 0; l < kLanes; ++l)
            for (int k = 0; k < 3; ++k) lc.c[l][k] = qa.a[3 * u + k][l];
        isa::SampleLanes(*tg.frame, pass.texture[u], tg.options, lc, &tex[u],
                         wantTaps && u == 0 ? &taps : nullptr, mask,
                         &(*footprints)[static_cast<size_t>(u)]);
    }

    const int co = PassColourAttrib(pass);
    const bool linear = tg.options.profile == Profile::Linear;
    const bool floatTarget = linear || frame.colorFormat == ColorFormat::Rgba32F;
    // The renderers' float blends inline (BlendFloatLlvmpipe's operations): replace, which does
    // not read the buffer, and premultiplied over, src + dst * (1 - src.a).
    const BlendState& b = pass.blend;
    const bool replace = !b.enabled;
    const bool over = b.enabled && b.srcRgb == BlendFactor::One && b.srcAlpha == BlendFactor::One &&
                      b.dstRgb == BlendFactor::OneMinusSrcAlpha &&
                      b.dstAlpha == BlendFactor::OneMinusSrcAlpha &&
                      b.eqRgb == BlendEquation::Add && b.eqAlpha == BlendEquation::Add;
    if (mask == 0xFFu && !wantTaps && !floatTarget && replace &&
        tg.options.rounding == UnormRounding::HalfEven) {
        StoreFullGroup8(tg, pass, qa, co, tex, gx, gy);
        return;
    }
    for (unsigned set = mask; set; set &= set - 1) {  // the set lanes, no branch per lane
        const int l = std::countr_zero(set);
        const int x = gx + kLaneDx[l], y = gy + kLaneDy[l];
        const size_t pixel = tg.Index(x, y);

        // Fragment colour: texture(u0) * texture(u1) * colour, left to right; `m` is what
        // multiplies unit 0's sample.
        const F4 col = {qa.a[co][l], qa.a[co + 1][l], qa.a[co + 2][l], qa.a[co + 3][l]};
        F4 v = col, m = col;
        if (pass.numUnits == 1) v = ToF4(tex[0][l]) * col;
        if (pass.numUnits == 2) {
            const F4 t1 = ToF4(tex[1][l]);
            v = (ToF4(tex[0][l]) * t1) * col;
            m = t1 * col;
        }
        const RgbaF src = FromF4(v);

        if (wantTaps) {
            const PixelTaps& lane = taps[static_cast<size_t>(l)];
            AddFragmentRows(
                tg.matrix, tg.rows, pixel, y, pass, src, [&](MatrixRows::Appender& row) {
                    const RgbaF mod = FromF4(m);
                    for (int k = 0; k < lane.Count(); ++k)
                        row.Add(lane.At(k).texel, static_cast<double>(lane.At(k).weight), mod);
                });
        }
        if (floatTarget) {  // unclamped
            float* d = &tg.imageF->rgba[4 * pixel];
            if (replace) {
                std::memcpy(d, src.data(), sizeof src);
                continue;
            }
            if (over && !linear) {
                const float keep = 1.0f - src[3];
                for (int c = 0; c < 4; ++c) d[c] = src[c] + d[c] * keep;
                continue;
            }
            const RgbaF dst{d[0], d[1], d[2], d[3]};
            const RgbaF out =
                linear ? BlendF(pass.blend, src, dst) : BlendFloatLlvmpipe(pass.blend, src, dst);
            for (int c = 0; c < 4; ++c) d[c] = out[c];
        } else {
            uint8_t* d = &tg.image8->rgba[4 * pixel];
            const uint32_t packed = PackUnorm(v, tg.options.rounding);
            if (!pass.blend.enabled) {
                // One 32-bit store from registers (byte stores read back as a word stall).
                std::memcpy(d, &packed, 4);
                continue;
            }
            const Rgba8 s8{static_cast<uint8_t>(packed), static_cast<uint8_t>(packed >> 8),
                           static_cast<uint8_t>(packed >> 16), static_cast<uint8_t>(packed >> 24)};
            const Rgba8 out = Blend8(pass.blend, s8, {d[0], d[1], d[2], d[3]});
            for (int c = 0; c < 4; ++c) d[c] = out[c];
        }
    }
}

// The depth tests done in one lane group, by depth buffer (the owner's: FragmentTarget::
// depthTwin) and pass: a target drawn with a twin takes the test its owner's buffer gave (the
// first draw of the pair tests, whichever it is), as its own buffer would have given it.
struct LaneTests {
    struct Entry {
        const FragmentTarget* owner;
        size_t pass;
        unsigned passed;
    };
    std::vector<Entry> done;  // capacity: one entry per draw (reserved by the caller)

    unsigned Test(const PassDraw& d, const Plane& zPlane, int gx, int gy, unsigned mask,
                  LaneDepth* depth) {
        const FragmentTarget& owner = d.first->depthTwin ? *d.first->depthTwin : *d.first;
        const auto pass = static_cast<size_t>(d.second - d.first->frame->frame().passes.data());
        for (const Entry& e : done)
            if (e.owner == &owner && e.pass == pass) return e.passed;
        const unsigned passed =
            DepthTestLanes(owner, *d.second->depthTest, zPlane, gx, gy, mask, depth);
        done.push_back({&owner, pass, passed});
        return passed;
    }
};

// Draws the covered lanes `mask` of lane group (gx, gy) of triangle i into every draw: each
// draw's depth test (fragment depth computed once; once per depth buffer and pass, LaneTests),
// then interpolation (once per variant, only if some draw has lanes left) and shading. `qa`,
// `tests`, `footprints`: the caller's scratch.
void DrawGroup(const std::vector<std::vector<PassDraw>>& variants, const SetupChunk& triangles,
               size_t i, int gx, int gy, unsigned mask, LaneAttribs* qa, LaneTests* tests,
               std::array<FastFootprints, kMaxUnits>* footprints) {
    LaneDepth depth;
    tests->done.clear();
    for (size_t k = 0; k < variants.size(); ++k) {
        bool interpolated = false;
        for (const PassDraw& d : variants[k]) {
            unsigned live = mask;
            if ((d.first->depth || d.first->depthTwin) && d.second->depthTest) {
                live = tests->Test(d, triangles[0][i].z, gx, gy, mask, &depth);
                if (!live) continue;
            }
            if (!interpolated) {
                InterpolateLanes(triangles[k][i], gx, gy, qa);
                for (FastFootprints& f : *footprints) f.shape = nullptr;  // new coordinates
                interpolated = true;
            }
            ShadeGroup(*d.first, *d.second, *qa, gx, gy, live, footprints);
        }
    }
}

// Draws the 4x2 lane groups of triangle i that lie in the bands owned by `worker`, into every
// draw of every variant (variants[k] draws triangles[k][i]: the same coverage and depth, its own
// attributes; each draw tests its own depth buffer, samples its own textures and writes its own
// target). A group is shaded when at least one of its pixels is covered and passes the draw's
// depth test (llvmpipe skips empty 8-lane vectors).
// `footprints`: the caller's scratch (reset per lane group and variant).
void DrawTriangle(const std::vector<std::vector<PassDraw>>& variants, const SetupChunk& triangles,
                  size_t i, int worker, int workers, LaneTests* tests,
                  std::array<FastFootprints, kMaxUnits>* footprints) {
    const TriangleSetup& t = triangles[0][i];
    // A triangle in fewer bands than there are workers may lie in none of this worker's.
    const int band0 = (t.y0 & ~1) / 2 / kBandQuadRows, band1 = t.y1 / 2 / kBandQuadRows;
    if (band1 - band0 + 1 < workers) {
        bool mine = false;
        for (int b = band0; b <= band1; ++b) mine |= b % workers == worker;
        if (!mine) return;
    }
    // Edge values per lane relative to the group origin, so a group costs 8 adds per edge, and
    // their least and greatest: a group whose origin value plus the least is positive lies inside
    // the edge, one whose value plus the greatest is not positive lies outside (the edge function
    // is linear; the sums cannot wrap while |origin value| < 2^62 and every offset < 2^61).
    // Lane l's offset is sx * dx + sy * dy (dx 0..3, dy 0..1): by adds, and its extremes at the
    // group's corners.
    int64_t leastOffset[3], greatestOffset[3];
    U64x4 offset[3][2];  // the lanes' offsets as two vectors of four lanes
    constexpr int64_t kNoWrap = int64_t{1} << 61;
    bool smallOffsets = true;
    for (int e = 0; e < 3; ++e) {
        const int64_t sx = -t.edge[e].dcdx, sy = t.edge[e].dcdy;
        const int64_t x2 = sx + sx, x3 = x2 + sx;
        const int64_t laneOffset[kLanes] = {0, sx, sy, sx + sy, x2, x3, x2 + sy, x3 + sy};
        std::memcpy(offset[e], laneOffset, sizeof offset[e]);
        leastOffset[e] = std::min<int64_t>(0, x3) + std::min<int64_t>(0, sy);
        greatestOffset[e] = std::max<int64_t>(0, x3) + std::max<int64_t>(0, sy);
        smallOffsets &= leastOffset[e] > -kNoWrap && greatestOffset[e] < kNoWrap;
    }
    const int gy0 = t.y0 & ~1, gx0 = t.x0 & ~3;
    LaneAttribs qa;
    for (int gy = gy0; gy <= t.y1; gy += 2) {
        if ((gy / 2 / kBandQuadRows) % workers != worker) continue;
        unsigned rowMask = 0;  // lanes whose row lies inside the bounding box
        for (int l = 0; l < kLanes; ++l) {
            const int y = gy + kLaneDy[l];
            rowMask |= static_cast<unsigned>(y >= t.y0 && y <= t.y1) << l;
        }
        // Edge values at the row's first group origin, then stepped 4 columns a group (wrapping
        // sums: the values c - dcdx * gx + dcdy * gy).
        int64_t base[3], step[3];
        for (int e = 0; e < 3; ++e) {
            base[e] = WrapAdd64(WrapSub64(t.edge[e].c, t.edge[e].dcdx * gx0), t.edge[e].dcdy * gy);
            step[e] = WrapMul64(t.edge[e].dcdx, -4);
        }
        for (int gx = gx0; gx <= t.x1; gx += 4) {
            // Columns gx + d inside the bounding box: d >= x0 - gx (at most 3, as gx >= gx0)
            // and d <= x1 - gx (at least 0), then their lanes.
            const int lo = t.x0 - gx, hi = t.x1 - gx;
            unsigned columns = 0xFu;
            if (lo > 0) columns &= 0xFu << lo;
            if (hi < 3) columns &= 0xFu >> (3 - hi);
            unsigned mask = rowMask & kColumnLanes[columns & 0xFu];
            I64x4 outside[2] = {};  // lanes outside some edge tested lane by lane
            for (int e = 0; e < 3 && mask; ++e) {
                if (smallOffsets && base[e] > -2 * kNoWrap && base[e] < 2 * kNoWrap) {
                    if (base[e] + leastOffset[e] > 0) continue;  // every lane inside
                    if (base[e] + greatestOffset[e] <= 0) {      // every lane outside
                        mask = 0;
                        break;
                    }
                }
                // Lane l is outside when WrapAdd64(base, laneOffset[e][l]) <= 0.
                const auto b = static_cast<uint64_t>(base[e]);
                const U64x4 bv = {b, b, b, b};
                for (int h = 0; h < 2; ++h)
                    outside[h] |= reinterpret_cast<I64x4>(bv + offset[e][h]) <= 0;
            }
            mask &= ~LaneBits(outside);
            if (mask) DrawGroup(variants, triangles, i, gx, gy, mask, &qa, tests, footprints);
            for (int e = 0; e < 3; ++e) base[e] = WrapAdd64(base[e], step[e]);  // next group
        }
    }
}

void DrawBands(const std::vector<std::vector<PassDraw>>& variants, const SetupChunk& triangles,
               int worker, int workers) {
    std::array<FastFootprints, kMaxUnits> footprints;
    LaneTests tests;
    size_t draws = 0;
    for (const std::vector<PassDraw>& v : variants) draws += v.size();
    tests.done.reserve(draws);
    for (size_t i = 0; i < triangles[0].size(); ++i)
        DrawTriangle(variants, triangles, i, worker, workers, &tests, &footprints);
}

}  // namespace
}  // namespace pem::raster::isa
