// SPDX-License-Identifier: MIT
// map_files.h — the image files of one PEM map: <stem>.exr (the float map, infer/pem_file.h)
// and <stem>.png (its 8-bit copy for people: levels stacked, a cube's six faces side by side).
// Written by infer and by unpack (pem_pack.h); the renderers read the EXR.
#pragma once

#include <string>

#include "infer/env_map.h"
#include "raster/frame.h"

namespace pem::pipeline {

// The 8-bit copy as one PNG (each file appears atomically).
void WriteTexturePng(const raster::Texture& texture, const std::string& path);

// stem.exr from `map` and stem.png from its 8-bit copy `texture`.
void WriteMapImages(const infer::EnvMapF& map, const raster::Texture& texture,
                    const std::string& stem, int threads);

}  // namespace pem::pipeline
