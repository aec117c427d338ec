// SPDX-License-Identifier: MIT
// shell_test.cpp — shell intersections against analytic values and a brute-force ray march,
// the minimum-volume ellipsoid, boxes on the floor, the quad impostor fit and its forced hits,
// cube lookups and the EM origin.
#include "trace/shell.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

namespace pem::trace {
namespace {

using Inside = std::function<bool(const glm::dvec3&)>;

// Brute force: march t in small steps from 0 to tMax, find the first change of inside-ness, then
// bisect. Returns nullopt when nothing changes.
std::optional<double> MarchT(const Inside& inside, const Ray& ray, double tMax) {
    const glm::dvec3 o(ray.origin);
    const glm::dvec3 d(ray.dir);
    const double step = 1e-3;
    const bool start = inside(o + 1e-9 * d);
    for (double t = step; t <= tMax; t += step) {
        if (inside(o + t * d) == start) continue;
        double lo = t - step, hi = t;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (inside(o + mid * d) == start ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }
    return std::nullopt;
}

// Fixed-seed rays (raw mt19937 output is portable): origins in [-4, 4]^3; every other ray aims
// near the origin so that many rays starting outside hit the shell too.
std::vector<Ray> RandomRays(int n) {
    std::mt19937 rng(12345);
    auto uniform = [&]() { return static_cast<double>(rng() >> 8) * 0x1.0p-24 * 2.0 - 1.0; };
    std::vector<Ray> rays;
    while (static_cast<int>(rays.size()) < n) {
        const glm::dvec3 o(4.0 * uniform(), 4.0 * uniform(), 4.0 * uniform());
        glm::dvec3 d(uniform(), uniform(), uniform());
        if (rays.size() % 2 == 1) d = 1.5 * d - o;
        if (glm::length(d) < 0.1) continue;
        rays.push_back({glm::vec3(o), glm::vec3(glm::normalize(d))});
    }
    return rays;
}

// The march covers t <= 20; analytic hits beyond that must have no marched counterpart. A ray
// that only grazes an edge (in and out within one march step) is invisible to the march; at most
// a few such rays are allowed, and only when the point one step past the hit is on the start side.
void ExpectMatchesMarch(const Shell& shell, const Inside& inside) {
    constexpr double kTMax = 20.0;
    int hits = 0, grazes = 0;
    for (const Ray& ray : RandomRays(300)) {
        std::optional<ShellHit> hit = Intersect(shell, ray);
        if (hit && hit->t > kTMax) hit.reset();
        const std::optional<double> march = MarchT(inside, ray, kTMax);
        const glm::dvec3 o(ray.origin), d(ray.dir);
        if (hit && !march && inside(o + (hit->t + 1e-3) * d) == inside(o + 1e-9 * d)) {
            ++grazes;
            continue;
        }
        ASSERT_EQ(hit.has_value(), march.has_value()) << shell.index() << " " << ray.origin.x;
        if (!hit) continue;
        ++hits;
        EXPECT_NEAR(hit->t, *march, 1e-6);
        EXPECT_NEAR(glm::length(hit->point - (o + hit->t * d)), 0.0, 1e-9);
    }
    EXPECT_GT(hits, 150);
    EXPECT_LE(grazes, 3);
}

TEST(Shell, SphereAnalytic) {
    const SphereShell s{{1.0, 2.0, 3.0}, 5.0};
    // Outside, toward the centre: the near side.
    const std::optional<ShellHit> outside =
        Intersect(s, {glm::vec3(1, 2, 13), glm::vec3(0, 0, -1)});
    ASSERT_TRUE(outside);
    EXPECT_DOUBLE_EQ(outside->t, 5.0);
    EXPECT_EQ(outside->point, glm::dvec3(1, 2, 8));
    // Inside: the far side.
    const std::optional<ShellHit> inside = Intersect(s, {glm::vec3(1, 2, 4), glm::vec3(0, 0, -1)});
    ASSERT_TRUE(inside);
    EXPECT_DOUBLE_EQ(inside->t, 6.0);
    // Outside, away from the sphere, or passing by: no hit.
    EXPECT_FALSE(Intersect(s, {glm::vec3(1, 2, 13), glm::vec3(0, 0, 1)}));
    EXPECT_FALSE(Intersect(s, {glm::vec3(7, 2, 13), glm::vec3(0, 0, -1)}));
    // A non-unit direction scales t.
    EXPECT_DOUBLE_EQ(Intersect(s, {glm::vec3(1, 2, 13), glm::vec3(0, 0, -2)})->t, 2.5);
}

TEST(Shell, SphereEllipsoidBoxCylinderMatchBruteForce) {
    const SphereShell sphere{{0.3, -0.2, 0.1}, 2.5};
    ExpectMatchesMarch(sphere, [&](const glm::dvec3& p) {
        return glm::length(p - sphere.centre) < sphere.radius;
    });
    const EllipsoidShell ellipsoid{{0.2, 0.1, -0.3}, {3.0, 1.5, 2.0}};
    ExpectMatchesMarch(ellipsoid, [&](const glm::dvec3& p) {
        const glm::dvec3 q = (p - ellipsoid.centre) / ellipsoid.radii;
        return glm::dot(q, q) < 1.0;
    });
    const BoxShell box{{-2.0, -1.0, -3.0}, {3.0, 2.0, 1.5}};
    ExpectMatchesMarch(box, [&](const glm::dvec3& p) {
        return glm::all(glm::greaterThan(p, box.min)) && glm::all(glm::lessThan(p, box.max));
    });
    const CylinderShell finite{{0.5, -0.5}, 2.0, -1.5, 2.5};
    ExpectMatchesMarch(finite, [&](const glm::dvec3& p) {
        const glm::dvec2 h(p.x - 0.5, p.z + 0.5);
        return glm::dot(h, h) < 4.0 && p.y > -1.5 && p.y < 2.5;
    });
    const double inf = std::numeric_limits<double>::infinity();
    const CylinderShell infinite{{0.5, -0.5}, 2.0, -inf, inf};
    ExpectMatchesMarch(infinite, [&](const glm::dvec3& p) {
        const glm::dvec2 h(p.x - 0.5, p.z + 0.5);
        return glm::dot(h, h) < 4.0;
    });
}

TEST(Shell, BoxAndCylinderSpecialCases) {
    const BoxShell box = BoxAround({0, 1, 0}, 4.0, 0.0);
    EXPECT_EQ(box.min, glm::dvec3(-4, 0, -4));
    EXPECT_EQ(box.max, glm::dvec3(4, 5, 4));
    // Inside, straight down: the floor. Parallel to a face outside its slab: miss.
    EXPECT_DOUBLE_EQ(Intersect(box, {glm::vec3(1, 2, 1), glm::vec3(0, -1, 0)})->t, 2.0);
    EXPECT_FALSE(Intersect(box, {glm::vec3(0, 7, 0), glm::vec3(1, 0, 0)}));
    const std::vector<glm::dvec3> points{{1, 2, 3}, {-1, 5, 0}, {2, 3, -2}};
    const BoxShell fitted = FitBox(points, -0.5);
    EXPECT_EQ(fitted.min, glm::dvec3(-1, -0.5, -2));
    EXPECT_EQ(fitted.max, glm::dvec3(2, 5, 3));
    // Cylinder: straight up from inside hits the cap; an infinite one is never left vertically.
    const CylinderShell cyl = FitCylinder(points, {0.0, 0.0});
    EXPECT_DOUBLE_EQ(cyl.radius, std::sqrt(10.0));
    EXPECT_DOUBLE_EQ(Intersect(cyl, {glm::vec3(0, 2, 0), glm::vec3(0, 1, 0)})->t, 3.0);
    EXPECT_FALSE(
        Intersect(FitCylinder(points, {0.0, 0.0}, true), {glm::vec3(0, 2, 0), glm::vec3(0, 1, 0)}));
}

TEST(Shell, EllipsoidContainsPointsAndBeatsBoundingSphere) {
    std::mt19937 rng(7);
    auto uniform = [&]() { return static_cast<double>(rng() >> 8) * 0x1.0p-24 * 2.0 - 1.0; };
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 500; ++i)
        points.push_back({3.0 * uniform(), 1.0 * uniform(), 0.5 * uniform()});
    const glm::dvec3 centre(0.1, 0.0, -0.05);
    const EllipsoidShell e = FitEllipsoid(points, centre);
    for (const glm::dvec3& p : points) {
        const glm::dvec3 q = (p - centre) / e.radii;
        EXPECT_LE(glm::dot(q, q), 1.0 + 1e-9);
    }
    const SphereShell s = BoundingSphere(points, centre);
    EXPECT_LT(Volume(e), 0.5 * Volume(s));
    EXPECT_EQ(e.centre, centre);
}

TEST(Shell, EllipsoidThroughAxisPointsIsTheirAxes) {
    // The smallest axis-aligned ellipsoid containing +-a x, +-b y, +-c z has semi-axes (a, b, c).
    const double a = 3.0, b = 1.3, c = 0.7;
    const std::vector<glm::dvec3> points{{a, 0, 0},  {-a, 0, 0}, {0, b, 0},
                                         {0, -b, 0}, {0, 0, c},  {0, 0, -c}};
    const EllipsoidShell e = FitEllipsoid(points, glm::dvec3(0.0));
    const double optimal = Volume(EllipsoidShell{glm::dvec3(0.0), {a, b, c}});
    EXPECT_GE(Volume(e), optimal * (1.0 - 1e-9));
    EXPECT_LT(Volume(e), optimal * 1.01);
    EXPECT_NEAR(e.radii.x, a, 0.02 * a);
    EXPECT_NEAR(e.radii.y, b, 0.02 * b);
    EXPECT_NEAR(e.radii.z, c, 0.02 * c);
}

TEST(Shell, QuadFitRecoversPlaneAndRectangle) {
    // Points on a tilted plane through (2, 1, -6), spanning 4 x 2 in the plane's own axes.
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 0.1, 1.0));
    const glm::dvec3 u = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), n));
    const glm::dvec3 v = glm::cross(n, u);
    const glm::dvec3 origin(2, 1, -6);
    std::vector<glm::dvec3> points;
    for (int i = 0; i <= 8; ++i) {
        for (int j = 0; j <= 4; ++j) {
            const double s = -2.0 + 0.5 * i, t = -1.0 + 0.5 * j;
            points.push_back(origin + s * u + t * v);
        }
    }
    const QuadShell quad = FitQuad(points, glm::dvec3(0.0));
    EXPECT_NEAR(std::abs(glm::dot(quad.normal, n)), 1.0, 1e-12);
    EXPECT_GT(glm::dot(quad.normal, -origin), 0.0);         // faces the lens object at the origin
    EXPECT_NEAR(std::abs(glm::dot(quad.u, u)), 1.0, 1e-9);  // the long axis
    EXPECT_NEAR(glm::dot(glm::cross(quad.u, quad.v), quad.normal), 1.0, 1e-12);
    EXPECT_NEAR(quad.halfExtent.x, 2.0, 1e-9);
    EXPECT_NEAR(quad.halfExtent.y, 1.0, 1e-9);
    EXPECT_NEAR(glm::length(quad.centre - origin), 0.0, 1e-9);
    for (const glm::dvec3& p : points) {
        const glm::dvec3 q = p - quad.centre;
        EXPECT_NEAR(glm::dot(q, quad.normal), 0.0, 1e-9);
        EXPECT_LE(std::abs(glm::dot(q, quad.u)), quad.halfExtent.x + 1e-9);
        EXPECT_LE(std::abs(glm::dot(q, quad.v)), quad.halfExtent.y + 1e-9);
    }
}

TEST(Shell, QuadForcedHitForRaysRunningAway) {
    QuadShell quad;  // plane z = -5 facing +z, half extents 2 x 1
    quad.centre = {0, 0, -5};
    quad.halfExtent = {2.0, 1.0};
    // Toward the plane: the ordinary plane hit (even outside the rectangle).
    const std::optional<ShellHit> toward =
        Intersect(quad, {glm::vec3(0), glm::vec3(0.6f, 0, -0.8f)});
    ASSERT_TRUE(toward);
    EXPECT_FALSE(toward->forced);
    EXPECT_NEAR(toward->point.z, -5.0, 1e-6);
    EXPECT_NEAR(toward->point.x, 3.75, 1e-6);
    // Away from the plane: tangential direction, farScale * 2 from the centre.
    const std::optional<ShellHit> away = Intersect(quad, {glm::vec3(0), glm::vec3(0.6f, 0, 0.8f)});
    ASSERT_TRUE(away);
    EXPECT_TRUE(away->forced);
    EXPECT_NEAR(glm::length(away->point - quad.centre), 2000.0, 1e-9);
    EXPECT_NEAR(glm::normalize(away->point - quad.centre).x, 1.0, 1e-12);
    // Parallel: forced too.
    EXPECT_TRUE(Intersect(quad, {glm::vec3(0), glm::vec3(0, 1, 0)})->forced);
    // Lookup vector = hit point minus the EM origin, through the variant.
    const Shell shell = quad;
    const glm::vec3 lookup = *CubeLookup(shell, {glm::vec3(0), glm::vec3(0, 0, -1)}, {0, 0, 1});
    EXPECT_EQ(lookup, glm::vec3(0, 0, -6));
}

TEST(Shell, CubeLookupIsHitMinusOrigin) {
    const Shell sphere = SphereShell{{0, 0, 0}, 10.0};
    const Ray ray{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};  // starts inside: far side
    const glm::vec3 lookup = *CubeLookup(sphere, ray, {1, 0, 0});
    EXPECT_NEAR(lookup.x, 0.0f, 1e-6f);
    EXPECT_NEAR(lookup.y, static_cast<float>(std::sqrt(99.0)), 1e-5f);
    EXPECT_FALSE(CubeLookup(sphere, {glm::vec3(20, 0, 0), glm::vec3(0, 1, 0)}, {0, 0, 0}));
}

TEST(Shell, EmOriginIsAreaWeighted) {
    // A big triangle (area 8) with centroid (4/3, 4/3, 0) and a small one (area 0.5) far away.
    const std::vector<glm::vec3> positions{{0, 0, 0},  {4, 0, 0},  {0, 4, 0},
                                           {10, 0, 0}, {11, 0, 0}, {10, 1, 0}};
    const std::vector<uint32_t> indices{0, 1, 2, 3, 4, 5};
    const glm::vec3 origin = EmOrigin(positions, indices);
    const glm::dvec3 expected =
        (8.0 * glm::dvec3(4.0 / 3, 4.0 / 3, 0) + 0.5 * glm::dvec3(31.0 / 3, 1.0 / 3, 0)) / 8.5;
    EXPECT_NEAR(origin.x, expected.x, 1e-5);
    EXPECT_NEAR(origin.y, expected.y, 1e-5);
    // Degenerate triangles only: the plain mean of the centroids.
    const std::vector<uint32_t> flat{0, 1, 1};
    EXPECT_NEAR(EmOrigin(positions, flat).x, 8.0f / 3.0f, 1e-6f);
}

}  // namespace
}  // namespace pem::trace
