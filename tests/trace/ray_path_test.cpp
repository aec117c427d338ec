// SPDX-License-Identifier: MIT
// ray_path_test.cpp — the greedy two-term model against the full ray tree on analytic spheres and
// slabs (mirror: identical; glass with IOR near 1: close), slab transmittance and Snell exit,
// energy of the full tree, cut-offs, total internal reflection and the path-difference criterion.
#include "trace/ray_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/trace/analytic_surfaces.h"

namespace pem::trace {
namespace {

using testing::AnalyticSlab;
using testing::AnalyticSphere;

// A smooth environment: radiance per channel from the direction.
glm::dvec3 Environment(const glm::vec3& dir) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(dir));
    return {0.5 + 0.5 * d.y, 0.5 + 0.5 * d.x, 1.0 + 0.25 * d.z};
}

glm::dvec3 GreedyRadiance(const GreedyPaths& paths) {
    glm::dvec3 sum(0.0);
    for (const RayPath* p : {&paths.reflection, &paths.refraction}) {
        if (p->escaped) sum += p->Weight() * Environment(p->exitDir);
    }
    return sum;
}

glm::dvec3 TreeRadiance(const std::vector<ExitRay>& leaves) {
    glm::dvec3 sum(0.0);
    for (const ExitRay& leaf : leaves) {
        if (leaf.escaped) sum += leaf.weight * Environment(leaf.ray.dir);
    }
    return sum;
}

double MaxAbs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// Primary rays toward a unit sphere at the origin, from z = 4, at several impact offsets.
std::vector<Ray> SphereRays() {
    std::vector<Ray> rays;
    for (double b : {0.0, 0.2, 0.45, 0.7, 0.9}) {
        rays.push_back({glm::vec3(static_cast<float>(b), 0.1f, 4.0f), glm::vec3(0, 0, -1)});
    }
    return rays;
}

TEST(RayPath, MirrorSphereGreedyEqualsFullTree) {
    AnalyticSphere sphere;
    sphere.material.kind = SurfaceKind::Mirror;
    sphere.material.mirrorF0 = {0.9, 0.7, 0.5};
    for (const Ray& ray : SphereRays()) {
        const std::optional<GreedyPaths> paths = TraceGreedyPaths(ray, sphere, 8, 0.0);
        ASSERT_TRUE(paths.has_value());
        const std::vector<ExitRay> tree = TraceFullTree(ray, sphere, 8, 0.0);
        ASSERT_EQ(tree.size(), 1u);
        EXPECT_TRUE(tree[0].escaped);
        EXPECT_EQ(paths->reflection.exitDir, tree[0].ray.dir);
        EXPECT_EQ(paths->reflection.Weight(), tree[0].weight);
        EXPECT_EQ(paths->refraction.F, glm::dvec3(0.0));  // a mirror has no refraction term
        EXPECT_FALSE(paths->refraction.escaped);
        EXPECT_EQ(GreedyRadiance(*paths), TreeRadiance(tree));
    }
}

TEST(RayPath, MirrorReflectionMatchesAnalyticDirection) {
    AnalyticSphere sphere;
    sphere.material.kind = SurfaceKind::Mirror;
    const Ray ray{glm::vec3(0.6f, 0.0f, 4.0f), glm::vec3(0, 0, -1)};
    const RayPath path = TraceGreedyPaths(ray, sphere, 8, 0.0)->reflection;
    ASSERT_EQ(path.vertices.size(), 1u);
    const glm::dvec3 n(0.6, 0.0, 0.8);  // the hit point on the unit sphere
    const glm::dvec3 expected = glm::dvec3(0, 0, -1) - 2.0 * glm::dot(glm::dvec3(0, 0, -1), n) * n;
    EXPECT_LT(AngleBetweenDeg(glm::dvec3(path.exitDir), expected), 1e-4);
    EXPECT_EQ(path.F, glm::dvec3(1.0));  // F0 = 1 stays 1 at any angle
    EXPECT_TRUE(path.escaped);
}

TEST(RayPath, GlassSphereNearIorOneGreedyApproximatesTree) {
    AnalyticSphere sphere;
    sphere.material.ior = 1.02;
    for (const Ray& ray : SphereRays()) {
        const GreedyPaths paths = *TraceGreedyPaths(ray, sphere, 16, 0.0);
        const std::vector<ExitRay> tree = TraceFullTree(ray, sphere, 16, 0.0);
        // Greedy: reflect and leave; refract in, refract out (T dominates at the exit).
        EXPECT_EQ(paths.reflection.vertices.size(), 1u);
        ASSERT_EQ(paths.refraction.vertices.size(), 2u);
        EXPECT_EQ(paths.refraction.vertices[1].event, Event::Refract);
        EXPECT_FALSE(paths.refraction.vertices[1].entering);
        // The two paths are tree leaves, so the error is at most the weight of the other leaves
        // (1 - the greedy weights, no absorption) times the brightest radiance (1.25).
        const double missing = 1.0 - paths.reflection.Weight().x - paths.refraction.Weight().x;
        EXPECT_LT(missing, 5e-3) << ray.origin.x;
        const glm::dvec3 greedy = GreedyRadiance(paths);
        const glm::dvec3 full = TreeRadiance(tree);
        EXPECT_LE(MaxAbs(greedy - full), 1.25 * missing + 1e-12) << ray.origin.x;
        EXPECT_LT(MaxAbs(greedy - full), 5e-3 * MaxAbs(full)) << ray.origin.x;
        EXPECT_GT(tree.size(), 2u);  // the tree has more leaves than the two paths
    }
}

TEST(RayPath, GreedyPathsAreLeavesOfTheTree) {
    AnalyticSphere sphere;
    sphere.material.ior = 1.5;
    const Ray ray{glm::vec3(0.3f, 0.2f, 4.0f), glm::vec3(0, 0, -1)};
    const GreedyPaths paths = *TraceGreedyPaths(ray, sphere, 16, 0.0);
    const std::vector<ExitRay> tree = TraceFullTree(ray, sphere, 16, 0.0);
    for (const RayPath* p : {&paths.reflection, &paths.refraction}) {
        bool found = false;
        for (const ExitRay& leaf : tree) {
            found |= leaf.ray.dir == p->exitDir && leaf.ray.origin == p->exitOrigin &&
                     leaf.weight == p->Weight() &&
                     leaf.depth == static_cast<int>(p->vertices.size());
        }
        EXPECT_TRUE(found) << *p;
    }
}

TEST(RayPath, FullTreeConservesEnergyWithoutAbsorption) {
    AnalyticSphere sphere;
    sphere.material.ior = 1.5;
    for (const Ray& ray : SphereRays()) {
        for (int maxDepth : {1, 3, 12}) {
            glm::dvec3 sum(0.0);
            for (const ExitRay& leaf : TraceFullTree(ray, sphere, maxDepth, 1e-3)) {
                sum += leaf.weight;
                EXPECT_LE(leaf.depth, maxDepth);
            }
            EXPECT_NEAR(sum.x, 1.0, 1e-12);
            EXPECT_NEAR(sum.z, 1.0, 1e-12);
        }
    }
}

TEST(RayPath, SlabExitIsParallelAndTransmittanceMatches) {
    AnalyticSlab slab;
    slab.halfThickness = 0.5;
    slab.material.ior = 1.5;
    slab.material.absorption = {0.1, 0.5, 2.0};
    const double angle = 40.0 * std::numbers::pi / 180.0;
    const glm::vec3 dir(static_cast<float>(std::sin(angle)), -static_cast<float>(std::cos(angle)),
                        0.0f);
    const Ray ray{glm::vec3(0.0f, 3.0f, 0.0f), dir};
    const GreedyPaths paths = *TraceGreedyPaths(ray, slab, 16, 0.0);
    const RayPath& t = paths.refraction;
    ASSERT_EQ(t.vertices.size(), 2u);
    ASSERT_TRUE(t.escaped);
    EXPECT_LT(AngleBetweenDeg(glm::dvec3(t.exitDir), glm::dvec3(dir)), 1e-4);
    // Inside length = thickness / cos(theta_t), G = exp(-sigma length) per channel.
    const double cosT = *CosTransmitted(std::cos(angle), 1.0, 1.5);
    const double length = 1.0 / cosT;
    EXPECT_NEAR(t.G.x, std::exp(-0.1 * length), 1e-6);
    EXPECT_NEAR(t.G.y, std::exp(-0.5 * length), 1e-6);
    EXPECT_NEAR(t.G.z, std::exp(-2.0 * length), 1e-6);
    // F = T_in T_out with the same transmittance both ways.
    const double tIn = 1.0 - FresnelDielectric(std::cos(angle), 1.0, 1.5);
    const double tOut = 1.0 - FresnelDielectric(cosT, 1.5, 1.0);
    EXPECT_NEAR(t.F.x, tIn * tOut, 1e-6);
    EXPECT_NEAR(tIn, tOut, 1e-6);
    EXPECT_EQ(paths.reflection.G, glm::dvec3(1.0));  // never inside
}

TEST(RayPath, SlabNearIorOneGreedyApproximatesTree) {
    AnalyticSlab slab;
    slab.material.ior = 1.02;
    slab.material.absorption = {0.2, 0.1, 0.0};
    for (double deg : {0.0, 20.0, 45.0, 60.0}) {
        const double a = deg * std::numbers::pi / 180.0;
        const Ray ray{
            glm::vec3(0.0f, 2.0f, 0.0f),
            glm::vec3(static_cast<float>(std::sin(a)), -static_cast<float>(std::cos(a)), 0.0f)};
        const glm::dvec3 greedy = GreedyRadiance(*TraceGreedyPaths(ray, slab, 32, 0.0));
        const glm::dvec3 full = TreeRadiance(TraceFullTree(ray, slab, 32, 0.0));
        EXPECT_LT(MaxAbs(greedy - full), 2e-3 * MaxAbs(full)) << deg;
    }
}

TEST(RayPath, PrimaryMissAndCutOffs) {
    AnalyticSphere sphere;
    const Ray miss{glm::vec3(3.0f, 0.0f, 4.0f), glm::vec3(0, 0, -1)};
    EXPECT_FALSE(TraceGreedyPaths(miss, sphere, 8, 0.0).has_value());
    const std::vector<ExitRay> tree = TraceFullTree(miss, sphere, 8, 0.0);
    ASSERT_EQ(tree.size(), 1u);
    EXPECT_TRUE(tree[0].escaped);
    EXPECT_EQ(tree[0].depth, 0);

    // Depth 1: the refraction path stops inside the sphere.
    const Ray hit{glm::vec3(0.2f, 0.0f, 4.0f), glm::vec3(0, 0, -1)};
    const GreedyPaths cut = *TraceGreedyPaths(hit, sphere, 1, 0.0);
    EXPECT_TRUE(cut.reflection.escaped);
    EXPECT_EQ(cut.refraction.vertices.size(), 1u);
    EXPECT_FALSE(cut.refraction.escaped);
    // Weight: the reflection path (R ~ 0.04) stops below 0.1 before asking for the next hit.
    const GreedyPaths light = *TraceGreedyPaths(hit, sphere, 8, 0.1);
    EXPECT_FALSE(light.reflection.escaped);
    EXPECT_TRUE(light.refraction.escaped);
}

TEST(RayPath, TotalInternalReflectionChoosesReflection) {
    SurfaceHit hit;  // leaving glass through a surface with normal +y, 60 degrees off the normal
    hit.material.ior = 1.5;
    hit.entering = false;
    const double a = 60.0 * std::numbers::pi / 180.0;
    const glm::dvec3 dir(std::sin(a), std::cos(a), 0.0);
    const Interaction in = Scatter(dir, hit);
    EXPECT_FALSE(in.refractDir.has_value());
    EXPECT_EQ(in.reflectance, glm::dvec3(1.0));
    EXPECT_EQ(in.transmittance, glm::dvec3(0.0));
    EXPECT_EQ(GreedyChoice(in), Event::Reflect);
    // At 20 degrees refraction wins.
    const double b = 20.0 * std::numbers::pi / 180.0;
    const Interaction in2 = Scatter({std::sin(b), std::cos(b), 0.0}, hit);
    EXPECT_EQ(GreedyChoice(in2), Event::Refract);
    EXPECT_NEAR(in2.reflectance.x + in2.transmittance.x, 1.0, 1e-15);
}

RayPath MakePath(std::vector<Event> events, glm::vec3 exitDir) {
    RayPath p;
    for (Event e : events) p.vertices.push_back({{}, {}, e, true, 0, 0});
    p.exitDir = exitDir;
    p.escaped = true;
    return p;
}

TEST(RayPath, PathsDifferCriterion) {
    const auto dirAt = [](double deg) {
        const double a = deg * std::numbers::pi / 180.0;
        return glm::vec3(static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a)));
    };
    const RayPath base = MakePath({Event::Refract, Event::Refract}, dirAt(0.0));
    EXPECT_FALSE(PathsDiffer(base, base));
    EXPECT_FALSE(PathsDiffer(base, MakePath({Event::Refract, Event::Refract}, dirAt(2.9))));
    EXPECT_TRUE(PathsDiffer(base, MakePath({Event::Refract, Event::Refract}, dirAt(3.1))));
    EXPECT_TRUE(PathsDiffer(base, MakePath({Event::Refract, Event::Reflect}, dirAt(0.0))));
    EXPECT_TRUE(PathsDiffer(base, MakePath({Event::Refract}, dirAt(0.0))));
    EXPECT_FALSE(PathsDiffer(base, MakePath({Event::Refract, Event::Refract}, dirAt(4.0)), 5.0));
    RayPath cut = base;
    cut.escaped = false;
    EXPECT_TRUE(PathsDiffer(base, cut));
}

}  // namespace
}  // namespace pem::trace
