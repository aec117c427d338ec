// SPDX-License-Identifier: MIT
// layers_test.cpp — the parallax that chooses a layer's shell, against values worked out by hand.
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

}  // namespace
}  // namespace pem::trace
