// SPDX-License-Identifier: MIT
// layers_test.cpp — the parallax that chooses a layer's shell, against values worked out by hand,
// and the PEM local shell it chooses.
#include "trace/layers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pem::trace {
namespace {

TEST(ShellParallax, RaysFromTheEmOriginSeeNone) {
    const glm::dvec3 c(0.0, 1.0, 0.0);
    std::vector<RayHit> hits;
    for (int k = 0; k < 20; ++k)
        hits.push_back({c, c + glm::dvec3(std::cos(k), -0.5 - 0.1 * k, std::sin(k)) * 3.0});
    for (const Shell& s : {Shell{SphereShell{c, 1.0}}, Shell{BoxShell{{-5, -5, -5}, {5, 5, 5}}},
                           Shell{EllipsoidShell{c, {1.0, 2.0, 3.0}}}})
        EXPECT_NEAR(ShellParallax(s, hits, c), 0.0, 1e-4);
}

TEST(ShellParallax, SphereAgainstAFloorByHand) {
    // From (1, 1, 0) straight down to the floor at (1, 0, 0); EM origin (0, 1, 0). A sphere of
    // radius 2 is met at (1, 1 - sqrt 3, 0): seen from the origin, 15° from the floor point.
    const glm::dvec3 c(0.0, 1.0, 0.0);
    const std::vector<RayHit> hits{{{1.0, 1.0, 0.0}, {1.0, 0.0, 0.0}}};
    EXPECT_NEAR(ShellParallax(SphereShell{c, 2.0}, hits, c), 15.0, 1e-4);
    // A box whose bottom is the floor passes through the point: no parallax.
    EXPECT_NEAR(ShellParallax(BoxShell{{-3, 0, -3}, {3, 3, 3}}, hits, c), 0.0, 1e-4);
    // A ray that misses the shell counts 90°.
    EXPECT_EQ(ShellParallax(BoxShell{{5, 5, 5}, {6, 6, 6}}, hits, c), 90.0);
}

TEST(ShellParallax, CylinderCapIsTheFloor) {
    const glm::dvec3 c(0.0, 0.5, 0.0);
    std::vector<RayHit> hits;
    for (int k = 0; k < 16; ++k) {
        const double a = k * 0.4;
        const glm::dvec3 o(0.3 * std::cos(a), 0.6, 0.3 * std::sin(a));
        hits.push_back({o, {2.0 * std::cos(a + 0.3), 0.0, 2.0 * std::sin(a + 0.3)}});
    }
    EXPECT_NEAR(ShellParallax(CylinderShell{{0.0, 0.0}, 4.0, 0.0, 3.0}, hits, c), 0.0, 1e-4);
    EXPECT_GT(ShellParallax(SphereShell{c, 1.0}, hits, c), 5.0);
}

// Self hits on a sphere of radius 0.7 about the EM origin, from origins inside it (a reflector
// seeing a surface that wraps around it): the chosen shell passes through every hit point,
// although the vertex ellipsoid (the vertices span a box twice as large) does not.
TEST(ChooseLocalShell, PassesThroughSelfHitsOnASphere) {
    const glm::dvec3 c(0.0, 0.5, 0.0);
    std::vector<glm::dvec3> vertices;
    for (int k = 0; k < 8; ++k)
        vertices.push_back(c + glm::dvec3(k & 1 ? 1.4 : -1.4, k & 2 ? 0.7 : -0.7, k & 4 ? 1 : -1));
    std::vector<RayHit> hits;
    for (int k = 0; k < 40; ++k) {
        const double a = 0.37 * k, b = 0.11 * k - 2.0;
        const glm::dvec3 o = c + 0.3 * glm::dvec3(std::cos(a), 0.5, std::sin(a));
        const glm::dvec3 u(std::cos(b) * std::cos(a + 2.0), std::sin(b),
                           std::cos(b) * std::sin(a + 2.0));
        hits.push_back({o, c + 0.7 * u});
    }
    const LocalShellChoice local = ChooseLocalShell(vertices, hits, c);
    EXPECT_LT(local.parallaxDeg, 1e-3);
    EXPECT_GT(ShellParallax(FitEllipsoid(vertices, c), hits, c), 1.0);  // not vacuous
    for (const RayHit& h : hits) {
        const std::optional<ShellHit> s = Intersect(
            local.shell, Ray{glm::vec3(h.origin), glm::vec3(glm::normalize(h.point - h.origin))});
        ASSERT_TRUE(s.has_value());
        EXPECT_NEAR(glm::length(s->point - h.point), 0.0, 1e-5);
    }
}

// Without self hits (a convex reflector), the PEM paper's ellipsoid over the vertices.
TEST(ChooseLocalShell, WithoutSelfHitsTheVertexEllipsoid) {
    const glm::dvec3 c(0.0, 0.5, 0.0);
    const std::vector<glm::dvec3> vertices{{1, 0.5, 0}, {-1, 0.5, 0}, {0, 1, 0},
                                           {0, 0, 0},   {0, 0.5, 2},  {0, 0.5, -2}};
    const LocalShellChoice local = ChooseLocalShell(vertices, {}, c);
    EXPECT_TRUE(local.shell == Shell{FitEllipsoid(vertices, c)});
    EXPECT_TRUE(std::isnan(local.parallaxDeg));
}

}  // namespace
}  // namespace pem::trace
