// SPDX-License-Identifier: MIT
// intersect_test.cpp — EmbreeScene against the double-precision brute force (brute_force.h) on
// random triangle soups and on the bundled teapot scenes: same object/prim except on exact ties,
// t within 1e-4 relative; identical hits for threads=1 and 2; IntersectAll and Occluded agree;
// 8-ray packets (IntersectPacket8 / OccludedPacket8) bit-identical to single rays.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <cstring>
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

// Every field of two hits with the same bits (operator== would equate 0 and -0).
bool SameBits(const Hit& a, const Hit& b) {
    auto bits = [](float f) { return std::bit_cast<uint32_t>(f); };
    return a.valid == b.valid && a.object == b.object && a.prim == b.prim &&
           bits(a.t) == bits(b.t) && bits(a.u) == bits(b.u) && bits(a.v) == bits(b.v) &&
           bits(a.ng.x) == bits(b.ng.x) && bits(a.ng.y) == bits(b.ng.y) &&
           bits(a.ng.z) == bits(b.ng.z);
}

// Packets of every size 1..8 (cycling) over `queries` against Intersect/Occluded one by one.
// Returns the number of hits.
int ComparePackets(const EmbreeScene& es, const std::vector<RayQuery>& queries) {
    int hits = 0;
    size_t size = 1;
    for (size_t base = 0; base < queries.size(); base += size, size = size % 8 + 1) {
        const size_t n = std::min(size, queries.size() - base);
        const std::span<const RayQuery> packet(queries.data() + base, n);
        std::vector<Hit> got(n);
        es.IntersectPacket8(packet, got);
        const unsigned occluded = es.OccludedPacket8(packet);
        for (size_t i = 0; i < n; ++i) {
            const RayQuery& q = packet[i];
            const Hit want = es.Intersect(q.ray, q.tnear, q.tfar);
            EXPECT_TRUE(SameBits(got[i], want)) << "ray " << base + i;
            EXPECT_EQ(((occluded >> i) & 1u) != 0, es.Occluded(q.ray, q.tnear, q.tfar))
                << "ray " << base + i;
            hits += want.valid;
        }
    }
    return hits;
}

TEST(Embree, PacketsGiveTheSameBitsAsSingleRays) {
    const EmbreeDevice device = Device(2);
    // Random soups: random rays with assorted t ranges.
    for (unsigned seed = 1; seed <= 2; ++seed) {
        const Scene scene = RandomScene(seed, 4, 500);
        const EmbreeScene es(device, scene);
        Bounds all;
        for (const Object& o : scene.objects) all.Extend(o.bounds);
        std::vector<RayQuery> queries;
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        for (const raster::Ray& r : RandomRays(200 + seed, 3000, all)) {
            const float tnear = unit(rng) < 0.5f ? 0.0f : unit(rng);
            const float tfar = unit(rng) < 0.5f ? EmbreeScene::kInfinity : tnear + 4.0f * unit(rng);
            queries.push_back({r, tnear, tfar});
        }
        EXPECT_GT(ComparePackets(es, queries), 1000);
    }
    // The hybrid scene: camera rays (as RenderFrame makes them), then from their hits reflected
    // rays and shadow rays toward the lights (tnear / tfar as the tracer sets them), plus random
    // rays at the lens group.
    const Scene scene = LoadScene(kRoot + "/data/scenes/hybrid_glass_teapot.gltf");
    const EmbreeScene es(device, scene);
    const raster::Camera cam = CameraForSize(*scene.camera, 64, 48);
    const raster::PixelRays pixelRays(cam);
    std::vector<RayQuery> camera, secondary;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            for (int s = 0; s < 4; ++s) {
                const raster::Ray r =
                    pixelRays(static_cast<float>(x) + 0.25f + 0.5f * static_cast<float>(s % 2),
                              static_cast<float>(y) + 0.25f + 0.5f * static_cast<float>(s / 2));
                camera.push_back({r});
                const Hit h = es.Intersect(r);
                if (!h.valid) continue;
                const glm::vec3 p = r.origin + h.t * r.dir;
                const glm::vec3 n = glm::dot(h.ng, r.dir) > 0.0f ? -h.ng : h.ng;
                const glm::vec3 o = p + n * 1e-4f;
                secondary.push_back({{o, glm::normalize(glm::reflect(r.dir, n))}, 1e-5f});
                for (const Light& light : scene.lights) {
                    const glm::vec3 d = light.position - o;
                    const float dist = glm::length(d);
                    secondary.push_back({{o, d / dist}, 0.0f, dist * 0.9999f});
                }
            }
    for (const raster::Ray& r : RandomRays(13, 2000, scene.lensGroups[0].bounds))
        secondary.push_back({r});
    EXPECT_GT(ComparePackets(es, camera), static_cast<int>(camera.size()) / 2);
    EXPECT_GT(ComparePackets(es, secondary), 1000);
    // Empty packets and size checks.
    EXPECT_EQ(es.OccludedPacket8({}), 0u);
    std::vector<RayQuery> nine(9);
    std::vector<Hit> nineHits(9);
    EXPECT_THROW(es.IntersectPacket8(nine, nineHits), std::invalid_argument);
    EXPECT_THROW(es.OccludedPacket8(nine), std::invalid_argument);
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
