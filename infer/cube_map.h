// SPDX-License-Identifier: MIT
// cube_map.h — the inferred environment map as a value type: a float RGBA cube map with every
// MIP level, and its conversions to and from the solver's vector and raster's RGBA8 Texture.
//
// Conventions: levels[l] holds 6 * n_l * n_l texels of 4 floats (RGBA, premultiplied as the
// pixels are), face-major in GL face order, texel (i, j) at ((face * n_l + j) * n_l + i) * 4,
// n_l = max(1, size >> l): the same layout as raster::Texture and raster/texel_index.h, so the
// solver's column 4 * texel + c maps to element 4 * texel + c of the concatenated levels.
// The 8-bit copy is what the hardware gets: RNE(clamp(v, 0, 1) * 255) per component.
// Not here: files (pem_file.h).
#pragma once

#include <vector>

#include "infer/regularizer.h"
#include "infer/vector_ops.h"
#include "raster/frame.h"

namespace pem::infer {

struct CubeMapF {
    int size = 0;                            // level-0 face width
    std::vector<std::vector<float>> levels;  // see the header comment

    int NumLevels() const { return static_cast<int>(levels.size()); }
    int LevelSize(int level) const { return std::max(1, size >> level); }
    bool operator==(const CubeMapF&) const = default;
};

// The solver's local vector (layout.firstTexel must be 0) as a cube map, and back.
CubeMapF CubeMapFromSolution(const Vector& x, const TexelLayout& layout);
Vector SolutionFromCubeMap(const CubeMapF& map);

// The 8-bit copy of a solution over every local texel of `layout` (a cube or a 2D texture of
// runtime/parameterization.h's layouts), with the given sampler state.
raster::Texture Texture8FromSolution(const Vector& x, const TexelLayout& layout,
                                     const raster::SamplerState& sampler);

// The 8-bit copy with the given sampler state, and the inverse conversion (bytes / 255).
raster::Texture ToTexture8(const CubeMapF& map, const raster::SamplerState& sampler);
CubeMapF FromTexture8(const raster::Texture& texture);

}  // namespace pem::infer
