// SPDX-License-Identifier: MIT
// intersect_test.cpp — EmbreeScene against the double-precision brute force (brute_force.h) on
// random triangle soups and on the bundled teapot scenes: same object/prim except on exact ties,
// t within 1e-4 relative; identical hits for threads=1 and 2; IntersectAll and Occluded agree.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <stdexcept>

#include "trace/brute_force.h"
#include "trace/embree_scene.h"

namespace pem::trace {
namespace {

const std::string kRoot = PEM_SOURCE_DIR;

// `objects` random triangles soups inside [-1, 1]^3, fixed seed.
Scene RandomScene(unsigned seed, int objects, int trianglesEach) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), small(-0.2f, 0.2f);
    Scene s;
    s.materials.resize(1);
    for (int o = 0; o < objects; ++o) {
        Object obj;
        obj.name = "soup" + std::to_string(o);
        obj.material = 0;
        for (int t = 0; t < trianglesEach; ++t) {
            const glm::vec3 c(pos(rng), pos(rng), pos(rng));
            for (int k = 0; k < 3; ++k) {
                obj.positions.push_back(c + glm::vec3(small(rng), small(rng), small(rng)));
                obj.normals.push_back({0.0f, 0.0f, 1.0f});
            }
            const unsigned b = static_cast<unsigned>(3 * t);
            obj.triangles.push_back({b, b + 1, b + 2});
        }
        for (const glm::vec3& p : obj.positions) obj.bounds.Extend(p);
        s.objects.push_back(std::move(obj));
    }
    return s;
}

std::vector<raster::Ray> RandomRays(unsigned seed, int n, const Bounds& target) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), sphere(-1.0f, 1.0f);
    std::vector<raster::Ray> rays;
    const glm::vec3 c = target.Center();
    const float radius = 1.5f * glm::length(target.hi - target.lo);
    while (static_cast<int>(rays.size()) < n) {
        const glm::vec3 d(sphere(rng), sphere(rng), sphere(rng));
        if (glm::length(d) > 1.0f || glm::length(d) < 0.1f) continue;
        const glm::vec3 origin = c + radius * glm::normalize(d);
        const glm::vec3 aim =
            target.lo + (target.hi - target.lo) * glm::vec3(unit(rng), unit(rng), unit(rng));
        rays.push_back({origin, glm::normalize(aim - origin)});
    }
    return rays;
}

struct Agreement {
    int rays = 0, hits = 0, ties = 0;
    double maxRelT = 0.0;
};

// Compares one ray; a different (object, prim) is accepted only when brute force also hits
// Embree's triangle at (nearly) the same t (an exact tie).
void Compare(const Scene& scene, const EmbreeScene& es, const raster::Ray& ray, Agreement* a) {
    const Hit e = es.Intersect(ray),
              b = BruteForceIntersect(scene, ray, 0.0f, EmbreeScene::kInfinity);
    ++a->rays;
    ASSERT_EQ(e.valid, b.valid);
    EXPECT_EQ(es.Occluded(ray), b.valid);
    if (!b.valid) return;
    ++a->hits;
    const double rel =
        std::abs(static_cast<double>(e.t) - static_cast<double>(b.t)) / static_cast<double>(b.t);
    a->maxRelT = std::max(a->maxRelT, rel);
    EXPECT_LE(rel, 1e-4);
    if (e.object == b.object && e.prim == b.prim) {
        EXPECT_NEAR(e.u, b.u, 1e-3f);
        EXPECT_NEAR(e.v, b.v, 1e-3f);
        EXPECT_GT(glm::dot(e.ng, b.ng), 0.9999f);
        return;
    }
    bool tie = false;
    for (const Hit& h : BruteForceIntersectAll(scene, ray, 0.0f, EmbreeScene::kInfinity))
        tie |= h.object == e.object && h.prim == e.prim && std::abs(h.t - b.t) <= 1e-5f * b.t;
    EXPECT_TRUE(tie) << "embree " << e.object << "/" << e.prim << " vs brute " << b.object << "/"
                     << b.prim;
    ++a->ties;
}

EmbreeDevice Device(int threads) {
    return EmbreeDevice(EmbreeOptions{threads, "auto"});
}

TEST(Embree, AgreesWithBruteForceOnRandomSoups) {
    const EmbreeDevice device = Device(2);
    for (unsigned seed = 1; seed <= 3; ++seed) {
        const Scene scene = RandomScene(seed, 4, 500);
        const EmbreeScene es(device, scene);
        Bounds all;
        for (const Object& o : scene.objects) all.Extend(o.bounds);
        Agreement a;
        for (const raster::Ray& r : RandomRays(100 + seed, 2000, all)) Compare(scene, es, r, &a);
        EXPECT_GT(a.hits, 1000);
        EXPECT_LE(a.ties, 2);
        RecordProperty("max_rel_t_seed" + std::to_string(seed), std::to_string(a.maxRelT));
        std::printf("soup %u: %d rays, %d hits, %d ties, max rel t diff %.3g\n", seed, a.rays,
                    a.hits, a.ties, a.maxRelT);
    }
}

TEST(Embree, AgreesWithBruteForceOnTheBundledScenes) {
    for (const char* file :
         {"/data/scenes/hybrid_glass_teapot.gltf", "/data/scenes/pem_mirror_teapot.gltf"}) {
        const Scene scene = LoadScene(kRoot + file);
        const EmbreeDevice device = Device(2);
        const EmbreeScene es(device, scene);
        Agreement a;
        // Camera rays over a 32x24 grid, plus random rays aimed at the lens group.
        const raster::Camera cam = CameraForSize(*scene.camera, 32, 24);
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x)
                Compare(scene, es, raster::PixelRay(cam, x + 0.5f, y + 0.5f), &a);
        for (const raster::Ray& r : RandomRays(5, 400, scene.lensGroups[0].bounds))
            Compare(scene, es, r, &a);
        EXPECT_GT(a.hits, a.rays / 2) << file;
        RecordProperty(std::string("max_rel_t") + (file[14] == 'h' ? "_hybrid" : "_pem"),
                       std::to_string(a.maxRelT));
        std::printf("%s: %d rays, %d hits, %d ties, max rel t diff %.3g\n", file, a.rays, a.hits,
                    a.ties, a.maxRelT);
    }
}

TEST(Embree, OneAndTwoThreadsGiveIdenticalHits) {
    const Scene scene = LoadScene(kRoot + "/data/scenes/hybrid_glass_teapot.gltf");
    const EmbreeDevice d1 = Device(1), d2 = Device(2);
    const EmbreeScene s1(d1, scene), s2(d2, scene);
    const std::vector<raster::Ray> rays = RandomRays(9, 5000, scene.lensGroups[0].bounds);
    for (const raster::Ray& r : rays) {
        ASSERT_EQ(s1.Intersect(r), s2.Intersect(r));
        ASSERT_EQ(s1.IntersectAll(r), s2.IntersectAll(r));
    }
}

TEST(Embree, IntersectAllMatchesBruteForceAndCrossesClosedShellsEvenly) {
    const Scene scene = LoadScene(kRoot + "/data/scenes/pem_mirror_teapot.gltf");
    Scene teapotOnly;
    teapotOnly.materials = scene.materials;
    teapotOnly.objects.push_back(
        scene.objects[static_cast<size_t>(scene.lensGroups[0].objects[0])]);
    const EmbreeDevice device = Device(2);
    const EmbreeScene es(device, teapotOnly);
    int crossings = 0;
    for (const raster::Ray& r : RandomRays(11, 300, teapotOnly.objects[0].bounds)) {
        const std::vector<Hit> e = es.IntersectAll(r),
                               b = BruteForceIntersectAll(teapotOnly, r, 0.0f,
                                                          EmbreeScene::kInfinity);
        ASSERT_EQ(e.size(), b.size());
        for (size_t i = 0; i < e.size(); ++i) {
            EXPECT_NEAR(e[i].t, b[i].t, 1e-4f * b[i].t);
            if (i > 0) {
                EXPECT_LE(e[i - 1].t, e[i].t);
            }
        }
        // Three closed shells: a ray from outside enters and leaves each (edge hits aside).
        if (e.size() % 2 == 0) ++crossings;
        // Intersect() is the first entry of IntersectAll().
        if (!e.empty()) {
            EXPECT_EQ(es.Intersect(r).t, e[0].t);
        }
    }
    EXPECT_GE(crossings, 295);
}

TEST(Embree, MissesAndRangesBehave) {
    const Scene scene = LoadScene(kRoot + "/tests/data/trace_scenes/triangle.gltf");
    const EmbreeDevice device = Device(1);
    const EmbreeScene es(device, scene);
    const raster::Ray up{{0.25f, 0.25f, -1.0f}, {0.0f, 0.0f, 1.0f}};
    const Hit h = es.Intersect(up);
    ASSERT_TRUE(h.valid);
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_NEAR(h.u, 0.25f, 1e-6f);
    EXPECT_NEAR(h.v, 0.25f, 1e-6f);
    EXPECT_EQ(h.ng, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(es.Intersect(up, 0.0f, 0.5f), Hit{});  // beyond tfar
    EXPECT_EQ(es.Intersect(up, 1.5f), Hit{});        // before tnear
    EXPECT_FALSE(es.Occluded(up, 0.0f, 0.5f));
    EXPECT_EQ(es.Intersect({{2.0f, 2.0f, -1.0f}, {0.0f, 0.0f, 1.0f}}), Hit{});
    EXPECT_EQ(BruteForceIntersect(scene, up, 0.0f, 0.5f), Hit{});
    const Hit b = BruteForceIntersect(scene, up, 0.0f, EmbreeScene::kInfinity);
    EXPECT_FLOAT_EQ(b.t, h.t);
    EXPECT_EQ(b.ng, h.ng);
}

TEST(Embree, ConfigPinsIsaAndReportsErrors) {
    EXPECT_EQ(EmbreeConfig({2, ""}), "threads=2");
    EXPECT_EQ(EmbreeConfig({0, "sse4.2"}), "isa=sse4.2");
#if defined(__x86_64__)
    if (__builtin_cpu_supports("avx2")) {
        EXPECT_EQ(EmbreeConfig({1, "auto"}), "threads=1,isa=avx2");
    }
#endif
    EXPECT_THROW(EmbreeDevice(EmbreeOptions{1, "no_such_isa"}), std::runtime_error);
    EXPECT_EQ(EmbreeDevice(EmbreeOptions{1, ""}).config(), "threads=1");
}

}  // namespace
}  // namespace pem::trace
