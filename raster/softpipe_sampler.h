// SPDX-License-Identifier: MIT
// softpipe_sampler.h — texture sampling as Mesa 22.3.6 softpipe's sp_tex_sample.c does it for the
// fragment shader's TEX (implicit derivatives), restated in our own words (docs/raster-model.md
// §12), for a 2x2 quad at a time.
//
//   RgbaF colour[4];
//   SampleSoftpipeQuad(prepared.texture(i), coords, colour);
//
//  - One LOD per quad from the differences of the quad's raw coordinates (bottom row for x,
//    left column for y): 2D rho = max(max(|ds|) * w, max(|dt|) * h), cube rho =
//    max(|ds|, |dt|, |dp|) * size / 2 on the unprojected direction; lambda = fast log2 (a
//    257-entry table) + bias, clamped to [min_lod, max_lod].
//  - Cube face per pixel (x wins ties, then y), face coordinates (sign * ma' * (-0.5 / |ma|)) +
//    0.5; seamless linear taps that leave the face move to the neighbour face (corners: the
//    other coordinate clamped first); non-seamless and nearest taps clamp to the edge.
//  - 2D wrap modes as softpipe's wrap_* functions, power-of-two fast paths for repeat; a tap
//    outside the level returns the border colour (0, 0, 0, 0).
//  - Bilinear taps are read through softpipe's texture tile cache (16 direct-mapped 32x32
//    tiles): a tap whose slot a later tap of the same filter refilled reads the later tile.
//  - MIP: lambda <= 0 magnifies at level 0; nearest level trunc(lambda + 0.5); linear blends
//    trunc(lambda) and the next level by lambda - floor(lambda); floats lerp as a + w * (b - a).
//  - Anisotropy (max anisotropy >= 2 with LINEAR_MIPMAP_LINEAR): Heckbert's EWA at one level,
//    weights from a table of glibc's expf (softpipe_tables.h). A frame whose footprint boxes
//    hold more than 2^31 texels in all throws std::invalid_argument (softpipe would scan them).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/blend.h"
#include "raster/render.h"

namespace pem::raster {

// The interpolated coordinates of one texture unit at the quad's pixels (0 (x, y), 1 (x+1, y),
// 2 (x, y+1), 3 (x+1, y+1)): s, t, p (2D textures ignore p).
struct QuadCoords {
    std::array<float, 4> s, t, p;
};

// One texel a sample read and its weight: the sample is sum(weight * texel) (to float rounding).
struct SoftpipeTap {
    int level, face, x, y;  // face 0 for 2D textures
    double weight;          // the filters' weights multiplied out in double
};

// What a frame may still spend: the texels of its EWA bounding boxes (softpipe scans any box;
// a LOD clamped far below a footprint to the horizon can ask for billions per pixel).
struct SoftpipeBudget {
    static constexpr int64_t kEwaTexels = int64_t{1} << 31;
    int64_t ewaTexels = kEwaTexels;
};

// The quad's four samples; with `taps`, also the texels each one read (matrix mode). Throws
// std::invalid_argument when the frame's budget runs out.
void SampleSoftpipeQuad(const PreparedTexture& texture, const QuadCoords& coords,
                        std::array<RgbaF, 4>* colour, SoftpipeBudget* budget,
                        std::array<std::vector<SoftpipeTap>, 4>* taps = nullptr);

// softpipe's util_fast_log2: exponent plus a table of log2(1 + i / 256), i the mantissa's top
// 8 bits rounded.
float SoftpipeFastLog2(float x);

// softpipe's util_ifloor: floor through two doubles rounded to float, exact for |x| < 2^22,
// defined (not floor) beyond.
int32_t SoftpipeIfloor(float x);

}  // namespace pem::raster
