// SPDX-License-Identifier: MIT
// stability_geometry.cpp — the shell and ray-path families of the stability suite (stability.h):
// trace/shell.h under tangent, nearly coplanar and zero-length rays and fits of flat point sets;
// trace/ray_path.h on analytic surfaces with IOR 1 and 4, total internal reflection to maxDepth,
// and viewpoints inside a sphere or exactly on a surface.
// The analytic sphere and slab are small copies of tests/trace/analytic_surfaces.h.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "trace/ray_path.h"
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

// Analytic surfaces (after tests/trace/analytic_surfaces.h) ------------------------------------

class AnalyticSurface : public trace::SurfaceHitFn {
  public:
    trace::SurfaceMaterial material;
    std::optional<trace::SurfaceHit> Next(const Ray& ray) override {
        const glm::dvec3 o(ray.origin), d(ray.dir);
        const std::optional<double> t = NearestT(o, d);
        if (!t) return std::nullopt;
        const glm::dvec3 p = o + *t * d;
        const glm::dvec3 n = NormalAt(p);
        trace::SurfaceHit hit;
        hit.t = static_cast<float>(*t);
        hit.position = glm::vec3(p);
        hit.geometricNormal = hit.shadingNormal = glm::vec3(n);
        hit.material = material;
        hit.entering = glm::dot(d, n) < 0.0;
        return hit;
    }

  protected:
    static constexpr double kTMin = 1e-7;
    virtual std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const = 0;
    virtual glm::dvec3 NormalAt(const glm::dvec3& p) const = 0;
};

class Sphere : public AnalyticSurface {
  public:
    double radius = 1.0;  // centred at the origin

  protected:
    std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const override {
        const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius;
        const double disc = b * b - a * c;
        if (disc < 0.0) return std::nullopt;
        for (double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a})
            if (t > kTMin) return t;
        return std::nullopt;
    }
    glm::dvec3 NormalAt(const glm::dvec3& p) const override { return glm::normalize(p); }
};

class Slab : public AnalyticSurface {  // |y| <= halfThickness
  public:
    double halfThickness = 0.5;

  protected:
    std::optional<double> NearestT(const glm::dvec3& o, const glm::dvec3& d) const override {
        if (d.y == 0.0) return std::nullopt;
        std::optional<double> best;
        for (double y : {-halfThickness, halfThickness}) {
            const double t = (y - o.y) / d.y;
            if (t > kTMin && (!best || t < *best)) best = t;
        }
        return best;
    }
    glm::dvec3 NormalAt(const glm::dvec3& p) const override { return {0.0, p.y > 0 ? 1 : -1, 0}; }
};

trace::SurfaceMaterial Glass(double ior, double sigma = 0.0) {
    trace::SurfaceMaterial m;
    m.ior = ior;
    m.absorption = glm::dvec3(sigma);
    return m;
}

// Path checks shared by the ray-path cases
// ---------------------------------------------------------

// F and G finite and in [0, 1] per channel; the exit ray finite (and unit when escaped).
bool PathSane(const trace::RayPath& p) {
    const glm::dvec3 exitDir(p.exitDir);
    const auto unit = [](const glm::dvec3& v) {
        return v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0 && v.x <= 1.0 && v.y <= 1.0 && v.z <= 1.0;
    };
    bool ok = Finite(p.F) && Finite(p.G) && unit(p.F) && unit(p.G) &&
              Finite(glm::dvec3(p.exitOrigin)) && Finite(exitDir);
    if (p.escaped) ok = ok && std::fabs(glm::length(exitDir) - 1.0) < 1e-5;
    for (const trace::PathVertex& v : p.vertices)
        ok = ok && Finite(glm::dvec3(v.position)) && Finite(glm::dvec3(v.normal));
    return ok;
}

// |sum of leaf weights - 1| of the full tree (no absorption: the weights sum to 1 per channel).
double TreeEnergyError(const std::vector<trace::ExitRay>& leaves, bool* finite) {
    glm::dvec3 sum(0.0);
    for (const trace::ExitRay& leaf : leaves) {
        *finite = *finite && Finite(leaf.weight) && Finite(glm::dvec3(leaf.ray.dir));
        sum += leaf.weight;
    }
    return std::max({std::fabs(sum.x - 1.0), std::fabs(sum.y - 1.0), std::fabs(sum.z - 1.0)});
}

// Primary rays toward the unit sphere from z = 4 at impact offsets up to grazing.
std::vector<Ray> SphereRays() {
    std::vector<Ray> rays;
    for (float b : {0.0f, 0.3f, 0.7f, 0.95f, 0.999f, 0.999999f})
        rays.push_back({glm::vec3(b, 0.0f, 4.0f), glm::vec3(0, 0, -1)});
    return rays;
}

void IorOne(StabilityCase* c) {
    Sphere sphere;
    sphere.material = Glass(1.0);
    Checks checks;
    double worstAngle = 0.0, energy = 0.0;
    bool finite = true;
    for (const Ray& ray : SphereRays()) {
        const std::optional<trace::GreedyPaths> paths = TraceGreedyPaths(ray, sphere, 8, 1e-3);
        if (!checks.Expect(paths.has_value(), "primary ray missed the sphere")) continue;
        const trace::RayPath& t = paths->refraction;
        checks.Expect(PathSane(t) && PathSane(paths->reflection), "non-finite or unbounded path");
        checks.Expect(paths->reflection.F == glm::dvec3(0.0), "reflection F != 0 at IOR 1");
        checks.Expect(t.escaped && t.vertices.size() == 2, "refraction path not straight through");
        checks.Expect(std::fabs(t.F.x - 1.0) < 1e-12, Format("refraction F %.17g != 1", t.F.x));
        worstAngle = std::max(worstAngle,
                              trace::AngleBetweenDeg(glm::dvec3(t.exitDir), glm::dvec3(ray.dir)));
        energy = std::max(energy, TreeEnergyError(TraceFullTree(ray, sphere, 8, 0.0), &finite));
    }
    checks.Expect(worstAngle < 1e-3, Format("exit direction bent by %.3g deg", worstAngle));
    checks.Expect(finite && energy < 1e-9, Format("full-tree energy error %.3g", energy));
    c->residual = worstAngle;
    c->detail = Format(
        "glass sphere with ior 1.0 in air, 6 primary rays up to impact 0.999999; residual = worst "
        "angle (deg) between the T exit and the primary direction; full-tree |sum w - 1| = %.3g; "
        "condition not applicable",
        energy);
    stability::Conclude(checks,
                        Format("straight through, F_T = 1, F_R = 0, bent %.2g deg", worstAngle), c);
}

void IorFour(StabilityCase* c) {
    Sphere sphere;
    sphere.material = Glass(4.0);
    Checks checks;
    double energy = 0.0;
    bool finite = true;
    int escaped = 0, cut = 0;
    for (const Ray& ray : SphereRays()) {
        const std::optional<trace::GreedyPaths> paths = TraceGreedyPaths(ray, sphere, 16, 1e-3);
        if (!checks.Expect(paths.has_value(), "primary ray missed the sphere")) continue;
        for (const trace::RayPath* p : {&paths->reflection, &paths->refraction}) {
            checks.Expect(PathSane(*p), "non-finite or unbounded path");
            (p->escaped ? escaped : cut) += 1;
        }
        energy = std::max(energy, TreeEnergyError(TraceFullTree(ray, sphere, 16, 0.0), &finite));
    }
    checks.Expect(finite && energy < 1e-9, Format("full-tree energy error %.3g", energy));
    c->residual = energy;
    c->detail = Format(
        "glass sphere with ior 4.0, 6 primary rays up to impact 0.999999, maxDepth 16; %d greedy "
        "paths escaped, %d cut off; residual = worst full-tree |sum of leaf weights - 1| (no "
        "absorption); condition not applicable",
        escaped, cut);
    stability::Conclude(checks, Format("finite F, G in [0, 1]; energy error %.2g", energy), c);
}

void TotalInternalReflection(StabilityCase* c) {
    Slab slab;
    slab.material = Glass(1.5, 0.1);
    Checks checks;
    const double a = 60.0 * std::numbers::pi / 180.0;  // critical angle 41.8 deg
    const Ray ray{glm::vec3(0.0f), glm::vec3(glm::dvec3(std::sin(a), std::cos(a), 0.0))};
    const int maxDepth = 32;
    const std::optional<trace::GreedyPaths> paths = TraceGreedyPaths(ray, slab, maxDepth, 0.0);
    double residual = std::numeric_limits<double>::quiet_NaN();
    if (checks.Expect(paths.has_value(), "primary ray from inside found no surface")) {
        const trace::RayPath& r = paths->reflection;
        checks.Expect(PathSane(r) && PathSane(paths->refraction), "non-finite or unbounded path");
        checks.Expect(r.vertices.size() == static_cast<size_t>(maxDepth) && !r.escaped,
                      Format("reflection path has %zu events, escaped %d (want %d, cut off)",
                             r.vertices.size(), r.escaped, maxDepth));
        checks.Expect(r.F == glm::dvec3(1.0), "TIR path F != 1");
        checks.Expect(paths->refraction.F == glm::dvec3(0.0), "impossible refraction has F != 0");
        double length = 0.0;  // every segment between the events runs inside
        for (size_t i = 1; i < r.vertices.size(); ++i)
            length += glm::length(glm::dvec3(r.vertices[i].position) -
                                  glm::dvec3(r.vertices[i - 1].position));
        const double expected = std::exp(-0.1 * length);
        residual = std::fabs(r.G.x - expected) / expected;
        checks.Expect(residual < 1e-5, Format("G %.9g vs exp(-sigma L) %.9g", r.G.x, expected));
    }
    bool finite = true;
    const double energy = TreeEnergyError(TraceFullTree(ray, slab, maxDepth, 0.0), &finite);
    checks.Expect(finite, "full tree has non-finite leaves");
    c->residual = residual;
    c->detail = Format(
        "primary ray inside a glass slab (ior 1.5, thickness 1, sigma 0.1) at 60 deg from the "
        "normal (critical 41.8 deg), maxDepth %d; residual = |G - exp(-sigma L)| / G with L the "
        "polyline length of the path; full-tree |sum w - 1| = %.3g (absorbed energy); condition "
        "not applicable",
        maxDepth, energy);
    stability::Conclude(checks, Format("cut off at maxDepth %d with F = 1, finite G", maxDepth), c);
}

void InsideSphere(StabilityCase* c) {
    Checks checks;
    double worstAngle = 0.0;
    int depthCut = 0;
    for (trace::SurfaceKind kind : {trace::SurfaceKind::Dielectric, trace::SurfaceKind::Mirror}) {
        Sphere sphere;
        sphere.material = Glass(1.5);
        sphere.material.kind = kind;
        sphere.material.mirrorF0 = glm::dvec3(0.9);
        for (const glm::vec3& dir :
             {glm::vec3(0, 0, 1), glm::vec3(0.6f, 0.0f, 0.8f), glm::vec3(0, -1, 0)}) {
            const Ray fromCentre{glm::vec3(0.0f), dir};
            const Ray offCentre{glm::vec3(0.5f, 0.2f, 0.0f), dir};
            for (const Ray& ray : {fromCentre, offCentre}) {
                const auto paths = TraceGreedyPaths(ray, sphere, 24, 0.0);
                if (!checks.Expect(paths.has_value(), "no hit from inside")) continue;
                checks.Expect(PathSane(paths->reflection) && PathSane(paths->refraction),
                              "non-finite or unbounded path");
                depthCut += !paths->reflection.escaped;
                if (kind == trace::SurfaceKind::Dielectric && ray.origin == glm::vec3(0.0f)) {
                    checks.Expect(paths->refraction.escaped, "normal-incidence exit not escaped");
                    worstAngle = std::max(
                        worstAngle, trace::AngleBetweenDeg(glm::dvec3(paths->refraction.exitDir),
                                                           glm::dvec3(dir)));
                }
            }
        }
    }
    checks.Expect(worstAngle < 1e-3, Format("normal-incidence exit bent by %.3g deg", worstAngle));
    c->residual = worstAngle;
    c->detail = Format(
        "viewpoints at the centre and at (0.5, 0.2, 0) of a unit glass (ior 1.5) and mirror (F0 "
        "0.9) sphere, 3 directions, maxDepth 24; %d reflection paths cut off inside; residual = "
        "worst angle (deg) of the glass exit from the centre against the primary direction "
        "(normal incidence); condition not applicable",
        depthCut);
    stability::Conclude(checks, "finite paths; glass exits unbent, mirror bounces cut off", c);
}

// Step: one shell hit from an origin exactly on the surface; nullopt or a finite point on it.
template <class ShellT>
void ExpectOnSurfaceHit(const ShellT& shell, const Ray& ray,
                        double (*surfaceError)(const ShellT&, const glm::dvec3&), Checks* checks,
                        double* worst, int* hits) {
    const std::optional<trace::ShellHit> hit = trace::Intersect(shell, ray);
    const std::optional<glm::vec3> lookup =
        trace::CubeLookup(trace::Shell(shell), ray, glm::dvec3(0.1, 0.2, 0.3));
    checks->Expect(hit.has_value() == lookup.has_value(), "Intersect and CubeLookup disagree");
    if (!hit) return;
    ++*hits;
    checks->Expect(Finite(hit->point) && !std::isnan(hit->t), "non-finite shell hit");
    checks->Expect(Finite(glm::dvec3(*lookup)), "non-finite cube lookup vector");
    if (!hit->forced) *worst = std::max(*worst, surfaceError(shell, hit->point));
}

double SphereError(const trace::SphereShell& s, const glm::dvec3& p) {
    return std::fabs(glm::length(p - s.centre) - s.radius) / s.radius;
}
double BoxError(const trace::BoxShell& b, const glm::dvec3& p) {
    double e = std::numeric_limits<double>::infinity();  // distance to the nearest face plane (the
                                                         // point lies on one)
    for (int k = 0; k < 3; ++k)
        e = std::min({e, std::fabs(p[k] - b.min[k]), std::fabs(p[k] - b.max[k])});
    return e;
}
double QuadError(const trace::QuadShell& q, const glm::dvec3& p) {
    return std::fabs(glm::dot(p - q.centre, q.normal)) / std::max(1.0, glm::length(p));
}

void OnSurface(StabilityCase* c) {
    Checks checks;
    // Ray paths from a point exactly on a unit glass sphere: inward, outward, tangent, oblique.
    Sphere sphere;
    sphere.material = Glass(1.5);
    int misses = 0;
    const glm::vec3 onSphere(1.0f, 0.0f, 0.0f);
    const std::array<glm::vec3, 4> dirs = {glm::vec3(-1, 0, 0), glm::vec3(1, 0, 0),
                                           glm::vec3(0, 1, 0), glm::vec3(-0.6f, 0.8f, 0.0f)};
    for (const glm::vec3& d : dirs) {
        const auto paths = TraceGreedyPaths({onSphere, d}, sphere, 16, 1e-3);
        if (!paths) {
            ++misses;
            continue;
        }
        checks.Expect(PathSane(paths->reflection) && PathSane(paths->refraction),
                      "non-finite or unbounded path from the surface");
    }
    // Shell intersections from origins exactly on every shell kind.
    double worst = 0.0;
    int hits = 0, tried = 0;
    const trace::SphereShell s{glm::dvec3(0.0), 1.0};
    const trace::BoxShell box{glm::dvec3(-1.0), glm::dvec3(1.0)};
    trace::QuadShell quad;
    for (const glm::vec3& d : dirs) {
        ExpectOnSurfaceHit(s, {onSphere, d}, SphereError, &checks, &worst, &hits);
        ExpectOnSurfaceHit(box, {onSphere, d}, BoxError, &checks, &worst, &hits);
        ExpectOnSurfaceHit(box, {glm::vec3(1.0f, 1.0f, 0.0f), d}, BoxError, &checks, &worst,
                           &hits);  // on an edge
        ExpectOnSurfaceHit(quad, {glm::vec3(0.25f, 0.5f, 0.0f), d}, QuadError, &checks, &worst,
                           &hits);
        const glm::vec3 dz = d + glm::vec3(0.0f, 0.0f, 0.5f);
        ExpectOnSurfaceHit(quad, {glm::vec3(0.25f, 0.5f, 0.0f), dz}, QuadError, &checks, &worst,
                           &hits);
        tried += 5;
    }
    const trace::EllipsoidShell ell{glm::dvec3(0.0), glm::dvec3(2.0, 1.0, 0.5)};
    const trace::CylinderShell cyl{glm::dvec2(0.0), 1.0, -1.0, 1.0};
    for (const glm::vec3& d : dirs) {
        for (const glm::vec3& o : {glm::vec3(2, 0, 0), glm::vec3(0, 0, 0.5f)}) {
            const std::optional<trace::ShellHit> h = trace::Intersect(ell, {o, d});
            checks.Expect(!h || (Finite(h->point) && std::isfinite(h->t)), "ellipsoid hit");
        }
        const std::optional<trace::ShellHit> h = trace::Intersect(cyl, {onSphere, d});
        checks.Expect(!h || (Finite(h->point) && std::isfinite(h->t)), "cylinder hit");
        tried += 3;
    }
    checks.Expect(worst < 1e-9, Format("hit %.3g off the shell surface", worst));
    c->residual = worst;
    c->detail = Format(
        "greedy paths from (1, 0, 0) on a unit glass sphere in 4 directions (%d leave without a "
        "hit: nullopt); %d shell queries (sphere, box face and edge, quad plane, ellipsoid, "
        "cylinder) from origins on the surface, %d hits; residual = worst relative distance of a "
        "non-forced hit from its surface; condition not applicable",
        misses, tried, hits);
    stability::Conclude(checks, Format("nullopt or finite hits on the surface (%d hits)", hits), c);
}

}  // namespace

std::vector<StabilityCase> RunRayPathStabilityCases(const StabilityOptions&) {
    const std::string finite = "finite F, G in [0, 1], finite unit exit rays, no NaN";
    return {
        stability::RunCase(
            "ray paths: IOR 1.0", "extreme",
            "no reflection (F_R = 0), refraction straight through with F_T = 1; " + finite, IorOne),
        stability::RunCase("ray paths: IOR 4.0", "extreme",
                           finite + "; full-tree weights sum to 1 (no absorption)", IorFour),
        stability::RunCase("ray paths: total internal reflection", "extreme",
                           "the TIR path is cut off at maxDepth (not escaped) with F = 1 and G = "
                           "exp(-sigma L); the impossible refraction has F = 0; " +
                               finite,
                           TotalInternalReflection),
        stability::RunCase("ray paths: viewpoint inside a sphere", "extreme",
                           "glass exits at normal incidence unbent; mirror bounces cut off at "
                           "maxDepth; " +
                               finite,
                           InsideSphere),
        stability::RunCase("ray paths: viewpoint on a surface", "extreme",
                           "paths from a point exactly on the surface: nullopt (no further hit) "
                           "or " +
                               finite +
                               "; shell queries from a point on each shell: nullopt "
                               "or a finite hit on the surface",
                           OnSurface),
    };
}

}  // namespace pem::stability
