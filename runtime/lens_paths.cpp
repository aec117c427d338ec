// SPDX-License-Identifier: MIT
// lens_paths.cpp — vertex rays and adaptive tessellation of a lens group (lens_paths.h).
#include "runtime/lens_paths.h"

#include <chrono>
#include <cstring>
#include <unordered_map>

#include "trace/parallel.h"
#include "trace/segment.h"

namespace pem::runtime {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The vertex's paths from the eye's ray through it.
trace::VertexPaths VertexRay(const trace::Tracer& tracer, const trace::EmbreeScene& embree,
                             const glm::vec3& eye, int group, const glm::vec3& position,
                             trace::RayCounts& counts) {
    const glm::vec3 d = position - eye;
    const float dist = glm::length(d);
    trace::VertexPaths none;
    none.reflection.F = none.refraction.F = glm::dvec3(0.0);
    if (!(dist > 0.0f)) return none;
    const raster::Ray ray{eye, d / dist};
    // Step 1: the surface at the vertex (hidden vertices too), else the group's first hit.
    ++counts.primary;
    trace::Hit hit = embree.Intersect(ray, 0.999f * dist);
    if (!hit.valid || tracer.GroupOf(hit.object) != group)
        hit = trace::IncomingHit(tracer, ray, group, counts);
    if (!hit.valid) return none;
    // Step 2: the two greedy paths from it.
    const std::optional<trace::GreedyPaths> paths = tracer.GreedyPathsAt(ray, hit, group, counts);
    return paths ? *paths : none;
}

struct VertexKey {
    uint32_t bits[6];
    bool operator==(const VertexKey& o) const {
        return std::memcmp(bits, o.bits, sizeof bits) == 0;
    }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
        return static_cast<size_t>(h);
    }
};
VertexKey KeyOf(const glm::vec3& p, const glm::vec3& n) {
    VertexKey k{};
    std::memcpy(k.bits, &p, sizeof p);
    std::memcpy(k.bits + 3, &n, sizeof n);
    return k;
}

}  // namespace

LensMesh GroupMesh(const trace::Scene& scene, int group) {
    LensMesh mesh;
    for (int o : scene.lensGroups.at(static_cast<size_t>(group)).objects) {
        const trace::Object& obj = scene.objects[static_cast<size_t>(o)];
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), obj.positions.begin(), obj.positions.end());
        mesh.normals.insert(mesh.normals.end(), obj.normals.begin(), obj.normals.end());
        for (const glm::uvec3& t : obj.triangles) mesh.triangles.push_back(t + glm::uvec3(base));
    }
    return mesh;
}

LensPaths TraceLensPaths(const trace::Tracer& tracer, const trace::EmbreeScene& embree,
                         const raster::Camera& camera, int group, const LensPathsOptions& options) {
    const LensMesh mesh = GroupMesh(tracer.scene(), group);
    const trace::BackFacingFn backFacing = trace::CameraBackFacing(camera);
    LensPaths out;

    // Step 1: the input vertices of front-facing triangles, in parallel chunks.
    const auto t0 = Clock::now();
    std::vector<uint8_t> wanted(mesh.positions.size(), 0);
    for (const glm::uvec3& t : mesh.triangles) {
        const trace::TriangleGeometry g{
            {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]},
            {mesh.normals[t.x], mesh.normals[t.y], mesh.normals[t.z]}};
        if (!backFacing(g)) wanted[t.x] = wanted[t.y] = wanted[t.z] = 1;
    }
    constexpr int kChunk = 256;
    const int n = static_cast<int>(mesh.positions.size());
    const int chunks = (n + kChunk - 1) / kChunk;
    std::vector<trace::VertexPaths> cache(mesh.positions.size());
    std::vector<trace::RayCounts> chunkCounts(static_cast<size_t>(chunks));
    trace::ParallelRows(chunks, options.threads, [&](int c) {
        for (int v = c * kChunk; v < std::min(n, (c + 1) * kChunk); ++v)
            if (wanted[static_cast<size_t>(v)])
                cache[static_cast<size_t>(v)] = VertexRay(tracer, embree, camera.eye, group,
                                                          mesh.positions[static_cast<size_t>(v)],
                                                          chunkCounts[static_cast<size_t>(c)]);
    });
    for (const trace::RayCounts& c : chunkCounts) out.counts += c;
    std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
    for (uint32_t v = 0; v < static_cast<uint32_t>(n); ++v)
        if (wanted[v]) index.emplace(KeyOf(mesh.positions[v], mesh.normals[v]), v);
    out.traceSeconds = Since(t0);

    // Step 2: the tessellation; new vertices are traced as it creates them.
    const auto t1 = Clock::now();
    double newTrace = 0.0;
    trace::TessInput in;
    in.positions = mesh.positions;
    in.normals = mesh.normals;
    in.triangles = mesh.triangles;
    in.project = trace::CameraProjection(camera, options.supersampling);
    in.backFacing = backFacing;
    in.evaluate = [&](const glm::vec3& p, const glm::vec3& nrm) {
        const auto it = index.find(KeyOf(p, nrm));
        if (it != index.end()) return cache[it->second];
        const auto ts = Clock::now();
        trace::VertexPaths paths = VertexRay(tracer, embree, camera.eye, group, p, out.counts);
        newTrace += Since(ts);
        return paths;
    };
    trace::TessOptions tess = options.tess;
    if (!options.adaptive) tess.maxDepth = 0;
    out.tess = trace::Tessellate(in, tess);
    out.traceSeconds += newTrace;
    out.tessSeconds = Since(t1) - newTrace;
    return out;
}

}  // namespace pem::runtime
