// SPDX-License-Identifier: MIT
// trace_bench.cpp — throughput of pemref's tracer against Embree's own packets on one scene
// (bench/trace_bench.sh runs it).
//   trace_bench SCENE.gltf [WxH=640x480] [K=3] [threads=2] [repeats=3] [all|frames|reference]
// Primary rays: the camera's K×K samples per pixel. Secondary rays: from every primary hit, one
// direction in the hemisphere of the facing geometric normal, picked by an integer hash (an
// incoherent, diffuse-like set). Each set is traced with EmbreeScene::Intersect (our single-ray
// path, as the tracer uses it) and with rtcIntersect1/8/16 (EmbreeScene::PacketThroughputMrays).
// Then the reference (full tree) and greedy frames are rendered `repeats` times (median time)
// with their rays per frame.
// Not here: correctness (trace_tests), image output (pemref trace).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include "base/parallel.h"
#include "trace/embree_scene.h"
#include "trace/render.h"
#include "trace/scene.h"
#include "trace/tracer.h"

namespace {

using namespace pem;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

uint32_t Hash(uint32_t x) {
    x ^= x >> 16, x *= 0x7feb352dU, x ^= x >> 15, x *= 0x846ca68bU, x ^= x >> 16;
    return x;
}

float Unit(uint32_t h) {
    return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

std::vector<raster::Ray> PrimaryRays(const raster::Camera& cam, int k) {
    std::vector<raster::Ray> rays;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            for (int s = 0; s < k * k; ++s) {
                const glm::vec2 p = trace::SamplePosition(x, y, k, s);
                rays.push_back(raster::PixelRay(cam, p.x, p.y));
            }
    return rays;
}

std::vector<raster::Ray> SecondaryRays(const trace::EmbreeScene& scene,
                                       const std::vector<raster::Ray>& primary) {
    std::vector<raster::Ray> rays;
    for (size_t i = 0; i < primary.size(); ++i) {
        const raster::Ray& r = primary[i];
        const trace::Hit h = scene.Intersect(r);
        if (!h.valid) continue;
        const glm::vec3 n = glm::dot(h.ng, r.dir) > 0.0f ? -h.ng : h.ng;
        const float z = Unit(Hash(static_cast<uint32_t>(2 * i))) * 2.0f - 1.0f;
        const float a = Unit(Hash(static_cast<uint32_t>(2 * i + 1))) * 6.2831853f;
        const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        glm::vec3 d(s * std::cos(a), z, s * std::sin(a));
        if (glm::dot(d, n) < 0.0f) d = -d;
        rays.push_back({r.origin + h.t * r.dir + n * 1e-4f, d});
    }
    return rays;
}

// Our single-ray path (EmbreeScene::Intersect) on `threads` threads, best of `repeats`.
double OursMrays(const trace::EmbreeScene& scene, const std::vector<raster::Ray>& rays, int threads,
                 int repeats) {
    const int chunks = 256;
    const size_t per = (rays.size() + chunks - 1) / chunks;
    double best = 0.0;
    std::vector<size_t> hits(chunks, 0);
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        base::ParallelFor(chunks, threads, [&](int c) {
            const size_t lo = std::min(rays.size(), static_cast<size_t>(c) * per);
            const size_t hi = std::min(rays.size(), lo + per);
            size_t found = 0;  // counted locally: neighbouring chunks' slots share a cache line
            for (size_t i = lo; i < hi; ++i) found += scene.Intersect(rays[i]).valid;
            hits[static_cast<size_t>(c)] = found;
        });
        best = std::max(best, static_cast<double>(rays.size()) / Since(t0) * 1e-6);
    }
    return best;
}

void Throughput(const char* name, const trace::EmbreeScene& scene,
                const std::vector<raster::Ray>& rays, int threads, int repeats) {
    std::printf(
        "%-9s %9zu rays  ours %6.2f Mrays/s | embree rtcIntersect1 %6.2f, 8-packets %6.2f, "
        "16-packets %6.2f Mrays/s\n",
        name, rays.size(), OursMrays(scene, rays, threads, repeats),
        scene.PacketThroughputMrays(rays, 1, threads, repeats),
        scene.PacketThroughputMrays(rays, 8, threads, repeats),
        scene.PacketThroughputMrays(rays, 16, threads, repeats));
}

void Frame(const char* name, const trace::Tracer& tracer, const raster::Camera& cam, int k,
           trace::Model model, int threads, int repeats) {
    std::vector<double> s, cpu;
    trace::RayCounts counts;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        const std::clock_t c0 = std::clock();
        counts = trace::RenderFrame(tracer, cam, k, model, threads).counts;
        s.push_back(Since(t0));
        cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    std::sort(s.begin(), s.end());
    std::sort(cpu.begin(), cpu.end());
    std::printf(
        "%-9s frame %dx%d k=%d, %d threads: median %.3f s (min %.3f, max %.3f; cpu %.3f s), "
        "%.3f M rays (primary %.3f, secondary %.3f, shadow %.3f)\n",
        name, cam.width, cam.height, k, threads, s[s.size() / 2], s.front(), s.back(),
        cpu[cpu.size() / 2], static_cast<double>(counts.Total()) * 1e-6,
        static_cast<double>(counts.primary) * 1e-6, static_cast<double>(counts.secondary) * 1e-6,
        static_cast<double>(counts.shadow) * 1e-6);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: trace_bench SCENE.gltf [WxH] [K] [threads] [repeats]\n");
        return 2;
    }
    int w = 640, h = 480;
    if (argc > 2) std::sscanf(argv[2], "%dx%d", &w, &h);
    const int k = argc > 3 ? std::atoi(argv[3]) : 3;
    const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
    const int repeats = argc > 5 ? std::atoi(argv[5]) : 3;
    const std::string mode = argc > 6 ? argv[6] : "all";
    try {
        const trace::Scene scene = trace::LoadScene(argv[1]);
        const trace::EmbreeDevice device({threads, "auto"});
        const trace::EmbreeScene embree(device, scene);
        const raster::Camera cam = trace::CameraForSize(*scene.camera, w, h);
        std::printf("scene %s: %zu triangles; embree %s\n", argv[1], scene.NumTriangles(),
                    device.config().c_str());
        if (mode == "all") {
            const std::vector<raster::Ray> primary = PrimaryRays(cam, k);
            Throughput("primary", embree, primary, threads, repeats);
            Throughput("secondary", embree, SecondaryRays(embree, primary), threads, repeats);
        }
        const trace::Tracer tracer(scene, embree);
        Frame("reference", tracer, cam, k, trace::Model::FullTree, threads, repeats);
        if (mode != "reference")
            Frame("greedy", tracer, cam, k, trace::Model::Greedy, threads, repeats);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trace_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
