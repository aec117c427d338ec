// SPDX-License-Identifier: MIT
// texel_index.h — the one numbering of texels shared by raster/ (taps), infer/ (columns of A)
// and every file format that stores a rendering matrix.
//
// Global texel index of texel (i, j) of face f, level l of texture k of a Frame:
//   TexelBase(k) + LevelBase(k, l) + (f * h_l + j) * w_l + i
// where TexelBase(k) = sum of the texel counts of textures 0..k-1 (all levels, all faces),
// LevelBase(k, l) = Faces(k) * sum_{l' < l} w_l' * h_l', w_l = max(1, width >> l),
// h_l = max(1, height >> l). Faces are in GL order (+X, -X, +Y, -Y, +Z, -Z), i is the column
// along s and j the row along t (frame.h).
// A matrix over colour channels numbers column (texel, channel) as 4 * texel + channel, and row
// (pixel, channel) as 4 * (row * width + x) + channel with rows top-down.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/frame.h"

namespace pem::raster {

class TexelIndexer {
  public:
    explicit TexelIndexer(const std::vector<Texture>& textures);

    uint32_t Index(int texture, int level, int face, int i, int j) const {
        const Layout& t = layout_[static_cast<size_t>(texture)];
        const int w = std::max(1, t.width >> level), h = std::max(1, t.height >> level);
        return t.levelBase[static_cast<size_t>(level)] +
               static_cast<uint32_t>((face * h + j) * w + i);
    }
    // First global index of a texture's level (the texel (0, 0) of face 0).
    uint32_t LevelBase(int texture, int level) const {
        return layout_[static_cast<size_t>(texture)].levelBase[static_cast<size_t>(level)];
    }
    uint32_t TotalTexels() const { return total_; }

  private:
    struct Layout {
        int width, height;
        std::vector<uint32_t> levelBase;  // global index of each level's first texel
    };
    std::vector<Layout> layout_;
    uint32_t total_ = 0;
};

}  // namespace pem::raster
