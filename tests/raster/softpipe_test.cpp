// SPDX-License-Identifier: MIT
// softpipe_test.cpp — units of the softpipe profile against independent references (the whole
// profile is checked against live softpipe by conformance_tests' Softpipe.*):
//  - the tables softpipe builds with libm at start-up equal this machine's glibc (Debian 12, as
//    the driver they model): log2(1 + i/256) and expf(-2 i/1023);
//  - util_fast_log2 within its table's step of log2, util_ifloor equal to floor where exact;
//  - EWA boxes are paid from the frame's budget; running out throws std::invalid_argument.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "raster/render.h"
#include "raster/softpipe_sampler.h"
#include "raster/softpipe_tables.h"
#include "tests/case_generator.h"

namespace pem::raster {
namespace {

TEST(SoftpipeTables, EqualThisGlibc) {
    for (int i = 0; i <= 256; ++i)
        EXPECT_EQ(kLog2Table[i], static_cast<float>(std::log2(1.0 + i / 256.0))) << i;
    for (int i = 0; i < 1024; ++i) {
        const float r2 = static_cast<float>(i) / 1023.0f;
        EXPECT_EQ(kEwaWeights[i], expf(-2.0f * r2)) << i;
    }
}

TEST(SoftpipeNumeric, FastLog2AndIfloor) {
    for (float x = 1e-6f; x < 1e6f; x *= 1.0137f)
        EXPECT_NEAR(SoftpipeFastLog2(x), std::log2(x), 0.003) << x;
    for (float x = -4194303.5f; x < 4194304.0f; x += 9973.37f)
        EXPECT_EQ(SoftpipeIfloor(x), static_cast<int32_t>(std::floor(x))) << x;
    EXPECT_EQ(SoftpipeIfloor(-0.5f), -1);
    EXPECT_EQ(SoftpipeIfloor(2.0f), 2);
}

// A quad on a 64x64 anisotropic texture whose coordinates step 50 texels per pixel both ways
// with the LOD clamped to level 0: each pixel's EWA box holds ~40000 texels. A budget of 10^5
// texels pays for two pixels and stops at the third (a frame's budget is SoftpipeBudget's).
TEST(SoftpipeAniso, StopsWhenTheFrameBudgetRunsOut) {
    Texture tex;
    tex.kind = TextureKind::Tex2D;
    tex.width = tex.height = 64;
    for (int l = 0, n = 64; n >= 1; ++l, n /= 2)
        tex.levels.push_back(std::vector<uint8_t>(4 * static_cast<size_t>(n * n), 128));
    tex.sampler.minFilter = Filter::Linear;
    tex.sampler.mipFilter = MipFilter::Linear;
    tex.sampler.maxAnisotropy = 16.0f;
    tex.sampler.maxLod = 0.0f;
    const std::shared_ptr<const PreparedTexture> prepared = PrepareTexture(tex);
    const float d = 50.0f / 64.0f;  // 50 texels in s and t per pixel
    const QuadCoords q{{0.5f, 0.5f + d, 0.5f, 0.5f + d}, {0.5f + d, 0.5f + d, 0.5f, 0.5f}, {}};
    std::array<RgbaF, 4> colour;
    SoftpipeBudget plenty;
    SampleSoftpipeQuad(*prepared, q, &colour, &plenty);
    EXPECT_NEAR(colour[0][0], 128.0f / 255.0f, 1e-5f);  // a uniform texture, float sums
    const int64_t perPixel = (SoftpipeBudget::kEwaTexels - plenty.ewaTexels) / 4;
    EXPECT_GT(perPixel, 10000);
    SoftpipeBudget small{};
    small.ewaTexels = 2 * perPixel + perPixel / 2;
    EXPECT_THROW(SampleSoftpipeQuad(*prepared, q, &colour, &small), std::invalid_argument);
}

}  // namespace
}  // namespace pem::raster
