// SPDX-License-Identifier: MIT
// display_image.h — linear radiance → 8-bit sRGB pixels for PNG files and the terminal:
// v × exposure, clamped to [0, 1], sRGB-encoded, rounded.
#pragma once

#include <cstdint>
#include <vector>

#include "base/image8.h"

namespace pem::base {

uint8_t ToDisplay(float v, float exposure);

// `channels` floats per pixel (RGB first), rows top-down; alpha 255. `threads` > 1: row ranges
// in parallel (the same bytes).
Image8 ToDisplayImage(const std::vector<float>& data, int width, int height, int channels,
                      float exposure, int threads = 1);

}  // namespace pem::base
