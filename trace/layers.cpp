// SPDX-License-Identifier: MIT
// layers.cpp — layer clustering, shell choice and layer images (layers.h).
#include "trace/layers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <tuple>

#include "base/parallel.h"
#include "trace/segment.h"

namespace pem::trace {

namespace {

constexpr int kCells = 16;  // per cube face side, for the occupancy measure

int DirectionCell(const glm::dvec3& d) {
    const glm::dvec3 a = glm::abs(d);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    const int face = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    const double m = std::max(a[axis], 1e-300);
    auto cell = [&](double c) {
        return std::clamp(static_cast<int>((c / m * 0.5 + 0.5) * kCells), 0, kCells - 1);
    };
    return (face * kCells + cell(d[(axis + 1) % 3])) * kCells + cell(d[(axis + 2) % 3]);
}

double Occupancy(std::span<const glm::dvec3> points, const glm::dvec3& origin) {
    std::vector<char> used(6 * kCells * kCells, 0);
    for (const glm::dvec3& p : points) used[static_cast<size_t>(DirectionCell(p - origin))] = 1;
    return static_cast<double>(std::count(used.begin(), used.end(), 1)) /
           static_cast<double>(used.size());
}

// The floor under the group: the scene's lowest height when the group rests on it.
std::optional<double> FloorUnder(const Scene& scene, int group) {
    float sceneLow = std::numeric_limits<float>::infinity();
    for (const Object& o : scene.objects) sceneLow = std::min(sceneLow, o.bounds.lo.y);
    const float groupLow = scene.lensGroups[static_cast<size_t>(group)].bounds.lo.y;
    if (groupLow - sceneLow < 0.01f) return static_cast<double>(sceneLow);
    return std::nullopt;
}

// What the shell choice looks at: per layer, the frontmost record of each ray in the layer (what
// the layer image shows), as (exit ray origin, hit point); at most kParallaxRecords of them,
// evenly spaced in record order.
constexpr size_t kParallaxRecords = 20000;

}  // namespace

double ShellParallax(const Shell& shell, std::span<const RayHit> hits, const glm::dvec3& emOrigin) {
    if (hits.empty()) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    for (const RayHit& h : hits) {
        const glm::dvec3 d = h.point - h.origin;
        const double len = glm::length(d);
        const std::optional<ShellHit> s =
            len > 0.0 ? Intersect(shell, Ray{glm::vec3(h.origin), glm::vec3(d / len)})
                      : std::nullopt;
        if (!s || s->forced) {
            sum += s ? 0.0 : 90.0;  // a forced quad hit keeps the ray's direction
            continue;
        }
        const glm::dvec3 a = glm::normalize(s->point - emOrigin);
        const glm::dvec3 b = glm::normalize(h.point - emOrigin);
        sum += glm::degrees(std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)));
    }
    return sum / static_cast<double>(hits.size());
}

namespace {

// The candidate shells of a layer (sphere first: it wins ties).
std::vector<LayerShell> Candidates(const LayerCluster& layer, std::span<const glm::dvec3> points,
                                   const glm::dvec3& origin, std::optional<double> floorY,
                                   double occupancy, double sparseOccupancy) {
    std::vector<LayerShell> c;
    c.push_back({"sphere", SphereShell{origin, layer.radius}, occupancy, 0.0, {}});
    if (points.size() < 3) return c;
    if (occupancy < sparseOccupancy)
        c.push_back({"quad", FitQuad(points, origin), occupancy, 0.0, {}});
    c.push_back({"box", BoxAround(origin, layer.radius, floorY), occupancy, 0.0, {}});
    c.push_back({"box", FitBox(points, floorY), occupancy, 0.0, {}});
    c.push_back({"ellipsoid", FitEllipsoid(points, origin), occupancy, 0.0, {}});
    CylinderShell cyl = FitCylinder(points, glm::dvec2(origin.x, origin.z), false);
    if (floorY) cyl.yMin = *floorY;
    c.push_back({"cylinder", cyl, occupancy, 0.0, {}});
    cyl.radius = layer.radius;
    c.push_back({"cylinder", cyl, occupancy, 0.0, {}});
    return c;
}

// The shell with the least parallax over the layer's records; without ray origins, the sphere
// (or the quad impostor for a sparsely occupied layer), as before.
LayerShell ChooseShell(const LayerCluster& layer, std::span<const glm::dvec3> points,
                       std::span<const RayHit> hits, const glm::dvec3& origin,
                       std::optional<double> floorY, double sparseOccupancy) {
    const double occupancy = Occupancy(points, origin);
    std::vector<LayerShell> candidates =
        Candidates(layer, points, origin, floorY, occupancy, sparseOccupancy);
    if (hits.empty()) {
        LayerShell s =
            candidates.size() > 1 && candidates[1].kind == "quad" ? candidates[1] : candidates[0];
        s.parallaxDeg = std::numeric_limits<double>::quiet_NaN();
        return s;
    }
    size_t best = 0;
    std::vector<std::pair<std::string, double>> tried;
    for (size_t k = 0; k < candidates.size(); ++k) {
        candidates[k].parallaxDeg = ShellParallax(candidates[k].shell, hits, origin);
        tried.emplace_back(candidates[k].kind, candidates[k].parallaxDeg);
        if (candidates[k].parallaxDeg < candidates[best].parallaxDeg) best = k;
    }
    candidates[best].candidates = tried;
    return candidates[best];
}

// Per layer, the frontmost record of each ray in the layer, thinned to kParallaxRecords.
std::vector<std::vector<RayHit>> FrontmostHits(const LayerInput& in, const LayerClustering& c) {
    std::vector<std::vector<RayHit>> hits(c.layers.size());
    if (in.origins.size() != in.records.size()) return hits;
    std::set<std::tuple<size_t, uint32_t, uint64_t>> seen;  // (layer, viewpoint, ray)
    for (size_t i = 0; i < in.records.size(); ++i) {
        const auto l = static_cast<size_t>(c.recordLayer[i]);
        if (seen.insert({l, in.records[i].viewpointId, in.records[i].rayId}).second)
            hits[l].push_back({glm::dvec3(in.origins[i]), glm::dvec3(in.points[i])});
    }
    for (std::vector<RayHit>& h : hits) {
        if (h.size() <= kParallaxRecords) continue;
        std::vector<RayHit> thinned;
        for (size_t k = 0; k < kParallaxRecords; ++k)
            thinned.push_back(h[k * h.size() / kParallaxRecords]);
        h.swap(thinned);
    }
    return hits;
}

// All vertices of the group's objects (for the local ellipsoid).
std::vector<glm::dvec3> GroupVertices(const Scene& scene, int group) {
    std::vector<glm::dvec3> v;
    for (int o : scene.lensGroups[static_cast<size_t>(group)].objects)
        for (const glm::vec3& p : scene.objects[static_cast<size_t>(o)].positions)
            v.emplace_back(p);
    return v;
}

void SetMirrorShells(const Scene& scene, int group, const LayerInput& in, GroupLayers& out) {
    out.mirror = true;
    const glm::dvec3 origin(out.emOrigin);
    std::vector<RayHit> selfHits;  // thinned to kParallaxRecords
    const size_t n = std::min(in.localOrigins.size(), in.localPoints.size());
    const size_t kept = std::min(n, kParallaxRecords);
    for (size_t k = 0; k < kept; ++k)
        selfHits.push_back(
            {glm::dvec3(in.localOrigins[k * n / kept]), glm::dvec3(in.localPoints[k * n / kept])});
    const LocalShellChoice local = ChooseLocalShell(GroupVertices(scene, group), selfHits, origin);
    out.localShell = local.shell;
    out.localParallaxDeg = local.parallaxDeg;
    out.distantMeanDistance =
        in.distantCount ? in.distantDistanceSum / static_cast<double>(in.distantCount) : 0.0;
    out.distantShell = BoxAround(origin, out.distantMeanDistance, FloorUnder(scene, group));
}

}  // namespace

LocalShellChoice ChooseLocalShell(std::span<const glm::dvec3> vertices,
                                  std::span<const RayHit> selfHits, const glm::dvec3& emOrigin) {
    // Step 1: the candidates.
    std::vector<Shell> candidates{FitEllipsoid(vertices, emOrigin)};
    if (selfHits.size() >= 3) {
        std::vector<glm::dvec3> points;
        std::vector<double> radii;
        for (const RayHit& h : selfHits) {
            points.push_back(h.point);
            radii.push_back(glm::length(h.point - emOrigin));
        }
        candidates.emplace_back(FitEllipsoid(points, emOrigin));
        candidates.emplace_back(FitBox(points, std::nullopt));
        std::sort(radii.begin(), radii.end());
        for (size_t q = 1; q <= 9; ++q)
            candidates.emplace_back(SphereShell{emOrigin, radii[q * radii.size() / 10]});
    }
    if (selfHits.empty()) return {candidates[0], std::numeric_limits<double>::quiet_NaN()};
    // Step 2: the least parallax (the first of equals).
    LocalShellChoice best{candidates[0], std::numeric_limits<double>::infinity()};
    for (const Shell& c : candidates) {
        const double p = ShellParallax(c, selfHits, emOrigin);
        if (p < best.parallaxDeg) best = {c, p};
    }
    return best;
}

glm::vec3 GroupEmOrigin(const Scene& scene, int group) {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    for (int o : scene.lensGroups[static_cast<size_t>(group)].objects) {
        const Object& obj = scene.objects[static_cast<size_t>(o)];
        const auto base = static_cast<uint32_t>(positions.size());
        positions.insert(positions.end(), obj.positions.begin(), obj.positions.end());
        for (const glm::uvec3& t : obj.triangles)
            indices.insert(indices.end(), {base + t.x, base + t.y, base + t.z});
    }
    return EmOrigin(positions, indices);
}

GroupLayers BuildLayers(const Scene& scene, int group, bool mirror, const LayerInput& in) {
    GroupLayers out;
    out.group = group;
    out.emOrigin = GroupEmOrigin(scene, group);
    out.clustering = ClusterLayers(in.records, std::max(1, in.layers));
    out.objectLayer.assign(scene.objects.size(), -1);
    const size_t n = out.clustering.layers.size();
    std::vector<std::vector<glm::dvec3>> points(n);
    for (size_t i = 0; i < in.records.size(); ++i)
        points[static_cast<size_t>(out.clustering.recordLayer[i])].emplace_back(in.points[i]);
    const std::vector<std::vector<RayHit>> hits = FrontmostHits(in, out.clustering);
    const std::optional<double> floorY = FloorUnder(scene, group);
    for (size_t l = 0; l < n; ++l) {
        const LayerCluster& layer = out.clustering.layers[l];
        for (uint32_t o : layer.objects) out.objectLayer[o] = static_cast<int>(l);
        out.shells.push_back(ChooseShell(layer, points[l], hits[l], glm::dvec3(out.emOrigin),
                                         floorY, in.sparseOccupancy));
    }
    if (mirror) SetMirrorShells(scene, group, in, out);
    return out;
}

int LayerOf(const GroupLayers& layers, int object, double distance) {
    const int assigned = layers.objectLayer[static_cast<size_t>(object)];
    if (assigned >= 0) return assigned;
    int best = 0;
    const auto& ls = layers.clustering.layers;
    for (size_t l = 1; l < ls.size(); ++l)
        if (std::abs(ls[l].radius - distance) <
            std::abs(ls[static_cast<size_t>(best)].radius - distance))
            best = static_cast<int>(l);
    return best;
}

std::vector<glm::vec4> LayerColours(const Tracer& tracer, const GroupLayers& layers, const Ray& ray,
                                    int depthBudget, RayCounts& counts) {
    const size_t n = layers.clustering.layers.size();
    std::vector<glm::vec4> out(n, glm::vec4(0.0f));
    for (const Hit& h : EnvironmentHits(tracer, ray, layers.group, counts)) {
        const glm::vec3 p = ray.origin + h.t * ray.dir;
        const auto l = static_cast<size_t>(
            LayerOf(layers, h.object, glm::length(glm::dvec3(p) - glm::dvec3(layers.emOrigin))));
        if (out[l].a > 0.0f) continue;
        out[l] = glm::vec4(tracer.HitRadiance(ray, h, depthBudget, 1.0, counts), 1.0f);
    }
    if (n > 0 && out[n - 1].a == 0.0f)
        out[n - 1] = glm::vec4(EnvRadiance(tracer.scene().environment, ray.dir), 1.0f);
    return out;
}

namespace {

struct LayerPainter {
    const Tracer& tracer;
    const raster::Camera& camera;
    int k, terms;
    const GroupLayers& layers;
    LayerImages& out;

    // The layer colours seen along one exit ray.
    void Exit(const TermSample& term, int t, glm::ivec2 cell, RayCounts& counts) const {
        const int budget = tracer.options().fullTreeDepth - term.events;
        const std::vector<glm::vec4> c = LayerColours(tracer, layers, term.exit, budget, counts);
        for (size_t l = 0; l < c.size(); ++l)
            if (c[l].a > 0.0f) out.samples[t][l].Add(cell.x, cell.y, glm::vec3(c[l]), 1.0f);
    }

    void Pixel(int x, int y, RayCounts& counts) const {
        for (int s = 0; s < k * k; ++s) {
            const glm::vec2 pos = SamplePosition(x, y, k, s);
            const Ray ray = raster::PixelRay(camera, pos.x, pos.y);
            const Hit hit = IncomingHit(tracer, ray, layers.group, counts);
            if (!hit.valid) continue;
            const GreedySample g = tracer.TraceGreedy(ray, hit, layers.group, counts);
            const glm::ivec2 cell = SampleCell(x, y, k, s);
            if (g.reflection.escaped) Exit(g.reflection, 0, cell, counts);
            if (terms > 1 && g.refraction.escaped) Exit(g.refraction, 1, cell, counts);
        }
    }
};

}  // namespace

LayerImages RenderLayers(const Tracer& tracer, const raster::Camera& camera, int k,
                         const GroupLayers& layers, int threads,
                         const std::function<void(int, int)>& progress) {
    LayerImages out;
    const size_t n = layers.clustering.layers.size();
    if (n == 0) return out;
    const int terms = tracer.GroupHasGlass(layers.group) ? 2 : 1;
    for (int t = 0; t < terms; ++t)
        out.samples[t].assign(n, FloatImage(k * camera.width, k * camera.height, 4));
    std::vector<RayCounts> rowCounts(static_cast<size_t>(camera.height));
    const LayerPainter painter{tracer, camera, k, terms, layers, out};
    base::ParallelFor(
        camera.height, threads,
        [&](int y) {
            for (int x = 0; x < camera.width; ++x)
                painter.Pixel(x, y, rowCounts[static_cast<size_t>(y)]);
        },
        progress);
    for (int t = 0; t < terms; ++t)
        for (const FloatImage& img : out.samples[t]) out.term[t].push_back(BoxFilter(img, k));
    for (const RayCounts& c : rowCounts) out.counts += c;
    return out;
}

}  // namespace pem::trace
