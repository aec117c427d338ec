// SPDX-License-Identifier: MIT
// frame.cpp — definitions of the named BlendState presets declared in frame.h.
// Conventions: the same factors for RGB and alpha, equation ADD (gl_ref_case/1 blend table).
// Not here: blending arithmetic (the rasterizer's job).
#include "raster/frame.h"

namespace pem::raster {

namespace {

BlendState Symmetric(BlendFactor src, BlendFactor dst) {
    BlendState state;
    state.enabled = true;
    state.srcRgb = state.srcAlpha = src;
    state.dstRgb = state.dstAlpha = dst;
    return state;
}

}  // namespace

BlendState BlendState::Over() {
    return Symmetric(BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha);
}
BlendState BlendState::Additive() {
    return Symmetric(BlendFactor::One, BlendFactor::One);
}
BlendState BlendState::Multiply() {
    return Symmetric(BlendFactor::DstColor, BlendFactor::Zero);
}

}  // namespace pem::raster
