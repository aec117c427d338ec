// SPDX-License-Identifier: MIT
// shell.cpp — shell intersections, cube lookups and fits (see shell.h for the conventions).
#include "trace/shell.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace pem::trace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct DRay {
    glm::dvec3 o;
    glm::dvec3 d;
};

DRay ToDouble(const Ray& ray) {
    return {glm::dvec3(ray.origin), glm::dvec3(ray.dir)};
}

ShellHit HitAt(const DRay& r, double t) {
    return {t, r.o + t * r.d, false};
}

// The smaller positive value of two candidates, if any (t > 0 only).
std::optional<double> NearestPositive(double t0, double t1) {
    const double lo = std::min(t0, t1);
    const double hi = std::max(t0, t1);
    if (lo > 0.0) return lo;
    if (hi > 0.0) return hi;
    return std::nullopt;
}

// Roots of a t^2 + 2 b t + c = 0 in the cancellation-free form; nullopt if none are real.
std::optional<std::pair<double, double>> SolveQuadratic(double a, double b, double c) {
    if (a == 0.0) return std::nullopt;
    const double disc = b * b - a * c;
    if (disc < 0.0) return std::nullopt;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) return std::make_pair(0.0, 0.0);  // b = 0 and c = 0
    return std::make_pair(q / a, c / q);
}

// Ray against the unit sphere at the origin.
std::optional<double> UnitSphereT(const DRay& r) {
    const auto roots =
        SolveQuadratic(glm::dot(r.d, r.d), glm::dot(r.o, r.d), glm::dot(r.o, r.o) - 1.0);
    if (!roots) return std::nullopt;
    return NearestPositive(roots->first, roots->second);
}

// Slab interval of one axis; false if the ray is parallel to the slab and outside it.
bool ClipSlab(double o, double d, double lo, double hi, double* tNear, double* tFar) {
    if (d == 0.0) return o >= lo && o <= hi;
    const double t0 = (lo - o) / d;
    const double t1 = (hi - o) / d;
    *tNear = std::max(*tNear, std::min(t0, t1));
    *tFar = std::min(*tFar, std::max(t0, t1));
    return true;
}

}  // namespace

std::optional<ShellHit> Intersect(const SphereShell& s, const Ray& ray) {
    const DRay r = ToDouble(ray);
    const DRay unit{(r.o - s.centre) / s.radius, r.d / s.radius};
    const std::optional<double> t = UnitSphereT(unit);
    if (!t) return std::nullopt;
    return HitAt(r, *t);
}

std::optional<ShellHit> Intersect(const EllipsoidShell& s, const Ray& ray) {
    // Scale space so that the ellipsoid becomes the unit sphere; t is unchanged.
    const DRay r = ToDouble(ray);
    const DRay unit{(r.o - s.centre) / s.radii, r.d / s.radii};
    const std::optional<double> t = UnitSphereT(unit);
    if (!t) return std::nullopt;
    return HitAt(r, *t);
}

std::optional<ShellHit> Intersect(const BoxShell& s, const Ray& ray) {
    const DRay r = ToDouble(ray);
    double tNear = -kInf;
    double tFar = kInf;
    for (int i = 0; i < 3; ++i) {
        if (!ClipSlab(r.o[i], r.d[i], s.min[i], s.max[i], &tNear, &tFar)) return std::nullopt;
    }
    if (tNear > tFar) return std::nullopt;
    const std::optional<double> t = NearestPositive(tNear, tFar);
    if (!t) return std::nullopt;
    return HitAt(r, *t);
}

std::optional<ShellHit> Intersect(const CylinderShell& s, const Ray& ray) {
    const DRay r = ToDouble(ray);
    double best = kInf;
    auto consider = [&](double t, bool valid) {
        if (valid && t > 0.0 && t < best) best = t;
    };
    // Step 1: the side, a quadratic in x and z, limited to [yMin, yMax].
    const glm::dvec2 o(r.o.x - s.axisXZ.x, r.o.z - s.axisXZ.y);
    const glm::dvec2 d(r.d.x, r.d.z);
    const auto roots =
        SolveQuadratic(glm::dot(d, d), glm::dot(o, d), glm::dot(o, o) - s.radius * s.radius);
    auto inHeight = [&](double t) {
        const double y = r.o.y + t * r.d.y;
        return y >= s.yMin && y <= s.yMax;
    };
    if (roots) {
        consider(roots->first, inHeight(roots->first));
        consider(roots->second, inHeight(roots->second));
    }
    // Step 2: the caps of a finite cylinder, limited to the disc.
    auto inDisc = [&](double t) {
        const glm::dvec2 p = o + t * d;
        return glm::dot(p, p) <= s.radius * s.radius;
    };
    for (double y : {s.yMin, s.yMax}) {
        if (std::isfinite(y) && r.d.y != 0.0) {
            const double t = (y - r.o.y) / r.d.y;
            consider(t, inDisc(t));
        }
    }
    if (best == kInf) return std::nullopt;
    return HitAt(r, best);
}

std::optional<ShellHit> Intersect(const QuadShell& s, const Ray& ray) {
    const DRay r = ToDouble(ray);
    // Step 1: the plane, when the ray heads toward it.
    const double dn = glm::dot(r.d, s.normal);
    if (dn != 0.0) {
        const double t = glm::dot(s.centre - r.o, s.normal) / dn;
        if (t > 0.0 && std::isfinite(t)) return HitAt(r, t);
    }
    // Step 2: forced hit, tangential component scaled far from the centre (hybrid §4.2).
    glm::dvec3 tangent = r.d - dn * s.normal;
    const double len = glm::length(tangent);
    tangent = len > 0.0 ? tangent / len : s.u;
    const double far = s.farScale * std::max({s.halfExtent.x, s.halfExtent.y, 1e-12});
    return ShellHit{kInf, s.centre + far * tangent, true};
}

std::optional<ShellHit> Intersect(const Shell& s, const Ray& ray) {
    return std::visit([&](const auto& shape) { return Intersect(shape, ray); }, s);
}

std::optional<glm::vec3> CubeLookup(const Shell& s, const Ray& ray, const glm::dvec3& emOrigin) {
    const std::optional<ShellHit> hit = Intersect(s, ray);
    if (!hit) return std::nullopt;
    return LookupVector(hit->point - emOrigin);
}

glm::vec3 LookupVector(const glm::dvec3& d) {
    // A cube lookup needs only the direction: scale vectors beyond float range down (a plane hit
    // of a nearly parallel ray lies at 1/cos, up to ~1e45) before the conversion to float.
    const double m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    return m > 1e30 ? glm::vec3(d / m) : glm::vec3(d);
}

double Volume(const SphereShell& s) {
    return 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius;
}

double Volume(const EllipsoidShell& s) {
    return 4.0 / 3.0 * std::numbers::pi * s.radii.x * s.radii.y * s.radii.z;
}

SphereShell BoundingSphere(std::span<const glm::dvec3> points, const glm::dvec3& centre) {
    double r2 = 0.0;
    for (const glm::dvec3& p : points) r2 = std::max(r2, glm::dot(p - centre, p - centre));
    return {centre, std::sqrt(r2)};
}

}  // namespace pem::trace
