// SPDX-License-Identifier: MIT
// lens_paths.cpp — vertex rays and adaptive tessellation of a lens group (lens_paths.h).
#include "runtime/lens_paths.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>

#include "trace/segment.h"

namespace pem::runtime {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The vertex's paths from the eye's ray through it; `surface` (optional): the vertex's surface
// hit, known without a ray; `fallback` (optional): its surface when the ray misses the group.
trace::VertexPaths VertexRay(const trace::Tracer& tracer, const trace::EmbreeScene& embree,
                             const glm::vec3& eye, int group, const glm::vec3& position,
                             const std::optional<trace::Hit>& surface,
                             const std::optional<trace::Hit>& fallback, trace::RayCounts& counts) {
    const glm::vec3 d = position - eye;
    const float dist = glm::length(d);
    trace::VertexPaths none;
    none.reflection.F = none.refraction.F = glm::dvec3(0.0);
    if (!(dist > 0.0f)) return none;
    const raster::Ray ray{eye, d / dist};
    // Step 1: the surface at the vertex (hidden vertices too), else the group's first hit.
    trace::Hit hit;
    if (surface) {
        hit = *surface;
        hit.t = dist;
    } else {
        ++counts.primary;
        hit = embree.Intersect(ray, 0.999f * dist);
        if (!hit.valid || tracer.GroupOf(hit.object) != group)
            hit = trace::IncomingHit(tracer, ray, group, counts);
        if (!hit.valid && fallback) {
            hit = *fallback;
            hit.t = dist;
        }
        if (!hit.valid) return none;
    }
    // Step 2: the two greedy paths from it.
    std::optional<trace::GreedyPaths> paths = tracer.GreedyPathsAt(ray, hit, group, counts);
    return paths ? std::move(*paths) : none;
}

// Per input vertex, the triangles using it (CSR, in mesh order).
struct VertexTriangles {
    std::vector<uint32_t> start, tri;
    explicit VertexTriangles(const LensMesh& mesh) : start(mesh.positions.size() + 1, 0) {
        for (const glm::uvec3& t : mesh.triangles)
            for (int k = 0; k < 3; ++k) ++start[t[k] + 1];
        for (size_t v = 0; v < mesh.positions.size(); ++v) start[v + 1] += start[v];
        tri.resize(start.back());
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (uint32_t i = 0; i < mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) tri[fill[mesh.triangles[i][k]]++] = i;
    }
};

// Triangle i at barycentric (u, v) as a hit seen from the eye, when its geometric normal (unit,
// along (p1 − p0) × (p2 − p0), as Embree reports it) faces the eye at `position`.
std::optional<trace::Hit> TriangleSurface(const LensMesh& mesh, size_t i, float u, float v,
                                          const glm::vec3& position, const glm::vec3& eye) {
    const glm::uvec3 t = mesh.triangles[i];
    const glm::vec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
    const glm::vec3 ng = n / len;
    if (!(glm::dot(position - eye, ng) < 0.0f)) return std::nullopt;
    trace::Hit hit;
    hit.object = mesh.source[i].x;
    hit.prim = mesh.source[i].y;
    hit.u = u;
    hit.v = v;
    hit.ng = ng;
    hit.valid = true;
    return hit;
}

// Input vertex v's surface seen from the eye: the first triangle using it that faces the eye,
// at v's corner.
std::optional<trace::Hit> InputSurface(const LensMesh& mesh, const VertexTriangles& vt, size_t v,
                                       const glm::vec3& eye) {
    for (uint32_t k = vt.start[v]; k < vt.start[v + 1]; ++k) {
        const uint32_t i = vt.tri[k];
        const glm::uvec3 t = mesh.triangles[i];
        if (std::optional<trace::Hit> hit = TriangleSurface(
                mesh, i, t.y == v ? 1.0f : 0.0f, t.z == v ? 1.0f : 0.0f, mesh.positions[v], eye))
            return hit;
    }
    return std::nullopt;
}

// A point on input edge (a, b) seen from the eye: the first triangle holding the edge, in mesh
// order, that faces the eye, at the point's barycentric weights.
std::optional<trace::Hit> EdgeSurface(const LensMesh& mesh, const VertexTriangles& vt,
                                      const trace::EdgeMidpoint& at, const glm::vec3& position,
                                      const glm::vec3& eye) {
    for (uint32_t k = vt.start[at.a]; k < vt.start[at.a + 1]; ++k) {
        const uint32_t i = vt.tri[k];
        const glm::uvec3 t = mesh.triangles[i];
        if (t.x != at.b && t.y != at.b && t.z != at.b) continue;
        // Weight of corner c: 1 − s at a, s at b, 0 at the third corner.
        const auto weight = [&](uint32_t c) {
            return static_cast<float>(c == at.a ? 1.0 - at.s : c == at.b ? at.s : 0.0);
        };
        if (std::optional<trace::Hit> hit =
                TriangleSurface(mesh, i, weight(t.y), weight(t.z), position, eye))
            return hit;
    }
    return std::nullopt;
}

}  // namespace

LensMesh GroupMesh(const trace::Scene& scene, int group) {
    LensMesh mesh;
    for (int o : scene.lensGroups.at(static_cast<size_t>(group)).objects) {
        const trace::Object& obj = scene.objects[static_cast<size_t>(o)];
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), obj.positions.begin(), obj.positions.end());
        mesh.normals.insert(mesh.normals.end(), obj.normals.begin(), obj.normals.end());
        for (size_t i = 0; i < obj.triangles.size(); ++i) {
            mesh.triangles.push_back(obj.triangles[i] + glm::uvec3(base));
            mesh.source.emplace_back(o, static_cast<int>(i));
        }
    }
    return mesh;
}

LensPaths TraceLensPaths(const trace::Tracer& tracer, const trace::EmbreeScene& embree,
                         const raster::Camera& camera, int group, const LensPathsOptions& options) {
    const LensMesh mesh = GroupMesh(tracer.scene(), group);
    const trace::BackFacingFn backFacing = trace::CameraBackFacing(camera);
    LensPaths out;

    // The tessellation traces the vertices (in parallel): each call's rays and time are summed
    // in integer atomics (sums of integers do not depend on the order).
    const auto t0 = Clock::now();
    std::atomic<uint64_t> primary{0}, secondary{0}, shadow{0}, traceNs{0};
    trace::TessInput in;
    in.positions = mesh.positions;
    in.normals = mesh.normals;
    in.triangles = mesh.triangles;
    in.project = trace::CameraProjection(camera, options.supersampling);
    in.backFacing = backFacing;
    const VertexTriangles vertexTriangles(mesh);
    auto evaluate = [&](const glm::vec3& p, const std::optional<trace::Hit>& surface,
                        const std::optional<trace::Hit>& fallback = std::nullopt) {
        const auto ts = Clock::now();
        trace::RayCounts counts;
        trace::VertexPaths paths =
            VertexRay(tracer, embree, camera.eye, group, p, surface, fallback, counts);
        traceNs += static_cast<uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - ts).count());
        primary += counts.primary;
        secondary += counts.secondary;
        shadow += counts.shadow;
        return paths;
    };
    in.evaluate = [&](const glm::vec3& p, const glm::vec3&) { return evaluate(p, std::nullopt); };
    in.evaluateInput = [&](size_t v) {
        return evaluate(mesh.positions[v], InputSurface(mesh, vertexTriangles, v, camera.eye));
    };
    in.evaluateMidpoint = [&](const glm::vec3& p, const glm::vec3&, const trace::MeshPoint& at) {
        return evaluate(p, TriangleSurface(mesh, at.triangle, static_cast<float>(at.u),
                                           static_cast<float>(at.v), p, camera.eye));
    };
    // On an input edge the eye's ray grazes past the mesh at a silhouette: the edge's surface.
    in.evaluateEdge = [&](const glm::vec3& p, const glm::vec3&, const trace::EdgeMidpoint& at) {
        return evaluate(p, std::nullopt, EdgeSurface(mesh, vertexTriangles, at, p, camera.eye));
    };
    trace::TessOptions tess = options.tess;
    if (!options.adaptive) tess.maxDepth = 0;
    tess.threads = options.threads;
    out.tess = trace::Tessellate(in, tess);
    out.counts = {primary.load(), secondary.load(), shadow.load()};
    const double traceCpu = 1e-9 * static_cast<double>(traceNs.load());
    // The wall time split by the share of the threads' time spent in vertex rays.
    const double wall = Since(t0);
    out.traceSeconds = std::min(wall, traceCpu / std::max(1, options.threads));
    out.tessSeconds = wall - out.traceSeconds;
    return out;
}

}  // namespace pem::runtime
