// SPDX-License-Identifier: MIT
// layout_directions.h — the notes' parameterizations written backwards (seed 001), for tests:
// texture coordinates on a chart → the unit direction they show, and a map of any layout filled
// from a function of direction at its texel centres. Independent of runtime/parameterization.cpp
// (which maps directions forwards).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <numbers>

#include "raster/cube_lookup.h"
#include "raster/frame.h"
#include "runtime/parameterization.h"

namespace pem::runtime::testing {

// (s, t) on chart `chart` (atlas coordinates) → unit direction; the sphere map's in eye space.
inline glm::dvec3 LayoutInverse(Parameterization p, glm::dvec2 st, int chart) {
    constexpr double kPi = std::numbers::pi;
    switch (p) {
        case Parameterization::LatLong: {
            const double phi = (st.x - 0.5) * 2.0 * kPi, theta = st.y * kPi;  // from +Y
            return {std::sin(theta) * std::sin(phi), std::cos(theta),
                    -std::sin(theta) * std::cos(phi)};
        }
        case Parameterization::Sphere: {
            // The gazing ball's normal n = (u', v', nz) reflects the view ray (0, 0, -1) into r.
            const double u = 2.0 * st.x - 1.0, v = 2.0 * st.y - 1.0;
            const glm::dvec3 n(u, v, std::sqrt(std::max(0.0, 1.0 - u * u - v * v)));
            const glm::dvec3 in(0.0, 0.0, -1.0);
            return in - 2.0 * glm::dot(n, in) * n;
        }
        case Parameterization::Paraboloid: {
            // (u', v') = (x, y) / (1 ± z) solved for a unit direction: |z| = (1 - q) / (1 + q).
            const double u = 2.0 * (2.0 * st.x - chart) - 1.0, v = 2.0 * st.y - 1.0;
            const double q = u * u + v * v, a = (1.0 - q) / (1.0 + q);
            return {u * (1.0 + a), v * (1.0 + a), chart == 0 ? a : -a};
        }
        case Parameterization::Tennis: {
            const double phi = (st.x - 0.5) * 1.5 * kPi;
            const double theta = (2.0 * st.y - chart - 0.5) * 0.5 * kPi;
            // Band 0: y = sin θ, (x, -z) at angle φ; band 1: x = sin θ, (y, z) at angle φ.
            const double c = std::cos(theta);
            if (chart == 0) return {c * std::sin(phi), std::sin(theta), -c * std::cos(phi)};
            return {std::sin(theta), c * std::sin(phi), c * std::cos(phi)};
        }
        case Parameterization::Cube:
            break;
    }
    return {};
}

// The chart an atlas position belongs to.
inline int ChartAt(Parameterization p, glm::dvec2 st) {
    if (p == Parameterization::Paraboloid) return st.x >= 0.5 ? 1 : 0;
    if (p == Parameterization::Tennis) return st.y >= 0.5 ? 1 : 0;
    return 0;
}

// A map of layout `p` at `size`, every level's texel (bytes) = env(world direction of its
// centre); worldFromEye turns the sphere map's eye-space directions into world ones.
inline raster::Texture FilledMap(Parameterization p, int size,
                                 const std::function<glm::dvec4(glm::dvec3)>& env,
                                 const glm::dmat3& worldFromEye = glm::dmat3(1.0)) {
    raster::Texture t = EmptyTexture(LayoutOf(p, size), {});
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
                        d = LayoutInverse(p, st, ChartAt(p, st));
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

}  // namespace pem::runtime::testing
