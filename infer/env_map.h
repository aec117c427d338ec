// SPDX-License-Identifier: MIT
// env_map.h — the inferred environment map as a value type: a float RGBA cube map or 2D map
// (runtime/parameterization.h's layouts) with every MIP level, and its conversions to and from
// the solver's vector and raster's RGBA8 Texture.
//
// Conventions: levels[l] holds the level's texels of 4 floats (RGBA, premultiplied as the pixels
// are) in raster::Texture's order: a cube's 6 * n_l * n_l face-major in GL face order, texel
// (i, j) at ((face * n_l + j) * n_l + i) * 4; a 2D map's w_l * h_l rows, texel (i, j) at
// (j * w_l + i) * 4; n_l = max(1, size >> l) (h_l likewise from height). A map of a two-image
// layout (runtime/parameterization.h) has two charts, stored as a 2D map's faces: level l holds
// chart 0's w_l * h_l texels, then chart 1's. The solver's local order (regularizer.h), so its
// column 4 * texel + c maps to element 4 * texel + c of the concatenated levels. The hardware
// gets one texture per chart (a cube: one): the 8-bit copy RNE(clamp(v, 0, 1) * 255) per
// component, or the floats themselves (RGBA32F).
// Not here: files (pem_file.h).
#pragma once

#include <span>
#include <vector>

#include "infer/regularizer.h"
#include "infer/vector_ops.h"
#include "raster/frame.h"

namespace pem::infer {

struct EnvMapF {
    raster::TextureKind kind = raster::TextureKind::Cube;
    int size = 0;                            // level-0 width (a cube's face size)
    int height = 0;                          // level-0 height of a 2D map (cubes: ignored, = size)
    int charts = 1;                          // a 2D map's images (textures): 1 or 2
    std::vector<std::vector<float>> levels;  // see the header comment

    bool IsCube() const { return kind == raster::TextureKind::Cube; }
    int Faces() const { return IsCube() ? 6 : charts; }
    int NumLevels() const { return static_cast<int>(levels.size()); }
    int LevelSize(int level) const { return std::max(1, size >> level); }
    int LevelHeight(int level) const {
        return IsCube() ? LevelSize(level) : std::max(1, height >> level);
    }
    // Texels of one level, every face.
    size_t LevelTexels(int level) const {
        return static_cast<size_t>(Faces()) * static_cast<size_t>(LevelSize(level)) *
               static_cast<size_t>(LevelHeight(level));
    }
    bool operator==(const EnvMapF& o) const {
        return kind == o.kind && size == o.size && LevelHeight(0) == o.LevelHeight(0) &&
               Faces() == o.Faces() && levels == o.levels;
    }
};

// The solver's local vector (layout.firstTexel must be 0) as a map of the layout's shape, and
// back.
EnvMapF EnvMapFromSolution(const Vector& x, const TexelLayout& layout);
Vector SolutionFromEnvMap(const EnvMapF& map);

// The 8-bit copy of a solution over every local texel of `layout` (a cube or a 2D map of
// runtime/parameterization.h's layouts), with the given sampler state: one texture per chart.
std::vector<raster::Texture> Texture8FromSolution(const Vector& x, const TexelLayout& layout,
                                                  const raster::SamplerState& sampler);

// The 8-bit copy with the given sampler state (a 2D map keeps the sampler's wrap modes), one
// texture per chart, and the inverse conversion (bytes / 255) of a map's textures.
std::vector<raster::Texture> ToTextures8(const EnvMapF& map, const raster::SamplerState& sampler);
EnvMapF FromTextures8(std::span<const raster::Texture> textures);

// The hardware's copy in `format`: ToTextures8, or RGBA32F textures holding the floats as they
// are.
std::vector<raster::Texture> ToTextures(const EnvMapF& map, const raster::SamplerState& sampler,
                                        raster::TexelFormat format);

}  // namespace pem::infer
