// SPDX-License-Identifier: MIT
// supersampling.cpp — the k×k box filter over covered subpixels (supersampling.h).
#include "runtime/supersampling.h"

#include <algorithm>
#include <utility>

#include "raster/depth.h"

namespace pem::runtime {

namespace {

template <class Image, class Scale>
int Mean(const Image& image, const std::vector<uint8_t>& covered, int width, int k, uint32_t pixel,
         Scale scale, double rgba[4]) {
    std::fill(rgba, rgba + 4, 0.0);
    int n = 0;
    for (int s = 0; s < k * k; ++s) {
        const size_t i = SubpixelIndex(pixel, width, k, s);
        if (!covered[i]) continue;
        ++n;
        for (size_t c = 0; c < 4; ++c) rgba[c] += scale(image.rgba[4 * i + c]);
    }
    if (n > 1)
        for (size_t c = 0; c < 4; ++c) rgba[c] /= n;
    return n;
}

}  // namespace

size_t SubpixelIndex(uint32_t pixel, int width, int k, int s) {
    const size_t x = pixel % static_cast<uint32_t>(width), y = pixel / static_cast<uint32_t>(width);
    const size_t i = static_cast<size_t>(s % k), j = static_cast<size_t>(s / k);
    const size_t kk = static_cast<size_t>(k);
    return (kk * y + j) * kk * static_cast<size_t>(width) + kk * x + i;
}

std::vector<uint8_t> CoveredSubpixels(const std::vector<uint32_t>& depth,
                                      const raster::DepthBuffer& buffer) {
    const uint32_t clear = raster::DepthClearValue(buffer.format, buffer.clear);
    std::vector<uint8_t> covered(depth.size());
    for (size_t i = 0; i < depth.size(); ++i) covered[i] = depth[i] != clear ? 1 : 0;
    return covered;
}

int CoveredMean(const raster::Image8& image, const std::vector<uint8_t>& covered, int width, int k,
                uint32_t pixel, double rgba[4]) {
    return Mean(
        image, covered, width, k, pixel, [](uint8_t v) { return v / 255.0; }, rgba);
}

int CoveredMean(const raster::ImageF& image, const std::vector<uint8_t>& covered, int width, int k,
                uint32_t pixel, double rgba[4]) {
    return Mean(
        image, covered, width, k, pixel, [](float v) { return static_cast<double>(v); }, rgba);
}

}  // namespace pem::runtime
