// SPDX-License-Identifier: MIT
// aniso.h — GL_TEXTURE_MAX_ANISOTROPY as Mesa 22.3.6 llvmpipe implements it: an elliptical
// weighted average (Heckbert's EWA) of nearest texels of one MIP level, with Gaussian weights
// from a 1024-entry table (docs/raster-model.md §10 states each rule with its Mesa source).
//
//   SamplerState s;
//   s.maxAnisotropy = 16.0f;                          // glTexParameterf(..., MAX_ANISOTROPY, 16)
//   const bool on = PipeMaxAnisotropy(s.maxAnisotropy) > 1;   // llvmpipe's aniso path
//   // per 2x2 quad: derivatives of (s, t) in texels of the level sampled (see below)
//   const AnisoEllipse e = AnisoEllipseOf({dsdx, dsdy, dtdx, dtdy});
//   for (const AnisoProbe& p : AnisoProbesOf(e, texU, texV)) sum += p.weight * texel(p.u, p.v);
//   colour = sum / total weight;
//
// The rules, in short:
//  - On when the pipe's max_anisotropy > 1: the GL value clamped to 16 and truncated to an
//    integer, so 1.5 is off and 2.5 acts as 2. Every value >= 2 filters the same way: llvmpipe's
//    clamp of the minor axis by max_anisotropy compares the minor axis with itself and never
//    applies (AnisoRhoSquared keeps the comparison as written).
//  - The min/mag/mip filters then only decide whether a LOD is computed (a MIP filter, or
//    min != mag) and how many: one level for the whole 8-lane block without a MIP filter (its
//    first quad's), else one per quad. The level is trunc(lambda) clamped to the levels, lambda =
//    0.5 * FastLog2(rho^2) (+ bias, clamps) with rho^2 the *minor* axis: min over x, y of
//    (N ds)^2 + (N dt)^2, coarse quad differences of the (face) coordinates, level-0 size N.
//  - The ellipse (texels of that level): u = (ds/dx, ds/dy), v = (dt/dx, dt/dy);
//    A = |v|^2 + 1, B = -2 u.v, C = |u|^2 + 1, F = AC - B^2/4, scaled so that the edge is 1023;
//    its bounding box half-extents are (2/d) sqrt(d C F), (2/d) sqrt(A d F), d = 4AC - B^2.
//  - Every texel (u, v) of the box, rows v outer, columns u inner, q = A U^2 + B U V + C V^2
//    stepped incrementally along the row (U = u - texU, V = v - texV): weight table[trunc(q)]
//    for trunc(q) <= 1023 (negative q gives table[0], and so do NaN and q >= 2^31, through
//    cvttps2dq's INT32_MIN), else 0.
//  - Colour = (sum of weight * texel, float, in that order) / (sum of weights). Nearest texels:
//    coordinate u / level width, the sampler's wrap; cube faces clamp at their edges (no seams).
//  - All on llvmpipe's float ("SoA") path, whatever the wrap; a total weight of 0 (only for
//    coordinates near 2^31 texels) falls back to bilinear filtering of the same level.
// Not here: cube face selection (cube_lookup.h), the LOD's bias and clamps (lod.h), texel
// addressing and the bilinear fallback (sample_float_impl.h). Implemented, with the 8-lane
// sampling that uses it, in aniso_impl.h.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pem::raster {

// The pipe sampler's max_anisotropy for glTexParameterf(GL_TEXTURE_MAX_ANISOTROPY, v): Mesa
// clamps v to the driver's 16, keeps 0 for exactly 1, and stores it in a 5-bit unsigned field
// (main/texparam.c, p_state.h). Values below 1 are GL errors that leave the state alone: 1 here.
inline int PipeMaxAnisotropy(float v) {
    if (v < 1.0f) return 0;
    const float clamped = v < 16.0f ? v : 16.0f;  // MIN2(v, 16): NaN -> 16
    if (clamped == 1.0f) return 0;
    return static_cast<int>(clamped) & 31;
}

// The filter table (lp_bld_sample.c aniso_filter_table): entry i is exp(-2 i / 1023) as expf
// rounds it, printed with six decimals and read back as a float. Built at compile time with
// IEEE double arithmetic only (a Taylor series; no libm), so every build holds the same bits.
constexpr int kAnisoTableSize = 1024;

namespace aniso_detail {

constexpr double ExpOfNonNegative(double y) {  // e^y for 0 <= y <= 2, all terms positive
    double sum = 1.0, term = 1.0;
    for (int k = 1; k <= 40; ++k) {
        term = term * y / static_cast<double>(k);
        sum = sum + term;
    }
    return sum;
}

constexpr float TableEntry(int i) {
    // Step 1: expf(-2 * (i / 1023.0f)), correctly rounded (the double error is ~1e-16).
    const float r2 = static_cast<float>(i) / static_cast<float>(kAnisoTableSize - 1);
    const float x = -2.0f * r2;
    const float e = static_cast<float>(1.0 / ExpOfNonNegative(-static_cast<double>(x)));
    // Step 2: "%f" (six decimals, half to even on the exact value; e * 1e6 is exact in double).
    const double scaled = static_cast<double>(e) * 1e6;
    auto n = static_cast<int64_t>(scaled);
    const double frac = scaled - static_cast<double>(n);
    if (frac > 0.5 || (frac == 0.5 && (n & 1) != 0)) ++n;
    // Step 3: the C literal: decimal -> double -> float.
    return static_cast<float>(static_cast<double>(n) / 1e6);
}

constexpr std::array<float, kAnisoTableSize> MakeTable() {
    std::array<float, kAnisoTableSize> t{};
    for (int i = 0; i < kAnisoTableSize; ++i) t[static_cast<std::size_t>(i)] = TableEntry(i);
    return t;
}

}  // namespace aniso_detail

inline constexpr std::array<float, kAnisoTableSize> kAnisoWeights = aniso_detail::MakeTable();

// llvmpipe's rho^2 under anisotropy (lp_build_pmin): d = (ds/dx, ds/dy, dt/dx, dt/dy) in texels
// of level 0; the minor axis min(px^2, py^2), "clamped" by maxAniso as llvmpipe writes it.
float AnisoRhoSquared(const std::array<float, 4>& d, int maxAniso);

// One quad's ellipse on the level sampled: q(U, V) = a U^2 + b U V + c V^2 with the edge at
// q = 1023, row step ddq = 2a, and the half extents of its bounding box in texels.
struct AnisoEllipse {
    float a = 0, b = 0, c = 0, ddq = 0;
    float boxU = 0, boxV = 0;
};

// From d = (ds/dx, ds/dy, dt/dx, dt/dy) in texels of the level sampled.
AnisoEllipse AnisoEllipseOf(const std::array<float, 4>& d);

struct AnisoProbe {
    int u = 0, v = 0;  // texel column and row on the level (before wrapping)
    float weight = 0;  // table weight, > 0
};

// The probes with a non-zero weight around (texU, texV) = (s * width - 0.5, t * height - 0.5),
// in llvmpipe's order (rows v ascending, columns u ascending). Empty when the box's far edge
// passes 2^31 (llvmpipe then filters bilinearly) or the box holds more than `maxProbes` texels
// (not modelled: llvmpipe would spend tens of seconds on it; pemref filters bilinearly too).
std::vector<AnisoProbe> AnisoProbesOf(const AnisoEllipse& e, float texU, float texV,
                                      int64_t maxProbes = int64_t{1} << 30);

}  // namespace pem::raster
