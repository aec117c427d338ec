// SPDX-License-Identifier: MIT
// supersampling_test.cpp — the subpixels of a k× frame sit where the ray tracer's samples do
// (renderer_test.cpp draws and box-filters them).
#include "runtime/supersampling.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raster/profile.h"
#include "raster/render.h"
#include "runtime/texgen.h"
#include "tests/case_generator.h"
#include "trace/tracer.h"

namespace pem::runtime {
namespace {

TEST(Supersampling, SubpixelsAreTheRayTracersSamples) {
    const int width = 7, k = 3;
    for (uint32_t pixel : {0u, 5u, 7u, 30u})
        for (int s = 0; s < k * k; ++s) {
            const size_t i = SubpixelIndex(pixel, WholeFrame(width, 5, k), s);
            const int x = static_cast<int>(pixel % width), y = static_cast<int>(pixel / width);
            const glm::vec2 sample = trace::SamplePosition(x, y, k, s);  // pixel units
            // The centre of k× frame pixel i, in pixel units of the 1× frame.
            const float cx = (static_cast<float>(i % (k * width)) + 0.5f) / k;
            const float cy = (static_cast<float>(i / (k * width)) + 0.5f) / k;
            EXPECT_FLOAT_EQ(cx, sample.x) << pixel << " " << s;
            EXPECT_FLOAT_EQ(cy, sample.y) << pixel << " " << s;
        }
}

// A k× frame drawn only over the box of some pixels' subpixels (SubpixelBox, a scissor) gives
// those pixels the means the whole k× frame gives them.
TEST(Supersampling, ABoxOfTheSubpixelsGivesTheWholeFramesMeans) {
    const int width = 32, height = 24, k = 3;
    const raster::Frame whole = test::BenchmarkFrame(k * width, k * height, 10, 20, 16);
    const raster::Image8 all = raster::Render(raster::PreparedFrame(whole), {}).image8;
    const glm::ivec2 lo(5, 3), hi(20, 17);
    raster::Frame part = whole;
    part.scissor = SubpixelBox(height, k, lo, hi);
    const raster::Image8 box = raster::Render(raster::PreparedFrame(part), {}).image8;
    ASSERT_EQ(box.width, k * (hi.x - lo.x + 1));
    ASSERT_EQ(box.height, k * (hi.y - lo.y + 1));
    const std::vector<uint8_t> coveredAll(all.rgba.size() / 4, 1),
        coveredBox(box.rgba.size() / 4, 1);
    const SubpixelLayout layout{width, height, k, *part.scissor};
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            const auto pixel = static_cast<uint32_t>(y * width + x);
            double a[4], b[4];
            ASSERT_EQ(CoveredMean(all, coveredAll, WholeFrame(width, height, k), pixel, a), k * k);
            ASSERT_EQ(CoveredMean(box, coveredBox, layout, pixel, b), k * k);
            for (int c = 0; c < 4; ++c) ASSERT_EQ(a[c], b[c]) << x << " " << y << " " << c;
        }
}

}  // namespace
}  // namespace pem::runtime
