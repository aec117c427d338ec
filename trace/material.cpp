// SPDX-License-Identifier: MIT
// material.cpp — material kind names and bilinear REPEAT texture sampling (material.h).
#include "trace/material.h"

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

int Wrap(int i, int n) {
    const int r = i % n;
    return r < 0 ? r + n : r;
}

glm::vec3 Texel(const Texture2D& t, int x, int y) {
    const size_t at = 3 * (static_cast<size_t>(Wrap(y, t.height)) * static_cast<size_t>(t.width) +
                           static_cast<size_t>(Wrap(x, t.width)));
    return {t.rgb[at], t.rgb[at + 1], t.rgb[at + 2]};
}

}  // namespace

glm::vec3 SampleTexture(const Texture2D& texture, glm::vec2 uv) {
    if (texture.width <= 0 || texture.height <= 0) return glm::vec3(1.0f);
    // Continuous texel position, centres at integer + 0.5; uv outside [0, 1) wraps.
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    const float x = u * static_cast<float>(texture.width) - 0.5f;
    const float y = v * static_cast<float>(texture.height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y);
    const float fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    const glm::vec3 top = (1.0f - fx) * Texel(texture, ix, iy) + fx * Texel(texture, ix + 1, iy);
    const glm::vec3 bottom =
        (1.0f - fx) * Texel(texture, ix, iy + 1) + fx * Texel(texture, ix + 1, iy + 1);
    return (1.0f - fy) * top + fy * bottom;
}

}  // namespace pem::trace
