// SPDX-License-Identifier: MIT
// embree_scene.h — Embree 3 ray queries over a trace::Scene. embree_scene.cpp is the ONLY file
// in pemref that includes <embree3/rtcore.h>; this header hides every Embree type.
//
// Conventions:
//  - One Embree triangle geometry per Scene object, geomID == object index; primID == index
//    into Object::triangles. Scene flags ROBUST (+ CONTEXT_FILTER_FUNCTION for IntersectAll),
//    build quality HIGH (deterministic for any thread count, docs/deps.md §4).
//  - Single rays (rtcIntersect1 / rtcOccluded1) and packets of up to 8 (rtcIntersect8 /
//    rtcOccluded8 with a valid mask), which give bit-identical hits (docs/deps.md §4; checked in
//    intersect_test.cpp). Never COHERENT streams: those break ties differently (docs/deps.md §4).
//  - Hits are accepted for tnear <= t <= tfar; two-sided (no back-face culling). On exact ties
//    (a ray through a shared edge or coincident triangles) Embree's winner is unspecified
//    but deterministic for a fixed ISA, build quality and scene.
//  - Reproducibility: EmbreeOptions::isa "auto" pins isa=avx2 when the CPU has AVX2 (results
//    differ across ISAs by ~1e-7 relative and on ties), otherwise lets Embree choose.
//  - Errors: Embree's error callback records the message; the wrapper throws
//    std::runtime_error("Embree: <call>: <message>") right after the failing call (throwing
//    from inside the callback would unwind through Embree's C frames).
// Not here: shading, path logic (the tracer), streams.
#pragma once

#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "trace/hit.h"
#include "trace/scene.h"

namespace pem::trace {

struct EmbreeOptions {
    int threads = 0;  // 0: Embree's default (all hardware threads)
    std::string isa =
        "auto";  // "auto", "" (Embree chooses), or "sse2", "sse4.2", "avx", "avx2", "avx512"
    bool operator==(const EmbreeOptions&) const = default;
};

// The rtcNewDevice config string for the options, e.g. "threads=2,isa=avx2". An unknown isa
// name throws std::runtime_error (Embree itself would ignore it silently).
std::string EmbreeConfig(const EmbreeOptions& options);

class EmbreeDevice {
  public:
    explicit EmbreeDevice(const EmbreeOptions& options = {});
    const std::string& config() const;

    struct State;  // device handle + error slot (embree_scene.cpp)
    const std::shared_ptr<State>& state() const { return state_; }

  private:
    std::shared_ptr<State> state_;
};

// One ray of a packet query with its accepted t range.
struct RayQuery {
    raster::Ray ray;
    float tnear = 0.0f;
    float tfar = std::numeric_limits<float>::infinity();
};

class EmbreeScene {
  public:
    // Builds the BVH (keeps the device alive; the Scene may be destroyed afterwards).
    EmbreeScene(const EmbreeDevice& device, const Scene& scene);
    ~EmbreeScene();
    EmbreeScene(EmbreeScene&&) noexcept;
    EmbreeScene& operator=(EmbreeScene&&) noexcept;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Nearest hit with t in [tnear, tfar] (valid == false on a miss).
    Hit Intersect(const raster::Ray& ray, float tnear = 0.0f, float tfar = kInfinity) const;

    // Whether anything is hit with t in [tnear, tfar].
    bool Occluded(const raster::Ray& ray, float tnear = 0.0f, float tfar = kInfinity) const;

    // Packets (rtcIntersect8 / rtcOccluded8): up to kPacketSize rays traced together, inactive
    // lanes masked off. The results are bit for bit those of Intersect / Occluded ray by ray
    // (same t, object, prim, u, v, ng), so callers may mix both freely.
    static constexpr size_t kPacketSize = 8;
    // hits[i] = Intersect(queries[i].ray, queries[i].tnear, queries[i].tfar); sizes equal, <= 8.
    void IntersectPacket8(std::span<const RayQuery> queries, std::span<Hit> hits) const;
    // Bit i set iff Occluded(queries[i].ray, queries[i].tnear, queries[i].tfar); size <= 8.
    unsigned OccludedPacket8(std::span<const RayQuery> queries) const;

    // Every hit with t in [tnear, tfar], sorted by (t, object, prim), each (object, prim) once.
    // Done in ONE traversal with an intersection filter that records each candidate and rejects
    // it (so traversal goes on). Unlike re-casting from just past the previous hit, this keeps
    // both hits where a ray crosses a shared edge or coincident surfaces at equal t; callers
    // that want one hit per surface crossing merge equal-t entries themselves.
    std::vector<Hit> IntersectAll(const raster::Ray& ray, float tnear = 0.0f,
                                  float tfar = kInfinity) const;

    // BENCHMARK ONLY (bench/trace_bench.sh): Embree's own packet throughput on this scene, in
    // million rays per second: `rays` traced with rtcIntersect{4,8,16} packets (packetSize 4, 8
    // or 16; 1 = rtcIntersect1) in consecutive groups, split into `threads` contiguous chunks,
    // timed `repeats` times, the fastest kept. Results are discarded (the tracer's own packets
    // are IntersectPacket8 / OccludedPacket8).
    double PacketThroughputMrays(std::span<const raster::Ray> rays, int packetSize, int threads,
                                 int repeats = 3) const;

    static constexpr float kInfinity = std::numeric_limits<float>::infinity();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pem::trace
