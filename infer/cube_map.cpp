// SPDX-License-Identifier: MIT
// cube_map.cpp — conversions of the inferred cube map (cube_map.h).
#include "infer/cube_map.h"

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

CubeMapF CubeMapFromSolution(const Vector& x, const TexelLayout& layout) {
    if (layout.firstTexel != 0 || static_cast<int64_t>(x.size()) != kChannels * layout.TexelCount())
        throw std::invalid_argument("CubeMapFromSolution: size differs from the layout");
    CubeMapF map;
    map.size = layout.size;
    size_t k = 0;
    for (int l = 0; l < layout.levels; ++l) {
        const int n = layout.LevelSize(l);
        std::vector<float> level(static_cast<size_t>(6 * n * n * kChannels));
        for (float& v : level) v = static_cast<float>(x[k++]);
        map.levels.push_back(std::move(level));
    }
    return map;
}

Vector SolutionFromCubeMap(const CubeMapF& map) {
    Vector x;
    for (const auto& level : map.levels)
        for (float v : level) x.push_back(static_cast<double>(v));
    return x;
}

raster::Texture ToTexture8(const CubeMapF& map, const raster::SamplerState& sampler) {
    raster::Texture t;
    t.kind = raster::TextureKind::Cube;
    t.width = t.height = map.size;
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

CubeMapF FromTexture8(const raster::Texture& texture) {
    if (texture.kind != raster::TextureKind::Cube)
        throw std::invalid_argument("FromTexture8: not a cube");
    CubeMapF map;
    map.size = texture.width;
    for (const auto& level : texture.levels) {
        std::vector<float> values(level.size());
        for (size_t k = 0; k < level.size(); ++k) values[k] = static_cast<float>(level[k] / 255.0);
        map.levels.push_back(std::move(values));
    }
    return map;
}

}  // namespace pem::infer
