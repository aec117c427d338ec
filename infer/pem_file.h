// SPDX-License-Identifier: MIT
// pem_file.h — the inferred environment map on disk: a tiled, mip-mapped OpenEXR file, float
// RGBA: a cube map in ImfEnvmap's cube layout (readable by exrheader, exrenvmap), or a 2D map
// (the lat-long, sphere, paraboloid and tennis layouts of runtime/parameterization.h) as a plain
// W x H image whose level l is the texture's level l, texel (i, j) at column i, row j from the
// top, without an envmap attribute (OpenEXR's lat-long convention is not GL's texgen's; which
// layout a 2D map is, is the PEM directory's manifest.json's to say). A map of two charts (the
// paraboloid's and the tennis ball's two textures) is one image of both side by side, level by
// level (chart c at columns [c w_l, (c + 1) w_l)), with the attribute "pemrefCharts" = 2; the
// chain of the wider image has one level more than the charts' (their mean, like a cube's tail).
//
// Cubes (docs/deps.md §5): level 0 is N wide by 6N tall, the faces stacked top to bottom in the
// order +X, -X, +Y, -Y, +Z, -Z, each face oriented as ImfEnvmap.h draws it. A texel keeps its
// direction: our texel (face, i, j) goes to the EXR pixel whose CubeMap::direction is the
// direction of that texel's centre in GL's face table (the per-face flips/transposition are
// derived once from OpenEXR's helpers, not written by hand). OpenEXR's mip chain (ROUND_DOWN)
// has floor(log2(6N)) + 1 levels; every level is written. Levels that are cube maps but absent
// from the map, and the degenerate tail levels (1 x 3, 1 x 1: not cube maps), hold the mean of
// the map's coarsest level (a 2D map's chain is the texture's: absent levels only).
// The attribute "pemrefLevels" records how many levels are real; the reader returns exactly
// those (every level of the texture's chain for files without it). The file appears
// atomically (base/atomic_file.h), so readers never see a half-written file.
// Not here: the 8-bit copy (env_map.h ToTexture8; PNG/case files are viewer_tty's).
#pragma once

#include <string>
#include <vector>

#include "infer/env_map.h"

namespace pem::infer {

// floor(log2(6 n)) + 1: the levels of OpenEXR's ROUND_DOWN chain for an n x 6n image.
int ExrLevelCount(int size);

// ZIP compression at zlib level 1 (fast; any OpenEXR reader reads it). `threads` > 1 lets
// OpenEXR compress tiles in parallel (the file's bytes do not depend on it).
void WriteEnvMapExr(const EnvMapF& map, const std::string& path, int threads = 1);
// A cube when the file has a cube envmap attribute, else a 2D map.
EnvMapF ReadEnvMapExr(const std::string& path);

// One level of the file as stored (RGBA floats, rows top-down), for checks and tools.
struct ExrLevelImage {
    int width = 0, height = 0;
    std::vector<float> rgba;
};
ExrLevelImage ReadExrLevel(const std::string& path, int level);

// Where our texel (face, i, j) of a level of face size n lands in the EXR level image
// (x column, y row from the top of the n x 6n data window).
struct ExrPixel {
    int x = 0, y = 0;
};
ExrPixel ExrPixelOf(int face, int i, int j, int n);

}  // namespace pem::infer
