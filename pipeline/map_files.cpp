// SPDX-License-Identifier: MIT
// map_files.cpp — a map's EXR and PNG (map_files.h).
#include "pipeline/map_files.h"

#include "base/png_io.h"
#include "infer/pem_file.h"

namespace pem::pipeline {

void WriteTexturePng(const raster::Texture& texture, const std::string& path) {
    int height = 0;
    for (int l = 0; l < texture.NumLevels(); ++l) height += texture.LevelHeight(l);
    base::Image8 img{6 * texture.width, height, {}};
    img.rgba.assign(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4, 0);
    int y0 = 0;
    for (int l = 0; l < texture.NumLevels(); ++l) {
        const int n = texture.LevelWidth(l);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    for (int c = 0; c < 4; ++c)
                        img.rgba[(static_cast<size_t>(y0 + j) * static_cast<size_t>(img.width) +
                                  static_cast<size_t>(f * n + i)) *
                                     4 +
                                 static_cast<size_t>(c)] =
                            texture.levels[static_cast<size_t>(l)]
                                          [((static_cast<size_t>(f) * n + j) * n + i) * 4 + c];
        y0 += n;
    }
    base::WritePng(path, img);
}

void WriteMapImages(const infer::CubeMapF& map, const raster::Texture& texture,
                    const std::string& stem, int threads) {
    infer::WriteCubeMapExr(map, stem + ".exr", threads);
    WriteTexturePng(texture, stem + ".png");
}

}  // namespace pem::pipeline
