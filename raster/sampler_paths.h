// SPDX-License-Identifier: MIT
// sampler_paths.h — the two filtering paths of llvmpipe's sampler, internal to raster/:
//  - FilterFloat: the float "SoA" path (seamless cubes with a linear filter, and the `linear`
//    profile for everything): texels c * fl(1/255), float bilinear lerps fma(w, b - a, a),
//    seamless edges and corners, float MIP lerp.
//  - FilterFixed8: the 8-bit fixed-point "AoS" path (2D RGBA8 textures, non-seamless cubes,
//    nearest-filtered cubes): 8-bit weights, lerps with intermediate rounding to 8 bits.
// Both emit taps with the ideal linear weights of the texels they read. The paths live in
// sample_float_impl.h and sample_fixed8_impl.h; this header holds what they share.
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
    unsigned live = 0xFF;  // lanes whose colour is used (the others only steer vector choices)
};

}  // namespace pem::raster
