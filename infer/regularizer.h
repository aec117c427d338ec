// SPDX-License-Identifier: MIT
// regularizer.h — the regularizer rows of the inference system for one cube map with every MIP
// level as unknowns (docs/method.md §5):
//  (a) smoothness L: x(a) - x(b) for every undirected pair of neighbouring texels within a level,
//      across cube seams with the sampler's adjacency (docs/hardware-model.md §2.3): inside a face
//      each texel with its right (i + 1) and down (j + 1) neighbour; across the 12 seams every
//      border texel with the texel beyond its edge (right/down alone would miss seams such as +Y
//      left / -X top), each undirected pair once: 12 n^2 pairs per level;
//  (b) pyramid coupling P: x(coarse) - mean of its four children at the next finer level;
//  (c) prior I: x itself (the right-hand side holds the constant prior value).
// Every row is repeated per colour channel: row 4 * k + c acts on columns 4 * texel + c.
//
// Weights and units (applied by problem.h as sqrt(lambda) on these unit rows): the image rows are
// pixel values in [0, 1] units, one row per (pixel, channel), weighted by the confidence w. So the
// objective is sum_pixels w (Ax - b)^2 + lambda_s sum_pairs (dx)^2 + lambda_p sum_parents
// (dx)^2 + lambda_0 sum_texels (x - xbar)^2, and lambda = 1 makes one squared texel difference
// cost as much as one squared pixel error of full confidence. Texels are in the same [0, 1]
// (8-bit) or HDR radiance units as the pixels. Each pair counts once at every level: no
// per-level or per-solid-angle scaling.
// Texel numbering (CubeLayout) is local to the unknown texture: texel (level, face, i, j) is
// firstTexel + LevelBase(level) + (face * n_l + j) * n_l + i, the raster/texel_index.h layout.
// Not here: 2D textures (cube maps only), weights per texel, the prior's value (problem.h).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "infer/sparse.h"

namespace pem::infer {

struct CubeLayout {
    uint32_t firstTexel = 0;  // index of texel (0, 0) of face 0 of level 0
    int size = 1;             // level-0 face width (a power of two)
    int levels = 1;           // MIP levels present (unknowns)

    int LevelSize(int level) const { return std::max(1, size >> level); }
    uint32_t LevelBase(int level) const;  // relative to firstTexel
    uint32_t Texel(int level, int face, int i, int j) const {
        const int n = LevelSize(level);
        return firstTexel + LevelBase(level) + static_cast<uint32_t>((face * n + j) * n + i);
    }
    int64_t TexelCount() const { return LevelBase(levels); }
};

// A texel of one level: face (GL order +X, -X, +Y, -Y, +Z, -Z), column i along s, row j along t.
struct FaceTexel {
    int face = 0, i = 0, j = 0;
    bool operator==(const FaceTexel&) const = default;
};

enum class Edge { Left, Right, Up, Down };  // i - 1, i + 1, j - 1, j + 1

// The neighbour of t in direction e on a level of face size n: inside the face, or across the
// seam by the sampler's adjacency table.
FaceTexel Neighbour(const FaceTexel& t, Edge e, int n);

// Every undirected neighbour pair of one level, as (smaller, larger) texel indices of `layout`,
// sorted. Each texel of a cube surface grid has exactly 4 neighbours, so there are 12 n^2 pairs.
std::vector<std::pair<uint32_t, uint32_t>> NeighbourPairs(const CubeLayout& layout, int level);

// Unit-weight rows (see the header comment); `cols` is the column count of the system.
CsrMatrix SmoothnessRows(const CubeLayout& layout, int64_t cols);
CsrMatrix PyramidRows(const CubeLayout& layout, int64_t cols);
CsrMatrix PriorRows(const CubeLayout& layout, int64_t cols);

// The same rows restricted to active texels, built in time proportional to them: `active` lists
// the active texels (relative to firstTexel, increasing) and index[t] is t's position in it (-1:
// inactive). A row is kept when all its texels are active, with columns 4 index[t] + c; kept
// rows stay in the order above (the rows of the full matrix whose columns are all active).
CsrMatrix SmoothnessRows(const CubeLayout& layout, const std::vector<uint32_t>& active,
                         const std::vector<int32_t>& index);
CsrMatrix PyramidRows(const CubeLayout& layout, const std::vector<uint32_t>& active,
                      const std::vector<int32_t>& index);
CsrMatrix PriorRows(const CubeLayout& layout, const std::vector<uint32_t>& active,
                    const std::vector<int32_t>& index);

}  // namespace pem::infer
