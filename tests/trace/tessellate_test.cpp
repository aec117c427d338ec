// SPDX-License-Identifier: MIT
// tessellate_test.cpp — adaptive tessellation on planar meshes with analytic fake vertex paths:
// watertightness after t-junction removal (edge pairing, original boundary, no vertex inside an
// edge), the split criteria on hand-made paths (topology, 2.9° vs 3.1°, short edges → 1-to-2 and
// 1-to-3, the finer topology threshold), back-facing and occluded triangles, area preservation,
// one trace per vertex, midpoints traced on their input triangle or input edge.
// Conventions: meshes lie in z = 0 with normals +z; the projection is (x, y) · scale subpixels.
#include "trace/tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <tuple>
#include <utility>

namespace pem::trace {
namespace {

using Edge = std::pair<uint32_t, uint32_t>;

RayPath MakePath(int length, Event first, Event later, const glm::vec3& exitDir) {
    RayPath path;
    for (int i = 0; i < length; ++i) {
        PathVertex v;
        v.event = i == 0 ? first : later;
        path.vertices.push_back(v);
    }
    path.exitDir = exitDir;
    path.escaped = true;
    return path;
}

VertexPaths MakePaths(int length, Event later, const glm::vec3& exitDir) {
    return {MakePath(length, Event::Reflect, later, exitDir),
            MakePath(length, Event::Refract, later, exitDir)};
}

// Exit direction rotated by angleDeg about +y from +z.
glm::vec3 Rotated(double angleDeg) {
    const double a = angleDeg * std::numbers::pi / 180.0;
    return {static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a))};
}

const VertexPaths kPlain = MakePaths(1, Event::Reflect, Rotated(0.0));

ProjectFn Scaled(float scale) {
    return [scale](const glm::vec3& p) { return glm::vec2(p.x, p.y) * scale; };
}

// An evaluator that counts its calls and records the positions it was asked for.
struct Recorder {
    std::vector<glm::vec3> asked;
    std::function<VertexPaths(const glm::vec3&)> paths;
    EvaluateFn Fn() {
        return [this](const glm::vec3& p, const glm::vec3&) {
            asked.push_back(p);
            return paths(p);
        };
    }
};

TessInput Triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    TessInput in;
    in.positions = {{a, 0.0f}, {b, 0.0f}, {c, 0.0f}};
    in.normals.assign(3, glm::vec3(0, 0, 1));
    in.triangles = {{0, 1, 2}};
    in.project = Scaled(1.0f);
    return in;
}

// (n+1)^2 vertices over [0, n]^2, two counter-clockwise triangles per unit cell.
TessInput Grid(int n) {
    TessInput in;
    for (int y = 0; y <= n; ++y) {
        for (int x = 0; x <= n; ++x) {
            in.positions.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.0f);
            in.normals.emplace_back(0.0f, 0.0f, 1.0f);
        }
    }
    const auto id = [n](int x, int y) { return static_cast<uint32_t>(y * (n + 1) + x); };
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            in.triangles.emplace_back(id(x, y), id(x + 1, y), id(x + 1, y + 1));
            in.triangles.emplace_back(id(x, y), id(x + 1, y + 1), id(x, y + 1));
        }
    }
    return in;
}

// Paths that change topology inside a few fixed circles and turn slowly with x.
VertexPaths RegionPaths(const glm::vec3& p) {
    const glm::vec2 centres[] = {{1.3f, 4.1f}, {4.6f, 1.7f}, {3.2f, 3.3f}};
    const float radii[] = {0.9f, 1.2f, 0.6f};
    int inside = 0;
    for (int k = 0; k < 3; ++k) {
        if (glm::length(glm::vec2(p) - centres[k]) < radii[k]) inside = k + 1;
    }
    const Event later = inside == 2 ? Event::Refract : Event::Reflect;
    return MakePaths(1 + (inside == 1 || inside == 3), later,
                     Rotated(2.0 * static_cast<double>(p.x)));
}

double Area(const std::vector<glm::vec3>& pos, const glm::uvec3& t) {
    const glm::dvec3 a(pos[t.x]), b(pos[t.y]), c(pos[t.z]);
    return 0.5 * glm::cross(b - a, c - a).z;  // signed: + for counter-clockwise in z = 0
}

double TotalArea(const std::vector<glm::vec3>& pos, const std::vector<glm::uvec3>& tris) {
    double sum = 0.0;
    for (const glm::uvec3& t : tris) sum += Area(pos, t);
    return sum;
}

std::map<Edge, int> DirectedEdges(const std::vector<glm::uvec3>& tris) {
    std::map<Edge, int> edges;
    for (const glm::uvec3& t : tris) {
        for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    }
    return edges;
}

// Boundary edges (directed edges without their reverse) as world segments.
std::vector<std::pair<glm::dvec3, glm::dvec3>> Boundary(const std::vector<glm::vec3>& pos,
                                                        const std::vector<glm::uvec3>& tris) {
    const std::map<Edge, int> edges = DirectedEdges(tris);
    std::vector<std::pair<glm::dvec3, glm::dvec3>> out;
    for (const auto& [e, count] : edges) {
        if (!edges.contains({e.second, e.first})) out.emplace_back(pos[e.first], pos[e.second]);
    }
    return out;
}

// Distance from p to segment ab and the parameter of its projection.
std::pair<double, double> SegmentDistance(const glm::dvec3& p, const glm::dvec3& a,
                                          const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double s = glm::dot(p - a, ab) / glm::dot(ab, ab);
    return {glm::length(p - (a + std::clamp(s, 0.0, 1.0) * ab)), s};
}

// Watertight and t-junction free, with exactly the input's boundary.
void ExpectWatertight(const TessInput& in, const TessellationResult& r) {
    // Step 1: every directed edge once; interior edges paired with their reverse.
    for (const auto& [e, count] : DirectedEdges(r.triangles)) {
        ASSERT_EQ(count, 1) << "edge " << e.first << "-" << e.second;
    }
    // Step 2: every output boundary edge lies on an input boundary edge; same total length.
    const auto inBoundary = Boundary(in.positions, in.triangles);
    double inLength = 0.0, outLength = 0.0;
    for (const auto& [a, b] : inBoundary) inLength += glm::length(b - a);
    for (const auto& [a, b] : Boundary(r.positions, r.triangles)) {
        outLength += glm::length(b - a);
        bool onInput = false;
        for (const auto& [c, d] : inBoundary) {
            onInput |=
                SegmentDistance(a, c, d).first < 1e-6 && SegmentDistance(b, c, d).first < 1e-6;
        }
        EXPECT_TRUE(onInput);
    }
    EXPECT_NEAR(outLength, inLength, 1e-6 * inLength);
    // Step 3: no used vertex in the interior of an edge it is not an endpoint of.
    std::set<uint32_t> used;
    for (const glm::uvec3& t : r.triangles) used.insert({t.x, t.y, t.z});
    for (const auto& [e, count] : DirectedEdges(r.triangles)) {
        const glm::dvec3 a(r.positions[e.first]), b(r.positions[e.second]);
        for (uint32_t v : used) {
            if (v == e.first || v == e.second) continue;
            const auto [dist, s] = SegmentDistance(glm::dvec3(r.positions[v]), a, b);
            ASSERT_FALSE(dist < 1e-6 && s > 1e-6 && s < 1.0 - 1e-6)
                << "vertex " << v << " inside edge " << e.first << "-" << e.second;
        }
    }
}

TEST(Tessellate, RegionsGiveWatertightMeshWithoutTJunctions) {
    TessInput in = Grid(6);
    in.project = Scaled(24.0f);
    Recorder rec{{}, RegionPaths};
    in.evaluate = rec.Fn();
    const TessellationResult r = Tessellate(in, {.maxEdgeSubpixels = 3.0});
    EXPECT_GT(r.stats.split4, 0u);
    EXPECT_GT(r.stats.split3 + r.stats.split2, 0u);
    EXPECT_GT(r.stats.junctionTriangles, 0u);
    EXPECT_EQ(r.stats.trianglesIn, in.triangles.size());
    EXPECT_EQ(r.stats.trianglesOut, r.triangles.size());
    ExpectWatertight(in, r);
    // Area preserved, and no triangle flipped or degenerate.
    EXPECT_NEAR(TotalArea(r.positions, r.triangles), 36.0, 36.0 * 1e-5);
    for (const glm::uvec3& t : r.triangles) EXPECT_GT(Area(r.positions, t), 0.0);
}

TEST(Tessellate, EachVertexTracedOnce) {
    TessInput in = Grid(4);
    in.project = Scaled(24.0f);
    Recorder rec{{}, RegionPaths};
    in.evaluate = rec.Fn();
    const TessellationResult r = Tessellate(in, {});
    EXPECT_GT(r.positions.size(), in.positions.size());
    EXPECT_EQ(rec.asked.size(), r.positions.size());
    EXPECT_EQ(r.stats.vertexRays, r.positions.size());
    EXPECT_EQ(r.stats.untracedVertices, 0u);
    std::set<std::tuple<float, float, float>> distinct;
    for (const glm::vec3& p : rec.asked) distinct.insert({p.x, p.y, p.z});
    EXPECT_EQ(distinct.size(), rec.asked.size());
    for (size_t v = 0; v < r.positions.size(); ++v) {
        ASSERT_TRUE(r.paths[v].has_value());
        EXPECT_EQ(r.paths[v]->reflection, RegionPaths(r.positions[v]).reflection);
    }
}

TEST(Tessellate, Deterministic) {
    TessInput in = Grid(4);
    in.project = Scaled(24.0f);
    in.evaluate = [](const glm::vec3& p, const glm::vec3&) { return RegionPaths(p); };
    const TessellationResult a = Tessellate(in, {});
    const TessellationResult b = Tessellate(in, {});
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.stats, b.stats);
}

// Runs of input triangles refined on several threads and merged give the serial result: the
// numbering, triangles, paths and statistics (a larger grid, some triangles back-facing, some
// vertices occluded, so runs meet across refined borders).
TEST(Tessellate, ThreadCountDoesNotChangeResult) {
    TessInput in = Grid(12);
    for (size_t v = 0; v < in.positions.size(); ++v)
        if (in.positions[v].x > 10.5f) in.normals[v] = glm::vec3(0.0f, 0.0f, -1.0f);
    in.project = Scaled(24.0f);
    in.evaluate = [](const glm::vec3& p, const glm::vec3&) { return RegionPaths(p * 0.5f); };
    in.backFacing = [](const TriangleGeometry& g) {
        return g.normals[0].z < 0.0f && g.normals[1].z < 0.0f && g.normals[2].z < 0.0f;
    };
    in.occluded = [](const glm::vec3& p) { return p.y > 9.0f; };
    const TessellationResult one = Tessellate(in, {});
    EXPECT_GT(one.stats.backFacingTriangles, 0u);
    EXPECT_GT(one.stats.occludedTriangles, 0u);
    for (int threads : {2, 3, 7}) {
        const TessellationResult many = Tessellate(in, {.threads = threads});
        EXPECT_EQ(many.positions, one.positions) << threads;
        EXPECT_EQ(many.normals, one.normals) << threads;
        EXPECT_EQ(many.triangles, one.triangles) << threads;
        EXPECT_EQ(many.stats, one.stats) << threads;
        ASSERT_EQ(many.paths.size(), one.paths.size());
        for (size_t v = 0; v < one.paths.size(); ++v) {
            ASSERT_EQ(many.paths[v].has_value(), one.paths[v].has_value()) << v;
            if (one.paths[v]) {
                EXPECT_EQ(many.paths[v]->reflection, one.paths[v]->reflection);
            }
        }
    }
}

// evaluateMidpoint: called for midpoints strictly inside an input triangle, with that triangle
// and the midpoint's barycentric weights; edge midpoints go to evaluate. Paths that depend on
// the triangle still give the same result for any thread count.
// Tessellate(in) at depth 6 on 2 and 3 threads gives `one` (the serial result): the vertices,
// triangles and each traced vertex's reflection path.
void ExpectSameOnThreads(const TessInput& in, const TessellationResult& one) {
    for (int threads : {2, 3}) {
        const TessellationResult many = Tessellate(in, {.maxDepth = 6, .threads = threads});
        EXPECT_EQ(many.positions, one.positions) << threads;
        EXPECT_EQ(many.triangles, one.triangles) << threads;
        ASSERT_EQ(many.paths.size(), one.paths.size());
        for (size_t v = 0; v < one.paths.size(); ++v) {
            if (!one.paths[v]) continue;
            EXPECT_EQ(many.paths[v]->reflection, one.paths[v]->reflection) << v;
        }
    }
}

TEST(Tessellate, InteriorMidpointsKnowTheirTriangle) {
    TessInput in = Grid(6);
    in.project = Scaled(40.0f);
    in.evaluate = [](const glm::vec3& p, const glm::vec3&) { return RegionPaths(p); };
    std::atomic<int> interior{0}, wrong{0};
    in.evaluateMidpoint = [&](const glm::vec3& p, const glm::vec3&, const MeshPoint& at) {
        ++interior;
        const glm::uvec3 t = in.triangles.at(at.triangle);
        const glm::dvec3 q = (1.0 - at.u - at.v) * glm::dvec3(in.positions[t.x]) +
                             at.u * glm::dvec3(in.positions[t.y]) +
                             at.v * glm::dvec3(in.positions[t.z]);
        if (!(at.u > 0.0 && at.v > 0.0 && at.u + at.v < 1.0) ||
            glm::length(q - glm::dvec3(p)) > 1e-6)
            ++wrong;
        // Paths depending on the triangle: odd triangles turn the exit 2° more.
        VertexPaths paths = RegionPaths(p);
        if (at.triangle % 2)
            paths.reflection.exitDir = Rotated(2.0 + 2.0 * static_cast<double>(p.x));
        return paths;
    };
    const TessellationResult one = Tessellate(in, {.maxDepth = 6});
    EXPECT_GT(interior.load(), 0);
    EXPECT_EQ(wrong.load(), 0);
    ExpectWatertight(in, one);
    ExpectSameOnThreads(in, one);
    EXPECT_EQ(wrong.load(), 0);
}

// A midpoint on an input edge is traced knowing the edge — its input vertices a < b and the
// exact fraction s from a — not the triangle that happened to create it, so neighbours and runs
// on other threads give it the same paths; `evaluate` then serves no midpoint.
TEST(Tessellate, EdgeMidpointsKnowTheirEdge) {
    TessInput in = Grid(6);
    in.project = Scaled(40.0f);
    std::atomic<int> byPosition{0}, onEdges{0}, wrong{0};
    in.evaluate = [&](const glm::vec3& p, const glm::vec3&) {
        ++byPosition;
        return RegionPaths(p);
    };
    in.evaluateInput = [&](size_t v) { return RegionPaths(in.positions[v]); };
    in.evaluateMidpoint = [](const glm::vec3& p, const glm::vec3&, const MeshPoint&) {
        return RegionPaths(p);
    };
    std::set<std::pair<uint32_t, uint32_t>> edges;  // the input mesh's, sorted pairs
    for (const glm::uvec3& t : in.triangles)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    in.evaluateEdge = [&](const glm::vec3& p, const glm::vec3&, const EdgeMidpoint& at) {
        ++onEdges;
        const glm::dvec3 q = (1.0 - at.s) * glm::dvec3(in.positions.at(at.a)) +
                             at.s * glm::dvec3(in.positions.at(at.b));
        if (!(at.a < at.b && at.s > 0.0 && at.s < 1.0 && edges.count({at.a, at.b}) == 1) ||
            glm::length(q - glm::dvec3(p)) > 1e-6)
            ++wrong;
        // Paths depending on the edge: edges from an even vertex turn the exit 2° more.
        VertexPaths paths = RegionPaths(p);
        if (at.a % 2 == 0) paths.reflection.exitDir = Rotated(2.0 + 2.0 * static_cast<double>(p.x));
        return paths;
    };
    const TessellationResult one = Tessellate(in, {.maxDepth = 6});
    EXPECT_GT(onEdges.load(), 0);
    EXPECT_EQ(wrong.load(), 0);
    EXPECT_EQ(byPosition.load(), 0);  // every input vertex and midpoint has its own callback
    ExpectWatertight(in, one);
    ExpectSameOnThreads(in, one);
    EXPECT_EQ(wrong.load(), 0);
}

TEST(Tessellate, IdenticalPathsNeverSplit) {
    TessInput in = Triangle({0, 0}, {100, 0}, {0, 100});
    Recorder rec{{}, [](const glm::vec3&) { return kPlain; }};
    in.evaluate = rec.Fn();
    const TessellationResult r = Tessellate(in, {});
    EXPECT_EQ(r.triangles.size(), 1u);
    EXPECT_EQ(rec.asked.size(), 3u);
}

// Exit angle grows with x: vertex (1, 0) is `angleDeg` away from the other two.
TessellationResult AngleCase(double angleDeg) {
    TessInput in = Triangle({0, 0}, {1, 0}, {0, 1});
    in.project = Scaled(100.0f);
    in.evaluate = [angleDeg](const glm::vec3& p, const glm::vec3&) {
        return MakePaths(1, Event::Reflect, Rotated(angleDeg * static_cast<double>(p.x)));
    };
    return Tessellate(in, {});
}

TEST(Tessellate, ExitAngleThreshold) {
    const TessellationResult below = AngleCase(2.9);
    EXPECT_EQ(below.triangles.size(), 1u);
    EXPECT_EQ(below.stats.vertexRays, 3u);
    // 3.1° splits once; the children differ by at most 1.55°.
    const TessellationResult above = AngleCase(3.1);
    EXPECT_EQ(above.stats.split4, 1u);
    EXPECT_EQ(above.triangles.size(), 4u);
    EXPECT_EQ(above.stats.vertexRays, 6u);
}

// Vertex (1, 0) gets `odd`, the others kPlain; one level of refinement at most.
TessellationResult OddVertexCase(const VertexPaths& odd) {
    TessInput in = Triangle({0, 0}, {100, 0}, {0, 100});
    in.evaluate = [odd](const glm::vec3& p, const glm::vec3&) {
        return p.x == 100.0f ? odd : kPlain;
    };
    return Tessellate(in, {.maxDepth = 1});
}

TEST(Tessellate, TopologyDifferencesSplit) {
    EXPECT_EQ(OddVertexCase(kPlain).stats.split4, 0u);
    // A longer path (one more interface).
    EXPECT_EQ(OddVertexCase(MakePaths(2, Event::Reflect, Rotated(0))).stats.split4, 1u);
    // Same length, the second interface chooses refraction instead of reflection.
    const VertexPaths base = MakePaths(2, Event::Reflect, Rotated(0));
    TessInput in = Triangle({0, 0}, {100, 0}, {0, 100});
    in.evaluate = [&](const glm::vec3& p, const glm::vec3&) {
        return p.x == 100.0f ? MakePaths(2, Event::Refract, Rotated(0)) : base;
    };
    EXPECT_EQ(Tessellate(in, {.maxDepth = 1}).stats.split4, 1u);
    // Only the refraction term differs: still split (either term).
    VertexPaths oneTerm = kPlain;
    oneTerm.refraction.escaped = false;
    EXPECT_EQ(OddVertexCase(oneTerm).stats.split4, 1u);
}

// A triangle 8 subpixels on its legs whose paths change topology at x = 6 (one interface more
// beyond) and turn by `degPerUnit` degrees per subpixel along x.
TessellationResult DiscontinuityCase(double t, double topologyT, double degPerUnit = 0.0) {
    TessInput in = Triangle({0, 0}, {8, 0}, {0, 8});
    in.evaluate = [degPerUnit](const glm::vec3& p, const glm::vec3&) {
        return MakePaths(p.x > 6.0f ? 2 : 1, Event::Reflect,
                         Rotated(degPerUnit * static_cast<double>(p.x)));
    };
    return Tessellate(in, {.maxEdgeSubpixels = t, .maxTopologyEdgeSubpixels = topologyT});
}

double LongestEdge(const TessellationResult& r, const glm::uvec3& t) {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
        longest = std::max(longest, static_cast<double>(glm::distance(
                                        r.positions[t[k]], r.positions[t[(k + 1) % 3]])));
    return longest;
}

bool Straddles(const TessellationResult& r, const glm::uvec3& t) {
    int beyond = 0;
    for (int k = 0; k < 3; ++k) beyond += r.positions[t[k]].x > 6.0f;
    return beyond == 1 || beyond == 2;
}

// Triangles across a change of topology refine down to the topology threshold, not t; exit
// directions that merely diverge stop at t; a threshold of 0 or at least t is the paper's rule.
TEST(Tessellate, TopologyThresholdRefinesDiscontinuitiesFurther) {
    const TessellationResult paper = DiscontinuityCase(5.0, 0.0);
    const TessellationResult fine = DiscontinuityCase(5.0, 2.0);
    double paperLongest = 0.0;
    for (const glm::uvec3& t : paper.triangles)
        if (Straddles(paper, t)) paperLongest = std::max(paperLongest, LongestEdge(paper, t));
    EXPECT_GT(paperLongest, 2.0);  // t alone leaves longer edges across the discontinuity
    size_t straddling = 0;
    for (const glm::uvec3& t : fine.triangles) {
        if (!Straddles(fine, t)) continue;
        ++straddling;
        EXPECT_LE(LongestEdge(fine, t), 2.0);
    }
    EXPECT_GT(straddling, 0u);
    EXPECT_GT(fine.stats.vertexRays, paper.stats.vertexRays);
    EXPECT_NEAR(TotalArea(fine.positions, fine.triangles), 32.0, 1e-4);
    for (const glm::uvec3& t : fine.triangles) EXPECT_GT(Area(fine.positions, t), 0.0);
    // A threshold at or above t changes nothing.
    EXPECT_EQ(DiscontinuityCase(5.0, 5.0).triangles, paper.triangles);
    EXPECT_EQ(DiscontinuityCase(5.0, 7.0).positions, paper.positions);
    // Without a change of topology (the same length everywhere) exit angles of 4° per subpixel
    // split down to t only: the threshold changes nothing.
    TessInput in = Triangle({0, 0}, {8, 0}, {0, 8});
    in.evaluate = [](const glm::vec3& p, const glm::vec3&) {
        return MakePaths(1, Event::Reflect, Rotated(4.0 * static_cast<double>(p.x)));
    };
    const TessellationResult angles = Tessellate(in, {.maxEdgeSubpixels = 5.0});
    const TessellationResult anglesFine =
        Tessellate(in, {.maxEdgeSubpixels = 5.0, .maxTopologyEdgeSubpixels = 2.0});
    EXPECT_GT(angles.stats.split4 + angles.stats.split3 + angles.stats.split2, 0u);
    EXPECT_EQ(anglesFine.positions, angles.positions);
    EXPECT_EQ(anglesFine.triangles, angles.triangles);
}

// Every vertex differs from every other (path length = call number).
EvaluateFn AlwaysDiffer() {
    auto calls = std::make_shared<int>(0);
    return [calls](const glm::vec3&, const glm::vec3&) {
        return MakePaths(++*calls, Event::Reflect, Rotated(0));
    };
}

// Opposite normals sum to zero: the midpoint takes the normal of the endpoint first in
// (position, normal) order, whichever way round the edge is numbered.
TEST(Tessellate, OppositeNormalsMidpointIndependentOfNumbering) {
    for (bool swapped : {false, true}) {
        TessInput in =
            swapped ? Triangle({100, 0}, {0, 0}, {0, 100}) : Triangle({0, 0}, {100, 0}, {0, 100});
        in.normals[swapped ? 1 : 0] = glm::vec3(0, 0, -1);  // the vertex at the origin
        in.evaluate = AlwaysDiffer();
        const TessellationResult r = Tessellate(in, {.maxDepth = 1});
        ASSERT_EQ(r.positions.size(), 6u);
        EXPECT_EQ(r.positions[3], glm::vec3(50, 0, 0));
        EXPECT_EQ(r.normals[3], glm::vec3(0, 0, -1)) << swapped;
    }
}

TEST(Tessellate, OnlyLongEdgesSplit) {
    const TessOptions oneLevel{.maxEdgeSubpixels = 3.0, .maxDepth = 1};
    // All edges ≤ t: no split even though the paths differ.
    TessInput small = Triangle({0, 0}, {2, 0}, {0, 2});
    small.evaluate = AlwaysDiffer();
    EXPECT_EQ(Tessellate(small, oneLevel).triangles.size(), 1u);
    // One long edge (4 > 3; the others √5): 1-to-2 at its midpoint.
    TessInput one = Triangle({0, 0}, {4, 0}, {2, 1});
    one.evaluate = AlwaysDiffer();
    const TessellationResult r2 = Tessellate(one, oneLevel);
    EXPECT_EQ(r2.stats.split2, 1u);
    EXPECT_EQ(r2.stats.split3 + r2.stats.split4, 0u);
    EXPECT_EQ(r2.triangles.size(), 2u);
    ASSERT_EQ(r2.positions.size(), 4u);
    EXPECT_EQ(r2.positions[3], glm::vec3(2, 0, 0));
    // Two long edges (4 and √22.25; the third 2.5): 1-to-3.
    TessInput two = Triangle({0, 0}, {4, 0}, {4, 2.5f});
    two.evaluate = AlwaysDiffer();
    const TessellationResult r3 = Tessellate(two, oneLevel);
    EXPECT_EQ(r3.stats.split3, 1u);
    EXPECT_EQ(r3.stats.split2 + r3.stats.split4, 0u);
    EXPECT_EQ(r3.triangles.size(), 3u);
    ASSERT_EQ(r3.positions.size(), 5u);
    EXPECT_NEAR(TotalArea(r3.positions, r3.triangles), 5.0, 1e-6);
    for (const glm::uvec3& t : r3.triangles) EXPECT_GT(Area(r3.positions, t), 0.0);
}

TEST(Tessellate, RefinesUntilEdgesAreShort) {
    TessInput in = Grid(2);
    in.project = Scaled(10.0f);
    in.evaluate = AlwaysDiffer();
    const TessellationResult r = Tessellate(in, {.maxEdgeSubpixels = 3.0, .maxDepth = 20});
    for (const glm::uvec3& t : r.triangles) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(10.0 * glm::distance(glm::dvec3(r.positions[t[k]]),
                                           glm::dvec3(r.positions[t[(k + 1) % 3]])),
                      3.0);
        }
    }
    ExpectWatertight(in, r);
    EXPECT_NEAR(TotalArea(r.positions, r.triangles), 4.0, 4.0 * 1e-5);
}

// Two triangles sharing the diagonal 1-2; only the lower one refines, the upper one is mended.
TEST(Tessellate, NeighbourOfRefinedTriangleIsRetriangulated) {
    TessInput in = Grid(1);
    in.triangles = {{0, 1, 2}, {1, 3, 2}};
    in.project = Scaled(100.0f);
    in.evaluate = [](const glm::vec3& p, const glm::vec3&) {
        return p == glm::vec3(0.0f) ? MakePaths(2, Event::Reflect, Rotated(0)) : kPlain;
    };
    const TessellationResult r = Tessellate(in, {.maxDepth = 1});
    EXPECT_EQ(r.stats.split4, 1u);
    EXPECT_EQ(r.stats.junctionTriangles, 1u);
    EXPECT_EQ(r.triangles.size(), 6u);
    ExpectWatertight(in, r);
}

TEST(Tessellate, BackFacingVerticesNotTraced) {
    // Front quad facing the eye at z = 5; a triangle sharing edge 1-3 whose normals face away.
    TessInput in = Grid(1);
    in.positions.emplace_back(2.0f, 0.5f, 0.0f);
    in.normals.emplace_back(0.0f, 0.0f, -1.0f);
    in.normals[1] = in.normals[3] = glm::vec3(0, 0, -1);  // shared edge: away from the eye too
    in.triangles.emplace_back(1, 4, 3);
    raster::Camera camera;
    camera.eye = {0.5f, 0.5f, 5.0f};
    camera.target = {0.5f, 0.5f, 0.0f};
    camera.width = camera.height = 64;
    in.project = CameraProjection(camera, 2);
    in.backFacing = CameraBackFacing(camera);
    Recorder rec{{}, [](const glm::vec3& p) {  // vertex 0 differs: the front quad refines
                     return p == glm::vec3(0.0f) ? MakePaths(2, Event::Reflect, Rotated(0))
                                                 : kPlain;
                 }};
    in.evaluate = rec.Fn();
    const TessellationResult r = Tessellate(in, {.maxDepth = 2});
    EXPECT_EQ(r.stats.backFacingTriangles, 1u);
    EXPECT_EQ(r.stats.untracedVertices, 1u);
    EXPECT_FALSE(r.paths[4].has_value());
    for (const glm::vec3& p : rec.asked) EXPECT_NE(p, in.positions[4]);
    EXPECT_EQ(rec.asked.size(), r.positions.size() - 1);
    ExpectWatertight(in, r);
}

TEST(Tessellate, OccludedTrianglesNotRefined) {
    TessInput in = Triangle({0, 0}, {100, 0}, {0, 100});
    in.evaluate = AlwaysDiffer();
    in.occluded = [](const glm::vec3&) { return true; };
    const TessellationResult hidden = Tessellate(in, {});
    EXPECT_EQ(hidden.triangles.size(), 1u);
    EXPECT_EQ(hidden.stats.vertexRays, 3u);  // still traced (texture coordinates)
    EXPECT_EQ(hidden.stats.occludedTriangles, 1u);
    EXPECT_EQ(hidden.stats.occlusionQueries, 3u);
    // One visible vertex is enough to refine.
    in.evaluate = AlwaysDiffer();
    in.occluded = [](const glm::vec3& p) { return p.x < 99.0f; };
    const TessellationResult partly = Tessellate(in, {.maxDepth = 1});
    EXPECT_EQ(partly.stats.split4, 1u);
    EXPECT_EQ(partly.triangles.size(), 4u);
}

TEST(Tessellate, CameraProjectionInSubpixels) {
    raster::Camera camera;
    camera.eye = {0.0f, 0.0f, 4.0f};
    camera.width = 40;
    camera.height = 30;
    const ProjectFn project = CameraProjection(camera, 3);
    const glm::vec2 centre = project(glm::vec3(0.0f));
    EXPECT_FLOAT_EQ(centre.x, 60.0f);
    EXPECT_FLOAT_EQ(centre.y, 45.0f);
    EXPECT_TRUE(std::isnan(project(glm::vec3(0.0f, 0.0f, 5.0f)).x));  // behind the eye
}

TEST(Tessellate, RejectsBadInput) {
    TessInput in = Triangle({0, 0}, {1, 0}, {0, 1});
    EXPECT_THROW(Tessellate(in, {}), std::invalid_argument);  // no evaluate callback
    in.evaluate = AlwaysDiffer();
    in.triangles.push_back({0, 1, 7});
    EXPECT_THROW(Tessellate(in, {}), std::invalid_argument);
}

}  // namespace
}  // namespace pem::trace
