// SPDX-License-Identifier: MIT
// scissor_test.cpp — a frame drawn with a scissor box holds, inside the box, exactly the bytes
// of the whole frame drawn without one (glScissor only discards fragments), for every generated
// case and profile; impossible boxes and the matrix of a scissored frame are refused.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/render.h"
#include "tests/case_generator.h"

namespace pem::raster {
namespace {

// The box's part of a whole-frame buffer (rows top-down, perPixel values a pixel).
template <class T>
std::vector<T> Crop(const std::vector<T>& whole, const Frame& frame, const PixelBox& b,
                    size_t perPixel) {
    std::vector<T> out;
    if (whole.empty()) return out;  // a buffer the frame does not have
    for (int row = 0; row < b.height; ++row) {
        const int wholeRow = frame.height - b.y - b.height + row;  // from the top
        for (int x = b.x; x < b.x + b.width; ++x)
            for (size_t c = 0; c < perPixel; ++c)
                out.push_back(whole[perPixel * (static_cast<size_t>(wholeRow) *
                                                    static_cast<size_t>(frame.width) +
                                                static_cast<size_t>(x)) +
                                    c]);
    }
    return out;
}

// Float buffers compared bit for bit (NaN included).
std::vector<uint32_t> Bits(const std::vector<float>& v) {
    std::vector<uint32_t> bits(v.size());
    for (size_t i = 0; i < v.size(); ++i) bits[i] = std::bit_cast<uint32_t>(v[i]);
    return bits;
}

// Boxes to try on a frame: the whole framebuffer, its corner pixels, and random boxes.
std::vector<PixelBox> Boxes(const Frame& f, test::Rng* rng) {
    std::vector<PixelBox> boxes{
        {0, 0, f.width, f.height}, {0, 0, 1, 1}, {f.width - 1, f.height - 1, 1, 1}};
    for (int i = 0; i < 3; ++i) {
        const int x = rng->Int(f.width), y = rng->Int(f.height);
        boxes.push_back({x, y, 1 + rng->Int(f.width - x), 1 + rng->Int(f.height - y)});
    }
    return boxes;
}

void ExpectCropOfWhole(const test::NamedCase& c, const RenderOptions& options, test::Rng* rng) {
    const RenderResult whole = Render(PreparedFrame(c.frame), options);
    for (const PixelBox& b : Boxes(c.frame, rng)) {
        Frame f = c.frame;
        f.scissor = b;
        const RenderResult r = Render(PreparedFrame(f), options);
        const auto where = [&] {
            return c.name + " box " + std::to_string(b.x) + "," + std::to_string(b.y) + " " +
                   std::to_string(b.width) + "x" + std::to_string(b.height);
        };
        ASSERT_EQ(r.image8.width, b.width) << where();
        ASSERT_EQ(r.image8.height, b.height) << where();
        ASSERT_EQ(r.image8.rgba, Crop(whole.image8.rgba, c.frame, b, 4)) << where();
        ASSERT_EQ(Bits(r.imageF.rgba), Bits(Crop(whole.imageF.rgba, c.frame, b, 4))) << where();
        ASSERT_EQ(r.depth, Crop(whole.depth, c.frame, b, 1)) << where();
    }
}

bool Rgba8Only(const Frame& f) {
    bool rgba8 = f.colorFormat == ColorFormat::Rgba8;
    for (const Texture& t : f.textures) rgba8 &= t.format == TexelFormat::Rgba8;
    return rgba8;
}

TEST(Scissor, InsideTheBoxTheWholeFramesBytes) {
    test::Rng rng(17);
    std::vector<test::NamedCase> cases = test::ConformanceCases();
    cases.push_back({"bench_small", test::BenchmarkFrame(160, 120, 25, 50, 64)});
    for (const test::NamedCase& c : cases) {
        RenderOptions llvmpipe;
        llvmpipe.threads = 2;
        ExpectCropOfWhole(c, llvmpipe, &rng);
        RenderOptions linear;
        linear.profile = Profile::Linear;
        ExpectCropOfWhole(c, linear, &rng);
        if (!Rgba8Only(c.frame)) continue;
        RenderOptions softpipe;
        softpipe.profile = Profile::Softpipe;
        ExpectCropOfWhole(c, softpipe, &rng);
        if (HasFatalFailure()) return;
    }
}

TEST(Scissor, FramesSharingTheirPassesKeepTheirOwnBoxes) {
    const Frame frame = test::BenchmarkFrame(96, 80, 12, 24, 32);
    Frame a = frame, b = frame;
    a.scissor = PixelBox{10, 20, 40, 30};
    b.scissor = PixelBox{50, 5, 46, 70};
    const PreparedFrame pa(a), pb(b), pw(frame);
    const std::vector<RenderResult> both = RenderFrames({&pa, &pw, &pb}, {});
    const RenderResult whole = Render(pw, {});
    EXPECT_EQ(both[0].image8.rgba, Crop(whole.image8.rgba, frame, *a.scissor, 4));
    EXPECT_EQ(both[1].image8, whole.image8);
    EXPECT_EQ(both[2].image8.rgba, Crop(whole.image8.rgba, frame, *b.scissor, 4));
}

TEST(Scissor, ImpossibleBoxesAndTheMatrixAreRefused) {
    const Frame frame = test::BenchmarkFrame(32, 24, 4, 8, 8);
    for (const PixelBox& box :
         {PixelBox{0, 0, 0, 5}, PixelBox{0, 0, 5, 0}, PixelBox{-1, 0, 4, 4}, PixelBox{0, -1, 4, 4},
          PixelBox{30, 0, 3, 4}, PixelBox{0, 20, 4, 5}}) {
        Frame f = frame;
        f.scissor = box;
        EXPECT_THROW(Render(PreparedFrame(f), {}), std::invalid_argument) << box.x << "," << box.y;
    }
    Frame f = frame;
    f.scissor = PixelBox{0, 0, 8, 8};
    EXPECT_THROW(BuildRenderingMatrix(PreparedFrame(f), {}), std::invalid_argument);
}

}  // namespace
}  // namespace pem::raster
