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

raster::RenderingMatrix BoxFilterRows(raster::RenderingMatrix a, int width, int height, int k) {
    if (k == 1) return a;  // moved: no copy
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    raster::RenderingMatrix m;
    m.rows = static_cast<int64_t>(4 * pixels);
    m.cols = a.cols;
    m.offset.assign(4 * pixels, 0.0);
    m.rendered.assign(4 * pixels, 0.0);
    m.fragments.assign(pixels, 0);
    m.rowPtr.reserve(4 * pixels + 1);
    m.rowPtr.push_back(0);
    std::vector<std::pair<uint32_t, double>> row;
    std::vector<size_t> subpixels;
    for (uint32_t p = 0; p < pixels; ++p) {
        // Step 1: the covered subpixels of p.
        subpixels.clear();
        for (int s = 0; s < k * k; ++s) {
            const size_t i = SubpixelIndex(p, width, k, s);
            if (a.fragments[i] > 0) subpixels.push_back(i);
        }
        m.fragments[p] = static_cast<uint16_t>(subpixels.size());
        const double inv = subpixels.empty() ? 0.0 : 1.0 / static_cast<double>(subpixels.size());
        // Step 2: per channel, the mean of their rows (columns sorted, duplicates summed).
        for (size_t c = 0; c < 4; ++c) {
            row.clear();
            double offset = 0.0, rendered = 0.0;
            for (size_t i : subpixels) {
                const size_t r = 4 * i + c;
                for (int64_t e = a.rowPtr[r]; e < a.rowPtr[r + 1]; ++e)
                    row.emplace_back(a.col[static_cast<size_t>(e)], a.val[static_cast<size_t>(e)]);
                offset += a.offset[r];
                rendered += a.rendered[r];
            }
            std::stable_sort(row.begin(), row.end(),
                             [](const auto& x, const auto& y) { return x.first < y.first; });
            for (size_t e = 0; e < row.size(); ++e) {
                if (e > 0 && row[e].first == row[e - 1].first) {
                    m.val.back() += row[e].second * inv;
                    continue;
                }
                m.col.push_back(row[e].first);
                m.val.push_back(row[e].second * inv);
            }
            m.rowPtr.push_back(static_cast<int64_t>(m.col.size()));
            // No covered subpixel: the first one's (the clear colour).
            const size_t first = 4 * SubpixelIndex(p, width, k, 0) + c;
            m.offset[4 * p + c] = subpixels.empty() ? a.offset[first] : offset * inv;
            m.rendered[4 * p + c] = subpixels.empty() ? a.rendered[first] : rendered * inv;
        }
    }
    return m;
}

}  // namespace pem::runtime
