// SPDX-License-Identifier: MIT
// softpipe_render.h — the `softpipe` profile's frame loop: a frame drawn the way Mesa 22.3.6
// softpipe draws it into an RGBA8 FBO (docs/raster-model.md §12).
//
//   RenderResult r = RenderSoftpipe(PreparedFrame(frame));   // via Render(), profile softpipe
//
//  - Vertices: the draw module without LLVM (clip.h, ViewportForm::Plain).
//  - Setup and scan conversion in float (softpipe_setup.h), 2x2 quads in span order.
//  - Fragments: per quad, a = a0 + dadx * x + dady * y at the quad's corner, the other three
//    pixels a + dadx, a + dady, (a + dadx) + dady; perspective attributes divided (not
//    multiplied) by the interpolated 1/w. Colour = texture(u0) * texture(u1) * colour.
//  - The colour buffer is a float tile cache: the clear colour as glClearColor's floats. An
//    unblended fragment colour is stored as it is (a core context does not clamp fragment
//    colours: 1.5 stays 1.5 for the next pass to blend with); a blended one is clamped to
//    [0, 1] (a NaN stays NaN), blended in float against the stored float (no 8-bit step between
//    passes) and clamped again. At the end each value is
//    packed by float_to_ubyte: 0 unless x > 0, 255 from 1 on, else the low byte of
//    x * (255/256) + 32768 in float.
//  - The whole draw runs with denormals flushed (draw_vbo sets DAZ|FTZ).
// Not modelled yet, and refused with std::invalid_argument: texture sampling of textures whose
// texels are not all equal, anisotropic filtering, texture coordinates that are not finite or
// large enough to leave softpipe's texel addressing, depth buffers, the rendering matrix.
#pragma once

#include <optional>
#include <string>

#include "raster/render.h"

namespace pem::raster {

// Why this model cannot draw `frame` yet, or nullopt.
std::optional<std::string> SoftpipeUnsupported(const Frame& frame);

// Throws std::invalid_argument("softpipe profile: " + SoftpipeUnsupported(frame)) if set.
RenderResult RenderSoftpipe(const PreparedFrame& frame);

// softpipe's float -> unorm8 (u_math.h float_to_ubyte).
uint8_t SoftpipeUbyte(float x);

}  // namespace pem::raster
