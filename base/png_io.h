// SPDX-License-Identifier: MIT
// png_io.h — write an RGBA8 image (rows top-down, frame.h) as an 8-bit RGBA PNG via libpng.
// Conventions: the file appears atomically: written to `<path>.tmp.<pid>`, then renamed.
// Not here: reading PNGs, colour management (no gAMA/sRGB chunks are written).
#pragma once

#include <string>

#include "base/image8.h"
#include "base/input_error.h"

namespace pem::base {

// Throws pem::InputError("<path>: <cause>") if the image is empty or the file cannot be written;
// no partial file is left behind.
void WritePng(const std::string& path, const Image8& image);

}  // namespace pem::base
