// SPDX-License-Identifier: MIT
// aniso_test.cpp — llvmpipe's anisotropic filter (raster/aniso.h) against independent references:
//  - the GL value -> pipe value rule and the weight table (libm's exp in double, printed with
//    six decimals like Mesa's generator; the bits of the installed driver's table);
//  - rho^2 and the ellipse against double-precision linear algebra: q(x) = 1023 x^T S^-1 x with
//    S = J J^T + I, J the derivatives in texels of the level sampled;
//  - the probe loop against a literal single-lane transcription of lp_build_sample_aniso's
//    loops (no shortcuts), also where q passes 2^31 and weighs 1 again;
//  - whole frames (linear profile) against a double-precision EWA with exact Gaussian weights.
#include "raster/aniso.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#include "raster/render.h"

namespace pem::raster {
namespace {

double D(float f) {
    return static_cast<double>(f);
}

TEST(AnisoState, GlValueToPipeValue) {
    // Clamped to 16, truncated, 1 -> 0 (off): only values >= 2 select the anisotropic path.
    const std::pair<float, int> cases[] = {{1.0f, 0},  {1.5f, 1}, {1.999f, 1}, {2.0f, 2},
                                           {2.5f, 2},  {7.3f, 7}, {16.0f, 16}, {16.7f, 16},
                                           {1e9f, 16}, {0.5f, 0}, {-3.0f, 0}};
    for (const auto& [gl, pipe] : cases) EXPECT_EQ(PipeMaxAnisotropy(gl), pipe) << gl;
    EXPECT_EQ(PipeMaxAnisotropy(std::nanf("")), 16);  // MIN2(NaN, 16) is 16
}

// Mesa's generator (lp_bld_sample.c): expf(-2 * (i / 1023.0f)), printed with "%f", compiled as
// a float initialiser; here with libm's double exp rounded to float.
float GeneratedEntry(int i) {
    const float r2 = static_cast<float>(i) / 1023.0f;
    const float e = static_cast<float>(std::exp(static_cast<double>(-2.0f * r2)));
    char text[32];
    std::snprintf(text, sizeof text, "%f", static_cast<double>(e));
    return static_cast<float>(std::strtod(text, nullptr));
}

TEST(AnisoTable, MatchesMesasGeneratorAndDriverBits) {
    uint64_t fnv = 1469598103934665603ull;
    for (int i = 0; i < kAnisoTableSize; ++i) {
        const float w = kAnisoWeights[static_cast<size_t>(i)];
        EXPECT_EQ(w, GeneratedEntry(i)) << i;
        EXPECT_NEAR(w, std::exp(-2.0 * i / 1023.0), 5.0e-7 + 6.0e-8) << i;
        if (i > 0) {
            EXPECT_LE(w, kAnisoWeights[static_cast<size_t>(i - 1)]) << i;
        }
        uint32_t bits;
        std::memcpy(&bits, &w, 4);
        for (int k = 0; k < 4; ++k) {
            fnv ^= (bits >> (8 * k)) & 255u;
            fnv *= 1099511628211ull;
        }
    }
    EXPECT_EQ(kAnisoWeights[0], 1.0f);
    // FNV-1a of the 4096 bytes of aniso_filter_table in Debian 12's swrast_dri.so (Mesa 22.3.6).
    EXPECT_EQ(fnv, 0xc3e5c1018aa7319dull);
}

TEST(AnisoLod, RhoIsTheMinorAxisWhateverTheMaximum) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> d(-300.0f, 300.0f);
    for (int k = 0; k < 2000; ++k) {
        const std::array<float, 4> j{d(rng), d(rng), d(rng), d(rng)};
        const double j0 = D(j[0]), j1 = D(j[1]), j2 = D(j[2]), j3 = D(j[3]);
        const double px = j0 * j0 + j2 * j2, py = j1 * j1 + j3 * j3;
        const float first = AnisoRhoSquared(j, 2);
        EXPECT_NEAR(first, std::min(px, py), 1e-6 * std::min(px, py));
        for (int m : {3, 4, 8, 16}) EXPECT_EQ(AnisoRhoSquared(j, m), first);
    }
}

// S^-1 of S = J J^T + I for J = [[ux, uy], [vx, vy]] (rows: texture axes; columns: screen x, y).
struct Quadratic {
    double a, b, c;  // x^T S^-1 x = a U^2 + b U V + c V^2
    double boxU, boxV;
};

Quadratic Reference(const std::array<float, 4>& d) {
    const double ux = D(d[0]), uy = D(d[1]), vx = D(d[2]), vy = D(d[3]);
    const double s00 = ux * ux + uy * uy + 1.0, s01 = ux * vx + uy * vy,
                 s11 = vx * vx + vy * vy + 1;
    const double det = s00 * s11 - s01 * s01;
    return {s11 / det, -2.0 * s01 / det, s00 / det, std::sqrt(s00), std::sqrt(s11)};
}

TEST(AnisoEllipse, IsTheInverseOfTheBlurredFootprint) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> d(-40.0f, 40.0f), x(-50.0f, 50.0f);
    for (int k = 0; k < 2000; ++k) {
        const std::array<float, 4> j{d(rng), d(rng), d(rng), d(rng)};
        const AnisoEllipse e = AnisoEllipseOf(j);
        const Quadratic r = Reference(j);
        EXPECT_NEAR(e.boxU, r.boxU, 1e-4 * r.boxU);  // the box is sqrt(diag S)
        EXPECT_NEAR(e.boxV, r.boxV, 1e-4 * r.boxV);
        EXPECT_EQ(e.ddq, e.a + e.a);
        for (int p = 0; p < 4; ++p) {
            const double u = D(x(rng)), v = D(x(rng));
            const double ea = D(e.a), eb = D(e.b), ec = D(e.c);
            const double ours = ea * u * u + eb * u * v + ec * v * v;
            const double exact = 1023.0 * (r.a * u * u + r.b * u * v + r.c * v * v);
            // Cancellation in F = AC - B^2/4 for thin ellipses: relative to the terms' size.
            const double scale =
                1023.0 * (std::fabs(r.a) * u * u + std::fabs(r.b * u * v) + std::fabs(r.c) * v * v);
            EXPECT_NEAR(ours, exact, 2e-3 * scale + 1e-3) << k;
        }
    }
}

// cvttps2dq: NaN and values outside int32 give INT32_MIN.
int32_t Cvtt(float v) {
    return (v >= -2147483648.0f && v < 2147483648.0f) ? static_cast<int32_t>(v) : INT32_MIN;
}

// lp_build_sample_aniso's loops for one lane, transcribed without shortcuts: do-while loops, the
// masks, q stepped over every column of the box.
std::vector<AnisoProbe> LlvmpipeLoop(const AnisoEllipse& e, float texU, float texV) {
    std::vector<AnisoProbe> out;
    const int32_t u0 = Cvtt(std::floor(texU - e.boxU)), u1 = Cvtt(std::ceil(texU + e.boxU));
    const int32_t v0 = Cvtt(std::floor(texV - e.boxV)), v1 = Cvtt(std::ceil(texV + e.boxV));
    const float uStart = static_cast<float>(u0) - texU;
    const float dqBase = (uStart * 2.0f + 1.0f) * e.a;
    const float qBase = (uStart * uStart) * e.a;
    int64_t v = v0;
    do {
        const bool vMask = v <= v1;
        const float vRel = static_cast<float>(v) - texV;
        float dq = vRel * e.b + dqBase;
        float q = (e.c * vRel + e.b * uStart) * vRel + qBase;
        int64_t u = u0;
        do {
            const bool uMask = u <= u1;
            int32_t qi = Cvtt(q);
            const bool qMask = qi <= 0x3ff;
            qi = std::max(qi, 0) & 0x3ff;
            if (uMask && vMask && qMask)
                out.push_back({static_cast<int>(u), static_cast<int>(v),
                               kAnisoWeights[static_cast<size_t>(qi)]});
            q = q + dq;
            dq = dq + e.ddq;
            ++u;
        } while (u <= u1);
        ++v;
    } while (v <= v1);
    return out;
}

void ExpectSameProbes(const std::vector<AnisoProbe>& got, const std::vector<AnisoProbe>& want,
                      const std::string& what) {
    ASSERT_EQ(got.size(), want.size()) << what;
    for (size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].u, want[i].u) << what << " probe " << i;
        ASSERT_EQ(got[i].v, want[i].v) << what << " probe " << i;
        ASSERT_EQ(got[i].weight, want[i].weight) << what << " probe " << i;
    }
}

TEST(AnisoProbes, EqualLlvmpipesLoopsOnRandomFootprints) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), centre(-200.0f, 200.0f);
    for (int k = 0; k < 1500; ++k) {
        // Anisotropy up to ~1000 at any angle, and near-isotropic footprints.
        const float major = std::pow(2.0f, (k % 100 == 0 ? 10.0f : 7.0f) * std::fabs(unit(rng)));
        const float minor = std::pow(2.0f, 2.0f * unit(rng));
        const float angle = 3.14159265f * unit(rng);
        const float c = std::cos(angle), s = std::sin(angle);
        const std::array<float, 4> j{major * c, -minor * s, major * s, minor * c};
        const AnisoEllipse e = AnisoEllipseOf(j);
        const float texU = centre(rng), texV = centre(rng);
        ExpectSameProbes(AnisoProbesOf(e, texU, texV), LlvmpipeLoop(e, texU, texV),
                         "footprint " + std::to_string(k));
    }
}

TEST(AnisoProbes, FarCornersOfHugeBoxesWeighOne) {
    // A rank-one footprint 1500 texels long at 45 degrees: q passes 2^31 towards the box's other
    // two corners, where cvttps2dq gives INT32_MIN and the table's first entry, 1.
    const float m = 1500.0f / std::sqrt(2.0f);
    const AnisoEllipse e = AnisoEllipseOf({m, 0.0f, m, 0.0f});
    const std::vector<AnisoProbe> probes = AnisoProbesOf(e, 10.3f, -4.6f);
    ExpectSameProbes(probes, LlvmpipeLoop(e, 10.3f, -4.6f), "huge");
    int farOnes = 0;
    for (const AnisoProbe& p : probes)
        if (p.weight == 1.0f && std::abs(p.u - 10) > 500 && std::abs(p.v + 5) > 500 &&
            (p.u - 10) * (p.v + 5) < 0)
            ++farOnes;
    EXPECT_GT(farOnes, 500);
}

TEST(AnisoProbes, BoxesBeyondInt32HaveNone) {
    // The far edge of the box overflows cvttps2dq (INT32_MIN < u0): the loop masks everything.
    const AnisoEllipse e = AnisoEllipseOf({300.0f, 0.0f, 0.0f, 1.0f});
    EXPECT_TRUE(AnisoProbesOf(e, 2147483520.0f, 3.0f).empty());
    EXPECT_TRUE(LlvmpipeLoop(e, 2147483520.0f, 3.0f).empty());
}

// Whole frames: an affine 2D mapping (w = 1) whose derivatives are known exactly, rendered by the
// linear profile, against a double-precision EWA with exact Gaussian weights exp(-2 q / 1023)
// over the same texels. The table steps weights by at most a factor e^(2/1023), which moves a
// weighted mean by less than 0.002; pixels with a texel within 0.05 of the q = 1024 edge (where
// float and exact arithmetic may disagree on membership) are skipped.
struct Affine {
    double s0, dsdx, dsdy, t0, dtdx, dtdy;  // per window pixel
    MipFilter mip;
};

TEST(AnisoFrame, LinearProfileMatchesDoublePrecisionEwa) {
    constexpr int kW = 48, kH = 40, kSize = 128;
    const Affine maps[] = {
        {0.3, 6.0 / kSize, 0.6 / kSize, 0.1, -1.5 / kSize, 0.7 / kSize, MipFilter::Linear},
        {0.7, 20.0 / kSize, 3.0 / kSize, 0.2, -4.0 / kSize, 2.2 / kSize, MipFilter::Nearest},
        {0.1, 3.0 / kSize, -1.0 / kSize, 0.4, 0.5 / kSize, 2.0 / kSize, MipFilter::None}};
    int checked = 0, skipped = 0;
    for (const Affine& m : maps) {
        // Step 1: the frame: a full-screen quad with the affine coordinates, a random texture.
        Frame f;
        f.width = kW;
        f.height = kH;
        Texture tex;
        tex.kind = TextureKind::Tex2D;
        tex.width = tex.height = kSize;
        tex.sampler.mipFilter = m.mip;
        tex.sampler.wrapS = tex.sampler.wrapT = Wrap::Repeat;
        tex.sampler.maxAnisotropy = 16.0f;
        std::mt19937 rng(static_cast<unsigned>(m.mip) + 40);
        for (int l = 0; (kSize >> l) >= 1; ++l) {
            std::vector<uint8_t> level(static_cast<size_t>((kSize >> l) * (kSize >> l) * 4));
            for (uint8_t& b : level) b = static_cast<uint8_t>(rng());
            tex.levels.push_back(level);
        }
        f.textures.push_back(tex);
        Pass p;
        const double corner[4][2] = {{0, 0}, {kW, 0}, {kW, kH}, {0, kH}};
        for (int k : {0, 1, 2, 0, 2, 3}) {
            Vertex v;
            const double x = corner[k][0], y = corner[k][1];
            v.pos = {static_cast<float>(2 * x / kW - 1), static_cast<float>(2 * y / kH - 1), 0, 1};
            v.coord[0] = {static_cast<float>(m.s0 + m.dsdx * x + m.dsdy * y),
                          static_cast<float>(m.t0 + m.dtdx * x + m.dtdy * y), 0.0f};
            p.vertices.push_back(v);
        }
        f.passes.push_back(p);
        RenderOptions opt;
        opt.profile = Profile::Linear;
        const ImageF img = Render(PreparedFrame(f), opt).imageF;

        // Step 2: the level: trunc(0.5 log2(minor axis^2)) (chosen away from integers, where
        // llvmpipe's fast log2 and the exact one agree), none without a MIP filter.
        const double j0[4] = {m.dsdx * kSize, m.dsdy * kSize, m.dtdx * kSize, m.dtdy * kSize};
        const double minor = std::min(j0[0] * j0[0] + j0[2] * j0[2], j0[1] * j0[1] + j0[3] * j0[3]);
        const int level =
            m.mip == MipFilter::None ? 0 : std::max(0, static_cast<int>(0.5 * std::log2(minor)));
        const int n = kSize >> level;
        const double scale = 1.0 / (1 << level);
        const std::array<float, 4> j{
            static_cast<float>(j0[0] * scale), static_cast<float>(j0[1] * scale),
            static_cast<float>(j0[2] * scale), static_cast<float>(j0[3] * scale)};
        const Quadratic quad = Reference(j);

        // Step 3: every pixel's EWA in double.
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const double s = m.s0 + m.dsdx * (x + 0.5) + m.dsdy * (y + 0.5);
                const double t = m.t0 + m.dtdx * (x + 0.5) + m.dtdy * (y + 0.5);
                const double tu = s * n - 0.5, tv = t * n - 0.5;
                double sum[4] = {0, 0, 0, 0}, den = 0;
                bool ambiguous = false;
                for (int v = static_cast<int>(std::floor(tv - quad.boxV));
                     v <= static_cast<int>(std::ceil(tv + quad.boxV)); ++v)
                    for (int u = static_cast<int>(std::floor(tu - quad.boxU));
                         u <= static_cast<int>(std::ceil(tu + quad.boxU)); ++u) {
                        const double du = u - tu, dv = v - tv;
                        const double q =
                            1023.0 * (quad.a * du * du + quad.b * du * dv + quad.c * dv * dv);
                        ambiguous |= std::fabs(q - 1024.0) < 0.05;
                        if (q >= 1024.0) continue;
                        const double w = std::exp(-2.0 * q / 1023.0);
                        const uint8_t* texel = &tex.levels[static_cast<size_t>(
                            level)][static_cast<size_t>(((v & (n - 1)) * n + (u & (n - 1))) * 4)];
                        for (int c = 0; c < 4; ++c) sum[c] += w * texel[c] / 255.0;
                        den += w;
                    }
                if (ambiguous) {
                    ++skipped;
                    continue;
                }
                const float* got = &img.rgba[static_cast<size_t>(((kH - 1 - y) * kW + x) * 4)];
                for (int c = 0; c < 4; ++c)
                    ASSERT_NEAR(got[c], sum[c] / den, 0.0025)
                        << "map " << checked / (kW * kH) << " pixel " << x << "," << y;
                ++checked;
            }
    }
    EXPECT_GT(checked, 3 * kW * kH * 9 / 10);
    EXPECT_LT(skipped, 3 * kW * kH / 10);
}

}  // namespace
}  // namespace pem::raster
