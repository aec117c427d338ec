// SPDX-License-Identifier: MIT
// blend.h — framebuffer blending. Blend8 is llvmpipe's 8-bit integer arithmetic (the source is
// first converted to unorm8, factors are 8-bit, products use Mul8, sums saturate); BlendF is the
// `linear` profile's float blend on unclamped values (exact GL formulas, no rounding to 8 bits);
// BlendFloatLlvmpipe is llvmpipe's blend into an RGBA32F colour buffer (unclamped floats, its
// factorisations: docs/raster-model.md).
// Not here: the float -> unorm8 conversion of the source (numeric.h).
#pragma once

#include <array>
#include <cstdint>

#include "raster/frame.h"

namespace pem::raster {

using Rgba8 = std::array<uint8_t, 4>;
using RgbaF = std::array<float, 4>;

Rgba8 Blend8(const BlendState& state, const Rgba8& src, const Rgba8& dst);
RgbaF BlendF(const BlendState& state, const RgbaF& src, const RgbaF& dst);
RgbaF BlendFloatLlvmpipe(const BlendState& state, const RgbaF& src, const RgbaF& dst);

}  // namespace pem::raster
