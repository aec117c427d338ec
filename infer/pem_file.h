// SPDX-License-Identifier: MIT
// pem_file.h — the inferred environment map on disk: a tiled, mip-mapped OpenEXR cube map
// (ImfEnvmap cube layout, float RGBA), readable by OpenEXR's tools (exrheader, exrenvmap).
//
// Layout (docs/deps.md §5): level 0 is N wide by 6N tall, the faces stacked top to bottom in the
// order +X, -X, +Y, -Y, +Z, -Z, each face oriented as ImfEnvmap.h draws it. A texel keeps its
// direction: our texel (face, i, j) goes to the EXR pixel whose CubeMap::direction is the
// direction of that texel's centre in GL's face table (the per-face flips/transposition are
// derived once from OpenEXR's helpers, not written by hand). OpenEXR's mip chain (ROUND_DOWN)
// has floor(log2(6N)) + 1 levels; every level is written. Levels that are cube maps but absent
// from the map, and the degenerate tail levels (1 x 3, 1 x 1: not cube maps), hold the mean of
// the map's coarsest level. The attribute "pemrefLevels" records how many levels are real; the
// reader returns exactly those (all cube levels for files without it). The file appears
// atomically (base/atomic_file.h), so readers never see a half-written file.
// Not here: the 8-bit copy (cube_map.h ToTexture8; PNG/case files are viewer_tty's).
#pragma once

#include <string>
#include <vector>

#include "infer/cube_map.h"

namespace pem::infer {

// floor(log2(6 n)) + 1: the levels of OpenEXR's ROUND_DOWN chain for an n x 6n image.
int ExrLevelCount(int size);

// ZIP compression at zlib level 1 (fast; any OpenEXR reader reads it). `threads` > 1 lets
// OpenEXR compress tiles in parallel (the file's bytes do not depend on it).
void WriteCubeMapExr(const CubeMapF& map, const std::string& path, int threads = 1);
CubeMapF ReadCubeMapExr(const std::string& path);

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
