// SPDX-License-Identifier: MIT
// static_em.cpp — the static environment map (static_em.h).
#include "runtime/static_em.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/parallel.h"
#include "raster/cube_lookup.h"
#include "trace/layers.h"
#include "trace/segment.h"

namespace pem::runtime {
namespace {

// The direction of face coordinates (s, t) in [0, 1] (raster::FaceDirection).
glm::vec3 FaceDirection(int face, float s, float t) {
    const raster::Vec3f d = raster::FaceDirection(face, 2.0f * s - 1.0f, 2.0f * t - 1.0f);
    return {d[0], d[1], d[2]};
}

// The world direction of texel (face, i, j) of an n_w x n_h level 0 of the layout (a 2D
// layout's face: its chart).
glm::vec3 TexelDirection(const MapLayout& layout, int face, int i, int j,
                         const glm::mat3& worldFromEye) {
    const double s = (i + 0.5) / layout.width, t = (j + 0.5) / layout.height;
    if (layout.kind == raster::TextureKind::Cube)
        return glm::normalize(FaceDirection(face, static_cast<float>(s), static_cast<float>(t)));
    glm::vec3 d(LayoutDirection(layout.parameterization, face, {s, t}));
    if (layout.parameterization == Parameterization::Sphere) d = worldFromEye * d;
    return glm::normalize(d);
}

// Level 0: the radiance seen from `origin` through each texel centre, the group left out.
std::vector<float> TraceLevel0(const trace::Tracer& tracer, int group, const glm::vec3& origin,
                               const MapLayout& layout, const glm::mat3& worldFromEye,
                               int threads) {
    const int faces = layout.charts == 6 ? 6 : layout.textures, w = layout.width, h = layout.height;
    std::vector<float> level0(static_cast<size_t>(faces * w * h) * 4, 0.0f);
    base::ParallelFor(faces * h, threads, [&](int row) {
        const int f = row / h, j = row % h;
        trace::RayCounts counts;
        for (int i = 0; i < w; ++i) {
            const raster::Ray ray{origin, TexelDirection(layout, f, i, j, worldFromEye)};
            const std::vector<trace::Hit> hits = trace::EnvironmentHits(tracer, ray, group, counts);
            const trace::Hit hit = hits.empty() ? trace::Hit{} : hits.front();
            const glm::vec3 l =
                tracer.HitRadiance(ray, hit, tracer.options().fullTreeDepth, 1.0, counts);
            float* p = &level0[((static_cast<size_t>(f) * h + j) * w + i) * 4];
            p[0] = l.x, p[1] = l.y, p[2] = l.z, p[3] = 1.0f;
        }
    });
    return level0;
}

// The next MIP level of a faces x w x h level: means of the 2x2 (2x1, 1x2) texels it covers.
std::vector<float> HalveLevel(const std::vector<float>& cur, int faces, int w, int h) {
    const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
    const int sx = w > 1 ? 2 : 1, sy = h > 1 ? 2 : 1;
    const float weight = 1.0f / static_cast<float>(sx * sy);
    std::vector<float> next(static_cast<size_t>(faces * nw * nh) * 4, 0.0f);
    for (int f = 0; f < faces; ++f)
        for (int j = 0; j < nh; ++j)
            for (int i = 0; i < nw; ++i)
                for (int c = 0; c < 4; ++c) {
                    float s = 0.0f;
                    for (int dj = 0; dj < sy; ++dj)
                        for (int di = 0; di < sx; ++di)
                            s +=
                                cur[((static_cast<size_t>(f) * h + sy * j + dj) * w + sx * i + di) *
                                        4 +
                                    c];
                    next[((static_cast<size_t>(f) * nh + j) * nw + i) * 4 + c] = weight * s;
                }
    return next;
}

// The layering of a group as trace/layers.h's LayerOf reads it: each layer's radius, each
// scene object's layer (by name; -1 when no layer lists it).
trace::GroupLayers LayeringOf(const trace::Scene& scene, const LensGroupEm& g) {
    trace::GroupLayers gl;
    gl.group = g.index;
    gl.emOrigin = g.emOrigin;
    gl.objectLayer.assign(scene.objects.size(), -1);
    for (size_t l = 0; l < g.layers.size(); ++l) {
        trace::LayerCluster c;
        c.radius = g.layers[l].radius;
        gl.clustering.layers.push_back(c);
        for (const std::string& name : g.layers[l].objects)
            for (size_t o = 0; o < scene.objects.size(); ++o)
                if (scene.objects[o].name == name) gl.objectLayer[o] = static_cast<int>(l);
    }
    return gl;
}

}  // namespace

std::vector<raster::Texture> TraceStaticMap(const trace::Tracer& tracer, int group,
                                            const glm::vec3& origin, const MapLayout& layout,
                                            int threads, const glm::mat3& worldFromEye) {
    // Step: the levels of every face (a cube's 6, a two-image layout's 2 charts), in float.
    const raster::Texture empty = EmptyTexture(layout, raster::SamplerState{});
    const int faces = layout.kind == raster::TextureKind::Cube ? 6 : layout.textures;
    std::vector<std::vector<float>> levels{
        TraceLevel0(tracer, group, origin, layout, worldFromEye, threads)};
    for (int l = 0; l + 1 < empty.NumLevels(); ++l)
        levels.push_back(
            HalveLevel(levels.back(), faces, empty.LevelWidth(l), empty.LevelHeight(l)));
    // Step: rounded to 8 bits, each chart of a 2D layout in its own texture.
    std::vector<raster::Texture> out(static_cast<size_t>(layout.textures), empty);
    for (size_t c = 0; c < out.size(); ++c)
        for (int l = 0; l < empty.NumLevels(); ++l) {
            std::vector<uint8_t>& bytes = out[c].levels[static_cast<size_t>(l)];
            const std::vector<float>& cur = levels[static_cast<size_t>(l)];
            for (size_t k = 0; k < bytes.size(); ++k)
                bytes[k] = static_cast<uint8_t>(
                    std::nearbyint(std::clamp(cur[c * bytes.size() + k], 0.0f, 1.0f) * 255.0f));
        }
    return out;
}

raster::Texture TraceStaticMap(const trace::Tracer& tracer, int group, const glm::vec3& origin,
                               int size, int threads) {
    MapLayout cube;  // LayoutOf's, for any power of two (1 included)
    cube.width = cube.height = size;
    cube.charts = 6;
    return std::move(TraceStaticMap(tracer, group, origin, cube, threads).front());
}

DirectImages TraceDirectImages(const trace::Tracer& tracer, const LensGroupEm& group, int size,
                               int threads) {
    const trace::GroupLayers layering = LayeringOf(tracer.scene(), group);
    const size_t layers = group.layers.size(), texels = 6 * static_cast<size_t>(size * size);
    DirectImages out;
    out.size = size;
    out.levels.assign(layers + 1, {std::vector<float>(4 * texels, 0.0f)});
    // Step: level 0 of every layer, row by row, and of the whole environment (the static map's).
    MapLayout cube;
    cube.width = cube.height = size;
    cube.charts = 6;
    base::ParallelFor(6 * size, threads, [&](int row) {
        const int f = row / size, j = row % size;
        trace::RayCounts counts;
        for (int i = 0; i < size; ++i) {
            const raster::Ray ray{group.emOrigin, TexelDirection(cube, f, i, j, glm::mat3(1.0f))};
            const std::vector<glm::vec4> c =
                trace::LayerColours(tracer, layering, ray, tracer.options().fullTreeDepth, counts);
            const size_t at = ((static_cast<size_t>(f) * size + j) * size + i) * 4;
            for (size_t l = 0; l < layers; ++l)
                for (int k = 0; k < 4; ++k) out.levels[l][0][at + k] = c[l][k];
        }
    });
    out.levels[layers][0] =
        TraceLevel0(tracer, group.index, group.emOrigin, cube, glm::mat3(1.0f), threads);
    // Step: the MIP levels.
    for (auto& chain : out.levels)
        for (int w = size; w > 1; w /= 2) chain.push_back(HalveLevel(chain.back(), 6, w, w));
    return out;
}

}  // namespace pem::runtime
