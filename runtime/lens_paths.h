// SPDX-License-Identifier: MIT
// lens_paths.h — per-vertex greedy ray paths of one lens group seen from one camera, on the
// adaptively tessellated mesh (hybrid §5): the vertex rays the run-time renderer and the
// inference's texgen both start from.
//
//   LensPaths lp = TraceLensPaths(tracer, embree, camera, group, {});
//   // lp.tess.positions / normals / triangles / paths: the refined mesh and each vertex's paths
//
// Vertex rays: the ray from the eye to the vertex starts at the vertex's own surface, so a vertex
// hidden behind another part of the object still gets it. That surface is known without a ray
// for a vertex of the input mesh (the first triangle using it, in mesh order, that faces the
// eye, at its corner) and for a midpoint inside an input triangle (that triangle, if it faces
// the eye, at the midpoint's barycentric weights). Other vertices (midpoints on the input mesh's
// edges, or no such triangle) intersect the ray from
// just before the vertex (tnear = 0.999 · distance); when that misses the group (a silhouette
// vertex grazed by float error), the group's first hit along the ray is used (segment.h
// IncomingHit), and when that misses too, a midpoint on an input edge takes the edge's surface
// (the first triangle holding the edge, in mesh order, that faces the eye, at the midpoint's
// weights; without it the silhouettes of a fine tessellation darken: 3410 such vertices at t = 1
// on sample 0 of scene (a)). From that hit the two greedy paths (Tracer::GreedyPathsAt). A vertex
// with no group hit gets paths with F = 0.
// Parallelism: the tessellation runs on `threads` threads (trace/tessellate.h: the input vertices
// in chunks, then runs of input triangles merged in index order); the result is the same for any
// thread count (the ray counts may include a few midpoints traced by two runs).
// Not here: texture coordinates and passes (texgen.h), the renderer (renderer.h).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "raster/camera.h"
#include "trace/embree_scene.h"
#include "trace/tessellate.h"
#include "trace/tracer.h"

namespace pem::runtime {

// The hybrid tessellation t (subpixels) that inference and rendering use unless told otherwise:
// maps fit the tessellation they were inferred on (MapSet::tessT), so a renderer draws with it.
inline constexpr double kDefaultTessT = 5.0;

// Where two vertices' greedy paths differ in topology (trace/tessellate.h
// maxTopologyEdgeSubpixels), inference and rendering refine down to min(t, this) subpixels unless
// told otherwise (MapSet::topologyT): a discontinuity that no interpolation bridges, while a
// merely diverging exit direction stops at t. Scene (a) at the demo's settings (the maps fitted
// through the same tessellations), hybrid at t = 5, report 10° above the circle against the 6×6
// reference (1-spp ray tracer: 20.32 dB): LOD bias -4 19.83 → 20.24 dB, the float maps' -2.5
// 20.55 (2.26 M vertex rays, 1.40 M without); a threshold of 3: 20.40 dB. The cost, between two
// samples (bench/render_bench.sh's view): 0.47 → 1.10 M vertex rays, 337 → 529 ms a frame (3:
// 0.71 M, 433 ms); `--t-topology 0` renders as the paper does.
inline constexpr double kDefaultTopologyT = 2.0;

// The triangles of one lens group as one world-space mesh (objects in group order).
struct LensMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::ivec2> source;  // per triangle: (object, its index in the object)
};
LensMesh GroupMesh(const trace::Scene& scene, int group);

struct LensPathsOptions {
    trace::TessOptions tess;  // t = tess.maxEdgeSubpixels, in units of 1 / supersampling pixels
    int supersampling = 1;
    bool adaptive = true;  // false: the input mesh only (every front-facing vertex traced)
    int threads = 1;
};

struct LensPaths {
    trace::TessellationResult tess;
    trace::RayCounts counts;
    double traceSeconds = 0.0;  // vertex rays (the tessellation's wall time × their time share)
    double tessSeconds = 0.0;   // tessellation bookkeeping without the vertex rays
};

LensPaths TraceLensPaths(const trace::Tracer& tracer, const trace::EmbreeScene& embree,
                         const raster::Camera& camera, int group, const LensPathsOptions& options);

}  // namespace pem::runtime
