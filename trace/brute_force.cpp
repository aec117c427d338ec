// SPDX-License-Identifier: MIT
// brute_force.cpp — Möller–Trumbore in double over all triangles (semantics: brute_force.h).
#include "trace/brute_force.h"

#include <algorithm>
#include <optional>

namespace pem::trace {

namespace {

// Hit of one triangle, or nothing. Double precision throughout.
struct TriangleHit {
    Hit hit;
    double t;  // unrounded, for ordering
};

std::optional<TriangleHit> IntersectTriangle(const Object& obj, int prim, const glm::dvec3& o,
                                             const glm::dvec3& d, double tnear, double tfar) {
    const glm::uvec3 tri = obj.triangles[static_cast<size_t>(prim)];
    const glm::dvec3 v0(obj.positions[tri.x]), v1(obj.positions[tri.y]), v2(obj.positions[tri.z]);
    // Step 1: determinant; zero means the ray is parallel to the plane (or the triangle is flat).
    const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return std::nullopt;
    const double inv = 1.0 / det;
    // Step 2: barycentrics, edges inclusive.
    const glm::dvec3 s = o - v0;
    const double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return std::nullopt;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) return std::nullopt;
    // Step 3: distance in range.
    const double t = glm::dot(e2, q) * inv;
    if (t < tnear || t > tfar) return std::nullopt;
    Hit h;
    h.t = static_cast<float>(t);
    h.prim = prim;
    h.u = static_cast<float>(u);
    h.v = static_cast<float>(v);
    h.ng = glm::vec3(glm::normalize(glm::cross(e1, e2)));
    h.valid = true;
    return TriangleHit{h, t};
}

// Calls fn(hit) for every hit, objects and triangles in index order.
template <typename Fn>
void ForEachHit(const Scene& scene, const raster::Ray& ray, float tnear, float tfar, Fn fn) {
    const glm::dvec3 o(ray.origin), d(ray.dir);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& obj = scene.objects[i];
        for (size_t k = 0; k < obj.triangles.size(); ++k) {
            std::optional<TriangleHit> h =
                IntersectTriangle(obj, static_cast<int>(k), o, d, static_cast<double>(tnear),
                                  static_cast<double>(tfar));
            if (!h) continue;
            h->hit.object = static_cast<int>(i);
            if (!fn(*h)) return;
        }
    }
}

}  // namespace

Hit BruteForceIntersect(const Scene& scene, const raster::Ray& ray, float tnear, float tfar) {
    std::optional<TriangleHit> best;
    ForEachHit(scene, ray, tnear, tfar, [&](const TriangleHit& h) {
        if (!best || h.t < best->t) best = h;  // strict: ties keep the lower (object, prim)
        return true;
    });
    return best ? best->hit : Hit{};
}

bool BruteForceOccluded(const Scene& scene, const raster::Ray& ray, float tnear, float tfar) {
    bool any = false;
    ForEachHit(scene, ray, tnear, tfar, [&](const TriangleHit&) {
        any = true;
        return false;  // stop at the first hit
    });
    return any;
}

std::vector<Hit> BruteForceIntersectAll(const Scene& scene, const raster::Ray& ray, float tnear,
                                        float tfar) {
    std::vector<TriangleHit> all;
    ForEachHit(scene, ray, tnear, tfar, [&](const TriangleHit& h) {
        all.push_back(h);
        return true;
    });
    // Stable: equal t keep the (object, prim) order of the loop.
    std::stable_sort(all.begin(), all.end(),
                     [](const TriangleHit& a, const TriangleHit& b) { return a.t < b.t; });
    std::vector<Hit> hits;
    for (const TriangleHit& h : all) hits.push_back(h.hit);
    return hits;
}

}  // namespace pem::trace
