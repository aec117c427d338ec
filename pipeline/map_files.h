// SPDX-License-Identifier: MIT
// map_files.h — the image files of one PEM map: <stem>.exr (the float cube map, infer/pem_file.h)
// and <stem>.png (its 8-bit copy for people: each level's six faces side by side, levels
// stacked). Written by infer and by unpack (pem_pack.h); the renderers read the EXR.
#pragma once

#include <string>

#include "infer/cube_map.h"
#include "raster/frame.h"

namespace pem::pipeline {

// The 8-bit copy as one PNG (each file appears atomically).
void WriteTexturePng(const raster::Texture& texture, const std::string& path);

// stem.exr from `map` and stem.png from its 8-bit copy `texture`.
void WriteMapImages(const infer::CubeMapF& map, const raster::Texture& texture,
                    const std::string& stem, int threads);

}  // namespace pem::pipeline
