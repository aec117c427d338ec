// SPDX-License-Identifier: MIT
#include "raster/texel_index.h"

namespace pem::raster {

TexelIndexer::TexelIndexer(const std::vector<Texture>& textures) {
    uint64_t next = 0;
    for (const Texture& t : textures) {
        Layout layout{t.width, t.height, {}};
        for (int l = 0; l < t.NumLevels(); ++l) {
            layout.levelBase.push_back(static_cast<uint32_t>(next));
            next += static_cast<uint64_t>(t.Faces()) * static_cast<uint64_t>(t.LevelWidth(l)) *
                    static_cast<uint64_t>(t.LevelHeight(l));
        }
        layout_.push_back(std::move(layout));
    }
    total_ = static_cast<uint32_t>(next);  // < 2^32: the loader caps texture sizes
}

}  // namespace pem::raster
