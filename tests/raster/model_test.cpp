// SPDX-License-Identifier: MIT
// model_test.cpp — the hardware model's small rules against independent references: exact
// rational arithmetic for the 8-bit operations, double-precision log2, hand-checked faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "raster/blend.h"
#include "raster/cube_lookup.h"
#include "raster/lod.h"
#include "raster/numeric.h"

namespace pem::raster {
namespace {

TEST(CubeFace, TiesPreferZThenY) {
    // llvmpipe: z if |z| >= max(|x|, |y|), else x if |x| > |y|, else y (measured on Mesa 22.3.6).
    EXPECT_EQ(CubeFace({1, 1, 0}), 2);      // +Y
    EXPECT_EQ(CubeFace({-1, 0, 1}), 4);     // +Z
    EXPECT_EQ(CubeFace({0, -1, -1}), 5);    // -Z
    EXPECT_EQ(CubeFace({1, 1, 1}), 4);      // +Z
    EXPECT_EQ(CubeFace({-1, -1, 0}), 3);    // -Y
    EXPECT_EQ(CubeFace({2, 1, 1}), 0);      // +X strictly largest
    EXPECT_EQ(CubeFace({0, 0, 0}), 4);      // zero vector: +Z (sign bit clear)
    EXPECT_EQ(CubeFace({0, 0, -0.0f}), 5);  // -0.0 selects the negative face
    EXPECT_EQ(CubeFace({-0.0f, 0, 0}), 4);
}

TEST(CubeFace, NanComparesAreUnordered) {
    // lp_build_cube_lookup: |x| > |y| and |z| >= maxps(|x|, |y|) are unordered (true on NaN);
    // maxps returns its second operand when either is NaN (raster-model.md §11).
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(CubeFace({nan, 1, 0.5f}), 0);      // max = |y|, z loses, |x| > |y| holds: +X
    EXPECT_EQ(CubeFace({nan, 1, 2}), 4);         // max = |y|, z wins
    EXPECT_EQ(CubeFace({1, nan, 0.5f}), 4);      // max is NaN: z
    EXPECT_EQ(CubeFace({2, 1, nan}), 4);         // |z| NaN: z
    EXPECT_EQ(CubeFace({-nan, -nan, -nan}), 5);  // the sign bit of the NaN picks the face
    // Without derivatives 0.5/|ma| is taken where |ma| > 0 holds unordered: NaN, not 0.
    const Vec3f zero{0, 0, 0};
    const CubeCoord c = CubeLookup({nan, nan, nan}, zero, zero, false);
    EXPECT_EQ(c.face, 4);
    EXPECT_TRUE(std::isnan(c.s) && std::isnan(c.t));
    EXPECT_EQ(CubeLookup({0, 0, 0}, zero, zero, false).s, 0.5f);  // |ma| = 0: 0.5/|ma| unused
}

TEST(CubeFace, ProjectionMatchesGlTable) {
    // Centre of each face maps to (0.5, 0.5); GL table 8.19 orientation at an off-centre point.
    const Vec3f zero{0, 0, 0};
    const CubeCoord px = CubeLookup({1, 0.5f, 0.25f}, zero, zero, false);  // +X: sc=-rz, tc=-ry
    EXPECT_EQ(px.face, 0);
    EXPECT_FLOAT_EQ(px.s, 0.5f * -0.25f + 0.5f);
    EXPECT_FLOAT_EQ(px.t, 0.5f * -0.5f + 0.5f);
    const CubeCoord ny = CubeLookup({0.25f, -1, 0.5f}, zero, zero, false);  // -Y: sc=rx, tc=-rz
    EXPECT_EQ(ny.face, 3);
    EXPECT_FLOAT_EQ(ny.s, 0.5f * 0.25f + 0.5f);
    EXPECT_FLOAT_EQ(ny.t, 0.5f * -0.5f + 0.5f);
    const CubeCoord nz = CubeLookup({0.25f, 0.5f, -2}, zero, zero, false);  // -Z: sc=-rx, tc=-ry
    EXPECT_EQ(nz.face, 5);
    EXPECT_FLOAT_EQ(nz.s, -0.25f / 4 + 0.5f);
    EXPECT_FLOAT_EQ(nz.t, -0.5f / 4 + 0.5f);
}

TEST(Numeric, Mul8DiffersFromExactRoundingIn24Products) {
    int differ = 0;
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b) {
            const int exact = (2 * a * b + 255) / 510;  // round(a*b/255), halves up (none occur)
            const int got = Mul8(static_cast<uint8_t>(a), static_cast<uint8_t>(b));
            if (got != exact) {
                ++differ;
                EXPECT_EQ(got, exact - 1);  // always one low
            }
        }
    EXPECT_EQ(differ, 24);
    EXPECT_EQ(Mul8(152, 229), 136);  // exact 136.502
    for (int a = 0; a < 256; ++a) EXPECT_EQ(Mul8(static_cast<uint8_t>(a), 255), a);
}

TEST(Numeric, Lerp8IsFloorOfRoundedProduct) {
    for (int w = 0; w < 256; ++w)
        for (int a = 0; a < 256; a += 3)
            for (int b = 0; b < 256; b += 5) {
                const double exact = a + w * (b - a) / 256.0;
                const int got = Lerp8(w, static_cast<uint8_t>(a), static_cast<uint8_t>(b));
                ASSERT_EQ(got, static_cast<int>(std::floor(exact + 0.5)))
                    << w << " " << a << " " << b;
            }
}

TEST(Numeric, FastLog2ExactAtPowersOfTwoAndBelowLog2) {
    for (int e = -126; e <= 127; ++e)
        EXPECT_EQ(FastLog2(std::ldexp(1.0f, e)), static_cast<float>(e));
    double worst = 0;
    for (int i = 0; i < 1 << 16; ++i) {
        const float x = 1.0f + static_cast<float>(i) / 65536.0f;
        const double d = std::log2(static_cast<double>(x)) - static_cast<double>(FastLog2(x));
        ASSERT_GE(d, -1e-7);
        worst = std::max(worst, d);
    }
    EXPECT_NEAR(worst, 0.0860713, 1e-5);  // log2(m) - (m - 1) peaks at m = 1/ln 2
}

TEST(Numeric, UnormConversionTies) {
    // fl(2.5/255) * 255 rounds in float to exactly 2.5: RNE gives 2, the D3D rule 3.
    const float f = 2.5f / 255.0f;
    ASSERT_EQ(f * 255.0f, 2.5f);
    EXPECT_EQ(UnormFromFloatRne(f), 2);
    EXPECT_EQ(UnormFromFloatHalfUp(f), 3);
    EXPECT_EQ(UnormFromFloatRne(-1.0f), 0);
    EXPECT_EQ(UnormFromFloatRne(2.0f), 255);
    EXPECT_EQ(UnormFromFloatRne(NAN), 0);
    EXPECT_EQ(UnormFromFloatRne(INFINITY), 255);
    for (int k = 0; k < 256; ++k)
        EXPECT_EQ(UnormFromFloatRne(FloatFromUnorm8(static_cast<uint8_t>(k))), k);
}

TEST(Numeric, UnormRneEqualsLibmNearbyint) {
    // Against libm's nearbyint of the same product: every 97th float of [0, 1] (bit patterns
    // 0 .. 0x3f800000), and every float within 512 ulps of each k / 255 and (k + 0.5) / 255,
    // where the product lands on or next to a tie.
    const auto check = [](float x) {
        const auto expected = static_cast<uint8_t>(std::nearbyint(x * 255.0f));
        return UnormFromFloatRne(x) == expected;
    };
    for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 97)
        ASSERT_TRUE(check(BitsFloat(bits))) << "bits " << bits;
    for (int k = 0; k <= 255; ++k)
        for (const float centre : {float(k) / 255.0f, (float(k) + 0.5f) / 255.0f}) {
            const uint32_t c = FloatBits(centre);
            for (uint32_t b = c > 512 ? c - 512 : 0; b <= std::min(c + 512, 0x3f800000u); ++b)
                ASSERT_TRUE(check(BitsFloat(b))) << "bits " << b;
        }
    EXPECT_EQ(UnormFromFloatRne(std::nextafter(1.0f, 2.0f)), 255);
    EXPECT_EQ(UnormFromFloatRne(-0.0f), 0);
    EXPECT_EQ(UnormFromFloatRne(-std::numeric_limits<float>::denorm_min()), 0);
}

TEST(Blend, OverMatchesMeasuredLlvmpipeFormula) {
    // over = sat(mul8(s, sa) + mul8(d, 255 - sa)) per channel, alpha too (hardware-model §10).
    const BlendState over = BlendState::Over();
    for (int s = 0; s < 256; s += 7)
        for (int a = 0; a < 256; a += 11)
            for (int d = 0; d < 256; d += 13) {
                const Rgba8 src{uint8_t(s), uint8_t(s), uint8_t(s), uint8_t(a)};
                const Rgba8 dst{uint8_t(d), uint8_t(d), uint8_t(d), uint8_t(d)};
                const Rgba8 out = Blend8(over, src, dst);
                const int e = std::min(
                    255, Mul8(uint8_t(s), uint8_t(a)) + Mul8(uint8_t(d), uint8_t(255 - a)));
                ASSERT_EQ(out[0], e);
            }
    EXPECT_EQ(Blend8(BlendState::Additive(), {200, 10, 0, 255}, {100, 10, 0, 255})[0], 255);
    EXPECT_EQ(Blend8(BlendState::Multiply(), {128, 0, 0, 0}, {128, 0, 0, 0})[0], Mul8(128, 128));
}

TEST(Lod, NearestShortcutDiffersFromRoundingAtOddPowersOfTwo) {
    // rho^2 = 2: llvmpipe's default-state shortcut gives level 1, the general path (any clamp
    // or bias active, e.g. GL_TEXTURE_MAX_LOD 14) rounds lambda = 0.5 to even: level 0.
    SamplerState s;
    s.minFilter = Filter::Linear;
    s.mipFilter = MipFilter::Nearest;
    const PipeLodState plain = DerivePipeLodState(s, 9);
    EXPECT_EQ(SelectLod(2.0f, plain, MipFilter::Nearest, 9, false).level0, 1);
    s.maxLod = 14.0f;
    const PipeLodState clamped = DerivePipeLodState(s, 9);
    ASSERT_TRUE(clamped.applyMaxLod);
    EXPECT_EQ(SelectLod(2.0f, clamped, MipFilter::Nearest, 9, false).level0, 0);
    // Exact GL-spec variant: lambda = log2(sqrt(rho^2)).
    EXPECT_FLOAT_EQ(LambdaFromRhoSquared(8.0f, plain, true), 1.5f);
    EXPECT_FLOAT_EQ(LambdaFromRhoSquared(3.0f, plain, false), 0.75f);  // 0.5*(1 + 0.5)
}

TEST(Lod, NanRhoSquaredMinifies) {
    // lod_positive is rho^2 > 1 (shortcut) or lambda > 0, unordered: a NaN rho^2 (2D quads whose
    // differences are Inf - Inf) counts as minified.
    SamplerState s;
    s.minFilter = Filter::Linear;
    s.magFilter = Filter::Nearest;
    s.mipFilter = MipFilter::None;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(SelectLod(nan, DerivePipeLodState(s, 5), MipFilter::None, 5, false).magnify);
    s.lodBias = 0.5f;  // general path: lambda from FastLog2(NaN) is finite and positive
    EXPECT_FALSE(SelectLod(nan, DerivePipeLodState(s, 5), MipFilter::None, 5, false).magnify);
    EXPECT_FALSE(LevelsFor(nan, MipFilter::None, 5).magnify);
    EXPECT_TRUE(SelectLod(1.0f, DerivePipeLodState(SamplerState{}, 5), MipFilter::Nearest, 5, false)
                    .magnify);
}

TEST(Lod, LinearLevelsClampAndZeroFraction) {
    const LodResult below = LevelsFor(-0.5f, MipFilter::Linear, 5);
    EXPECT_TRUE(below.magnify);
    EXPECT_EQ(below.level0, 0);
    EXPECT_EQ(below.frac, 0.0f);
    const LodResult mid = LevelsFor(2.25f, MipFilter::Linear, 5);
    EXPECT_EQ(mid.level0, 2);
    EXPECT_EQ(mid.level1, 3);
    EXPECT_EQ(mid.frac, 0.25f);
    const LodResult top = LevelsFor(7.5f, MipFilter::Linear, 5);
    EXPECT_EQ(top.level0, 4);
    EXPECT_EQ(top.level1, 4);
    EXPECT_EQ(top.frac, 0.0f);
    const PipeLodState bias = DerivePipeLodState(
        [] {
            SamplerState s;
            s.lodBias = 0.3337f;
            return s;
        }(),
        5);
    EXPECT_EQ(bias.lodBias, 85.0f / 256.0f);  // quantised to 1/256
}

}  // namespace
}  // namespace pem::raster
