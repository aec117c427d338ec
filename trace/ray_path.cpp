// SPDX-License-Identifier: MIT
// ray_path.cpp — greedy two-term ray paths, the full ray tree, and the path-difference criterion.
#include "trace/ray_path.h"

#include <algorithm>
#include <cmath>
#include <ostream>

namespace pem::trace {

namespace {

// Continued rays start on their own line, a step along the new direction that puts them
// kRayOffset * max(1, |position|_inf) off the surface (well above float rounding of the hit
// position); within ~6 degrees of tangent the step is capped at 10x that.
constexpr double kRayOffset = 1e-4;
constexpr double kMinOffsetCos = 0.1;

double MaxComponent(const glm::dvec3& v) {
    return std::max({v.x, v.y, v.z});
}
double MeanComponent(const glm::dvec3& v) {
    return (v.x + v.y + v.z) / 3.0;
}

// The segment after a hit: whether it runs inside the hit's object, its absorption, and where it
// starts (the hit position, not the offset ray origin, so the offset does not shorten the path).
struct Medium {
    bool inside = false;
    glm::dvec3 absorption{0.0};
    glm::dvec3 from{0.0};
};

Medium MediumAfter(const SurfaceHit& hit, Event event) {
    const bool inside = hit.entering == (event == Event::Refract);
    return {inside, hit.material.absorption, glm::dvec3(hit.position)};
}

// exp(-sigma d) per channel for the segment from the medium's start to `to`; 1 outside.
glm::dvec3 SegmentTransmittance(const Medium& medium, const glm::vec3& to) {
    if (!medium.inside) return glm::dvec3(1.0);
    const double length = glm::length(glm::dvec3(to) - medium.from);
    const glm::dvec3 a = medium.absorption;
    return {std::exp(-a.x * length), std::exp(-a.y * length), std::exp(-a.z * length)};
}

Ray ContinueRay(const SurfaceHit& hit, const glm::dvec3& dir) {
    const glm::dvec3 p(hit.position);
    const double scale = std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const double cosN = std::abs(glm::dot(dir, glm::dvec3(hit.geometricNormal)));
    const double step = kRayOffset * scale / std::max(cosN, kMinOffsetCos);
    return {glm::vec3(p + dir * step), glm::vec3(dir)};
}

Ray Normalized(const Ray& ray) {
    return {ray.origin, glm::normalize(ray.dir)};
}

PathVertex MakeVertex(const SurfaceHit& hit, Event event) {
    return {hit.position, hit.shadingNormal, event, hit.entering, hit.objectId, hit.primId};
}

// The coefficient and direction of one child; no direction when the child does not exist.
struct Child {
    glm::dvec3 coefficient{0.0};
    std::optional<glm::dvec3> dir;
};

Child ChildOf(const Interaction& interaction, Event event) {
    if (event == Event::Reflect) return {interaction.reflectance, interaction.reflectDir};
    return {interaction.transmittance, interaction.refractDir};
}

}  // namespace

Interaction Scatter(const glm::dvec3& dir, const SurfaceHit& hit) {
    // Step 1: the shading normal, on the incident side of the geometric surface.
    const glm::dvec3 ng(hit.geometricNormal);
    const glm::dvec3 facing = hit.entering ? ng : -ng;
    glm::dvec3 ns(hit.shadingNormal);
    if (glm::dot(ns, facing) < 0.0) ns = -ns;
    const double cosI = std::clamp(-glm::dot(dir, ns), 0.0, 1.0);

    // Step 2: reflection always exists.
    Interaction out;
    out.reflectDir = Reflect(dir, ns);
    const SurfaceMaterial& m = hit.material;
    if (m.kind == SurfaceKind::Mirror) {
        out.reflectance = FresnelSchlick(cosI, m.mirrorF0);
        return out;
    }

    // Step 3: dielectric, IORs by crossing direction; refraction unless totally reflected.
    const double n1 = hit.entering ? m.outsideIor : m.ior;
    const double n2 = hit.entering ? m.ior : m.outsideIor;
    out.refractDir = Refract(dir, ns, n1, n2);
    const double r = out.refractDir ? FresnelReflectance(m.fresnel, cosI, n1, n2) : 1.0;
    out.reflectance = glm::dvec3(r);
    out.transmittance = glm::dvec3(1.0 - r);
    return out;
}

Event GreedyChoice(const Interaction& interaction) {
    const bool refract = interaction.refractDir && MeanComponent(interaction.transmittance) >
                                                       MeanComponent(interaction.reflectance);
    return refract ? Event::Refract : Event::Reflect;
}

namespace {

// Follow one path from `hit` (reached by `ray` through `medium`); the first event is forced.
// The events are gathered in a per-thread scratch list and copied out at their exact count: a
// path holds one to a few events of a possible maxDepth, and the hybrid renderer keeps two paths
// for each of hundreds of thousands of vertices (exact sizes are a quarter of the memory, and
// small blocks are freed fast).
RayPath TraceGreedyPath(Ray ray, SurfaceHit hit, Event event, SurfaceHitFn& hits, int maxDepth,
                        double minWeight) {
    thread_local std::vector<PathVertex> events;
    events.clear();
    RayPath path;
    const auto done = [&]() {
        path.vertices.assign(events.begin(), events.end());
        return std::move(path);
    };
    Medium medium;
    for (;;) {
        // Step 1: attenuate the segment to this hit, then apply the event's coefficient.
        path.G *= SegmentTransmittance(medium, hit.position);
        const Interaction interaction = Scatter(glm::dvec3(ray.dir), hit);
        const Child child = ChildOf(interaction, event);
        events.push_back(MakeVertex(hit, event));
        path.F *= child.coefficient;
        if (!child.dir) {  // forced first event impossible (mirror or TIR): a dead path
            path.F = glm::dvec3(0.0);
            path.exitOrigin = hit.position;
            path.exitDir = ray.dir;
            return done();
        }
        // Step 2: continue; stop on weight, escape or depth.
        ray = ContinueRay(hit, *child.dir);
        medium = MediumAfter(hit, event);
        path.exitOrigin = ray.origin;
        path.exitDir = ray.dir;
        if (MaxComponent(path.Weight()) < minWeight) return done();
        const std::optional<SurfaceHit> next = hits.Next(ray);
        if (!next) {
            path.escaped = true;
            return done();
        }
        if (static_cast<int>(events.size()) >= maxDepth) return done();
        // Step 3: the greedy choice at the next interface.
        hit = *next;
        event = GreedyChoice(Scatter(glm::dvec3(ray.dir), hit));
    }
}

struct TreeWalk {
    SurfaceHitFn& hits;
    int maxDepth;
    double minWeight;
    std::vector<ExitRay>& leaves;

    void Leaf(const Ray& ray, const glm::dvec3& weight, int depth, bool escaped) {
        leaves.push_back({ray, weight, depth, escaped});
    }

    // Expand the node at `hit`, reached by `ray` through `medium` with accumulated `weight`.
    void Expand(const Ray& ray, const SurfaceHit& hit, const Medium& medium, glm::dvec3 weight,
                int depth) {
        weight *= SegmentTransmittance(medium, hit.position);
        const Interaction interaction = Scatter(glm::dvec3(ray.dir), hit);
        for (Event event : {Event::Reflect, Event::Refract}) {
            const Child child = ChildOf(interaction, event);
            if (!child.dir || MaxComponent(child.coefficient) <= 0.0) continue;
            const Ray childRay = ContinueRay(hit, *child.dir);
            const glm::dvec3 childWeight = weight * child.coefficient;
            if (MaxComponent(childWeight) < minWeight) {
                Leaf(childRay, childWeight, depth + 1, false);
                continue;
            }
            const std::optional<SurfaceHit> next = hits.Next(childRay);
            if (!next || depth + 1 >= maxDepth) {
                Leaf(childRay, childWeight, depth + 1, !next);
                continue;
            }
            Expand(childRay, *next, MediumAfter(hit, event), childWeight, depth + 1);
        }
    }
};

}  // namespace

std::optional<GreedyPaths> TraceGreedyPaths(const Ray& primary, SurfaceHitFn& hits, int maxDepth,
                                            double minWeight) {
    const Ray ray = Normalized(primary);
    const std::optional<SurfaceHit> first = hits.Next(ray);
    if (!first) return std::nullopt;
    return GreedyPaths{TraceGreedyPath(ray, *first, Event::Reflect, hits, maxDepth, minWeight),
                       TraceGreedyPath(ray, *first, Event::Refract, hits, maxDepth, minWeight)};
}

void TraceFullTree(const Ray& primary, SurfaceHitFn& hits, int maxDepth, double minWeight,
                   std::vector<ExitRay>& leaves) {
    const Ray ray = Normalized(primary);
    leaves.clear();
    TreeWalk walk{hits, maxDepth, minWeight, leaves};
    const std::optional<SurfaceHit> first = hits.Next(ray);
    if (!first) {
        walk.Leaf(ray, glm::dvec3(1.0), 0, true);
    } else {
        walk.Expand(ray, *first, Medium{}, glm::dvec3(1.0), 0);
    }
}

std::vector<ExitRay> TraceFullTree(const Ray& primary, SurfaceHitFn& hits, int maxDepth,
                                   double minWeight) {
    std::vector<ExitRay> leaves;
    TraceFullTree(primary, hits, maxDepth, minWeight, leaves);
    return leaves;
}

bool TopologyDiffers(const RayPath& a, const RayPath& b) {
    if (a.vertices.size() != b.vertices.size() || a.escaped != b.escaped) return true;
    for (size_t i = 0; i < a.vertices.size(); ++i) {
        if (a.vertices[i].event != b.vertices[i].event) return true;
    }
    return false;
}

bool PathsDiffer(const RayPath& a, const RayPath& b, double maxAngleDeg) {
    // Topology, then geometry: the angle between the exit directions.
    return TopologyDiffers(a, b) ||
           AngleBetweenDeg(glm::dvec3(a.exitDir), glm::dvec3(b.exitDir)) > maxAngleDeg;
}

std::ostream& operator<<(std::ostream& os, Event event) {
    return os << (event == Event::Reflect ? "Reflect" : "Refract");
}

std::ostream& operator<<(std::ostream& os, const PathVertex& v) {
    return os << "{" << v.event << (v.entering ? " in" : " out") << " obj " << v.objectId << " p ("
              << v.position.x << ", " << v.position.y << ", " << v.position.z << ")}";
}

std::ostream& operator<<(std::ostream& os, const RayPath& path) {
    os << "RayPath{[";
    for (const PathVertex& v : path.vertices) os << v;
    os << "] exit (" << path.exitDir.x << ", " << path.exitDir.y << ", " << path.exitDir.z
       << ") F (" << path.F.x << ", " << path.F.y << ", " << path.F.z << ") G (" << path.G.x << ", "
       << path.G.y << ", " << path.G.z << ")" << (path.escaped ? " escaped" : " cut") << "}";
    return os;
}

}  // namespace pem::trace
