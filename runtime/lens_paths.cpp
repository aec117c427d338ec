// SPDX-License-Identifier: MIT
// lens_paths.cpp — vertex rays and adaptive tessellation of a lens group (lens_paths.h).
#include "runtime/lens_paths.h"

#include <algorithm>
#include <atomic>
#include <chrono>

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
    in.evaluate = [&](const glm::vec3& p, const glm::vec3&) {
        const auto ts = Clock::now();
        trace::RayCounts counts;
        trace::VertexPaths paths = VertexRay(tracer, embree, camera.eye, group, p, counts);
        traceNs += static_cast<uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - ts).count());
        primary += counts.primary;
        secondary += counts.secondary;
        shadow += counts.shadow;
        return paths;
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
