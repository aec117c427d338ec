// SPDX-License-Identifier: MIT
// lod.h — level-of-detail selection as llvmpipe's lp_build_lod_selector computes it, and the
// mapping from LOD to the MIP level(s) to sample.
//
//  lambda = 0.5 * FastLog2(rho^2)   (rho^2 from squared scaled derivatives; Inf/NaN -> 0)
//         + lodBias                 (when non-zero)
//  then min(lambda, maxLod) and max(lambda, minLod) when the GL state asks for them, magnified
//  when lambda <= 0. MIP linear: floor/fraction, levels clamped to [0, last] with the fraction
//  zeroed at the ends; MIP nearest: round half away from zero (see LevelsFor).
// Not here: derivatives (cube_lookup.h for cubes, sampler_impl.h for 2D). Implemented in
// lod_impl.h.
#pragma once

#include "raster/frame.h"

namespace pem::raster {

// The pipe sampler state the GL state tracker derives from a SamplerState.
struct PipeLodState {
    float lodBias = 0, minLod = 0, maxLod = 0;
    bool applyMinLod = false, applyMaxLod = false, biasNonZero = false;
    bool minMaxEqual = false;
    int maxAnisotropy = 0;  // the pipe's max_anisotropy (aniso.h): > 1 selects the aniso path
};

PipeLodState DerivePipeLodState(const SamplerState& s, int numLevels);

struct LodResult {
    bool magnify = false;  // lambda <= 0: the mag filter applies
    int level0 = 0, level1 = 0;
    float frac = 0;  // weight of level1 (MIP linear)
};

// lambda from rho^2 with llvmpipe's arithmetic (exactLog2: GL-spec variant with log2 in double).
float LambdaFromRhoSquared(float rhoSquared, const PipeLodState& st, bool exactLog2);

// MIP level(s) of a lambda for the sampler's MIP filter and the texture's level count.
LodResult LevelsFor(float lambda, MipFilter mip, int numLevels);

// The whole selection from rho^2, including llvmpipe's shortcut for MIP none/nearest without
// bias or clamps: level = floor((exponent(rho^2) + 1) / 2) from the float's exponent bits,
// magnified when rho^2 <= 1 (this differs from rounding 0.5 * FastLog2 at some powers of two).
LodResult SelectLod(float rhoSquared, const PipeLodState& st, MipFilter mip, int numLevels,
                    bool exactLog2);

}  // namespace pem::raster
