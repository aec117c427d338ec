// SPDX-License-Identifier: MIT
// static_em.cpp — the static environment map (static_em.h).
#include "runtime/static_em.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/parallel.h"
#include "raster/cube_lookup.h"
#include "trace/segment.h"

namespace pem::runtime {
namespace {

// The direction of face coordinates (s, t) in [0, 1] (raster::FaceDirection).
glm::vec3 FaceDirection(int face, float s, float t) {
    const raster::Vec3f d = raster::FaceDirection(face, 2.0f * s - 1.0f, 2.0f * t - 1.0f);
    return {d[0], d[1], d[2]};
}

// Level 0: the radiance seen from `origin` through each texel centre, the group left out.
std::vector<float> TraceLevel0(const trace::Tracer& tracer, int group, const glm::vec3& origin,
                               int n, int threads) {
    std::vector<float> level0(static_cast<size_t>(6 * n * n) * 4, 0.0f);
    base::ParallelFor(6 * n, threads, [&](int row) {
        const int f = row / n, j = row % n;
        trace::RayCounts counts;
        for (int i = 0; i < n; ++i) {
            const glm::vec3 d = glm::normalize(
                FaceDirection(f, (static_cast<float>(i) + 0.5f) / static_cast<float>(n),
                              (static_cast<float>(j) + 0.5f) / static_cast<float>(n)));
            const raster::Ray ray{origin, d};
            const std::vector<trace::Hit> hits = trace::EnvironmentHits(tracer, ray, group, counts);
            const trace::Hit hit = hits.empty() ? trace::Hit{} : hits.front();
            const glm::vec3 l =
                tracer.HitRadiance(ray, hit, tracer.options().fullTreeDepth, 1.0, counts);
            float* p = &level0[((static_cast<size_t>(f) * n + j) * n + i) * 4];
            p[0] = l.x, p[1] = l.y, p[2] = l.z, p[3] = 1.0f;
        }
    });
    return level0;
}

// The next MIP level: 2×2 means.
std::vector<float> HalveLevel(const std::vector<float>& cur, int m) {
    const int h = m / 2;
    std::vector<float> next(static_cast<size_t>(6 * h * h) * 4, 0.0f);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < h; ++i)
                for (int c = 0; c < 4; ++c) {
                    float s = 0.0f;
                    for (int dj = 0; dj < 2; ++dj)
                        for (int di = 0; di < 2; ++di)
                            s += cur[((static_cast<size_t>(f) * m + 2 * j + dj) * m + 2 * i + di) *
                                         4 +
                                     c];
                    next[((static_cast<size_t>(f) * h + j) * h + i) * 4 + c] = 0.25f * s;
                }
    return next;
}

}  // namespace

raster::Texture TraceStaticMap(const trace::Tracer& tracer, int group, const glm::vec3& origin,
                               int size, int threads) {
    raster::Texture tex;
    tex.kind = raster::TextureKind::Cube;
    tex.width = tex.height = size;
    std::vector<float> cur = TraceLevel0(tracer, group, origin, size, threads);
    for (int m = size; m >= 1; m /= 2) {
        std::vector<uint8_t> bytes(cur.size());
        for (size_t k = 0; k < cur.size(); ++k)
            bytes[k] =
                static_cast<uint8_t>(std::nearbyint(std::clamp(cur[k], 0.0f, 1.0f) * 255.0f));
        tex.levels.push_back(std::move(bytes));
        if (m == 1) break;
        cur = HalveLevel(cur, m);
    }
    return tex;
}

}  // namespace pem::runtime
