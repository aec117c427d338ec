// SPDX-License-Identifier: MIT
// env_map.cpp — conversions of the inferred environment map (env_map.h).
#include "infer/env_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
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
    map.charts = map.IsCube() ? 1 : layout.charts;
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

namespace {

// The map's textures (one per chart; a cube: one), each level holding its chart's share of the
// map's level converted by `convert` (the share's floats → the texel bytes).
template <class Convert>
std::vector<raster::Texture> Textures(const EnvMapF& map, const raster::SamplerState& sampler,
                                      raster::TexelFormat format, const Convert& convert) {
    std::vector<raster::Texture> out(map.IsCube() ? 1 : static_cast<size_t>(map.charts));
    for (size_t c = 0; c < out.size(); ++c) {
        raster::Texture& t = out[c];
        t.kind = map.kind;
        t.format = format;
        t.width = map.size;
        t.height = map.LevelHeight(0);
        t.sampler = sampler;
        for (const auto& level : map.levels) {
            const size_t n = level.size() / out.size();
            t.levels.push_back(convert(std::span<const float>(level).subspan(c * n, n)));
        }
    }
    return out;
}

}  // namespace

std::vector<raster::Texture> ToTextures8(const EnvMapF& map, const raster::SamplerState& sampler) {
    return Textures(map, sampler, raster::TexelFormat::Rgba8, [](std::span<const float> share) {
        std::vector<uint8_t> bytes(share.size());
        for (size_t k = 0; k < share.size(); ++k) bytes[k] = ToByte(share[k]);
        return bytes;
    });
}

std::vector<raster::Texture> ToTextures(const EnvMapF& map, const raster::SamplerState& sampler,
                                        raster::TexelFormat format) {
    if (format == raster::TexelFormat::Rgba8) return ToTextures8(map, sampler);
    return Textures(map, sampler, format, raster::FloatBytes);
}

std::vector<raster::Texture> Texture8FromSolution(const Vector& x, const TexelLayout& layout,
                                                  const raster::SamplerState& sampler) {
    return ToTextures8(EnvMapFromSolution(x, layout), sampler);
}

EnvMapF FromTextures8(std::span<const raster::Texture> textures) {
    if (textures.empty() ||
        (textures[0].kind != raster::TextureKind::Cube &&
         textures[0].kind != raster::TextureKind::Tex2D) ||
        (textures[0].kind == raster::TextureKind::Cube && textures.size() != 1))
        throw std::invalid_argument("FromTextures8: neither a cube nor 2D textures");
    for (const raster::Texture& t : textures)
        if (t.kind != textures[0].kind || t.width != textures[0].width ||
            t.height != textures[0].height || t.levels.size() != textures[0].levels.size())
            throw std::invalid_argument("FromTextures8: the charts differ in shape");
    EnvMapF map;
    map.kind = textures[0].kind;
    map.size = textures[0].width;
    map.height = textures[0].height;
    map.charts = static_cast<int>(textures.size());
    for (size_t l = 0; l < textures[0].levels.size(); ++l) {
        std::vector<float> values;
        for (const raster::Texture& t : textures)
            for (uint8_t b : t.levels[l]) values.push_back(static_cast<float>(b / 255.0));
        map.levels.push_back(std::move(values));
    }
    return map;
}

}  // namespace pem::infer
