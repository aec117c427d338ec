// SPDX-License-Identifier: MIT
// image8.h — an RGBA8 picture, the one 8-bit image type of pemref (raster/'s framebuffer, PNG
// files, previews, the terminal viewer).
// Conventions: rows top-down (row 0 is the top of the picture), 4 bytes per pixel (R, G, B, A),
// no padding: byte 4·(y·width + x) + c.
#pragma once

#include <cstdint>
#include <vector>

namespace pem::base {

struct Image8 {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    bool operator==(const Image8&) const = default;
};

}  // namespace pem::base
