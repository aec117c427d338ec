// SPDX-License-Identifier: MIT
// env_map.cpp — conversions of the inferred environment map (env_map.h).
#include "infer/env_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace pem::infer {
namespace {

// RNE(clamp(v, 0, 1) * 255); NaN maps to 0 (std::clamp would keep it). Rounded half to even as
// nearbyint does in the default rounding mode, without a library call: adding and subtracting
// 2^52 leaves v * 255 (in [0, 255]) rounded to an integer.
uint8_t ToByte(float value) {
    const double v = value >= 0.0f ? std::min(static_cast<double>(value), 1.0) : 0.0;
    return static_cast<uint8_t>((v * 255.0 + 0x1p52) - 0x1p52);
}

}  // namespace

EnvMapF EnvMapFromSolution(const Vector& x, const TexelLayout& layout) {
    if (layout.firstTexel != 0 || static_cast<int64_t>(x.size()) != kChannels * layout.TexelCount())
        throw std::invalid_argument("EnvMapFromSolution: size differs from the layout");
    EnvMapF map;
    map.kind = layout.kind;
    map.size = layout.size;
    map.height = layout.LevelHeight(0);
    size_t k = 0;
    for (int l = 0; l < layout.levels; ++l) {
        std::vector<float> level(map.LevelTexels(l) * kChannels);
        for (float& v : level) v = static_cast<float>(x[k++]);
        map.levels.push_back(std::move(level));
    }
    return map;
}

Vector SolutionFromEnvMap(const EnvMapF& map) {
    Vector x;
    for (const auto& level : map.levels)
        for (float v : level) x.push_back(static_cast<double>(v));
    return x;
}

raster::Texture ToTexture8(const EnvMapF& map, const raster::SamplerState& sampler) {
    raster::Texture t;
    t.kind = map.kind;
    t.width = map.size;
    t.height = map.LevelHeight(0);
    t.sampler = sampler;
    for (const auto& level : map.levels) {
        std::vector<uint8_t> bytes(level.size());
        for (size_t k = 0; k < level.size(); ++k) bytes[k] = ToByte(level[k]);
        t.levels.push_back(std::move(bytes));
    }
    return t;
}

raster::Texture Texture8FromSolution(const Vector& x, const TexelLayout& layout,
                                     const raster::SamplerState& sampler) {
    if (layout.firstTexel != 0 || static_cast<int64_t>(x.size()) != kChannels * layout.TexelCount())
        throw std::invalid_argument("Texture8FromSolution: size differs from the layout");
    raster::Texture t;
    t.kind = layout.kind;
    t.width = layout.size;
    t.height = layout.LevelHeight(0);
    t.sampler = sampler;
    for (int l = 0; l < layout.levels; ++l) {
        const size_t begin = size_t{kChannels} * layout.LevelBase(l);
        const size_t end = size_t{kChannels} * layout.LevelBase(l + 1);
        std::vector<uint8_t> bytes(end - begin);
        for (size_t k = begin; k < end; ++k) bytes[k - begin] = ToByte(static_cast<float>(x[k]));
        t.levels.push_back(std::move(bytes));
    }
    return t;
}

EnvMapF FromTexture8(const raster::Texture& texture) {
    if (texture.kind != raster::TextureKind::Cube && texture.kind != raster::TextureKind::Tex2D)
        throw std::invalid_argument("FromTexture8: neither a cube nor a 2D texture");
    EnvMapF map;
    map.kind = texture.kind;
    map.size = texture.width;
    map.height = texture.height;
    for (const auto& level : texture.levels) {
        std::vector<float> values(level.size());
        for (size_t k = 0; k < level.size(); ++k) values[k] = static_cast<float>(level[k] / 255.0);
        map.levels.push_back(std::move(values));
    }
    return map;
}

}  // namespace pem::infer
