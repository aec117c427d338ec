// SPDX-License-Identifier: MIT
// embree_scene.cpp — the ONLY includer of <embree3/rtcore.h> (conventions in embree_scene.h).
// Order of Embree calls follows Embree's tutorials/minimal: device → per-object geometry
// (buffers → commit → attach → release our reference) → scene flags/quality → commit scene.
// Not here: anything about materials or shading.
#include "trace/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iterator>
#include <mutex>
#include <stdexcept>

#include "base/worker_pool.h"

namespace pem::trace {

// Device handle plus the error slot the callback writes (shared by every EmbreeScene built on
// it, so the device outlives them).
struct EmbreeDevice::State {
    RTCDevice device = nullptr;
    std::string config;
    std::mutex mutex;
    std::atomic<bool> failed{false};
    std::string message;

    ~State() {
        if (device) rtcReleaseDevice(device);
    }

    // Throws if the callback recorded an error since the last check.
    void Check(const char* call) {
        if (!failed.load(std::memory_order_relaxed)) return;
        std::lock_guard<std::mutex> lock(mutex);
        const std::string text = message;
        message.clear();
        failed = false;
        throw std::runtime_error(std::string("Embree: ") + call + ": " + text);
    }
};

namespace {

// Records the first message; the wrapper throws after the call returns (see header).
void OnEmbreeError(void* user, RTCError code, const char* text) {
    auto* state = static_cast<EmbreeDevice::State*>(user);
    std::lock_guard<std::mutex> lock(state->mutex);
    if (state->failed) return;
    state->message = (text ? std::string(text) : std::string("no message")) + " (code " +
                     std::to_string(static_cast<int>(code)) + ")";
    state->failed = true;
}

bool CpuHasAvx2() {
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

}  // namespace

std::string EmbreeConfig(const EmbreeOptions& options) {
    std::string config;
    auto add = [&](const std::string& item) { config += (config.empty() ? "" : ",") + item; };
    if (options.threads > 0) add("threads=" + std::to_string(options.threads));
    if (options.isa == "auto") {
        if (CpuHasAvx2()) add("isa=avx2");
    } else if (!options.isa.empty()) {
        // Embree silently ignores unknown names, so they are checked here.
        static const char* const kKnown[] = {"sse2", "sse4.2", "avx", "avx2", "avx512"};
        if (std::find(std::begin(kKnown), std::end(kKnown), options.isa) == std::end(kKnown))
            throw std::runtime_error("Embree: unknown isa \"" + options.isa +
                                     "\" (expected auto, sse2, sse4.2, avx, avx2 or avx512)");
        add("isa=" + options.isa);
    }
    return config;
}

EmbreeDevice::EmbreeDevice(const EmbreeOptions& options) : state_(std::make_shared<State>()) {
    state_->config = EmbreeConfig(options);
    state_->device = rtcNewDevice(state_->config.c_str());
    if (!state_->device)
        throw std::runtime_error("Embree: rtcNewDevice(\"" + state_->config + "\") failed (code " +
                                 std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) +
                                 ")");
    rtcSetDeviceErrorFunction(state_->device, OnEmbreeError, state_.get());
}

const std::string& EmbreeDevice::config() const {
    return state_->config;
}

// EmbreeScene ----------------------------------------------------------------------------------

struct EmbreeScene::Impl {
    std::shared_ptr<EmbreeDevice::State> device;
    RTCScene scene = nullptr;
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
    }
};

namespace {

// One triangle geometry for one object; Embree owns (and pads) the buffers it allocates.
void AddObject(RTCDevice device, RTCScene scene, const Object& obj, unsigned id) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geom) return;  // the error callback has the reason
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          obj.positions.size()));
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             obj.triangles.size()));
    if (v && t) {
        for (size_t i = 0; i < obj.positions.size(); ++i)
            for (size_t k = 0; k < 3; ++k) v[3 * i + k] = obj.positions[i][static_cast<int>(k)];
        for (size_t i = 0; i < obj.triangles.size(); ++i)
            for (size_t k = 0; k < 3; ++k) t[3 * i + k] = obj.triangles[i][static_cast<int>(k)];
    }
    rtcCommitGeometry(geom);                 // "you must commit geometry" before attaching
    rtcAttachGeometryByID(scene, geom, id);  // geomID == object index
    rtcReleaseGeometry(geom);                // the scene holds its own reference now
}

RTCRayHit MakeRayHit(const raster::Ray& ray, float tnear, float tfar) {
    RTCRayHit rh{};
    rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.dir.x, rh.ray.dir_y = ray.dir.y, rh.ray.dir_z = ray.dir.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

Hit ToHit(float t, unsigned geomID, unsigned primID, float u, float v, glm::vec3 ng) {
    Hit h;
    h.t = t;
    h.object = static_cast<int>(geomID);
    h.prim = static_cast<int>(primID);
    h.u = u;
    h.v = v;
    const float len = glm::length(ng);
    h.ng = len > 0.0f ? ng / len : ng;
    h.valid = true;
    return h;
}

// IntersectAll: the context carries the output list; the filter records and rejects.
struct CollectContext {
    RTCIntersectContext context;  // first member: Embree passes &context back to the filter
    std::vector<Hit>* hits;
};

void CollectFilter(const RTCFilterFunctionNArguments* args) {
    const auto* cc = reinterpret_cast<const CollectContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const glm::vec3 ng(RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                           RTCHitN_Ng_z(args->hit, args->N, i));
        cc->hits->push_back(
            ToHit(RTCRayN_tfar(args->ray, args->N, i), RTCHitN_geomID(args->hit, args->N, i),
                  RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                  RTCHitN_v(args->hit, args->N, i), ng));
        args->valid[i] = 0;  // reject: traversal continues with the original tfar
    }
}

}  // namespace

EmbreeScene::EmbreeScene(const EmbreeDevice& device, const Scene& scene)
    : impl_(std::make_unique<Impl>()) {
    impl_->device = device.state();
    RTCDevice dev = impl_->device->device;
    impl_->scene = rtcNewScene(dev);
    impl_->device->Check("rtcNewScene");
    for (size_t i = 0; i < scene.objects.size(); ++i)
        AddObject(dev, impl_->scene, scene.objects[i], static_cast<unsigned>(i));
    impl_->device->Check("geometry setup");
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(impl_->scene);  // builds the BVH (TBB, deterministic for MEDIUM)
    impl_->device->Check("rtcCommitScene");
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

Hit EmbreeScene::Intersect(const raster::Ray& ray, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = MakeRayHit(ray, tnear, tfar);
    rtcIntersect1(impl_->scene, &ctx, &rh);
    impl_->device->Check("rtcIntersect1");
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit{};
    return ToHit(rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
                 glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
}

bool EmbreeScene::Occluded(const raster::Ray& ray, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r = MakeRayHit(ray, tnear, tfar).ray;
    rtcOccluded1(impl_->scene, &ctx, &r);
    impl_->device->Check("rtcOccluded1");
    return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

namespace {

// Lane i of an 8-ray packet from queries[i]; inactive lanes repeat lane 0 (valid, never traced).
template <typename RayN>
void FillPacket(std::span<const RayQuery> queries, RayN& r, int* valid) {
    for (size_t i = 0; i < EmbreeScene::kPacketSize; ++i) {
        const bool active = i < queries.size();
        const RayQuery& q = queries[active ? i : 0];
        valid[i] = active ? -1 : 0;
        r.org_x[i] = q.ray.origin.x, r.org_y[i] = q.ray.origin.y, r.org_z[i] = q.ray.origin.z;
        r.dir_x[i] = q.ray.dir.x, r.dir_y[i] = q.ray.dir.y, r.dir_z[i] = q.ray.dir.z;
        r.tnear[i] = q.tnear, r.tfar[i] = q.tfar;
        r.time[i] = 0.0f, r.mask[i] = ~0u, r.id[i] = 0, r.flags[i] = 0;
    }
}

void CheckPacket(size_t n) {
    if (n > EmbreeScene::kPacketSize)
        throw std::invalid_argument("EmbreeScene: more than 8 rays in a packet");
}

}  // namespace

void EmbreeScene::IntersectPacket8(std::span<const RayQuery> queries, std::span<Hit> hits) const {
    CheckPacket(queries.size());
    if (hits.size() != queries.size())
        throw std::invalid_argument("EmbreeScene::IntersectPacket8: size mismatch");
    if (queries.empty()) return;
    alignas(32) RTCRayHit8 rh;
    alignas(32) int valid[kPacketSize];
    FillPacket(queries, rh.ray, valid);
    for (size_t i = 0; i < kPacketSize; ++i) {
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect8(valid, impl_->scene, &ctx, &rh);
    impl_->device->Check("rtcIntersect8");
    for (size_t i = 0; i < queries.size(); ++i)
        hits[i] =
            rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID
                ? Hit{}
                : ToHit(rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i],
                        rh.hit.v[i], glm::vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]));
}

unsigned EmbreeScene::OccludedPacket8(std::span<const RayQuery> queries) const {
    CheckPacket(queries.size());
    if (queries.empty()) return 0;
    alignas(32) RTCRay8 r;
    alignas(32) int valid[kPacketSize];
    FillPacket(queries, r, valid);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcOccluded8(valid, impl_->scene, &ctx, &r);
    impl_->device->Check("rtcOccluded8");
    unsigned occluded = 0;
    for (size_t i = 0; i < queries.size(); ++i)
        if (r.tfar[i] < 0.0f) occluded |= 1u << i;  // Embree sets tfar = -inf on a hit
    return occluded;
}

std::vector<Hit> EmbreeScene::IntersectAll(const raster::Ray& ray, float tnear, float tfar) const {
    std::vector<Hit> hits;
    CollectContext cc{};
    rtcInitIntersectContext(&cc.context);
    cc.context.filter = CollectFilter;
    cc.hits = &hits;
    RTCRayHit rh = MakeRayHit(ray, tnear, tfar);
    rtcIntersect1(impl_->scene, &cc.context, &rh);
    impl_->device->Check("rtcIntersect1 (all hits)");
    // Deterministic order; drop repeats (a primitive referenced by several BVH leaves).
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
        return a.t != b.t             ? a.t < b.t
               : a.object != b.object ? a.object < b.object
                                      : a.prim < b.prim;
    });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const Hit& a, const Hit& b) {
                               return a.object == b.object && a.prim == b.prim;
                           }),
               hits.end());
    return hits;
}

// Packet benchmark ------------------------------------------------------------------------------

namespace {

// One packet of N rays (RTCRayHit4/8/16 share a layout: arrays of N per field).
template <typename RayHitN, int N>
size_t TracePackets(RTCScene scene, std::span<const raster::Ray> rays,
                    void (*intersect)(const int*, RTCScene, RTCIntersectContext*, RayHitN*)) {
    alignas(64) RayHitN rh;
    alignas(64) int valid[N];
    size_t hits = 0;
    for (size_t base = 0; base < rays.size(); base += N) {
        for (int i = 0; i < N; ++i) {
            const size_t r = base + static_cast<size_t>(i);
            valid[i] = r < rays.size() ? -1 : 0;
            const raster::Ray& ray = rays[r < rays.size() ? r : base];
            rh.ray.org_x[i] = ray.origin.x, rh.ray.org_y[i] = ray.origin.y;
            rh.ray.org_z[i] = ray.origin.z;
            rh.ray.dir_x[i] = ray.dir.x, rh.ray.dir_y[i] = ray.dir.y, rh.ray.dir_z[i] = ray.dir.z;
            rh.ray.tnear[i] = 0.0f, rh.ray.tfar[i] = EmbreeScene::kInfinity;
            rh.ray.mask[i] = ~0u, rh.ray.time[i] = 0.0f, rh.ray.flags[i] = 0;
            rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        }
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        intersect(valid, scene, &ctx, &rh);
        for (int i = 0; i < N; ++i) hits += valid[i] && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

size_t TraceSingles(RTCScene scene, std::span<const raster::Ray> rays) {
    size_t hits = 0;
    for (const raster::Ray& ray : rays) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh = MakeRayHit(ray, 0.0f, EmbreeScene::kInfinity);
        rtcIntersect1(scene, &ctx, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

size_t TraceChunk(RTCScene scene, std::span<const raster::Ray> rays, int packetSize) {
    switch (packetSize) {
        case 4:
            return TracePackets<RTCRayHit4, 4>(scene, rays, rtcIntersect4);
        case 8:
            return TracePackets<RTCRayHit8, 8>(scene, rays, rtcIntersect8);
        case 16:
            return TracePackets<RTCRayHit16, 16>(scene, rays, rtcIntersect16);
        default:
            return TraceSingles(scene, rays);
    }
}

}  // namespace

double EmbreeScene::PacketThroughputMrays(std::span<const raster::Ray> rays, int packetSize,
                                          int threads, int repeats) const {
    if (rays.empty()) return 0.0;
    const size_t n = static_cast<size_t>(std::max(1, threads));
    const size_t chunk = (rays.size() + n - 1) / n;
    double best = 0.0;
    std::atomic<size_t> hits{0};
    for (int r = 0; r < std::max(1, repeats); ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        base::RunOnWorkers(static_cast<int>(n), [&](int t) {
            const size_t lo = std::min(rays.size(), static_cast<size_t>(t) * chunk);
            const size_t hi = std::min(rays.size(), lo + chunk);
            hits += TraceChunk(impl_->scene, rays.subspan(lo, hi - lo), packetSize);
        });
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        best = std::max(best, static_cast<double>(rays.size()) / s * 1e-6);
    }
    impl_->device->Check("rtcIntersectN (benchmark)");
    if (hits.load() == static_cast<size_t>(-1)) std::abort();  // keeps the work observable
    return best;
}

}  // namespace pem::trace
