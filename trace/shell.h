// SPDX-License-Identifier: MIT
// shell.h — EM layer geometry ("shells"): ray intersection and the cube-map lookup vector (hit
// point minus the EM origin; cube maps need no normalization), plus fits of each shell to points.
// Shapes: sphere, axis-aligned ellipsoid, axis-aligned box, cylinder with a vertical (y) axis
// (finite with caps, or infinite), and the hybrid paper's quad impostor.
//
// Intersection rule for closed shells: the smallest t > 0, so a ray starting inside hits the far
// side and a ray starting outside hits the nearest front face (or misses: nullopt). `dir` need not
// be unit; t is in units of dir. The quad always yields a point: its plane hit for t > 0, otherwise
// (parallel or running away) the hybrid §4.2 rule: the direction's tangential component,
// normalized and scaled to farScale * the quad's larger half extent from the quad centre
// (`forced`, t = +inf). Plane hits outside the quad's rectangle are kept (the texture lookup
// clamps). All arithmetic is double.
//
// Not here: texturing the shells (infer/), choosing a shell per layer (the caller).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <variant>

#include "trace/ray.h"

namespace pem::trace {

struct SphereShell {
    glm::dvec3 centre{0.0};
    double radius = 1.0;
    bool operator==(const SphereShell&) const = default;
};

struct EllipsoidShell {
    glm::dvec3 centre{0.0};
    glm::dvec3 radii{1.0};  // semi-axes along x, y, z
    bool operator==(const EllipsoidShell&) const = default;
};

struct BoxShell {
    glm::dvec3 min{-1.0};
    glm::dvec3 max{1.0};
    bool operator==(const BoxShell&) const = default;
};

struct CylinderShell {
    glm::dvec2 axisXZ{0.0};  // the vertical axis passes through (x, z)
    double radius = 1.0;
    double yMin = -1.0;  // -inf and +inf make it infinite (then no caps)
    double yMax = 1.0;
    bool operator==(const CylinderShell&) const = default;
};

struct QuadShell {
    glm::dvec3 centre{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0};  // unit, facing the lens object
    glm::dvec3 u{1.0, 0.0, 0.0};       // unit in-plane axes, u x v = normal
    glm::dvec3 v{0.0, 1.0, 0.0};
    glm::dvec2 halfExtent{1.0};  // along u and v
    double farScale = 1e3;       // forced hits lie farScale * max half extent from centre
    bool operator==(const QuadShell&) const = default;
};

using Shell = std::variant<SphereShell, EllipsoidShell, BoxShell, CylinderShell, QuadShell>;

struct ShellHit {
    double t = 0.0;  // +inf for a forced quad hit
    glm::dvec3 point{0.0};
    bool forced = false;
    bool operator==(const ShellHit&) const = default;
};

// Step: intersection.
std::optional<ShellHit> Intersect(const SphereShell& s, const Ray& ray);
std::optional<ShellHit> Intersect(const EllipsoidShell& s, const Ray& ray);
std::optional<ShellHit> Intersect(const BoxShell& s, const Ray& ray);
std::optional<ShellHit> Intersect(const CylinderShell& s, const Ray& ray);
std::optional<ShellHit> Intersect(const QuadShell& s, const Ray& ray);  // never nullopt
std::optional<ShellHit> Intersect(const Shell& s, const Ray& ray);

// Step: the cube-map index, hit point minus the EM origin (nullopt when the ray misses the shell).
// A double lookup vector as float, scaled down (direction kept) when beyond float range.
glm::vec3 LookupVector(const glm::dvec3& d);
std::optional<glm::vec3> CubeLookup(const Shell& s, const Ray& ray, const glm::dvec3& emOrigin);

// Step: fits. `points` are intersection points (or mesh vertices for the local layer).
SphereShell BoundingSphere(std::span<const glm::dvec3> points, const glm::dvec3& centre);
// Minimum-volume axis-aligned ellipsoid centred at `centre` containing all points (PEM §4, brute
// force): radii = lambda * (1, 2^a, 2^b); for each shape (a, b) the smallest containing lambda is
// exact (max over points), and (a, b) is searched on a 25 x 25 grid over [-6, 6]^2 followed by six
// 9 x 9 refinements, each around the best shape with half the step. (0, 0) (the bounding sphere)
// is on the grid, so the result is never larger than the bounding sphere.
EllipsoidShell FitEllipsoid(std::span<const glm::dvec3> points, const glm::dvec3& centre);
// Bounding box of the points; with floorY its bottom is put on the floor (y = floorY).
BoxShell FitBox(std::span<const glm::dvec3> points, std::optional<double> floorY = std::nullopt);
// Box of half size `halfSize` around `centre`, bottom on the floor if floorY is given (PEM §4).
BoxShell BoxAround(const glm::dvec3& centre, double halfSize,
                   std::optional<double> floorY = std::nullopt);
// Cylinder about a vertical axis through axisXZ: radius = largest horizontal distance, height =
// the points' y range (or infinite).
CylinderShell FitCylinder(std::span<const glm::dvec3> points, const glm::dvec2& axisXZ,
                          bool infinite = false);
// Quad impostor (hybrid §4.2): least-squares plane through the centroid (normal = eigenvector of
// the smallest covariance eigenvalue, turned toward lensCentre; u = the largest one, its largest
// component positive; v = normal x u). Extent = bounding rectangle of the points projected
// orthogonally onto the plane; the centre is moved to the rectangle's centre. Fewer than 3 points
// or collinear points use the paper's simpler normal: from the centroid toward lensCentre.
QuadShell FitQuad(std::span<const glm::dvec3> points, const glm::dvec3& lensCentre);

double Volume(const SphereShell& s);
double Volume(const EllipsoidShell& s);

// EM origin (PEM §4): the area-weighted mean of triangle centroids; `indices` holds 3 per triangle.
// With zero total area, the plain mean of the triangle centroids.
glm::vec3 EmOrigin(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

}  // namespace pem::trace
