// SPDX-License-Identifier: MIT
// texgen.cpp — exit rays, shell coordinates and layer passes (texgen.h).
#include "runtime/texgen.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "base/parallel.h"
#include "trace/fresnel.h"

namespace pem::runtime {
namespace {

// fn(first, last) over [0, n) in chunks, in parallel when threads > 1.
void ForChunks(size_t n, int threads, const std::function<void(size_t first, size_t last)>& fn) {
    constexpr size_t kChunk = 8192;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    if (threads <= 1 || chunks <= 1) {
        if (n > 0) fn(0, n);
        return;
    }
    base::ParallelFor(static_cast<int>(chunks), threads, [&](int c) {
        const size_t first = static_cast<size_t>(c) * kChunk;
        fn(first, std::min(n, first + kChunk));
    });
}

}  // namespace

PassMesh MeshOf(const LensMesh& mesh) {
    return {&mesh.positions, &mesh.normals, &mesh.triangles};
}

PassMesh MeshOf(const trace::TessellationResult& tess) {
    return {&tess.positions, &tess.normals, &tess.triangles};
}

std::vector<ExitRay> TermExits(const std::vector<std::optional<trace::VertexPaths>>& paths,
                               int term, int threads) {
    std::vector<ExitRay> exits(paths.size());
    ForChunks(paths.size(), threads, [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v) {
            if (!paths[v]) continue;
            const trace::RayPath& p = term == 0 ? paths[v]->reflection : paths[v]->refraction;
            if (!p.escaped) continue;
            exits[v] = {p.exitOrigin, p.exitDir, glm::vec3(p.F * p.G), true};
        }
    });
    return exits;
}

std::vector<ExitRay> ReflectionExits(const PassMesh& mesh, const glm::vec3& eye,
                                     const glm::vec3& f0) {
    std::vector<ExitRay> exits(mesh.positions->size());
    for (size_t v = 0; v < exits.size(); ++v) {
        const glm::vec3 p = (*mesh.positions)[v], n = (*mesh.normals)[v];
        const glm::vec3 d = glm::normalize(p - eye);
        const float cosTheta = -glm::dot(d, n);
        if (!(cosTheta > 0.0f)) continue;  // back-facing vertex: no reflection
        const glm::vec3 r = d + 2.0f * cosTheta * n;
        glm::vec3 f;
        for (int c = 0; c < 3; ++c)
            f[c] = static_cast<float>(
                trace::FresnelSchlick(static_cast<double>(cosTheta), static_cast<double>(f0[c])));
        exits[v] = {p, glm::normalize(r), f, true};
    }
    return exits;
}

std::vector<glm::vec3> ShellCoords(const std::vector<ExitRay>& exits, const trace::Shell& shell,
                                   const glm::vec3& emOrigin, int threads) {
    std::vector<glm::vec3> coords(exits.size());
    const glm::dvec3 o(emOrigin);
    ForChunks(exits.size(), threads, [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v) {
            const ExitRay& e = exits[v];
            if (!e.valid) {
                coords[v] = glm::vec3(0.0f, 0.0f, 1.0f);
                continue;
            }
            const std::optional<trace::ShellHit> hit = trace::Intersect(shell, {e.origin, e.dir});
            coords[v] = hit ? trace::LookupVector(hit->point - o) : e.dir;
            if (!std::isfinite(coords[v].x) || !std::isfinite(coords[v].y) ||
                !std::isfinite(coords[v].z) || coords[v] == glm::vec3(0.0f))
                coords[v] = e.dir;
        }
    });
    return coords;
}

std::vector<uint32_t> DrawOrder(const PassMesh& mesh, const raster::Camera& camera, int threads) {
    const auto& pos = *mesh.positions;
    const auto& nrm = *mesh.normals;
    const auto& tris = *mesh.triangles;
    // Step 1: per triangle, drawn or not: front-facing (some vertex normal toward the eye) and
    // at a distance that is a number.
    std::vector<uint8_t> drawn(tris.size());
    ForChunks(tris.size(), threads, [&](size_t first, size_t last) {
        for (size_t i = first; i < last; ++i) {
            const glm::uvec3 t = tris[i];
            bool front = false;
            for (int k = 0; k < 3; ++k) front |= glm::dot(nrm[t[k]], camera.eye - pos[t[k]]) > 0.0f;
            const glm::vec3 c = (pos[t.x] + pos[t.y] + pos[t.z]) / 3.0f;
            drawn[i] = front && !std::isnan(glm::length(c - camera.eye)) ? 1 : 0;
        }
    });
    // Step 2: the front-facing ones in mesh order (neighbours on the mesh are neighbours on
    // the screen, so a band's colour and depth stay in the caches from triangle to triangle).
    std::vector<uint32_t> order;
    order.reserve(tris.size());
    for (uint32_t i = 0; i < tris.size(); ++i)
        if (drawn[i]) order.push_back(i);
    return order;
}

glm::mat4 PassViewProjection(const PassMesh& mesh, const raster::Camera& camera) {
    // Near/far: the mesh's distance range from the eye, widened; depth is clamped anyway.
    float far = 1.0f;
    for (const glm::vec3& p : *mesh.positions) far = std::max(far, glm::length(p - camera.eye));
    return raster::ViewProjection(camera, 1e-3f * far, 4.0f * far);
}

raster::DepthTest LayerDepthTest(bool firstPass) {
    return firstPass ? raster::DepthTest{raster::DepthFunc::Less, true}
                     : raster::DepthTest{raster::DepthFunc::Equal, false};
}

std::vector<raster::Pass> LayerPass(const PassMesh& mesh, const std::vector<uint32_t>& order,
                                    const std::vector<glm::vec3>& coords,
                                    const std::vector<ExitRay>& exits,
                                    const glm::mat4& viewProjection, const PassOptions& options) {
    std::vector<raster::Pass> passes(static_cast<size_t>(MapTextures(options.parameterization)));
    FillLayerPass(MakePassGeometry(mesh, order, viewProjection), coords, exits, options, passes);
    return passes;
}

raster::Pass DepthOnlyPass(const PassMesh& mesh, const std::vector<uint32_t>& order,
                           const glm::mat4& viewProjection) {
    const PassGeometry g = MakePassGeometry(mesh, order, viewProjection);
    raster::Pass pass;
    pass.numUnits = 0;
    pass.depthTest = LayerDepthTest(true);
    pass.vertices.resize(g.clip.size());
    for (size_t v = 0; v < g.clip.size(); ++v) {
        pass.vertices[v].pos = g.clip[v];
        pass.vertices[v].color = glm::vec4(0.0f);
    }
    pass.indices = g.indices;
    return pass;
}

PassGeometry MakePassGeometry(const PassMesh& mesh, const std::vector<uint32_t>& order,
                              const glm::mat4& viewProjection, int threads) {
    PassGeometry g;
    const auto& pos = *mesh.positions;
    g.clip.resize(pos.size());
    g.indices.resize(order.size() * 3);
    ForChunks(pos.size(), threads, [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v) g.clip[v] = viewProjection * glm::vec4(pos[v], 1.0f);
    });
    ForChunks(order.size(), threads, [&](size_t first, size_t last) {
        for (size_t k = first; k < last; ++k) {
            const glm::uvec3 t = (*mesh.triangles)[order[k]];
            for (int c = 0; c < 3; ++c) g.indices[3 * k + static_cast<size_t>(c)] = t[c];
        }
    });
    return g;
}

void FillLayerPass(const PassGeometry& geometry, const std::vector<glm::vec3>& coords,
                   const std::vector<ExitRay>& exits, const PassOptions& options,
                   std::span<raster::Pass> passes, int threads) {
    if (passes.size() != static_cast<size_t>(MapTextures(options.parameterization)))
        throw std::invalid_argument("FillLayerPass: one pass per texture of the layout");
    raster::Pass* pass = &passes[0];
    pass->numUnits = 1;
    pass->texture = {options.texture, options.texture};
    pass->blend = options.blend;
    pass->depthTest = options.depthTest;
    pass->vertices.resize(geometry.clip.size());
    ForChunks(geometry.clip.size(), threads, [&](size_t first, size_t last) {
        for (size_t v = first; v < last; ++v) {
            raster::Vertex& out = pass->vertices[v];
            out.pos = geometry.clip[v];
            out.coord[0] = coords[v];
            out.coord[1] = glm::vec3(0.0f);
            out.color = options.modulate ? glm::vec4(exits[v].weight, 1.0f) : glm::vec4(1.0f);
        }
    });
    pass->indices = geometry.indices;
    if (options.parameterization == Parameterization::Cube) return;
    std::vector<raster::Pass> charts =
        ToLayout(*pass, 0, options.parameterization, options.eyeFromWorld);
    std::move(charts.begin(), charts.end(), passes.begin());
}

}  // namespace pem::runtime
