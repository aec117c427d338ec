// SPDX-License-Identifier: MIT
// layout_directions.h — for tests: a map of any layout filled from a function of direction at
// its texel centres (the cube's through GL's face table, the 2D layouts' through
// runtime::LayoutDirection, which parameterization_test checks against ChartCoord).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "raster/cube_lookup.h"
#include "raster/frame.h"
#include "runtime/parameterization.h"

namespace pem::runtime::testing {

// One texture (chart) of the map FilledMap gives.
inline raster::Texture FilledChart(Parameterization p, const MapLayout& layout, int chart,
                                   const std::function<glm::dvec4(glm::dvec3)>& env,
                                   const glm::dmat3& worldFromEye) {
    raster::Texture t = EmptyTexture(layout, {});
    for (int l = 0; l < t.NumLevels(); ++l) {
        const int w = t.LevelWidth(l), h = t.LevelHeight(l);
        for (int f = 0; f < t.Faces(); ++f)
            for (int j = 0; j < h; ++j)
                for (int i = 0; i < w; ++i) {
                    glm::dvec3 d;
                    if (p == Parameterization::Cube) {
                        // The texel centre through GL's face table (raster/cube_lookup.h).
                        const raster::Vec3f c =
                            raster::FaceDirection(f, static_cast<float>(2.0 * (i + 0.5) / w - 1.0),
                                                  static_cast<float>(2.0 * (j + 0.5) / h - 1.0));
                        d = glm::normalize(glm::dvec3(c[0], c[1], c[2]));
                    } else {
                        const glm::dvec2 st((i + 0.5) / w, (j + 0.5) / h);
                        d = LayoutDirection(p, chart, st);
                        if (p == Parameterization::Sphere) d = worldFromEye * d;
                    }
                    const glm::dvec4 v = env(d);
                    for (int c = 0; c < 4; ++c)
                        t.levels[static_cast<size_t>(l)]
                                [static_cast<size_t>(((f * h + j) * w + i) * 4 + c)] =
                            static_cast<uint8_t>(std::lround(std::clamp(v[c], 0.0, 1.0) * 255.0));
                }
    }
    return t;
}

// A map of layout `p` at `size` (its textures: one, or two charts), every level's texel (bytes)
// = env(world direction of its centre); worldFromEye turns the sphere map's eye-space
// directions into world ones.
inline std::vector<raster::Texture> FilledMap(Parameterization p, int size,
                                              const std::function<glm::dvec4(glm::dvec3)>& env,
                                              const glm::dmat3& worldFromEye = glm::dmat3(1.0)) {
    const MapLayout layout = LayoutOf(p, size);
    std::vector<raster::Texture> out;
    for (int chart = 0; chart < layout.textures; ++chart)
        out.push_back(FilledChart(p, layout, chart, env, worldFromEye));
    return out;
}

}  // namespace pem::runtime::testing
