// SPDX-License-Identifier: MIT
// supersampling_test.cpp — the k×k box filter over covered subpixels: subpixels sit where the
// ray tracer's samples do, and the merged rendering matrix times the texels is the mean of the
// covered subpixels of the k× frame as the hardware model renders it.
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

// A mirror sphere over an empty background, depth-tested, at k× the size.
raster::Frame SphereFrame(int width, int height, int k) {
    raster::Frame f = test::BenchmarkFrame(k * width, k * height, 10, 20, 16);
    f.passes.erase(f.passes.begin());  // no sky: the sphere covers part of the frame
    f.depth = kLensDepth;
    f.passes[0].depthTest = LayerDepthTest(true);
    return f;
}

TEST(Supersampling, MergedRowsTimesTexelsAreTheCoveredMeanOfTheFrame) {
    const int width = 40, height = 30;
    raster::RenderOptions ro = raster::ProfileNamed("llvmpipe").options;
    ro.profile = raster::Profile::Linear;
    for (int k : {1, 2, 3}) {
        const raster::Frame f = SphereFrame(width, height, k);
        const raster::PreparedFrame pf(f);
        const raster::RenderingMatrix m =
            BoxFilterRows(raster::BuildRenderingMatrix(pf, ro), width, height, k);
        ASSERT_EQ(m.rows, 4 * width * height);
        // The texels in column order (levels one after the other).
        std::vector<double> x;
        for (const auto& level : f.textures[0].levels)
            for (uint8_t b : level) x.push_back(b / 255.0);
        ASSERT_EQ(static_cast<int64_t>(x.size()), m.cols);
        // Reference: the k× frame rendered, each pixel the mean of its covered subpixels.
        const raster::RenderResult rr = raster::Render(pf, ro);
        const std::vector<uint8_t> covered = CoveredSubpixels(rr.depth, kLensDepth);
        int partial = 0, empty = 0;
        for (uint32_t p = 0; p < static_cast<uint32_t>(width * height); ++p) {
            double rgba[4];
            const int n = CoveredMean(rr.imageF, covered, width, k, p, rgba);
            EXPECT_EQ(m.fragments[p], n);
            partial += n > 0 && n < k * k;
            empty += n == 0;
            if (n == 0) {  // no fragment: no taps (the row stays the clear colour)
                EXPECT_EQ(m.rowPtr[4 * p + 4], m.rowPtr[4 * p]) << "k " << k << " pixel " << p;
                continue;
            }
            for (size_t c = 0; c < 4; ++c) {
                const size_t r = 4 * p + c;
                double y = m.offset[r];
                for (int64_t e = m.rowPtr[r]; e < m.rowPtr[r + 1]; ++e)
                    y += m.val[static_cast<size_t>(e)] * x[m.col[static_cast<size_t>(e)]];
                EXPECT_NEAR(y, rgba[c], 1e-5) << "k " << k << " pixel " << p << " c " << c;
                EXPECT_NEAR(m.rendered[r], rgba[c], 1e-6) << "k " << k << " pixel " << p;
            }
        }
        EXPECT_GT(empty, 50);  // not vacuous: the background, and for k > 1 partial pixels
        if (k > 1) {
            EXPECT_GT(partial, 20) << k;
        }
    }
}

}  // namespace
}  // namespace pem::runtime
