// SPDX-License-Identifier: MIT
// png_io.h — RGBA8 images (rows top-down, image8.h) as PNG files via libpng: the writer and,
// beside it, the reader (any PNG: grey, palette, 16-bit and alpha-less images are converted to
// 8-bit RGBA, alpha 255 where absent).
// Conventions: the written file appears atomically: `<path>.tmp.<pid>`, then renamed.
// Not here: colour management (no gAMA/sRGB chunks are written; read ones are ignored).
#pragma once

#include <string>

#include "base/image8.h"
#include "base/input_error.h"

namespace pem::base {

// Throws pem::InputError("<path>: <cause>") if the image is empty or the file cannot be written;
// no partial file is left behind.
void WritePng(const std::string& path, const Image8& image);

// Throws pem::base::InputError("<path>: <cause>") for a missing, truncated or malformed file, or
// one larger than 16384 × 16384.
Image8 ReadPng(const std::string& path);

}  // namespace pem::base
