// SPDX-License-Identifier: MIT
// display_image.cpp — sRGB display conversion (display_image.h).
#include "base/display_image.h"

#include <algorithm>
#include <cmath>

#include "base/worker_pool.h"

namespace pem::base {

uint8_t ToDisplay(float v, float exposure) {
    const float c = std::clamp(v * exposure, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(s * 255.0f));
}

Image8 ToDisplayImage(const std::vector<float>& data, int width, int height, int channels,
                      float exposure, int threads) {
    Image8 out{width, height, {}};
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    out.rgba.resize(4 * n);
    const int parts = std::clamp(threads, 1, std::max(1, height));
    RunOnWorkers(parts, [&](int part) {
        const size_t first = n * static_cast<size_t>(part) / static_cast<size_t>(parts);
        const size_t last = n * static_cast<size_t>(part + 1) / static_cast<size_t>(parts);
        for (size_t p = first; p < last; ++p) {
            for (size_t c = 0; c < 3; ++c)
                out.rgba[4 * p + c] =
                    ToDisplay(data[p * static_cast<size_t>(channels) + c], exposure);
            out.rgba[4 * p + 3] = 255;
        }
    });
    return out;
}

}  // namespace pem::base
