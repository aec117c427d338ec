// SPDX-License-Identifier: MIT
// frame.cpp — definitions of the named BlendState presets declared in frame.h, and the texel
// value helpers.
// Conventions: the same factors for RGB and alpha, equation ADD (gl_ref_case/1 blend table).
// Not here: blending arithmetic (the rasterizer's job).
#include "raster/frame.h"

#include <bit>
#include <cstring>

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

double TexelValue(const Texture& t, int level, size_t i) {
    const std::vector<uint8_t>& bytes = t.levels[static_cast<size_t>(level)];
    if (t.format == TexelFormat::Rgba8) return bytes[i] / 255.0;
    float v;
    std::memcpy(&v, bytes.data() + 4 * i, 4);
    return static_cast<double>(v);
}

std::vector<float> FloatsFromBytes(const std::vector<uint8_t>& bytes) {
    static_assert(std::endian::native == std::endian::little);
    std::vector<float> f(bytes.size() / 4);
    std::memcpy(f.data(), bytes.data(), 4 * f.size());
    return f;
}

std::vector<uint8_t> FloatBytes(std::span<const float> values) {
    static_assert(std::endian::native == std::endian::little);
    std::vector<uint8_t> bytes(4 * values.size());
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

}  // namespace pem::raster
