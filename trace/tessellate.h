// SPDX-License-Identifier: MIT
// tessellate.h — the hybrid paper's adaptive tessellation of a lens object (Hakura & Snyder 2001,
// §5): a triangle is refined while the greedy ray paths at its vertices differ (PathsDiffer on
// either term: path length, reflect/refract choice, escape, exit angle > maxAngleDeg) and some of
// its screen-projected edges are longer than t subpixels — 1-to-4, 1-to-3 or 1-to-2, splitting only
// the long edges. Optionally (maxTopologyEdgeSubpixels, not in the paper) a triangle whose
// vertices' paths differ in topology — a discontinuity that linear interpolation cannot bridge at
// any t — is refined down to a finer threshold than one whose exit directions merely diverge.
// Midpoints are shared through an edge hash (so each vertex ray is traced once), and the
// t-junctions left between differently refined neighbours are removed afterwards by
// re-triangulating each triangle with all vertices found (recursively) on its edges. A midpoint's
// normal is its edge's normals summed and normalized (opposite normals: the one of the endpoint
// first in (position, normal) order, so the choice never depends on the numbering).
//
// Conventions: output vertices 0..n-1 are the input vertices, new ones follow in creation order;
// triangles keep the winding of their input triangle. Input triangles are processed in index
// order, children in a fixed order: the output is a pure function of the input and callbacks.
// Threads: the input vertices are traced in parallel chunks, then runs of consecutive input
// triangles are refined in parallel (each with its own midpoint hash) and merged in index order,
// which reproduces the serial numbering; the callbacks must then be thread-safe pure functions.
// The output does not depend on the thread count; only `evaluate` (or `evaluateMidpoint`) may be
// called more than once for a midpoint on the border of two runs.
// Back-facing triangles are not refined and their vertices are not traced (unless a front-facing
// triangle shares them); triangles whose three vertices are occluded are traced but not refined.
//
// Not here: the tracer (the evaluate callback), occlusion rays, texture coordinates, rendering.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "raster/camera.h"
#include "trace/ray_path.h"

namespace pem::trace {

// The two greedy paths (R and T terms) of one vertex's primary ray.
using VertexPaths = GreedyPaths;

// One triangle as the visibility callback sees it.
struct TriangleGeometry {
    std::array<glm::vec3, 3> positions;
    std::array<glm::vec3, 3> normals;
};

// World position → continuous subpixel coordinates (pixels × supersampling). A non-finite result
// (point behind the eye) makes its edges count as long.
using ProjectFn = std::function<glm::vec2(const glm::vec3& position)>;
// Traces the primary ray through a vertex (called once per traced vertex).
using EvaluateFn = std::function<VertexPaths(const glm::vec3& position, const glm::vec3& normal)>;
// Traces input vertex `index` (its position and normal are the input's): lets the caller use
// what it knows of the input mesh (e.g. the surface point without a primary ray).
using EvaluateInputFn = std::function<VertexPaths(size_t index)>;
// Where a midpoint lies: inside input triangle `triangle`, at barycentric weights (u, v) of its
// corners 1 and 2 (exact dyadic fractions; the midpoint's position is its edge's midpoint).
struct MeshPoint {
    size_t triangle = 0;
    double u = 0.0, v = 0.0;
};
// Traces a midpoint inside an input triangle knowing that triangle (e.g. its surface without a
// primary ray). Midpoints on the input mesh's edges, which a neighbour's refinement may create
// too, use `evaluateEdge` (given the edge, not the triangle) or `evaluate` (the position only),
// so the result does not depend on which triangle or run created them.
using EvaluateMidpointFn = std::function<VertexPaths(const glm::vec3& position,
                                                     const glm::vec3& normal, const MeshPoint& at)>;
// Where a midpoint on an input edge lies: at fraction s (an exact dyadic fraction) of the way from
// input vertex a to input vertex b, a < b — the same whichever triangle's refinement creates it.
struct EdgeMidpoint {
    uint32_t a = 0, b = 0;
    double s = 0.0;
};
// Traces a midpoint on an input edge knowing that edge (e.g. its surface when the primary ray
// grazes past the mesh at a silhouette).
using EvaluateEdgeFn = std::function<VertexPaths(const glm::vec3& position, const glm::vec3& normal,
                                                 const EdgeMidpoint& at)>;
using BackFacingFn = std::function<bool(const TriangleGeometry& triangle)>;
using OccludedFn = std::function<bool(const glm::vec3& position)>;

struct TessInput {
    std::vector<glm::vec3> positions;     // world space
    std::vector<glm::vec3> normals;       // unit, one per position
    std::vector<glm::uvec3> triangles;    // indices into positions
    ProjectFn project;                    // required
    EvaluateFn evaluate;                  // required
    EvaluateInputFn evaluateInput;        // optional: input vertices (else evaluate)
    EvaluateMidpointFn evaluateMidpoint;  // optional: midpoints (else evaluate)
    EvaluateEdgeFn evaluateEdge;          // optional: midpoints on input edges (else evaluate)
    BackFacingFn backFacing;              // optional: empty = every triangle front-facing
    OccludedFn occluded;                  // optional: empty = every vertex visible
};

struct TessOptions {
    double maxEdgeSubpixels = 3.0;  // t: edges at most this long on screen are not split
    double maxAngleDeg = 3.0;       // exit directions further apart than this differ
    // > 0: a triangle whose vertices' paths differ in topology (TopologyDiffers, on either term)
    // is split while some edge is longer than min(t, this); 0: t for every triangle (the paper's).
    double maxTopologyEdgeSubpixels = 0.0;
    int maxDepth = 10;  // bound on the refinement levels of one input triangle
    int threads = 1;    // > 1: callbacks are called concurrently (see above)
};

struct TessStats {
    size_t vertexRays = 0;        // traced vertices (= evaluate calls with 1 thread)
    size_t occlusionQueries = 0;  // occluded calls
    size_t trianglesIn = 0;
    size_t trianglesOut = 0;
    size_t split4 = 0, split3 = 0, split2 = 0;  // refinements by kind
    size_t backFacingTriangles = 0;             // input triangles skipped as back-facing
    size_t occludedTriangles = 0;  // triangles not refined because all three vertices are occluded
    size_t untracedVertices = 0;   // vertices used only by back-facing triangles
    size_t junctionTriangles = 0;  // refined triangles re-triangulated to remove t-junctions

    bool operator==(const TessStats&) const = default;
};

struct TessellationResult {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;                 // unit
    std::vector<std::optional<VertexPaths>> paths;  // nullopt: not traced (back-facing only)
    std::vector<glm::uvec3> triangles;              // no t-junctions
    TessStats stats;
};

TessellationResult Tessellate(const TessInput& input, const TessOptions& options);

// Helpers binding the callbacks to the shared camera.
// ProjectToImage scaled by `supersampling`; NaN for points at or behind the eye plane.
ProjectFn CameraProjection(const raster::Camera& camera, int supersampling);
// Back-facing when every vertex normal points away from the eye: dot(n, eye − p) <= 0.
BackFacingFn CameraBackFacing(const raster::Camera& camera);

}  // namespace pem::trace
