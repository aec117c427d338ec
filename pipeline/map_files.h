// SPDX-License-Identifier: MIT
// map_files.h — the image files of one PEM map: <stem>.exr (the float map, infer/pem_file.h)
// and <stem>.png (its 8-bit copy for people: levels stacked, a cube's six faces or a two-image
// map's two charts side by side).
// Written by infer and by unpack (pem_pack.h); the renderers read the EXR.
#pragma once

#include <span>
#include <string>

#include "infer/env_map.h"
#include "raster/frame.h"

namespace pem::pipeline {

// The 8-bit copy (a map's textures: one, or two charts) as one PNG (each file appears
// atomically).
void WriteTexturePng(std::span<const raster::Texture> textures, const std::string& path);

// stem.exr from `map` and stem.png from its 8-bit copy `textures`.
void WriteMapImages(const infer::EnvMapF& map, std::span<const raster::Texture> textures,
                    const std::string& stem, int threads);

}  // namespace pem::pipeline
