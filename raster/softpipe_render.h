// SPDX-License-Identifier: MIT
// softpipe_render.h — the `softpipe` profile's frame loop: a frame drawn the way Mesa 22.3.6
// softpipe draws it into an RGBA8 FBO (docs/raster-model.md §12).
//
//   RenderResult r = RenderSoftpipe(PreparedFrame(frame));   // via Render(), profile softpipe
//
//  - Vertices: the draw module without LLVM (clip.h, ViewportForm::Plain).
//  - Setup and scan conversion in float (softpipe_setup.h), 2x2 quads in span order.
//  - Depth (sp_quad_depth_test.c), before shading: z = a0 + dzdx x + dzdy y per quad like
//    every attribute; a Z16 buffer with depth writes (and no GL_DEPTH_CLAMP) takes softpipe's
//    write path, which scales the first quad of each 16-pixel chunk to ushort and steps the
//    others by (ushort)(dzdx * 65535); otherwise (unsigned)(z * 65535.0f) or (z * 16777215.0f)
//    (Z24X8: compared with the stored word's low 24 bits, unsigned) or the float (Z32F), z
//    clamped to [0, 1] only under GL_DEPTH_CLAMP. The clear value is util_pack_z's (depth.h).
//  - Fragments: per quad, a = a0 + dadx * x + dady * y at the quad's corner, the other three
//    pixels a + dadx, a + dady, (a + dadx) + dady; perspective attributes divided (not
//    multiplied) by the interpolated 1/w. Colour = texture(u0) * texture(u1) * colour, the
//    texture units sampled by softpipe_sampler.h.
//  - The colour buffer is a float tile cache: the clear colour as glClearColor's floats. An
//    unblended fragment colour is stored as it is (a core context does not clamp fragment
//    colours: 1.5 stays 1.5 for the next pass to blend with); a blended one is clamped to
//    [0, 1] (Mesa's CLAMP: a NaN gives 0), blended in float against the stored float (no 8-bit
//    step between passes) and clamped again. At the end each value is packed by
//    float_to_ubyte: 0 unless x > 0, 255 from 1 on, else the low byte of x * (255/256) + 32768
//    in float.
//  - The whole draw runs with denormals flushed (draw_vbo sets DAZ|FTZ).
// Not here: threads (one thread draws the frame, as softpipe does).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raster/matrix_rows.h"
#include "raster/render.h"

namespace pem::raster {

RenderResult RenderSoftpipe(const PreparedFrame& frame);

// Matrix mode (render.h BuildRenderingMatrix, profile softpipe): the frame drawn as above while
// each fragment's texels go to its pixel's rows (*rows: one per pixel and channel, rows
// top-down) and matrix->offset / matrix->fragments (sized by the caller). Unit 0's texels with
// softpipe's weights (the sample is linear in the texels: bilinear and MIP lerps, EWA's
// normalised weights, the tile cache's substitutions), unit 1 and the colour folded in.
void SoftpipeMatrixRows(const PreparedFrame& frame, RenderingMatrix* matrix, MatrixRows* rows);

// softpipe's float -> unorm8 (u_math.h float_to_ubyte).
uint8_t SoftpipeUbyte(float x);

}  // namespace pem::raster
