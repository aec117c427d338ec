// SPDX-License-Identifier: MIT
// golden_render.h — one golden test drawn as an RGBA8 image with a profile (raster/profile.h):
// a raster case through raster/ (the linear profile's float framebuffer rounded to 8 bits), a glTF
// scene ray traced or with the static EM, a PEM directory with any method (sRGB display images,
// exposure 1, as `pemref render` writes its PNGs).
//
//   const Rendered r = RenderTest(test, "llvmpipe", /*threads=*/2);   // r.image, r.inputSha256
//
// inputSha256: the input file's bytes (a PEM directory: its manifest.json) and the test's
// settings, so a golden records what it was made from. Same bytes for any thread count.
// Errors: base::InputError naming the input.
#pragma once

#include <string>

#include "base/image8.h"
#include "viewer_tty/golden/suite.h"

namespace pem::golden {

struct Rendered {
    base::Image8 image;
    std::string inputSha256;
};

Rendered RenderTest(const GoldenTest& test, const std::string& profile, int threads);

}  // namespace pem::golden
