// SPDX-License-Identifier: MIT
// sampler_paths.h — the two filtering paths of llvmpipe's sampler, internal to raster/:
//  - FilterFloat: the float "SoA" path (seamless cubes with a linear filter, and the `linear`
//    profile for everything): texels c * fl(1/255), float bilinear lerps fma(w, b - a, a),
//    seamless edges and corners, float MIP lerp.
//  - FilterFixed8: the 8-bit fixed-point "AoS" path (2D RGBA8 textures, non-seamless cubes,
//    nearest-filtered cubes): 8-bit weights, lerps with intermediate rounding to 8 bits.
// Both emit taps with the ideal linear weights of the texels they read.
#pragma once

#include <array>

#include "raster/lod.h"
#include "raster/sampler.h"

namespace pem::raster {

struct LaneSample {
    int texture = 0;
    std::array<int, kLanes> face{};
    std::array<float, kLanes> s{}, t{};
    std::array<LodResult, kLanes> lod{};
};

// True when llvmpipe samples this texture with its 8-bit AoS path.
bool UsesAosPath(const Texture& t);

void FilterFloat(const PreparedFrame& frame, const Texture& tex, const PreparedTexture& pt,
                 bool exactTexels, const LaneSample& ls, std::array<RgbaF, kLanes>* colour,
                 std::array<PixelTaps, kLanes>* taps);

void FilterFixed8(const PreparedFrame& frame, const Texture& tex, const PreparedTexture& pt,
                  const LaneSample& ls, std::array<RgbaF, kLanes>* colour,
                  std::array<PixelTaps, kLanes>* taps);

}  // namespace pem::raster
