// SPDX-License-Identifier: MIT
// aniso_impl.h — implementation of aniso.h and llvmpipe's anisotropic sampling of eight lanes
// (lp_bld_sample_soa.c lp_build_sample_aniso, lp_bld_sample.c lp_build_pmin and
// lp_build_lod_selector), compiled into each fragment-stage variant (fragment.h). Every float
// operation is the one llvmpipe's generated code performs, in its order: no operation is fused
// (gallivm emits separate multiplies and adds here), divisions are true divisions.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>
#include <vector>

#include "raster/aniso.h"
#include "raster/lod_impl.h"
#include "raster/numeric.h"
#include "raster/sample_fast_impl.h"
#include "raster/sample_float_impl.h"
#include "raster/sampler_paths.h"

namespace pem::raster::isa {
namespace {

float AnisoRhoSquared(const std::array<float, 4>& d, int maxAniso) {
    // Step 1: squared lengths of the x and y derivative vectors, their max and min (maxps, minps).
    const float px2 = d[0] * d[0] + d[2] * d[2];
    const float py2 = d[1] * d[1] + d[3] * d[3];
    const float pmax2 = px2 > py2 ? px2 : py2;
    const float pmin2 = px2 < py2 ? px2 : py2;
    // Step 2: the clamp as lp_build_pmin writes it (compares pmin2 with pmin2 * max_aniso^2).
    const float m = static_cast<float>(maxAniso);
    const float m2 = m * m;
    const float temp = pmin2 * m2;
    return pmin2 > temp ? pmax2 / m2 : pmin2;
}

AnisoEllipse AnisoEllipseOf(const std::array<float, 4>& d) {
    const float ux = d[0], uy = d[1], vx = d[2], vy = d[3];
    // Step 1: the implicit ellipse A x^2 + B x y + C y^2 = F (each sum left to right).
    const float a = (vx * vx + vy * vy) + 1.0f;
    const float b = (ux * vx + uy * vy) * -2.0f;
    const float c = (ux * ux + uy * uy) + 1.0f;
    const float f = a * c - (b * b) / 4.0f;
    // Step 2: bounding box half extents.
    const float det = (0.0f - b * b) + (a * c) * 4.0f;
    AnisoEllipse e;
    e.boxU = (2.0f / det) * std::sqrt((det * c) * f);
    e.boxV = (2.0f / det) * std::sqrt((a * det) * f);
    // Step 3: scaled so that the edge is at the table's last entry.
    const float formScale = static_cast<float>(kAnisoTableSize - 1) / f;
    e.a = a * formScale;
    e.b = b * formScale;
    e.c = c * formScale;
    e.ddq = e.a + e.a;
    return e;
}

// Whether q, stepped n more times by q += dq, dq += ddq in float (all >= 0), stays below 2^31:
// the exact sum times a bound on the growth of n + n rounding errors of 2^-24 each.
inline bool StaysBelowInt32(float q, float dq, float ddq, int64_t n) {
    if (n > (int64_t{1} << 20)) return false;
    const double nd = static_cast<double>(n);
    const double exact = static_cast<double>(q) + nd * static_cast<double>(dq) +
                         0.5 * nd * (nd + 1.0) * static_cast<double>(ddq);
    return exact * 1.25 < 2147483648.0;  // (1 + 2^-24)^(2n) < 1.14 for n <= 2^20
}

// Whether a probe with this q weighs: trunc(q) <= 1023, or cvttps2dq's INT32_MIN (q >= 2^31,
// q <= -2^31, NaN); and its weight, table[max(trunc(q), 0)].
inline bool Weighs(float q) {
    return !(q >= 1024.0f && q < 2147483648.0f);
}
inline float WeightOf(float q) {
    return kAnisoWeights[static_cast<size_t>(std::max(TruncI32(q), 0))];
}

// q at the first column of row v, and its first difference (lp_build_sample_aniso's V loop).
struct RowStart {
    float q = 0, dq = 0;
};

inline RowStart RowStartOf(const AnisoEllipse& e, float uStart, float dqBase, float qBase,
                           float texV, int64_t v) {
    const float vRel = static_cast<float>(static_cast<int32_t>(v)) - texV;
    return {(e.c * vRel + e.b * uStart) * vRel + qBase, vRel * e.b + dqBase};
}

// Whether a row whose next q is `q` is done: q >= 1024 no longer decreases (dq >= 0, ddq >= 0:
// float addition is monotonic) and cannot reach 2^31, where it would weigh 1 again, within
// the n columns left. llvmpipe's loop runs on over them without effect.
inline bool RowDone(float q, float dq, float ddq, int64_t n) {
    return !Weighs(q) && dq >= 0.0f && ddq >= 0.0f && StaysBelowInt32(q, dq, ddq, n);
}

constexpr int kRowBlock = 8;      // rows of a wide box stepped together
constexpr int64_t kWideBox = 32;  // columns from which a box is stepped in row blocks
constexpr int kChunk = 32;        // columns stepped between two looks at the rows' weights

// The probes of up to eight rows of a wide box, stepped in lockstep: the rows' q chains are
// independent, so each row gets exactly its own values (and the chains overlap in the CPU).
// Row r's probes go to hits[r] as (column, weight), in column order.
inline void RowBlockProbes(const AnisoEllipse& e, const RowStart* starts, int rows, int32_t u0,
                           int64_t width, std::vector<std::pair<int32_t, float>>* hits) {
    alignas(32) float q[kRowBlock], dq[kRowBlock];
    for (int r = 0; r < kRowBlock; ++r) {
        q[r] = r < rows ? starts[r].q : 1024.0f;
        dq[r] = r < rows ? starts[r].dq : 0.0f;
    }
    alignas(32) uint32_t live[kRowBlock];  // 1 for the rows still stepped
    for (int r = 0; r < kRowBlock; ++r) live[r] = r < rows ? 1u : 0u;
    alignas(32) float chunk[kChunk][kRowBlock];  // q of every row over the chunk's columns
    int remaining = rows;
    for (int64_t k = 0; k < width && remaining > 0; k += kChunk) {
        // Step 1: step every row over the chunk's columns (pure float adds, vectorised).
        const int n = static_cast<int>(std::min<int64_t>(kChunk, width - k));
        for (int i = 0; i < n; ++i) {
            for (int r = 0; r < kRowBlock; ++r) chunk[i][r] = q[r];
            for (int r = 0; r < kRowBlock; ++r) q[r] = q[r] + dq[r];
            for (int r = 0; r < kRowBlock; ++r) dq[r] = dq[r] + e.ddq;
        }
        // Step 2: any weight in the chunk? (On the bits: q in [1024, 2^31) is the one range of
        // bit patterns without weight.) Then the probes, row by row.
        uint32_t any = 0;
        for (int i = 0; i < n; ++i)
            for (int r = 0; r < kRowBlock; ++r)
                any |= static_cast<uint32_t>(FloatBits(chunk[i][r]) - 0x44800000u >= 0x0A800000u) &
                       live[r];
        if (any)
            for (int r = 0; r < rows; ++r)
                for (int i = 0; live[r] && i < n; ++i)
                    if (Weighs(chunk[i][r]))
                        hits[r].push_back(
                            {static_cast<int32_t>(u0 + k + i), WeightOf(chunk[i][r])});
        // Step 3: retire the rows past their ellipse.
        for (int r = 0; r < rows; ++r)
            if (live[r] && RowDone(q[r], dq[r], e.ddq, width - k - n)) {
                live[r] = 0;
                --remaining;
            }
    }
}

// Calls fn(u, v, weight) for every probe of the box around (texU, texV) with a non-zero weight,
// rows v outer, columns u inner, q stepped along each row exactly as llvmpipe steps it. Returns
// false (and calls nothing) when the box holds more than maxProbes texels.
template <class Fn>
bool ForEachProbe(const AnisoEllipse& e, float texU, float texV, int64_t maxProbes, Fn&& fn) {
    // Step 1: the box (cvttps2dq of floor/ceil: NaN and out-of-range bounds become INT32_MIN).
    const int32_t u0 = TruncI32(std::floor(texU - e.boxU));
    const int32_t u1 = TruncI32(std::ceil(texU + e.boxU));
    const int32_t v0 = TruncI32(std::floor(texV - e.boxV));
    const int32_t v1 = TruncI32(std::ceil(texV + e.boxV));
    if (u0 > u1 || v0 > v1) return true;  // no texel passes the loop masks
    const int64_t width = int64_t{u1} - u0 + 1;
    if (width * (int64_t{v1} - v0 + 1) > maxProbes) return false;
    // Step 2: the quadratic form at the row start and its first difference.
    const float uStart = static_cast<float>(u0) - texU;
    const float dqBase = ((uStart + uStart) + 1.0f) * e.a;
    const float qBase = (uStart * uStart) * e.a;
    // Step 3, wide boxes: blocks of rows stepped together, then reported row by row.
    if (width > kWideBox) {
        std::vector<std::pair<int32_t, float>> hits[kRowBlock];
        for (int64_t v = v0; v <= v1; v += kRowBlock) {
            const int rows = static_cast<int>(std::min<int64_t>(kRowBlock, int64_t{v1} - v + 1));
            RowStart starts[kRowBlock];
            for (int r = 0; r < rows; ++r)
                starts[r] = RowStartOf(e, uStart, dqBase, qBase, texV, v + r);
            for (auto& h : hits) h.clear();
            RowBlockProbes(e, starts, rows, u0, width, hits);
            for (int r = 0; r < rows; ++r)
                for (const auto& [u, w] : hits[r]) fn(u, static_cast<int32_t>(v + r), w);
        }
        return true;
    }
    // Step 3, narrow boxes: row by row.
    for (int64_t v = v0; v <= v1; ++v) {
        const RowStart start = RowStartOf(e, uStart, dqBase, qBase, texV, v);
        float q = start.q, dq = start.dq;
        for (int64_t u = u0; u <= u1; ++u) {
            if (Weighs(q))
                fn(static_cast<int32_t>(u), static_cast<int32_t>(v), WeightOf(q));
            else if (RowDone(q, dq, e.ddq, u1 - u))
                break;
            q = q + dq;
            dq = dq + e.ddq;
        }
    }
    return true;
}

std::vector<AnisoProbe> AnisoProbesOf(const AnisoEllipse& e, float texU, float texV,
                                      int64_t maxProbes) {
    std::vector<AnisoProbe> out;
    ForEachProbe(e, texU, texV, maxProbes, [&](int32_t u, int32_t v, float w) {
        out.push_back({u, v, w});
    });
    return out;
}

// Coarse differences of a quad (top-left pixel to its right and lower neighbours), as
// lp_build_packed_ddx_ddy_twocoord: (ds/dx, ds/dy, dt/dx, dt/dy).
std::array<float, 4> QuadDerivatives(const LaneSample& ls, int q) {
    return {ls.s[q + 1] - ls.s[q], ls.s[q + 2] - ls.s[q], ls.t[q + 1] - ls.t[q],
            ls.t[q + 2] - ls.t[q]};
}

// The MIP level of each quad. The LOD exists only with a MIP filter or min != mag
// (lp_build_sample_common); lambda from the minor axis, lod_ipart = trunc(lambda), clamped to
// the levels (lp_build_nearest_mip_level). Without a MIP filter llvmpipe keeps one level for
// the whole block: its first quad's.
std::array<int, 2> AnisoLevels(const Texture& tex, const PipeLodState& st, const LaneSample& ls,
                               bool exactLog2) {
    const SamplerState& s = tex.sampler;
    std::array<int, 2> level{0, 0};
    if (s.mipFilter == MipFilter::None && s.minFilter == s.magFilter) return level;
    const float w0 = static_cast<float>(tex.width), h0 = static_cast<float>(tex.height);
    for (int q = 0; q < 2; ++q) {
        const std::array<float, 4> diff = QuadDerivatives(ls, 4 * q);
        const std::array<float, 4> d{diff[0] * w0, diff[1] * w0, diff[2] * h0, diff[3] * h0};
        const float rho2 = isa::AnisoRhoSquared(d, st.maxAnisotropy);
        const float lambda = isa::LambdaFromRhoSquared(rho2, st, exactLog2);
        level[static_cast<size_t>(q)] = std::clamp(TruncI32(lambda), 0, tex.NumLevels() - 1);
    }
    if (s.mipFilter == MipFilter::None) level[1] = level[0];
    return level;
}

// One quad's share of lp_build_sample_aniso: the ellipse on its level and the level sizes.
struct AnisoQuad {
    int level = 0;
    AnisoEllipse ellipse;
    float width = 0, height = 0;     // level-0 size * 2^-level (may drop below 1)
    float invDimW = 0, invDimH = 0;  // 1 / the level size the probe coordinates divide by
    int levelW = 1, levelH = 1;      // the level's texel size
};

AnisoQuad AnisoQuadOf(const Texture& tex, const LaneSample& ls, int q, int level, int dimLevel) {
    AnisoQuad aq;
    aq.level = level;
    // Step 1: derivatives in texels of the level: (difference * level-0 size) * 2^-level.
    const float scaling = 1.0f / static_cast<float>(1 << level);
    const float w0 = static_cast<float>(tex.width), h0 = static_cast<float>(tex.height);
    const std::array<float, 4> diff = QuadDerivatives(ls, 4 * q);
    const std::array<float, 4> d{(diff[0] * w0) * scaling, (diff[1] * w0) * scaling,
                                 (diff[2] * h0) * scaling, (diff[3] * h0) * scaling};
    aq.ellipse = isa::AnisoEllipseOf(d);
    // Step 2: sizes. Dividing by a power of two equals multiplying by its exact reciprocal.
    aq.width = w0 * scaling;
    aq.height = h0 * scaling;
    aq.invDimW = 1.0f / static_cast<float>(tex.LevelWidth(dimLevel));
    aq.invDimH = 1.0f / static_cast<float>(tex.LevelHeight(dimLevel));
    aq.levelW = tex.LevelWidth(level);
    aq.levelH = tex.LevelHeight(level);
    return aq;
}

// Probe boxes beyond this many texels per pixel take the bilinear fallback (not modelled:
// llvmpipe would spend tens of seconds on such a pixel, we a few).
constexpr int64_t kMaxAnisoProbes = int64_t{1} << 30;

// Sums the weights of equal texels (sorted by texel).
inline void MergeTapSums(std::vector<std::pair<uint32_t, double>>* sums) {
    std::sort(sums->begin(), sums->end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    size_t n = 0;
    for (size_t k = 0; k < sums->size(); ++k) {
        if (n > 0 && (*sums)[n - 1].first == (*sums)[k].first)
            (*sums)[n - 1].second += (*sums)[k].second;
        else
            (*sums)[n++] = (*sums)[k];
    }
    sums->resize(n);
}

// The weighted average of one lane; false when its total weight is 0 (or the box too large).
// Acc: float as llvmpipe sums (llvmpipe profile), double for the linear profile, whose frame
// must equal A x to float rounding however many texels a footprint holds. Taps: one per
// texel, weight (sum of its probes' weights) / (total weight); the sums are kept in double
// and merged as they grow (a footprint may visit a wrapped texel many times).
template <class Acc>
bool FilterAnisoLane(const Texture& tex, const LevelView& lv, const AnisoQuad& aq, float s, float t,
                     int face, RgbaF* out, PixelTaps* taps, std::vector<Tap>* overflow) {
    const SamplerState& smp = tex.sampler;
    const bool cube = tex.kind == TextureKind::Cube;
    const Wrap ws = cube ? Wrap::ClampToEdge : smp.wrapS;
    const Wrap wt = cube ? Wrap::ClampToEdge : smp.wrapT;
    const float texU = s * aq.width + -0.5f, texV = t * aq.height + -0.5f;
    std::array<Acc, 4> acc{};
    Acc den = 0;
    std::vector<std::pair<uint32_t, double>> tapSums;
    size_t mergeAt = 4096;
    const bool inRange =
        ForEachProbe(aq.ellipse, texU, texV, kMaxAnisoProbes, [&](int32_t u, int32_t v, float w) {
            // Nearest texel at (u / width, v / height) of the level, wrapped.
            const float su = static_cast<float>(u) * aq.invDimW;
            const float tv = static_cast<float>(v) * aq.invDimH;
            const int i = WrapNearest(su, aq.levelW, ws), j = WrapNearest(tv, aq.levelH, wt);
            const int32_t texel = TexelAt(face, i, j, aq.levelW, aq.levelH);
            const float* p = Fetch(lv, texel);
            for (int c = 0; c < 4; ++c)
                acc[c] = acc[c] + static_cast<Acc>(p[c]) * static_cast<Acc>(w);
            den = den + static_cast<Acc>(w);
            if (!taps) return;
            tapSums.push_back({TexelOf(lv, texel), static_cast<double>(w)});
            if (tapSums.size() >= mergeAt) {
                MergeTapSums(&tapSums);
                mergeAt = std::max<size_t>(4096, 2 * tapSums.size());
            }
        });
    if (!inRange || den == 0) return false;
    for (int c = 0; c < 4; ++c) (*out)[c] = static_cast<float>(acc[c] / den);
    if (taps) {
        MergeTapSums(&tapSums);
        for (const auto& [texel, w] : tapSums)
            taps->Append(texel, static_cast<float>(w / static_cast<double>(den)), overflow);
    }
    return true;
}

// Per thread and lane: the taps of an anisotropic footprint beyond PixelTaps' inline ones.
std::array<std::vector<Tap>, kLanes>& TapOverflow() {
    thread_local std::array<std::vector<Tap>, kLanes> overflow;
    return overflow;
}

// Anisotropic sampling of eight lanes (sampler.h's contract). Kept out of line: inlined into
// SampleLanes it would slow the other paths down.
[[gnu::noinline]] void SampleAniso(const PreparedFrame& frame, int textureIndex,
                                   const RenderOptions& options, const LaneCoords& coords,
                                   std::array<RgbaF, kLanes>* colour,
                                   std::array<PixelTaps, kLanes>* taps, unsigned live) {
    const PreparedTexture& pt = frame.texture(textureIndex);
    const Texture& tex = *pt.source;
    const SamplerState& s = tex.sampler;
    const bool cube = tex.kind == TextureKind::Cube;
    const bool exactTexels = options.profile == Profile::Linear;

    // Step 1: coordinates on the texture (cubes: face and projection as lp_build_cube_lookup,
    // through 1/ma when llvmpipe also computes derivatives).
    LaneSample ls;
    ls.texture = textureIndex;
    if (cube) {
        const bool lodUsed = s.mipFilter != MipFilter::None || s.minFilter != s.magFilter;
        alignas(32) float rho[kLanes], s0[kLanes], t0[kLanes];
        alignas(32) int32_t face[kLanes];
        CubeLanes(coords, lodUsed && !pt.lod.minMaxEqual, static_cast<float>(tex.width), face, s0,
                  t0, rho);
        for (int l = 0; l < kLanes; ++l) {
            ls.face[l] = face[l];
            ls.s[l] = s0[l];
            ls.t[l] = t0[l];
        }
    } else {
        for (int l = 0; l < kLanes; ++l) {
            ls.s[l] = coords.c[l][0];
            ls.t[l] = coords.c[l][1];
        }
    }

    // Step 2: levels, and the level whose size the probe coordinates divide by: with one level
    // per pixel (cubes with a MIP filter) llvmpipe reads the second quad's from lane 1, i.e. the
    // first quad's level.
    const std::array<int, 2> level =
        AnisoLevels(tex, pt.lod, ls, options.cubeLod == CubeLod::Exact);
    const bool perPixel = cube && s.mipFilter != MipFilter::None;
    const std::array<int, 2> dimLevel{level[0], perPixel ? level[0] : level[1]};

    // Step 3: the weighted average of each live lane.
    const auto& levels = exactTexels ? pt.levelsExact : pt.levelsF;
    unsigned fallback = 0;
    for (int q = 0; q < 2; ++q) {
        if (!((live >> (4 * q)) & 0xFu)) continue;
        const AnisoQuad aq = AnisoQuadOf(tex, ls, q, level[static_cast<size_t>(q)],
                                         dimLevel[static_cast<size_t>(q)]);
        const LevelView lv{levels[static_cast<size_t>(aq.level)].data(),
                           frame.indexer().LevelBase(textureIndex, aq.level)};
        for (int l = 4 * q; l < 4 * q + 4; ++l) {
            if (!(live & (1u << l))) continue;
            PixelTaps* tp = taps ? &(*taps)[l] : nullptr;
            std::vector<Tap>* spill = taps ? &TapOverflow()[static_cast<size_t>(l)] : nullptr;
            RgbaF* out = &(*colour)[l];
            const bool ok = exactTexels ? FilterAnisoLane<double>(tex, lv, aq, ls.s[l], ls.t[l],
                                                                  ls.face[l], out, tp, spill)
                                        : FilterAnisoLane<float>(tex, lv, aq, ls.s[l], ls.t[l],
                                                                 ls.face[l], out, tp, spill);
            if (!ok) fallback |= 1u << l;
        }
    }

    // Step 4: lanes without weight: bilinear on the same level (lp_build_sample_image_linear;
    // its corner decision spans all eight lanes).
    if (!fallback) return;
    SamplerState bilinear = s;
    bilinear.minFilter = bilinear.magFilter = Filter::Linear;
    bilinear.mipFilter = MipFilter::None;
    ls.live = fallback;
    for (int l = 0; l < kLanes; ++l) {
        const int lv = level[static_cast<size_t>(l / 4)];
        ls.lod[l] = LodResult{false, lv, lv, 0.0f};
    }
    FilterFloat(frame, tex, bilinear, pt, exactTexels, ls, colour, taps);
}

}  // namespace
}  // namespace pem::raster::isa
