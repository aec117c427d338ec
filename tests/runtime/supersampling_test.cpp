// SPDX-License-Identifier: MIT
// supersampling_test.cpp — the subpixels of a k× frame sit where the ray tracer's samples do
// (renderer_test.cpp draws and box-filters them).
#include "runtime/supersampling.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raster/profile.h"
#include "runtime/texgen.h"
#include "tests/case_generator.h"
#include "trace/tracer.h"

namespace pem::runtime {
namespace {

TEST(Supersampling, SubpixelsAreTheRayTracersSamples) {
    const int width = 7, k = 3;
    for (uint32_t pixel : {0u, 5u, 7u, 30u})
        for (int s = 0; s < k * k; ++s) {
            const size_t i = SubpixelIndex(pixel, width, k, s);
            const int x = static_cast<int>(pixel % width), y = static_cast<int>(pixel / width);
            const glm::vec2 sample = trace::SamplePosition(x, y, k, s);  // pixel units
            // The centre of k× frame pixel i, in pixel units of the 1× frame.
            const float cx = (static_cast<float>(i % (k * width)) + 0.5f) / k;
            const float cy = (static_cast<float>(i / (k * width)) + 0.5f) / k;
            EXPECT_FLOAT_EQ(cx, sample.x) << pixel << " " << s;
            EXPECT_FLOAT_EQ(cy, sample.y) << pixel << " " << s;
        }
}

}  // namespace
}  // namespace pem::runtime
