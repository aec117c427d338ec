// SPDX-License-Identifier: MIT
// map_files.cpp — a map's EXR and PNG (map_files.h).
#include "pipeline/map_files.h"

#include <algorithm>

#include "base/png_io.h"
#include "infer/pem_file.h"

namespace pem::pipeline {

void WriteTexturePng(const raster::Texture& texture, const std::string& path) {
    // A cube's levels as rows of six faces, a 2D texture's levels stacked, left-aligned.
    const int faces = texture.kind == raster::TextureKind::Cube ? 6 : 1;
    int height = 0;
    for (int l = 0; l < texture.NumLevels(); ++l) height += texture.LevelHeight(l);
    base::Image8 img{faces * texture.width, height, {}};
    img.rgba.assign(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4, 0);
    int y0 = 0;
    for (int l = 0; l < texture.NumLevels(); ++l) {
        const size_t w = static_cast<size_t>(texture.LevelWidth(l));
        const size_t h = static_cast<size_t>(texture.LevelHeight(l));
        const std::vector<uint8_t>& level = texture.levels[static_cast<size_t>(l)];
        for (size_t f = 0; f < static_cast<size_t>(faces); ++f)
            for (size_t j = 0; j < h; ++j)
                std::copy_n(level.begin() + static_cast<std::ptrdiff_t>(((f * h + j) * w) * 4),
                            w * 4,
                            img.rgba.begin() +
                                static_cast<std::ptrdiff_t>(((static_cast<size_t>(y0) + j) *
                                                                 static_cast<size_t>(img.width) +
                                                             f * w) *
                                                            4));
        y0 += static_cast<int>(h);
    }
    base::WritePng(path, img);
}

void WriteMapImages(const infer::EnvMapF& map, const raster::Texture& texture,
                    const std::string& stem, int threads) {
    infer::WriteEnvMapExr(map, stem + ".exr", threads);
    WriteTexturePng(texture, stem + ".png");
}

}  // namespace pem::pipeline
