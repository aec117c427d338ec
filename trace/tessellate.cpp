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
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "base/parallel.h"

namespace pem::trace {

namespace {

using Tri = std::array<uint32_t, 3>;
// Barycentric (u, v) of a triangle's corners in the input triangle being refined (weights of its
// corners 1 and 2; dyadic fractions, exact in double).
using Bary = std::array<glm::dvec2, 3>;

constexpr int kMaxDepthCap = 24;  // keeps the dyadic reference coordinates exact in double

uint64_t EdgeKey(uint32_t u, uint32_t v) {
    const uint32_t lo = std::min(u, v), hi = std::max(u, v);
    return (static_cast<uint64_t>(lo) << 32) | hi;
}

bool AnyTopologyDiffers(const VertexPaths& a, const VertexPaths& b) {
    return TopologyDiffers(a.reflection, b.reflection) ||
           TopologyDiffers(a.refraction, b.refraction);
}

bool AnyPathsDiffer(const VertexPaths& a, const VertexPaths& b, double maxAngleDeg) {
    return PathsDiffer(a.reflection, b.reflection, maxAngleDeg) ||
           PathsDiffer(a.refraction, b.refraction, maxAngleDeg);
}

// Edge (sorted pair) → midpoint vertex: open addressing with linear probing (only inserted and
// looked up, never iterated or erased).
class EdgeHash {
  public:
    EdgeHash() { Rehash(1024); }
    const uint32_t* Find(uint64_t key) const {
        for (size_t i = Slot(key);; i = (i + 1) & mask_) {
            if (keys_[i] == key) return &values_[i];
            if (keys_[i] == kEmpty) return nullptr;
        }
    }
    // Room for `n` entries without rehashing.
    void Reserve(size_t n) {
        size_t capacity = keys_.size();
        while (2 * n > capacity) capacity *= 2;
        if (capacity != keys_.size()) Rehash(capacity);
    }
    void Insert(uint64_t key, uint32_t value) {
        if (2 * (size_ + 1) > keys_.size()) Rehash(2 * keys_.size());
        size_t i = Slot(key);
        while (keys_[i] != kEmpty) i = (i + 1) & mask_;
        keys_[i] = key;
        values_[i] = value;
        ++size_;
    }

  private:
    static constexpr uint64_t kEmpty = ~uint64_t{0};  // no edge has two indices 2^32 - 1
    size_t Slot(uint64_t key) const {
        return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);  // Fibonacci hashing
    }
    void Rehash(size_t capacity) {
        std::vector<uint64_t> keys(capacity, kEmpty);
        std::vector<uint32_t> values(capacity, 0);
        keys.swap(keys_);
        values.swap(values_);
        mask_ = capacity - 1;
        shift_ = 64 - std::countr_zero(capacity);
        size_ = 0;
        for (size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty) Insert(keys[i], values[i]);
    }
    std::vector<uint64_t> keys_;
    std::vector<uint32_t> values_;
    size_t mask_ = 0, size_ = 0;
    int shift_ = 64;
};

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

// Read-only during refinement: the input, its projections, which input triangles face away,
// and the paths of the input vertices of front-facing triangles (traced before refinement).
struct Shared {
    const TessInput& in;
    const TessOptions& opt;
    int maxDepth = 0;
    std::vector<glm::vec2> screen;
    std::vector<uint8_t> backFacing;  // per input triangle
    std::vector<std::optional<VertexPaths>> paths;
};

// True when endpoint a comes before b in (position, normal) order: a choice that does not depend
// on the vertex numbering (the midpoint normal's fallback).
bool Before(const glm::vec3& pa, const glm::vec3& na, const glm::vec3& pb, const glm::vec3& nb) {
    return std::tie(pa.x, pa.y, pa.z, na.x, na.y, na.z) <
           std::tie(pb.x, pb.y, pb.z, nb.x, nb.y, nb.z);
}

// The midpoint of an edge: position and normal, independent of the endpoints' order.
void MidpointOf(const glm::vec3& pu, const glm::vec3& nu, const glm::vec3& pv, const glm::vec3& nv,
                glm::vec3* position, glm::vec3* normal) {
    *position = 0.5f * (pu + pv);
    const glm::vec3 sum = nu + nv;
    const float length = glm::length(sum);
    *normal = length > 0.0f ? sum / length : (Before(pu, nu, pv, nv) ? nu : nv);
}

// Refines a run of consecutive input triangles. Vertices 0..nIn-1 are the shared input vertices,
// the run's own new vertices follow (nIn + creation index). Runs over disjoint triangle ranges
// are independent; merging them in range order gives the serial run's numbering (Tessellator).
class Refiner {
  public:
    explicit Refiner(const Shared& shared)
        : s_(shared), nIn_(static_cast<uint32_t>(shared.in.positions.size())) {}

    void Run(size_t first, size_t last);

    // Per new vertex (index − nIn): its data and the edge (run indices) it is the midpoint of.
    std::vector<glm::vec3> positions, normals;
    std::vector<VertexPaths> paths;
    std::vector<glm::vec2> screen;
    std::vector<int8_t> occluded;  // -1 not queried, 0 visible, 1 occluded
    std::vector<std::array<uint32_t, 2>> parents;
    std::vector<int8_t> inputOccluded;  // the same for the input vertices
    std::vector<Tri> leaves;            // refined triangles, before t-junction removal
    TessStats stats;                    // split*, backFacing and occludedTriangles

  private:
    void Refine(const Tri& tri, const Bary& at, int depth);
    double EdgeThreshold(const Tri& tri) const;
    bool WantsSplit(const Tri& tri, const std::array<bool, 3>& longEdges);
    void Split(const Tri& tri, const Bary& at, const std::array<bool, 3>& longEdges, int depth);
    void Split2(const Tri& r, const Bary& at, int depth);
    void Split3(const Tri& r, const Bary& at, int depth);
    void Split4(const Tri& r, const Bary& at, int depth);
    uint32_t Midpoint(uint32_t u, uint32_t v, const glm::dvec2& au, const glm::dvec2& av);
    EdgeMidpoint EdgeOf(const glm::dvec2& at) const;
    bool Occluded(uint32_t v);
    double ScreenLength(uint32_t u, uint32_t v) const;

    const glm::vec3& Position(uint32_t v) const {
        return v < nIn_ ? s_.in.positions[v] : positions[v - nIn_];
    }
    const glm::vec3& Normal(uint32_t v) const {
        return v < nIn_ ? s_.in.normals[v] : normals[v - nIn_];
    }
    const VertexPaths& Paths(uint32_t v) const { return v < nIn_ ? *s_.paths[v] : paths[v - nIn_]; }
    const glm::vec2& Screen(uint32_t v) const { return v < nIn_ ? s_.screen[v] : screen[v - nIn_]; }

    const Shared& s_;
    const uint32_t nIn_;
    size_t input_ = 0;    // the input triangle being refined
    EdgeHash midpoints_;  // edge (sorted pair, run indices) → midpoint vertex
};

void Refiner::Run(size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) {
        const glm::uvec3& t = s_.in.triangles[i];
        const Tri tri{t.x, t.y, t.z};
        if (s_.backFacing[i]) {
            ++stats.backFacingTriangles;
            leaves.push_back(tri);
            continue;
        }
        input_ = i;
        Refine(tri, {glm::dvec2(0.0, 0.0), glm::dvec2(1.0, 0.0), glm::dvec2(0.0, 1.0)}, 0);
    }
}

void Refiner::Refine(const Tri& tri, const Bary& at, int depth) {
    const double t = EdgeThreshold(tri);
    std::array<bool, 3> longEdges{};
    for (size_t k = 0; k < 3; ++k) {
        // !(len <= t): a non-finite projection counts as long.
        longEdges[k] = !(ScreenLength(tri[k], tri[(k + 1) % 3]) <= t);
    }
    if (depth < s_.maxDepth && WantsSplit(tri, longEdges)) {
        Split(tri, at, longEdges, depth);
    } else {
        leaves.push_back(tri);
    }
}

// The length below which the triangle's edges are not split: t, or the finer topology threshold
// when two of its vertices' paths differ in topology.
double Refiner::EdgeThreshold(const Tri& tri) const {
    const double t = s_.opt.maxEdgeSubpixels, topology = s_.opt.maxTopologyEdgeSubpixels;
    if (!(topology > 0.0 && topology < t)) return t;
    for (size_t k = 0; k < 3; ++k)
        if (AnyTopologyDiffers(Paths(tri[k]), Paths(tri[(k + 1) % 3]))) return topology;
    return t;
}

// Cheapest test first: some edge long, then the paths, then (ray queries) the occlusion.
bool Refiner::WantsSplit(const Tri& tri, const std::array<bool, 3>& longEdges) {
    if (!longEdges[0] && !longEdges[1] && !longEdges[2]) return false;
    bool differ = false;
    for (size_t k = 0; k < 3 && !differ; ++k) {
        differ = AnyPathsDiffer(Paths(tri[k]), Paths(tri[(k + 1) % 3]), s_.opt.maxAngleDeg);
    }
    if (!differ) return false;
    if (Occluded(tri[0]) && Occluded(tri[1]) && Occluded(tri[2])) {
        ++stats.occludedTriangles;
        return false;
    }
    return true;
}

// Rotate so that the split edges come first (1-to-2: edge 0; 1-to-3: edges 0 and 1), keeping the
// winding.
void Refiner::Split(const Tri& tri, const Bary& at, const std::array<bool, 3>& longEdges,
                    int depth) {
    const int count = static_cast<int>(std::count(longEdges.begin(), longEdges.end(), true));
    size_t first = 0;
    for (size_t k = 0; k < 3; ++k) {
        const bool isFirst = count == 1 ? longEdges[k] : !longEdges[k];
        if (isFirst) first = count == 1 ? k : (k + 1) % 3;
    }
    const Tri r{tri[first], tri[(first + 1) % 3], tri[(first + 2) % 3]};
    const Bary ra{at[first], at[(first + 1) % 3], at[(first + 2) % 3]};
    if (count == 1) Split2(r, ra, depth);
    if (count == 2) Split3(r, ra, depth);
    if (count == 3) Split4(tri, at, depth);
}

void Refiner::Split2(const Tri& r, const Bary& a, int depth) {
    ++stats.split2;
    const glm::dvec2 am = 0.5 * (a[0] + a[1]);
    const uint32_t m = Midpoint(r[0], r[1], a[0], a[1]);
    Refine({r[0], m, r[2]}, {a[0], am, a[2]}, depth + 1);
    Refine({m, r[1], r[2]}, {am, a[1], a[2]}, depth + 1);
}

// Edges r0-r1 and r1-r2 split; the quad (r0, m0, m1, r2) is cut along its shorter screen diagonal.
void Refiner::Split3(const Tri& r, const Bary& a, int depth) {
    ++stats.split3;
    const glm::dvec2 a0 = 0.5 * (a[0] + a[1]), a1 = 0.5 * (a[1] + a[2]);
    const uint32_t m0 = Midpoint(r[0], r[1], a[0], a[1]);
    const uint32_t m1 = Midpoint(r[1], r[2], a[1], a[2]);
    Refine({m0, r[1], m1}, {a0, a[1], a1}, depth + 1);
    if (ScreenLength(m0, r[2]) < ScreenLength(r[0], m1)) {
        Refine({r[0], m0, r[2]}, {a[0], a0, a[2]}, depth + 1);
        Refine({m0, m1, r[2]}, {a0, a1, a[2]}, depth + 1);
    } else {
        Refine({r[0], m0, m1}, {a[0], a0, a1}, depth + 1);
        Refine({r[0], m1, r[2]}, {a[0], a1, a[2]}, depth + 1);
    }
}

void Refiner::Split4(const Tri& r, const Bary& a, int depth) {
    ++stats.split4;
    const glm::dvec2 a0 = 0.5 * (a[0] + a[1]), a1 = 0.5 * (a[1] + a[2]), a2 = 0.5 * (a[2] + a[0]);
    const uint32_t m0 = Midpoint(r[0], r[1], a[0], a[1]);
    const uint32_t m1 = Midpoint(r[1], r[2], a[1], a[2]);
    const uint32_t m2 = Midpoint(r[2], r[0], a[2], a[0]);
    Refine({r[0], m0, m2}, {a[0], a0, a2}, depth + 1);
    Refine({m0, r[1], m1}, {a0, a[1], a1}, depth + 1);
    Refine({m2, m1, r[2]}, {a2, a1, a[2]}, depth + 1);
    Refine({m0, m1, m2}, {a0, a1, a2}, depth + 1);
}

// The shared midpoint of edge (u, v): looked up in the hash, else created and traced once (on
// the input triangle being refined, where u and v are at au and av).
uint32_t Refiner::Midpoint(uint32_t u, uint32_t v, const glm::dvec2& au, const glm::dvec2& av) {
    const uint64_t key = EdgeKey(u, v);
    if (const uint32_t* m = midpoints_.Find(key)) return *m;
    glm::vec3 position, normal;
    MidpointOf(Position(u), Normal(u), Position(v), Normal(v), &position, &normal);
    const auto m = static_cast<uint32_t>(nIn_ + positions.size());
    positions.push_back(position);
    normals.push_back(normal);
    screen.push_back(s_.in.project(position));
    occluded.push_back(-1);
    parents.push_back({u, v});
    // Inside the input triangle only this run can create the midpoint; on an input edge a
    // neighbour's run may create it too, so its paths must not depend on the triangle.
    const glm::dvec2 at = 0.5 * (au + av);
    const bool inside = at.x > 0.0 && at.y > 0.0 && at.x + at.y < 1.0;
    if (inside && s_.in.evaluateMidpoint) {
        paths.push_back(s_.in.evaluateMidpoint(position, normal, {input_, at.x, at.y}));
    } else if (!inside && s_.in.evaluateEdge) {
        paths.push_back(s_.in.evaluateEdge(position, normal, EdgeOf(at)));
    } else {
        paths.push_back(s_.in.evaluate(position, normal));
    }
    midpoints_.Insert(key, m);
    return m;
}

// The input edge holding barycentric point `at` (weights of corners 1 and 2, one of the three
// weights 0) of the input triangle being refined, from its lower-numbered vertex.
EdgeMidpoint Refiner::EdgeOf(const glm::dvec2& at) const {
    const glm::uvec3& t = s_.in.triangles[input_];
    uint32_t from = t.x, to = t.y;
    double s = at.x;  // corner 0 → corner 1
    if (at.x == 0.0) {
        to = t.z, s = at.y;  // corner 0 → corner 2
    } else if (at.y != 0.0) {
        from = t.y, to = t.z, s = at.y;  // corner 1 → corner 2 (at.x + at.y == 1)
    }
    return from < to ? EdgeMidpoint{from, to, s} : EdgeMidpoint{to, from, 1.0 - s};
}

bool Refiner::Occluded(uint32_t v) {
    if (!s_.in.occluded) return false;
    int8_t& state = v < nIn_ ? inputOccluded[v] : occluded[v - nIn_];
    if (state < 0) state = s_.in.occluded(Position(v)) ? 1 : 0;
    return state == 1;
}

double Refiner::ScreenLength(uint32_t u, uint32_t v) const {
    const glm::dvec2 d = glm::dvec2(Screen(u)) - glm::dvec2(Screen(v));
    return std::sqrt(d.x * d.x + d.y * d.y);
}

class Tessellator {
  public:
    Tessellator(const TessInput& input, const TessOptions& options)
        : shared_{input, options, std::clamp(options.maxDepth, 0, kMaxDepthCap), {}, {}, {}},
          in_(input),
          threads_(std::max(1, options.threads)) {}

    TessellationResult Run();

  private:
    void Validate() const;
    void TraceInputVertices();
    void Merge(Refiner&& run, std::vector<int8_t>* occluded);
    void RemoveJunctions();
    void CollectEdge(uint32_t u, uint32_t v, double s0, double s1, size_t edge,
                     std::vector<PolyVertex>* poly) const;
    void EarClip(std::vector<PolyVertex> poly, std::vector<glm::uvec3>* out) const;
    bool IsEar(const std::vector<PolyVertex>& poly, size_t i) const;

    Shared shared_;
    const TessInput& in_;
    const int threads_;
    TessellationResult out_;
    EdgeHash midpoints_;       // edge (sorted pair) → midpoint vertex
    std::vector<Tri> leaves_;  // refined triangles, before t-junction removal
};

TessellationResult Tessellator::Run() {
    // Step 1: project the input vertices; trace those of front-facing triangles.
    Validate();
    TraceInputVertices();
    out_.positions = in_.positions;
    out_.normals = in_.normals;
    std::vector<int8_t> occluded(in_.positions.size(), -1);
    // Step 2: refine runs of consecutive input triangles (in parallel), merged in index order.
    out_.stats.trianglesIn = in_.triangles.size();
    const size_t nTri = in_.triangles.size();
    const size_t nRuns = threads_ == 1 ? 1 : std::min<size_t>(nTri, 4 * threads_);
    std::vector<std::unique_ptr<Refiner>> runs(nRuns);
    base::ParallelFor(static_cast<int>(nRuns), threads_, [&](int r) {
        auto run = std::make_unique<Refiner>(shared_);
        if (in_.occluded) run->inputOccluded.assign(in_.positions.size(), -1);
        run->Run(nTri * static_cast<size_t>(r) / nRuns, nTri * static_cast<size_t>(r + 1) / nRuns);
        runs[static_cast<size_t>(r)] = std::move(run);
    });
    out_.paths = std::move(shared_.paths);
    size_t created = 0, leaves = 0;
    for (const std::unique_ptr<Refiner>& run : runs) {
        created += run->positions.size();
        leaves += run->leaves.size();
    }
    const size_t total = in_.positions.size() + created;
    out_.positions.reserve(total);
    out_.normals.reserve(total);
    out_.paths.reserve(total);
    occluded.reserve(total);
    leaves_.reserve(leaves);
    midpoints_.Reserve(created);
    for (std::unique_ptr<Refiner>& run : runs) Merge(std::move(*run), &occluded);
    runs.clear();
    // Step 3: close the t-junctions between differently refined neighbours.
    RemoveJunctions();
    out_.stats.trianglesOut = out_.triangles.size();
    out_.stats.vertexRays = static_cast<size_t>(std::count_if(
        out_.paths.begin(), out_.paths.end(), [](const auto& p) { return p.has_value(); }));
    out_.stats.occlusionQueries = static_cast<size_t>(
        std::count_if(occluded.begin(), occluded.end(), [](int8_t o) { return o >= 0; }));
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

// Every vertex of a front-facing input triangle is traced (the serial refinement would trace them
// lazily, with the same calls).
void Tessellator::TraceInputVertices() {
    const size_t n = in_.positions.size(), nTri = in_.triangles.size();
    // Projections and back-facing flags in parallel chunks (pure callbacks).
    constexpr size_t kBookChunk = 4096;
    shared_.screen.resize(n);
    shared_.backFacing.assign(nTri, 0);
    const size_t bookChunks = (std::max(n, nTri) + kBookChunk - 1) / kBookChunk;
    base::ParallelFor(static_cast<int>(bookChunks), threads_, [&](int c) {
        const size_t first = static_cast<size_t>(c) * kBookChunk;
        for (size_t v = first; v < std::min(n, first + kBookChunk); ++v)
            shared_.screen[v] = in_.project(in_.positions[v]);
        if (!in_.backFacing) return;
        for (size_t i = first; i < std::min(nTri, first + kBookChunk); ++i) {
            const glm::uvec3& t = in_.triangles[i];
            TriangleGeometry g;
            for (int k = 0; k < 3; ++k) {
                g.positions[static_cast<size_t>(k)] = in_.positions[t[k]];
                g.normals[static_cast<size_t>(k)] = in_.normals[t[k]];
            }
            shared_.backFacing[i] = in_.backFacing(g) ? 1 : 0;
        }
    });
    std::vector<uint8_t> wanted(n, 0);
    for (size_t i = 0; i < nTri; ++i) {
        if (shared_.backFacing[i]) continue;
        const glm::uvec3& t = in_.triangles[i];
        wanted[t.x] = wanted[t.y] = wanted[t.z] = 1;
    }
    shared_.paths.assign(n, std::nullopt);
    constexpr size_t kChunk = 256;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    base::ParallelFor(static_cast<int>(chunks), threads_, [&](int c) {
        for (size_t v = static_cast<size_t>(c) * kChunk; v < std::min(n, (c + 1) * kChunk); ++v)
            if (wanted[v])
                shared_.paths[v] = in_.evaluateInput
                                       ? in_.evaluateInput(v)
                                       : in_.evaluate(in_.positions[v], in_.normals[v]);
    });
}

// Appends a run's new vertices that the earlier runs did not create (in the run's creation
// order), and its leaves renumbered.
void Tessellator::Merge(Refiner&& run, std::vector<int8_t>* occluded) {
    const auto nIn = static_cast<uint32_t>(in_.positions.size());
    if (!run.inputOccluded.empty())
        for (size_t v = 0; v < nIn; ++v)
            if ((*occluded)[v] < 0) (*occluded)[v] = run.inputOccluded[v];
    std::vector<uint32_t> global(run.positions.size());
    auto map = [&](uint32_t v) { return v < nIn ? v : global[v - nIn]; };
    for (size_t j = 0; j < run.positions.size(); ++j) {
        const uint64_t key = EdgeKey(map(run.parents[j][0]), map(run.parents[j][1]));
        if (const uint32_t* m = midpoints_.Find(key)) {
            global[j] = *m;
            int8_t& o = (*occluded)[*m];
            if (o < 0) o = run.occluded[j];
            continue;
        }
        global[j] = static_cast<uint32_t>(out_.positions.size());
        midpoints_.Insert(key, global[j]);
        out_.positions.push_back(run.positions[j]);
        out_.normals.push_back(run.normals[j]);
        out_.paths.emplace_back(std::move(run.paths[j]));
        occluded->push_back(run.occluded[j]);
    }
    for (const Tri& t : run.leaves) leaves_.push_back({map(t[0]), map(t[1]), map(t[2])});
    out_.stats.split2 += run.stats.split2;
    out_.stats.split3 += run.stats.split3;
    out_.stats.split4 += run.stats.split4;
    out_.stats.backFacingTriangles += run.stats.backFacingTriangles;
    out_.stats.occludedTriangles += run.stats.occludedTriangles;
}

// Every refined triangle with extra vertices on its edges becomes the ear-clipped polygon of its
// corners and those vertices (runs of leaves in parallel, joined in leaf order).
void Tessellator::RemoveJunctions() {
    const glm::dvec2 corners[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    constexpr size_t kChunk = 4096;
    const size_t chunks = (leaves_.size() + kChunk - 1) / kChunk;
    std::vector<std::vector<glm::uvec3>> parts(chunks);
    std::vector<size_t> junctions(chunks, 0);
    base::ParallelFor(static_cast<int>(chunks), threads_, [&](int c) {
        std::vector<glm::uvec3>& part = parts[static_cast<size_t>(c)];
        std::vector<PolyVertex> poly;
        const size_t end = std::min(leaves_.size(), (c + 1) * kChunk);
        for (size_t i = static_cast<size_t>(c) * kChunk; i < end; ++i) {
            const Tri& tri = leaves_[i];
            poly.clear();
            for (size_t k = 0; k < 3; ++k) {
                poly.push_back({tri[k], corners[k]});
                CollectEdge(tri[k], tri[(k + 1) % 3], 0.0, 1.0, k, &poly);
            }
            if (poly.size() == 3) {
                part.emplace_back(tri[0], tri[1], tri[2]);
            } else {
                ++junctions[static_cast<size_t>(c)];
                EarClip(poly, &part);
            }
        }
    });
    size_t total = 0;
    for (const auto& part : parts) total += part.size();
    out_.triangles.reserve(total);
    for (size_t c = 0; c < chunks; ++c) {
        out_.triangles.insert(out_.triangles.end(), parts[c].begin(), parts[c].end());
        out_.stats.junctionTriangles += junctions[c];
    }
}

// All vertices strictly inside edge (u, v), in order from u to v, found recursively through the
// midpoint hash.
void Tessellator::CollectEdge(uint32_t u, uint32_t v, double s0, double s1, size_t edge,
                              std::vector<PolyVertex>* poly) const {
    const uint32_t* found = midpoints_.Find(EdgeKey(u, v));
    if (!found) return;
    const uint32_t m = *found;
    const double s = 0.5 * (s0 + s1);
    CollectEdge(u, m, s0, s, edge, poly);
    poly->push_back({m, EdgePoint(edge, s)});
    CollectEdge(m, v, s, s1, edge, poly);
}

// Repeatedly clip the valid ear whose new edge is shortest in world space (first on ties).
void Tessellator::EarClip(std::vector<PolyVertex> poly, std::vector<glm::uvec3>* out) const {
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
        out->emplace_back(poly[prev].index, poly[best].index, poly[next].index);
        poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(best));
    }
    out->emplace_back(poly[0].index, poly[1].index, poly[2].index);
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
    return [projection = raster::ImageProjection(camera), scale](const glm::vec3& position) {
        float depth = 0.0f;
        const glm::vec2 image = projection(position, &depth);
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
