// SPDX-License-Identifier: MIT
// display_target.cpp — targets clipped to what the display shows (display_target.h).
#include "pipeline/display_target.h"

#include <algorithm>
#include <functional>

namespace pem::pipeline {

double WaterLevel(std::vector<std::pair<double, double>> valueWeight, double remove) {
    std::sort(valueWeight.begin(), valueWeight.end(), std::greater<>());
    // With the i + 1 brightest lowered to c: Σ_top w·(v − c) = remove; valid when c is not below
    // the next value.
    double sumWv = 0.0, sumW = 0.0;
    for (size_t i = 0; i < valueWeight.size(); ++i) {
        const auto [v, w] = valueWeight[i];
        sumWv += w * v, sumW += w;
        const double c = sumW > 0.0 ? (sumWv - remove) / sumW : v;
        if (i + 1 == valueWeight.size() || c >= valueWeight[i + 1].first) return std::max(c, 0.0);
    }
    return 0.0;
}

namespace {

// The entries of `cells` in each pixel of the W × H frame.
std::vector<std::vector<size_t>> CellsOfPixels(const std::vector<uint32_t>& cells, int kWidth,
                                               int k, int width, int height) {
    std::vector<std::vector<size_t>> of(static_cast<size_t>(width) * static_cast<size_t>(height));
    for (size_t i = 0; i < cells.size(); ++i) {
        const int x = static_cast<int>(cells[i] % static_cast<uint32_t>(kWidth));
        const int y = static_cast<int>(cells[i] / static_cast<uint32_t>(kWidth));
        of[static_cast<size_t>((y / k) * width + x / k)].push_back(i);
    }
    return of;
}

}  // namespace

void ClipToDisplay(const DisplayImages& images, const std::vector<uint32_t>& cells, int k,
                   double scale, std::vector<double>* b) {
    const trace::FloatImage& cov = *images.coverage;
    const trace::FloatImage& frame = *images.frame;
    const std::vector<std::vector<size_t>> ofPixel =
        CellsOfPixels(cells, cov.width, k, frame.width, frame.height);
    for (size_t p = 0; p < ofPixel.size(); ++p) {
        if (ofPixel[p].empty()) continue;
        const int px = static_cast<int>(p) % frame.width, py = static_cast<int>(p) / frame.width;
        const float* fg = images.fresnel->At(px, py);
        for (size_t c = 0; c < 3; ++c) {
            // Step 1: a pixel shown white gives up 1 − 1/P of its light, the brightest first.
            const double shown = static_cast<double>(frame.At(px, py)[c]);
            if (shown > 1.0) {
                std::vector<std::pair<double, double>> vw;
                double light = 0.0;
                for (size_t i : ofPixel[p]) {
                    const uint32_t cell = cells[i], w = static_cast<uint32_t>(cov.width);
                    const double weight = static_cast<double>(
                        cov.At(static_cast<int>(cell % w), static_cast<int>(cell / w))[3]);
                    vw.emplace_back((*b)[4 * i + c], weight);
                    light += weight * (*b)[4 * i + c];
                }
                const double level = WaterLevel(std::move(vw), light * (1.0 - 1.0 / shown));
                for (size_t i : ofPixel[p]) (*b)[4 * i + c] = std::min((*b)[4 * i + c], level);
            }
            // Step 2: nothing brighter than what alone whitens the pixel through F·G.
            if (fg[3] > 0.0f && fg[c] > 0.0f) {
                const double f = static_cast<double>(fg[c]) / static_cast<double>(fg[3]);
                const double cap = static_cast<double>(k * k) / (f * scale);
                for (size_t i : ofPixel[p]) (*b)[4 * i + c] = std::min((*b)[4 * i + c], cap);
            }
        }
    }
}

}  // namespace pem::pipeline
