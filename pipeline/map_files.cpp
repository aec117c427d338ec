// SPDX-License-Identifier: MIT
// map_files.cpp — a map's EXR and PNG (map_files.h).
#include "pipeline/map_files.h"

#include <algorithm>

#include "base/parallel.h"
#include "base/png_io.h"
#include "infer/pem_file.h"

namespace pem::pipeline {

void WriteTexturePng(std::span<const raster::Texture> textures, const std::string& path) {
    // Each level a row of every texture's faces (a cube's six, a two-image map's two charts),
    // the levels stacked, left-aligned.
    const raster::Texture& first = textures.front();
    const int faces = first.Faces() * static_cast<int>(textures.size());
    int height = 0;
    for (int l = 0; l < first.NumLevels(); ++l) height += first.LevelHeight(l);
    base::Image8 img{faces * first.width, height, {}};
    img.rgba.assign(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4, 0);
    int y0 = 0;
    for (int l = 0; l < first.NumLevels(); ++l) {
        const size_t w = static_cast<size_t>(first.LevelWidth(l));
        const size_t h = static_cast<size_t>(first.LevelHeight(l));
        size_t column = 0;  // the face's place in the row
        for (const raster::Texture& texture : textures) {
            const std::vector<uint8_t>& level = texture.levels[static_cast<size_t>(l)];
            for (size_t f = 0; f < static_cast<size_t>(texture.Faces()); ++f, ++column)
                for (size_t j = 0; j < h; ++j)
                    std::copy_n(
                        level.begin() + static_cast<std::ptrdiff_t>(((f * h + j) * w) * 4), w * 4,
                        img.rgba.begin() +
                            static_cast<std::ptrdiff_t>(
                                ((static_cast<size_t>(y0) + j) * static_cast<size_t>(img.width) +
                                 column * w) *
                                4));
        }
        y0 += static_cast<int>(h);
    }
    base::WritePng(path, img);
}

void WriteMapImages(const infer::EnvMapF& map, std::span<const raster::Texture> textures,
                    const std::string& stem, int threads) {
    // The two files at once (the PNG's deflate on one thread beside the EXR's tiles); an error
    // is the EXR's first, as when they were written one after the other.
    base::ParallelFor(2, std::min(threads, 2), [&](int file) {
        if (file == 0)
            infer::WriteEnvMapExr(map, stem + ".exr", threads);
        else
            WriteTexturePng(textures, stem + ".png");
    });
}

}  // namespace pem::pipeline
