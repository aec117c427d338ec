// SPDX-License-Identifier: MIT
// material.cpp — material kind names and texture sampling with glTF samplers (material.h).
#include "trace/material.h"

#include <algorithm>
#include <cmath>

namespace pem::trace {

const char* MaterialKindName(MaterialKind kind) {
    switch (kind) {
        case MaterialKind::Diffuse:
            return "diffuse";
        case MaterialKind::Mirror:
            return "mirror";
        case MaterialKind::Glass:
            return "glass";
    }
    return "?";
}

namespace {

// GL's wrap of an integer texel coordinate i for n texels.
int Wrap(int i, int n, TexWrap mode) {
    switch (mode) {
        case TexWrap::ClampToEdge:
            return std::clamp(i, 0, n - 1);
        case TexWrap::MirroredRepeat: {
            const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
            return m < n ? m : 2 * n - 1 - m;
        }
        case TexWrap::Repeat:
            break;
    }
    const int r = i % n;
    return r < 0 ? r + n : r;
}

glm::vec3 Texel(const Texture2D& t, int x, int y) {
    const size_t at = 3 * (static_cast<size_t>(Wrap(y, t.height, t.sampler.wrapT)) *
                               static_cast<size_t>(t.width) +
                           static_cast<size_t>(Wrap(x, t.width, t.sampler.wrapS)));
    return {t.rgb[at], t.rgb[at + 1], t.rgb[at + 2]};
}

// floor(v) as an int, saturated (uv far outside [0, 1] stays finite).
int FloorInt(float v) {
    return static_cast<int>(std::clamp(std::floor(v), -1e9f, 1e9f));
}

}  // namespace

glm::vec3 SampleTexture(const Texture2D& texture, glm::vec2 uv) {
    if (texture.width <= 0 || texture.height <= 0) return glm::vec3(1.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    const float x = uv.x * static_cast<float>(texture.width);
    const float y = uv.y * static_cast<float>(texture.height);
    if (texture.sampler.nearest) return Texel(texture, FloorInt(x), FloorInt(y));
    // Bilinear: texel centres at integer + 0.5.
    const float x0 = std::floor(x - 0.5f), y0 = std::floor(y - 0.5f);
    const float fx = x - 0.5f - x0, fy = y - 0.5f - y0;
    const int ix = FloorInt(x0), iy = FloorInt(y0);
    const glm::vec3 top = (1.0f - fx) * Texel(texture, ix, iy) + fx * Texel(texture, ix + 1, iy);
    const glm::vec3 bottom =
        (1.0f - fx) * Texel(texture, ix, iy + 1) + fx * Texel(texture, ix + 1, iy + 1);
    return (1.0f - fy) * top + fy * bottom;
}

}  // namespace pem::trace
