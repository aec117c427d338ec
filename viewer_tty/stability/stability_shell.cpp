// SPDX-License-Identifier: MIT
// stability_shell.cpp — the shell family of the stability suite (stability.h): trace/shell.h with
// rays nearly in a quad's plane, tangent to spheres and ellipsoids, along box faces and cylinder
// walls, zero-length directions, and fits of (nearly) coplanar, collinear and coincident points.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "raster/cube_lookup.h"
#include "trace/shell.h"
#include "viewer_tty/stability/stability_internal.h"

namespace pem::stability {
namespace {

using stability::Checks;
using stability::Format;
using trace::Ray;

bool Finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Largest |component| of a point: above FLT_MAX the float cube lookup vector cannot hold it.
double MaxAbs(const glm::dvec3& v) {
    return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

struct ShellTally {
    int queries = 0, hits = 0, forced = 0, misses = 0;
    double worstSurface = 0.0;    // relative distance of a non-forced hit from the surface
    double worstCondition = 1.0;  // 1 / |cos| between ray and quad normal over plane hits
    double largestPoint = 0.0;
    std::string overflow;  // the first query whose hit exceeds float range
};

// One query: nullopt or a finite hit; `error` measures the hit's distance from the surface.
template <class ShellT, class ErrorFn>
void Query(const ShellT& shell, const Ray& ray, const char* what, const ErrorFn& error,
           Checks* checks, ShellTally* tally) {
    ++tally->queries;
    const std::optional<trace::ShellHit> hit = trace::Intersect(shell, ray);
    if (!hit) {
        ++tally->misses;
        return;
    }
    ++tally->hits;
    tally->forced += hit->forced;
    checks->Expect(
        Finite(hit->point) && !std::isnan(hit->t),
        Format("%s: non-finite hit (%g, %g, %g)", what, hit->point.x, hit->point.y, hit->point.z));
    tally->largestPoint = std::max(tally->largestPoint, MaxAbs(hit->point));
    // CubeLookup scales lookup vectors beyond float range down (trace::LookupVector).
    const std::optional<glm::vec3> v = trace::CubeLookup(trace::Shell(shell), ray, {});
    checks->Expect(v && Finite(glm::dvec3(*v)), Format("%s: non-finite cube lookup", what));
    if (MaxAbs(hit->point) > static_cast<double>(FLT_MAX) && tally->overflow.empty())
        tally->overflow =
            Format("%s: hit point |x| = %.3g beyond float range", what, MaxAbs(hit->point));
    if (!hit->forced) tally->worstSurface = std::max(tally->worstSurface, error(hit->point));
}

void QuadQueries(Checks* checks, ShellTally* tally) {
    trace::QuadShell quad;  // z = 0, half extent 1
    const auto planeError = [&](const glm::dvec3& p) {
        return std::fabs(p.z) / std::max(1.0, MaxAbs(p));
    };
    // Directions nearly in the plane, toward it and away from it, down to float denormals.
    for (float e : {1e-3f, 1e-6f, 1e-9f, 1e-20f, 1e-30f, 1e-38f, 1e-40f, 1e-45f, 0.0f, -0.0f}) {
        for (float sign : {-1.0f, 1.0f}) {
            const Ray ray{glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(1.0f, 0.0f, sign * e)};
            Query(quad, ray, Format("quad, dir (1, 0, %g)", static_cast<double>(sign * e)).c_str(),
                  planeError, checks, tally);
            const double cosine =
                std::fabs(static_cast<double>(e)) / glm::length(glm::dvec3(ray.dir));
            const auto hit = trace::Intersect(quad, ray);
            if (hit && !hit->forced)
                tally->worstCondition = std::max(tally->worstCondition, 1.0 / cosine);
        }
    }
    Query(quad, Ray{glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(0.0f)}, "quad, zero direction",
          planeError, checks, tally);
}

void ClosedShellQueries(Checks* checks, ShellTally* tally) {
    const trace::SphereShell sphere{glm::dvec3(0.0), 1.0};
    const auto sphereError = [](const glm::dvec3& p) { return std::fabs(glm::length(p) - 1.0); };
    // Tangent (impact exactly 1) and within float rounding of tangent, from outside.
    for (float b : {1.0f, 0.99999994f, 1.0000001f, 0.9999f}) {
        Query(sphere, Ray{glm::vec3(-5.0f, b, 0.0f), glm::vec3(1, 0, 0)},
              Format("sphere, impact %.9g", static_cast<double>(b)).c_str(), sphereError, checks,
              tally);
    }
    Query(sphere, Ray{glm::vec3(-5.0f, 0.5f, 0.0f), glm::vec3(0.0f)}, "sphere, zero direction",
          sphereError, checks, tally);
    const trace::EllipsoidShell ell{glm::dvec3(0.0), glm::dvec3(2.0, 1.0, 0.5)};
    const auto ellError = [](const glm::dvec3& p) {
        const glm::dvec3 q = p / glm::dvec3(2.0, 1.0, 0.5);
        return std::fabs(glm::length(q) - 1.0);
    };
    for (float z : {0.5f, 0.49999997f, 0.50000006f})
        Query(ell, Ray{glm::vec3(-5.0f, 0.0f, z), glm::vec3(1, 0, 0)},
              Format("ellipsoid, grazing z = %.9g", static_cast<double>(z)).c_str(), ellError,
              checks, tally);
    // Box: rays running inside a face plane and along an edge.
    const trace::BoxShell box{glm::dvec3(-1.0), glm::dvec3(1.0)};
    const auto boxError = [](const glm::dvec3& p) {
        return std::fabs(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) - 1.0);
    };
    for (const glm::vec3& o :
         {glm::vec3(-5, 1, 0), glm::vec3(-5, 1, 1), glm::vec3(-5, 1.0000001f, 0)})
        Query(box, Ray{o, glm::vec3(1, 0, 0)}, "box, ray in a face plane or along an edge",
              boxError, checks, tally);
    Query(box, Ray{glm::vec3(-5, 0, 0), glm::vec3(1, 1e-30f, 0)}, "box, nearly axis-parallel",
          boxError, checks, tally);
    // Cylinder: rays parallel to the axis on the wall, and axis-parallel inside an infinite one.
    const trace::CylinderShell cyl{glm::dvec2(0.0), 1.0, -1.0, 1.0};
    const trace::CylinderShell tube{glm::dvec2(0.0), 1.0, -std::numeric_limits<double>::infinity(),
                                    std::numeric_limits<double>::infinity()};
    const auto cylError = [](const glm::dvec3& p) {
        const double r = std::hypot(p.x, p.z);
        return std::min(std::fabs(r - 1.0), std::fabs(std::fabs(p.y) - 1.0));
    };
    for (const trace::CylinderShell* s : {&cyl, &tube}) {
        Query(*s, Ray{glm::vec3(1, -5, 0), glm::vec3(0, 1, 0)}, "cylinder, ray on the wall",
              cylError, checks, tally);
        Query(*s, Ray{glm::vec3(0.5f, 0, 0), glm::vec3(0, 1, 0)}, "cylinder, axis-parallel",
              cylError, checks, tally);
        Query(*s, Ray{glm::vec3(0.5f, 0, 0), glm::vec3(1e-30f, 1, 0)}, "cylinder, nearly axial",
              cylError, checks, tally);
    }
}

void NearlyCoplanarRays(StabilityCase* c) {
    Checks checks;
    ShellTally tally;
    QuadQueries(&checks, &tally);
    ClosedShellQueries(&checks, &tally);
    checks.Expect(tally.worstSurface < 1e-6,
                  Format("a hit lies %.3g (relative) off its surface", tally.worstSurface));
    c->residual = tally.worstSurface;
    c->condition = tally.worstCondition;
    c->detail = Format(
        "%d queries (quad with directions (1, 0, +-e), e = 1e-3 .. 1e-45 and 0, -0; tangent and "
        "near-tangent spheres and ellipsoids; rays in box face planes and along edges; cylinders "
        "along the wall and axis; zero directions): %d hits (%d forced quad hits), %d nullopt; "
        "largest hit coordinate %.3g; residual = worst relative distance of a non-forced hit from "
        "its surface; condition = largest 1 / |cos(ray, quad normal)| over plane hits (how much "
        "the hit distance amplifies direction error); hits beyond float range are the case "
        "\"shells: cube lookup of far plane hits\"%s",
        tally.queries, tally.hits, tally.forced, tally.misses, tally.largestPoint,
        tally.overflow.empty() ? "" : " (some here too)");
    stability::Conclude(
        checks,
        Format("%d hits finite or nullopt, surface error %.2g", tally.hits, tally.worstSurface), c);
}

// The float lookup vector of a finite double hit beyond FLT_MAX (nearly parallel quad rays).
void FarPlaneLookups(StabilityCase* c) {
    Checks checks;
    const trace::QuadShell quad;  // z = 0
    int queries = 0, overflows = 0;
    double largest = 0.0;
    std::string first;
    for (float e : {1e-30f, 1e-38f, 1e-40f, 1e-45f})
        for (const glm::vec3& d : {glm::vec3(1, 0, -e), glm::vec3(1, 1, -e)}) {
            const Ray ray{glm::vec3(0.3f, 0.2f, 1.0f), d};
            const std::optional<trace::ShellHit> hit = trace::Intersect(quad, ray);
            ++queries;
            if (!checks.Expect(hit && Finite(hit->point), "non-finite quad hit")) continue;
            largest = std::max(largest, MaxAbs(hit->point));
            if (MaxAbs(hit->point) > static_cast<double>(FLT_MAX) && overflows++ == 0)
                first = Format("dir (%g, %g, %g) from (0.3, 0.2, 1)", static_cast<double>(d.x),
                               static_cast<double>(d.y), static_cast<double>(d.z));
            // The float lookup vector must be finite and point the hit's way.
            const std::optional<glm::vec3> v = trace::CubeLookup(trace::Shell(quad), ray, {});
            if (!checks.Expect(v && Finite(glm::dvec3(*v)),
                               Format("non-finite cube lookup for %s", first.c_str())))
                continue;
            const glm::dvec3 want = glm::normalize(hit->point / MaxAbs(hit->point));
            checks.Expect(glm::dot(glm::normalize(glm::dvec3(*v)), want) > 1.0 - 1e-6,
                          "cube lookup direction differs from the hit's");
        }
    c->residual = std::numeric_limits<double>::quiet_NaN();
    c->condition = std::numeric_limits<double>::quiet_NaN();
    c->detail = Format(
        "quad z = 0, rays from (0.3, 0.2, 1) with directions (1, 0, -e) and (1, 1, -e), e = 1e-30, "
        "1e-38, 1e-40, 1e-45 (the plane hit is at t = 1 / e): %d queries, %d hits beyond FLT_MAX "
        "(trace::LookupVector scales them into float range); largest hit coordinate %.3g; "
        "residual and condition not applicable",
        queries, overflows, largest);
    stability::Conclude(checks, "finite float lookup vectors", c);
}

// Fits --------------------------------------------------------------------------------------

std::vector<glm::dvec3> PlanePoints(double noise) {
    std::vector<glm::dvec3> points;
    uint64_t state = 99;
    for (int i = 0; i < 200; ++i) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double u = static_cast<double>(state >> 11) / 9007199254740992.0;
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double v = static_cast<double>(state >> 11) / 9007199254740992.0;
        points.push_back({4.0 * u - 2.0, 0.5 * v, ((i % 3) - 1) * noise});
    }
    return points;
}

bool QuadSane(const trace::QuadShell& q) {
    return Finite(q.centre) && Finite(q.normal) && Finite(q.u) && Finite(q.v) &&
           std::fabs(glm::length(q.normal) - 1.0) < 1e-9 && std::isfinite(q.halfExtent.x) &&
           std::isfinite(q.halfExtent.y);
}

void FlatFits(StabilityCase* c) {
    Checks checks;
    const glm::dvec3 lens(0.0, 0.0, 5.0);
    double worstTilt = 0.0, worstContain = 0.0;
    for (double noise : {1e-3, 1e-9, 1e-15, 0.0}) {
        const std::vector<glm::dvec3> pts = PlanePoints(noise);
        const trace::QuadShell q = trace::FitQuad(pts, lens);
        checks.Expect(QuadSane(q), Format("FitQuad(noise %g): non-finite or non-unit", noise));
        worstTilt = std::max(worstTilt, std::fabs(std::fabs(q.normal.z) - 1.0));
        const trace::EllipsoidShell e = trace::FitEllipsoid(pts, glm::dvec3(0.0, 0.25, 0.0));
        checks.Expect(Finite(e.radii) && e.radii.x > 0 && e.radii.y > 0 && e.radii.z > 0,
                      Format("FitEllipsoid(noise %g): radii (%g, %g, %g)", noise, e.radii.x,
                             e.radii.y, e.radii.z));
        for (const glm::dvec3& p : pts) {
            const glm::dvec3 d = (p - e.centre) / e.radii;
            worstContain = std::max(worstContain, glm::dot(d, d) - 1.0);
        }
        const trace::BoxShell b = trace::FitBox(pts);
        checks.Expect(Finite(b.min) && Finite(b.max), "FitBox non-finite");
        const trace::CylinderShell cy = trace::FitCylinder(pts, glm::dvec2(0.0));
        checks.Expect(std::isfinite(cy.radius) && std::isfinite(cy.yMin), "FitCylinder");
    }
    // Collinear and coincident points: the paper's fallback normal toward the lens.
    const std::vector<glm::dvec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    const std::vector<glm::dvec3> same(5, glm::dvec3(0.5, 0.5, 0.5));
    for (const auto* pts : {&line, &same}) {
        const trace::QuadShell q = trace::FitQuad(*pts, lens);
        checks.Expect(QuadSane(q), "FitQuad on degenerate points: non-finite");
        const trace::EllipsoidShell e = trace::FitEllipsoid(*pts, (*pts)[0]);
        checks.Expect(Finite(e.radii), "FitEllipsoid on degenerate points: non-finite radii");
    }
    checks.Expect(worstContain <= 1e-9, Format("ellipsoid misses a point by %.3g", worstContain));
    c->residual = worstTilt;
    c->detail = Format(
        "200 points on z = 0 with +-noise (1e-3, 1e-9, 1e-15, 0), then 4 collinear and 5 "
        "coincident points: FitQuad, FitEllipsoid, FitBox, FitCylinder; residual = worst |1 - "
        "|n_z|| of the fitted quad normal (tilt from the true plane); worst ellipsoid containment "
        "excess %.3g; condition not applicable",
        worstContain);
    stability::Conclude(checks, Format("finite fits, quad normal tilt %.2g", worstTilt), c);
}

}  // namespace

std::vector<StabilityCase> RunShellStabilityCases(const StabilityOptions&) {
    return {
        stability::RunCase("shells: nearly coplanar and tangent rays", "stiff",
                           "every query gives nullopt or a finite hit on the surface (quads: a "
                           "finite plane or forced hit), a finite cube lookup vector, no NaN; "
                           "residual and condition reported",
                           NearlyCoplanarRays),
        stability::RunCase("shells: cube lookup of far plane hits", "extreme",
                           "for a ray nearly parallel to a quad, trace::CubeLookup returns a "
                           "finite float vector (or nullopt / a forced hit), never +-inf or NaN",
                           FarPlaneLookups),
        stability::RunCase("shells: fits of flat, collinear, coincident points", "stiff",
                           "finite shells: unit quad normal close to the plane's, ellipsoid "
                           "radii > 0 containing every point, finite box and cylinder",
                           FlatFits),
    };
}

}  // namespace pem::stability
