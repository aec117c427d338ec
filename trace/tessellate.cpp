// SPDX-License-Identifier: MIT
// tessellate.cpp — adaptive refinement (1-to-4 / 1-to-3 / 1-to-2 on the long edges while the
// vertex paths differ) with an edge-midpoint hash, then t-junction removal by ear clipping each
// refined triangle's boundary polygon.
// The ear tests run in the triangle's own reference frame (corners (0,0), (1,0), (0,1); edge
// vertices at dyadic parameters), where every coordinate and orientation is exact in double, so
// collinear edge vertices are recognised exactly; only the choice among valid ears (shortest new
// edge) uses world positions. The hash is only looked up, never iterated.
#include "trace/tessellate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace pem::trace {

namespace {

using Tri = std::array<uint32_t, 3>;

constexpr int kMaxDepthCap = 24;  // keeps the dyadic reference coordinates exact in double

uint64_t EdgeKey(uint32_t u, uint32_t v) {
    const uint32_t lo = std::min(u, v), hi = std::max(u, v);
    return (static_cast<uint64_t>(lo) << 32) | hi;
}

bool AnyPathsDiffer(const VertexPaths& a, const VertexPaths& b, double maxAngleDeg) {
    return PathsDiffer(a.reflection, b.reflection, maxAngleDeg) ||
           PathsDiffer(a.refraction, b.refraction, maxAngleDeg);
}

// A vertex of a refined triangle's boundary polygon with its exact reference coordinates.
struct PolyVertex {
    uint32_t index = 0;
    glm::dvec2 ref{0.0};
};

// Twice the signed area of (a, b, c) in the reference frame (exact for dyadic inputs).
double Orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Reference point at parameter s along edge `edge` of the corners (0,0), (1,0), (0,1).
glm::dvec2 EdgePoint(size_t edge, double s) {
    if (edge == 0) return {s, 0.0};
    if (edge == 1) return {1.0 - s, s};
    return {0.0, 1.0 - s};
}

class Tessellator {
  public:
    Tessellator(const TessInput& input, const TessOptions& options)
        : in_(input), opt_(options), maxDepth_(std::clamp(options.maxDepth, 0, kMaxDepthCap)) {}

    TessellationResult Run();

  private:
    void Validate() const;
    void InitVertices();
    void RefineInputTriangle(const glm::uvec3& triangle);
    void Refine(const Tri& tri, int depth);
    bool WantsSplit(const Tri& tri, const std::array<bool, 3>& longEdges);
    void Split(const Tri& tri, const std::array<bool, 3>& longEdges, int depth);
    void Split2(const Tri& r, int depth);
    void Split3(const Tri& r, int depth);
    void Split4(const Tri& r, int depth);
    uint32_t Midpoint(uint32_t u, uint32_t v);
    uint32_t AddVertex(const glm::vec3& position, const glm::vec3& normal);
    void Trace(uint32_t v);
    bool Occluded(uint32_t v);
    double ScreenLength(uint32_t u, uint32_t v) const;
    TriangleGeometry Geometry(const Tri& tri) const;

    void RemoveJunctions();
    void CollectEdge(uint32_t u, uint32_t v, double s0, double s1, size_t edge,
                     std::vector<PolyVertex>* poly) const;
    void EarClip(std::vector<PolyVertex> poly);
    bool IsEar(const std::vector<PolyVertex>& poly, size_t i) const;

    const TessInput& in_;
    const TessOptions& opt_;
    const int maxDepth_;
    TessellationResult out_;
    std::vector<glm::vec2> screen_;                     // projected position per vertex
    std::vector<int8_t> occluded_;                      // -1 not queried, 0 visible, 1 occluded
    std::unordered_map<uint64_t, uint32_t> midpoints_;  // edge (sorted pair) → midpoint vertex
    std::vector<Tri> leaves_;  // refined triangles, before t-junction removal
};

TessellationResult Tessellator::Run() {
    // Step 1: copy the input vertices (traced lazily, by the first front-facing triangle).
    Validate();
    InitVertices();
    // Step 2: refine every input triangle, in index order.
    out_.stats.trianglesIn = in_.triangles.size();
    for (const glm::uvec3& triangle : in_.triangles) RefineInputTriangle(triangle);
    // Step 3: close the t-junctions between differently refined neighbours.
    RemoveJunctions();
    out_.stats.trianglesOut = out_.triangles.size();
    out_.stats.untracedVertices =
        static_cast<size_t>(std::count(out_.paths.begin(), out_.paths.end(), std::nullopt));
    return std::move(out_);
}

void Tessellator::Validate() const {
    if (!in_.project || !in_.evaluate) {
        throw std::invalid_argument("Tessellate: project and evaluate callbacks are required");
    }
    if (in_.normals.size() != in_.positions.size()) {
        throw std::invalid_argument("Tessellate: one normal per position is required");
    }
    for (const glm::uvec3& t : in_.triangles) {
        for (int k = 0; k < 3; ++k) {
            if (t[k] >= in_.positions.size()) {
                throw std::invalid_argument("Tessellate: triangle index out of range");
            }
        }
    }
}

void Tessellator::InitVertices() {
    out_.positions = in_.positions;
    out_.normals = in_.normals;
    out_.paths.assign(in_.positions.size(), std::nullopt);
    occluded_.assign(in_.positions.size(), -1);
    screen_.reserve(in_.positions.size());
    for (const glm::vec3& p : in_.positions) screen_.push_back(in_.project(p));
}

void Tessellator::RefineInputTriangle(const glm::uvec3& triangle) {
    const Tri tri{triangle.x, triangle.y, triangle.z};
    if (in_.backFacing && in_.backFacing(Geometry(tri))) {
        ++out_.stats.backFacingTriangles;
        leaves_.push_back(tri);
        return;
    }
    for (uint32_t v : tri) Trace(v);
    Refine(tri, 0);
}

void Tessellator::Refine(const Tri& tri, int depth) {
    std::array<bool, 3> longEdges{};
    for (size_t k = 0; k < 3; ++k) {
        // !(len <= t): a non-finite projection counts as long.
        longEdges[k] = !(ScreenLength(tri[k], tri[(k + 1) % 3]) <= opt_.maxEdgeSubpixels);
    }
    if (depth < maxDepth_ && WantsSplit(tri, longEdges)) {
        Split(tri, longEdges, depth);
    } else {
        leaves_.push_back(tri);
    }
}

// Cheapest test first: some edge long, then the paths, then (ray queries) the occlusion.
bool Tessellator::WantsSplit(const Tri& tri, const std::array<bool, 3>& longEdges) {
    if (!longEdges[0] && !longEdges[1] && !longEdges[2]) return false;
    bool differ = false;
    for (size_t k = 0; k < 3 && !differ; ++k) {
        differ =
            AnyPathsDiffer(*out_.paths[tri[k]], *out_.paths[tri[(k + 1) % 3]], opt_.maxAngleDeg);
    }
    if (!differ) return false;
    if (Occluded(tri[0]) && Occluded(tri[1]) && Occluded(tri[2])) {
        ++out_.stats.occludedTriangles;
        return false;
    }
    return true;
}

// Rotate so that the split edges come first (1-to-2: edge 0; 1-to-3: edges 0 and 1), keeping the
// winding.
void Tessellator::Split(const Tri& tri, const std::array<bool, 3>& longEdges, int depth) {
    const int count = static_cast<int>(std::count(longEdges.begin(), longEdges.end(), true));
    size_t first = 0;
    for (size_t k = 0; k < 3; ++k) {
        const bool isFirst = count == 1 ? longEdges[k] : !longEdges[k];
        if (isFirst) first = count == 1 ? k : (k + 1) % 3;
    }
    const Tri r{tri[first], tri[(first + 1) % 3], tri[(first + 2) % 3]};
    if (count == 1) Split2(r, depth);
    if (count == 2) Split3(r, depth);
    if (count == 3) Split4(tri, depth);
}

void Tessellator::Split2(const Tri& r, int depth) {
    ++out_.stats.split2;
    const uint32_t m = Midpoint(r[0], r[1]);
    Refine({r[0], m, r[2]}, depth + 1);
    Refine({m, r[1], r[2]}, depth + 1);
}

// Edges r0-r1 and r1-r2 split; the quad (r0, m0, m1, r2) is cut along its shorter screen diagonal.
void Tessellator::Split3(const Tri& r, int depth) {
    ++out_.stats.split3;
    const uint32_t m0 = Midpoint(r[0], r[1]);
    const uint32_t m1 = Midpoint(r[1], r[2]);
    Refine({m0, r[1], m1}, depth + 1);
    if (ScreenLength(m0, r[2]) < ScreenLength(r[0], m1)) {
        Refine({r[0], m0, r[2]}, depth + 1);
        Refine({m0, m1, r[2]}, depth + 1);
    } else {
        Refine({r[0], m0, m1}, depth + 1);
        Refine({r[0], m1, r[2]}, depth + 1);
    }
}

void Tessellator::Split4(const Tri& r, int depth) {
    ++out_.stats.split4;
    const uint32_t m0 = Midpoint(r[0], r[1]);
    const uint32_t m1 = Midpoint(r[1], r[2]);
    const uint32_t m2 = Midpoint(r[2], r[0]);
    Refine({r[0], m0, m2}, depth + 1);
    Refine({m0, r[1], m1}, depth + 1);
    Refine({m2, m1, r[2]}, depth + 1);
    Refine({m0, m1, m2}, depth + 1);
}

// The shared midpoint of edge (u, v): looked up in the hash, else created and traced once.
uint32_t Tessellator::Midpoint(uint32_t u, uint32_t v) {
    const uint64_t key = EdgeKey(u, v);
    if (auto it = midpoints_.find(key); it != midpoints_.end()) return it->second;
    const uint32_t lo = std::min(u, v), hi = std::max(u, v);
    const glm::vec3 position = 0.5f * (out_.positions[lo] + out_.positions[hi]);
    const glm::vec3 sum = out_.normals[lo] + out_.normals[hi];
    const float length = glm::length(sum);
    const glm::vec3 normal = length > 0.0f ? sum / length : out_.normals[lo];
    const uint32_t m = AddVertex(position, normal);
    midpoints_.emplace(key, m);
    Trace(m);
    return m;
}

uint32_t Tessellator::AddVertex(const glm::vec3& position, const glm::vec3& normal) {
    out_.positions.push_back(position);
    out_.normals.push_back(normal);
    out_.paths.emplace_back(std::nullopt);
    occluded_.push_back(-1);
    screen_.push_back(in_.project(position));
    return static_cast<uint32_t>(out_.positions.size() - 1);
}

void Tessellator::Trace(uint32_t v) {
    if (out_.paths[v]) return;
    const glm::vec3 position = out_.positions[v], normal = out_.normals[v];
    out_.paths[v] = in_.evaluate(position, normal);
    ++out_.stats.vertexRays;
}

bool Tessellator::Occluded(uint32_t v) {
    if (!in_.occluded) return false;
    if (occluded_[v] < 0) {
        occluded_[v] = in_.occluded(out_.positions[v]) ? 1 : 0;
        ++out_.stats.occlusionQueries;
    }
    return occluded_[v] == 1;
}

double Tessellator::ScreenLength(uint32_t u, uint32_t v) const {
    const glm::dvec2 d = glm::dvec2(screen_[u]) - glm::dvec2(screen_[v]);
    return std::sqrt(d.x * d.x + d.y * d.y);
}

TriangleGeometry Tessellator::Geometry(const Tri& tri) const {
    TriangleGeometry g;
    for (size_t k = 0; k < 3; ++k) {
        g.positions[k] = out_.positions[tri[k]];
        g.normals[k] = out_.normals[tri[k]];
    }
    return g;
}

// Every refined triangle with extra vertices on its edges becomes the ear-clipped polygon of its
// corners and those vertices.
void Tessellator::RemoveJunctions() {
    const glm::dvec2 corners[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    for (const Tri& tri : leaves_) {
        std::vector<PolyVertex> poly;
        for (size_t k = 0; k < 3; ++k) {
            poly.push_back({tri[k], corners[k]});
            CollectEdge(tri[k], tri[(k + 1) % 3], 0.0, 1.0, k, &poly);
        }
        if (poly.size() == 3) {
            out_.triangles.emplace_back(tri[0], tri[1], tri[2]);
        } else {
            ++out_.stats.junctionTriangles;
            EarClip(std::move(poly));
        }
    }
}

// All vertices strictly inside edge (u, v), in order from u to v, found recursively through the
// midpoint hash.
void Tessellator::CollectEdge(uint32_t u, uint32_t v, double s0, double s1, size_t edge,
                              std::vector<PolyVertex>* poly) const {
    const auto it = midpoints_.find(EdgeKey(u, v));
    if (it == midpoints_.end()) return;
    const uint32_t m = it->second;
    const double s = 0.5 * (s0 + s1);
    CollectEdge(u, m, s0, s, edge, poly);
    poly->push_back({m, EdgePoint(edge, s)});
    CollectEdge(m, v, s, s1, edge, poly);
}

// Repeatedly clip the valid ear whose new edge is shortest in world space (first on ties).
void Tessellator::EarClip(std::vector<PolyVertex> poly) {
    while (poly.size() > 3) {
        size_t best = poly.size();
        double bestLength = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < poly.size(); ++i) {
            if (!IsEar(poly, i)) continue;
            const size_t prev = (i + poly.size() - 1) % poly.size(), next = (i + 1) % poly.size();
            const double length = glm::length(glm::dvec3(out_.positions[poly[prev].index]) -
                                              glm::dvec3(out_.positions[poly[next].index]));
            if (best == poly.size() || length < bestLength) {
                best = i;
                bestLength = length;
            }
        }
        if (best == poly.size()) throw std::logic_error("Tessellate: boundary polygon has no ear");
        const size_t prev = (best + poly.size() - 1) % poly.size();
        const size_t next = (best + 1) % poly.size();
        out_.triangles.emplace_back(poly[prev].index, poly[best].index, poly[next].index);
        poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(best));
    }
    out_.triangles.emplace_back(poly[0].index, poly[1].index, poly[2].index);
}

// Strictly convex at i, and no other polygon vertex in the closed triangle (prev, i, next).
bool Tessellator::IsEar(const std::vector<PolyVertex>& poly, size_t i) const {
    const size_t n = poly.size();
    const glm::dvec2& a = poly[(i + n - 1) % n].ref;
    const glm::dvec2& b = poly[i].ref;
    const glm::dvec2& c = poly[(i + 1) % n].ref;
    if (Orient(a, b, c) <= 0.0) return false;
    for (size_t j = 0; j < n; ++j) {
        if (j == i || j == (i + n - 1) % n || j == (i + 1) % n) continue;
        const glm::dvec2& p = poly[j].ref;
        if (Orient(a, b, p) >= 0.0 && Orient(b, c, p) >= 0.0 && Orient(c, a, p) >= 0.0) {
            return false;
        }
    }
    return true;
}

}  // namespace

TessellationResult Tessellate(const TessInput& input, const TessOptions& options) {
    return Tessellator(input, options).Run();
}

ProjectFn CameraProjection(const raster::Camera& camera, int supersampling) {
    const float scale = static_cast<float>(supersampling);
    return [camera, scale](const glm::vec3& position) {
        float depth = 0.0f;
        const glm::vec2 image = raster::ProjectToImage(camera, position, &depth);
        if (!(depth > 0.0f)) return glm::vec2(std::numeric_limits<float>::quiet_NaN());
        return image * scale;
    };
}

BackFacingFn CameraBackFacing(const raster::Camera& camera) {
    const glm::vec3 eye = camera.eye;
    return [eye](const TriangleGeometry& triangle) {
        for (size_t k = 0; k < 3; ++k) {
            if (glm::dot(triangle.normals[k], eye - triangle.positions[k]) > 0.0f) return false;
        }
        return true;
    };
}

}  // namespace pem::trace
