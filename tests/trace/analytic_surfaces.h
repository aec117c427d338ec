// SPDX-License-Identifier: MIT
// analytic_surfaces.h — SurfaceHitFn implementations for tests: a sphere, a slab (|y - centre| <=
// half thickness, infinite in x and z) and a list of them (nearest hit wins). Intersections are
// solved in double. Normals point outward; `entering` follows the geometric normal.
// Not here: triangles (the Embree tracer and brute_force.h cover meshes).
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "trace/ray_path.h"

namespace pem::trace::testing {

class AnalyticSurface : public SurfaceHitFn {
  public:
    SurfaceMaterial material;
    uint32_t objectId = 0;
    int queries = 0;

    std::optional<SurfaceHit> Next(const Ray& ray) override {
        ++queries;
        const glm::dvec3 o(ray.origin);
        const glm::dvec3 d(ray.dir);
        const std::optional<double> t = NearestT(o, d);
        if (!t) return std::nullopt;
        const glm::dvec3 p = o + *t * d;
        const glm::dvec3 n = NormalAt(p, d, *t);
        SurfaceHit hit;
        hit.t = static_cast<float>(*t);
        hit.position = glm::vec3(p);
        hit.geometricNormal = glm::vec3(n);
        hit.shadingNormal = glm::vec3(n);
        hit.material = material;
        hit.entering = glm::dot(d, n) < 0.0;
        hit.objectId = objectId;
        return hit;
    }

  protected:
    static constexpr double kTMin = 1e-7;
    virtual std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const = 0;
    virtual glm::dvec3 NormalAt(const glm::dvec3& p, const glm::dvec3& d, double t) const = 0;
};

class AnalyticSphere : public AnalyticSurface {
  public:
    glm::dvec3 centre{0.0};
    double radius = 1.0;

  protected:
    std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const override {
        const glm::dvec3 oc = o - centre;
        const double a = glm::dot(d, d);
        const double b = glm::dot(oc, d);
        const double c = glm::dot(oc, oc) - radius * radius;
        const double disc = b * b - a * c;
        if (disc < 0.0) return std::nullopt;
        const double s = std::sqrt(disc);
        for (double t : {(-b - s) / a, (-b + s) / a}) {
            if (t > kTMin) return t;
        }
        return std::nullopt;
    }
    glm::dvec3 NormalAt(const glm::dvec3& p, const glm::dvec3&, double) const override {
        return glm::normalize(p - centre);
    }
};

class AnalyticSlab : public AnalyticSurface {
  public:
    double centreY = 0.0;
    double halfThickness = 0.5;

  protected:
    std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const override {
        if (d.y == 0.0) return std::nullopt;
        std::optional<double> best;
        for (double y : {centreY - halfThickness, centreY + halfThickness}) {
            const double t = (y - o.y) / d.y;
            if (t > kTMin && (!best || t < *best)) best = t;
        }
        return best;
    }
    glm::dvec3 NormalAt(const glm::dvec3& p, const glm::dvec3&, double) const override {
        return {0.0, p.y > centreY ? 1.0 : -1.0, 0.0};
    }
};

// Nearest hit among several surfaces.
class SurfaceList : public SurfaceHitFn {
  public:
    std::vector<std::unique_ptr<AnalyticSurface>> surfaces;

    std::optional<SurfaceHit> Next(const Ray& ray) override {
        std::optional<SurfaceHit> best;
        for (auto& s : surfaces) {
            const std::optional<SurfaceHit> h = s->Next(ray);
            if (h && (!best || h->t < best->t)) best = h;
        }
        return best;
    }
};

}  // namespace pem::trace::testing
