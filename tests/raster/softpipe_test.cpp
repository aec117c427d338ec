// SPDX-License-Identifier: MIT
// softpipe_test.cpp — units of the softpipe profile against independent references (the whole
// profile is checked against live softpipe by conformance_tests' Softpipe.*):
//  - the tables softpipe builds with libm at start-up equal this machine's glibc (Debian 12, as
//    the driver they model): log2(1 + i/256) and expf(-2 i/1023);
//  - util_fast_log2 within its table's step of log2, util_ifloor equal to floor where exact;
//  - an anisotropic footprint no frame could need is refused with std::invalid_argument.
#include <gtest/gtest.h>

#include <cmath>
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

// The anisotropic ground plane with its LOD clamped to level 0 and its coordinates stretched
// 30 times: footprints of millions of texels per pixel, which softpipe would scan for minutes.
TEST(SoftpipeAniso, RefusesFootprintsNoFrameNeeds) {
    Frame frame;
    for (test::NamedCase& c : test::ConformanceCases())
        if (c.name == "aniso_lod_max_lod_1") frame = std::move(c.frame);
    ASSERT_FALSE(frame.passes.empty());
    frame.textures[0].sampler.maxLod = 0.0f;
    for (Vertex& v : frame.passes[0].vertices)
        for (int k = 0; k < 2; ++k) v.coord[0][k] *= 30.0f;
    RenderOptions softpipe;
    softpipe.profile = Profile::Softpipe;
    EXPECT_THROW(Render(PreparedFrame(frame), softpipe), std::invalid_argument);
}

}  // namespace
}  // namespace pem::raster
