// SPDX-License-Identifier: MIT
// lod_impl.h — implementation of lod.h, compiled into each fragment-stage variant (fragment.h).
#pragma once
#include <algorithm>
#include <cmath>

#include "raster/aniso.h"
#include "raster/lod.h"
#include "raster/numeric.h"

namespace pem::raster::isa {
namespace {

PipeLodState DerivePipeLodState(const SamplerState& s, int /*numLevels*/) {
    // What Mesa's GL state tracker passes down: the bias clamped to [-16, 16] and quantised to
    // 1/256, min_lod clamped to >= 0, max_lod as given. llvmpipe applies a clamp only when it
    // can matter: min_lod > 0, max_lod < 15 (and neither when min_lod == max_lod: then the LOD
    // is min_lod itself).
    PipeLodState st;
    const float bias = std::clamp(s.lodBias, -16.0f, 16.0f);
    st.lodBias = std::round(bias * 256.0f) / 256.0f;
    st.minLod = std::max(s.minLod, 0.0f);
    st.maxLod = s.maxLod;
    st.biasNonZero = st.lodBias != 0.0f;
    st.maxAnisotropy = PipeMaxAnisotropy(s.maxAnisotropy);
    const bool lodUsed = s.mipFilter != MipFilter::None || s.minFilter != s.magFilter;
    if (lodUsed) {
        if (st.minLod == st.maxLod) {
            st.minMaxEqual = true;
        } else {
            st.applyMinLod = st.minLod > 0.0f;
            st.applyMaxLod = st.maxLod < 15.0f;
        }
    }
    return st;
}

[[gnu::always_inline]] inline float LambdaFromRhoSquared(float rhoSquared, const PipeLodState& st,
                                                         bool exactLog2) {
    if (st.minMaxEqual) return st.minLod;
    float lambda;
    if (exactLog2)
        lambda = static_cast<float>(0.5 * std::log2(static_cast<double>(rhoSquared)));
    else
        lambda = FastLog2(rhoSquared) * 0.5f;
    if (st.biasNonZero) lambda = lambda + st.lodBias;
    if (st.applyMaxLod) lambda = lambda < st.maxLod ? lambda : st.maxLod;  // minps
    if (st.applyMinLod) lambda = lambda > st.minLod ? lambda : st.minLod;  // maxps
    return lambda;
}

[[gnu::always_inline]] inline LodResult LevelsFor(float lambda, MipFilter mip, int numLevels) {
    LodResult r;
    r.magnify = lambda <= 0.0f;  // lod_positive: unordered lambda > 0 (NaN minifies)
    const int last = numLevels - 1;
    switch (mip) {
        case MipFilter::None:
            break;
        case MipFilter::Nearest: {
            const int level = RoundHalfEvenI32(lambda);
            r.level0 = r.level1 = std::clamp(level, 0, last);
            break;
        }
        case MipFilter::Linear: {
            const float fl = std::floor(lambda);
            float frac = lambda - fl;
            int l0 = TruncI32(fl);
            int l1 = l0 + 1;
            if (l0 < 0) {
                l0 = l1 = 0;
                frac = 0.0f;
            }
            if (l0 >= last) {
                l0 = l1 = last;
                frac = 0.0f;
            }
            r.level0 = l0;
            r.level1 = l1;
            r.frac = frac;
            break;
        }
    }
    return r;
}

[[gnu::always_inline]] inline LodResult SelectLod(float rhoSquared, const PipeLodState& st,
                                                  MipFilter mip, int numLevels, bool exactLog2) {
    const bool shortcut = !exactLog2 && !st.biasNonZero && !st.applyMinLod && !st.applyMaxLod &&
                          !st.minMaxEqual && mip != MipFilter::Linear;
    if (!shortcut)
        return isa::LevelsFor(isa::LambdaFromRhoSquared(rhoSquared, st, exactLog2), mip, numLevels);
    LodResult r;
    r.magnify = rhoSquared <= 1.0f;  // lod_positive: unordered rho > 1 (NaN minifies)
    if (mip == MipFilter::Nearest) {
        const int e = static_cast<int>((FloatBits(rhoSquared) >> 23) & 255u) - 126;
        r.level0 = r.level1 = std::clamp(e >> 1, 0, numLevels - 1);
    }
    return r;
}

}  // namespace
}  // namespace pem::raster::isa
