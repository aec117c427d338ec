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
// Texel numbering (TexelLayout) is local to the unknown texture: texel (level, face, i, j) is
// firstTexel + LevelBase(level) + (face * h_l + j) * w_l + i, the raster/texel_index.h layout.
// 2D textures: neighbours within each level's w_l x h_l grid (around s when it repeats), the
// pyramid's children 4, 2 or 1 as the level halves both sizes, one or neither. A map of two
// equal 2D textures (the two-image layouts: consecutive textures of the frame) is one layout
// whose charts are its faces, numbered level by level as a cube's faces are (no neighbours
// across charts); raster numbers them texture by texture, so the unknowns' order differs from
// the frame's by the permutation LocalOfFrameOrder / FrameOrderOfLocal.
// Not here: weights per texel, the prior's value (problem.h).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "infer/sparse.h"
#include "raster/frame.h"

namespace pem::infer {

// A texel of one level: face (GL order +X, -X, +Y, -Y, +Z, -Z; 0 for a 2D texture), column i
// along s, row j along t.
struct FaceTexel {
    int face = 0, i = 0, j = 0;
    bool operator==(const FaceTexel&) const = default;
};

enum class Edge { Left, Right, Up, Down };  // i - 1, i + 1, j - 1, j + 1

// The neighbour of t in direction e on a cube level of face size n: inside the face, or across
// the seam by the sampler's adjacency table.
FaceTexel Neighbour(const FaceTexel& t, Edge e, int n);

// The unknown texture's texels: a cube map, or a 2D texture (one of runtime/parameterization.h's
// layouts) whose neighbours are the grid's, across the s edge when s repeats.
struct TexelLayout {
    uint32_t firstTexel = 0;  // index of texel (0, 0) of face 0 of level 0
    int size = 1;             // level-0 width (a cube's face size; a power of two)
    int levels = 1;           // MIP levels present (unknowns)
    raster::TextureKind kind = raster::TextureKind::Cube;
    int height = 0;      // a 2D texture's level-0 height (a power of two); cubes: size
    bool wrapS = false;  // 2D: GL_REPEAT along s (columns 0 and w - 1 are neighbours)
    int charts = 1;      // 2D: textures of the map (2 for the two-image layouts), as faces

    int Faces() const { return kind == raster::TextureKind::Cube ? 6 : charts; }
    int LevelSize(int level) const { return std::max(1, size >> level); }  // level width
    int LevelHeight(int level) const {
        return std::max(1, (kind == raster::TextureKind::Cube ? size : height) >> level);
    }
    uint32_t LevelBase(int level) const;  // relative to firstTexel
    uint32_t Texel(int level, int face, int i, int j) const {
        const int w = LevelSize(level), h = LevelHeight(level);
        return firstTexel + LevelBase(level) + static_cast<uint32_t>((face * h + j) * w + i);
    }
    int64_t TexelCount() const { return LevelBase(levels); }
    // The texel of `level` at offset r from the level's first texel.
    FaceTexel Locate(int level, uint32_t r) const;
    // Texel index of t's neighbour in direction e: across cube seams by the sampler's adjacency;
    // in a 2D texture within the level (around s when wrapS), else t itself (no neighbour).
    uint32_t NeighbourTexel(int level, const FaceTexel& t, Edge e) const;
    // A texel's offset from firstTexel in raster's order (texture by texture, texel_index.h) to
    // the layout's (level by level), and back: the identity unless charts > 1.
    uint32_t LocalOfFrameOrder(uint32_t r) const;
    uint32_t FrameOrderOfLocal(uint32_t t) const;
};

// The layout of one texture of a frame (its kind, size, levels and wrap along s), or of
// `charts` consecutive equal 2D textures starting with it.
TexelLayout LayoutOfTexture(const raster::Texture& texture, uint32_t firstTexel = 0,
                            int charts = 1);

// Every undirected neighbour pair of one level, as (smaller, larger) texel indices of `layout`,
// sorted. Each texel of a cube surface grid has exactly 4 neighbours, so there are 12 n^2 pairs
// (a 2D level of w x h: (w - 1) h + w (h - 1), and h more when s repeats and w > 2).
std::vector<std::pair<uint32_t, uint32_t>> NeighbourPairs(const TexelLayout& layout, int level);

// Unit-weight rows (see the header comment); `cols` is the column count of the system.
CsrMatrix SmoothnessRows(const TexelLayout& layout, int64_t cols);
CsrMatrix PyramidRows(const TexelLayout& layout, int64_t cols);
CsrMatrix PriorRows(const TexelLayout& layout, int64_t cols);

// The same rows restricted to active texels, built in time proportional to them: `active` lists
// the active texels (relative to firstTexel, increasing) and index[t] is t's position in it (-1:
// inactive). A row is kept when all its texels are active, with columns 4 index[t] + c; kept
// rows stay in the order above (the rows of the full matrix whose columns are all active).
CsrMatrix SmoothnessRows(const TexelLayout& layout, const std::vector<uint32_t>& active,
                         const std::vector<int32_t>& index);
CsrMatrix PyramidRows(const TexelLayout& layout, const std::vector<uint32_t>& active,
                      const std::vector<int32_t>& index);
CsrMatrix PriorRows(const TexelLayout& layout, const std::vector<uint32_t>& active,
                    const std::vector<int32_t>& index);

}  // namespace pem::infer
