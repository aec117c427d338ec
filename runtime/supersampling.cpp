// SPDX-License-Identifier: MIT
// supersampling.cpp — the k×k box filter over covered subpixels (supersampling.h).
#include "runtime/supersampling.h"

#include <algorithm>
#include <utility>

#include "raster/depth.h"

namespace pem::runtime {

namespace {

template <class Image, class Scale>
int Mean(const Image& image, const std::vector<uint8_t>& covered, const SubpixelLayout& layout,
         uint32_t pixel, Scale scale, double rgba[4]) {
    std::fill(rgba, rgba + 4, 0.0);
    int n = 0;
    for (int s = 0; s < layout.k * layout.k; ++s) {
        const size_t i = SubpixelIndex(pixel, layout, s);
        if (!covered[i]) continue;
        ++n;
        for (size_t c = 0; c < 4; ++c) rgba[c] += scale(image.rgba[4 * i + c]);
    }
    if (n > 1)
        for (size_t c = 0; c < 4; ++c) rgba[c] /= n;
    return n;
}

}  // namespace

SubpixelLayout WholeFrame(int width, int height, int k) {
    return {width, height, k, {0, 0, k * width, k * height}};
}

raster::PixelBox SubpixelBox(int height, int k, glm::ivec2 lo, glm::ivec2 hi) {
    // Rows k lo.y .. k (hi.y + 1) - 1 from the top are GL rows k (height - 1 - hi.y) upwards.
    return {k * lo.x, k * (height - 1 - hi.y), k * (hi.x - lo.x + 1), k * (hi.y - lo.y + 1)};
}

size_t SubpixelIndex(uint32_t pixel, const SubpixelLayout& layout, int s) {
    const auto width = static_cast<uint32_t>(layout.width);
    const int x = static_cast<int>(pixel % width), y = static_cast<int>(pixel / width);
    const int k = layout.k;
    // The subpixel's column and its row from the top of the k× frame, then of the box.
    const int column = k * x + s % k, row = k * y + s / k;
    const raster::PixelBox& b = layout.box;
    const int boxTop = k * layout.height - b.y - b.height;
    return static_cast<size_t>(row - boxTop) * static_cast<size_t>(b.width) +
           static_cast<size_t>(column - b.x);
}

std::vector<uint8_t> CoveredSubpixels(const std::vector<uint32_t>& depth,
                                      const raster::DepthBuffer& buffer) {
    const uint32_t clear = raster::DepthClearValue(buffer.format, buffer.clear);
    std::vector<uint8_t> covered(depth.size());
    for (size_t i = 0; i < depth.size(); ++i) covered[i] = depth[i] != clear ? 1 : 0;
    return covered;
}

int CoveredMean(const raster::Image8& image, const std::vector<uint8_t>& covered,
                const SubpixelLayout& layout, uint32_t pixel, double rgba[4]) {
    return Mean(
        image, covered, layout, pixel, [](uint8_t v) { return v / 255.0; }, rgba);
}

int CoveredMean(const raster::ImageF& image, const std::vector<uint8_t>& covered,
                const SubpixelLayout& layout, uint32_t pixel, double rgba[4]) {
    return Mean(
        image, covered, layout, pixel, [](float v) { return static_cast<double>(v); }, rgba);
}

}  // namespace pem::runtime
