// SPDX-License-Identifier: MIT
// display.cpp — sRGB display conversion (display.h).
#include "viewer_tty/display.h"

#include <algorithm>
#include <cmath>

namespace pem::cli {

uint8_t ToDisplay(float v, float exposure) {
    const float c = std::clamp(v * exposure, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(s * 255.0f));
}

raster::Image8 ToDisplayImage(const std::vector<float>& data, int width, int height, int channels,
                              float exposure) {
    raster::Image8 out{width, height, {}};
    out.rgba.reserve(static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
    for (size_t p = 0; p < static_cast<size_t>(width) * static_cast<size_t>(height); ++p) {
        for (size_t c = 0; c < 3; ++c)
            out.rgba.push_back(ToDisplay(data[p * static_cast<size_t>(channels) + c], exposure));
        out.rgba.push_back(255);
    }
    return out;
}

}  // namespace pem::cli
