// SPDX-License-Identifier: MIT
// tracer.h — THE ray tracer: radiance of camera rays through a trace::Scene on Embree, with the
// full ray tree (the reference) or the hybrid paper's greedy two-term model for lens objects.
//
// Shading (deterministic, no Monte Carlo; radiance in linear float RGB, HDR):
//  - Diffuse: emission + albedo·ambient + albedo/π · Σ_lights E·visibility, where E is the
//    light's irradiance (point/spot: intensity·cosθ/d² with glTF's range window and spot cone
//    smoothstep; directional: intensity·cosθ) and visibility one shadow ray (Embree Occluded,
//    every object blocks light: glass casts an opaque shadow, no caustics).
//  - Lens objects (mirror, glass) are grouped (Scene::lensGroups). A ray that hits a group is
//    propagated through that group's "local system" with ray_path.h against GroupHits, whose
//    Next() is the nearest scene hit if it belongs to the group and "left the system"
//    otherwise. Leaves / exit rays take the radiance of what they hit next: diffuse shading,
//    the environment on a miss, or the FULL tree of another lens group (depth budget shared).
//  - Full tree (reference): ray_path.h TraceFullTree with depth `fullTreeDepth` and weight
//    cut-off `minWeight` (relative to the branch's absolute weight); cut leaves are black.
//  - Greedy: TraceGreedyPaths (same depth and cut-off); radiance = Σ_terms F·G·b, b the exit
//    ray's radiance. Mirrors have F_T = 0.
//  - Entering/exiting from the geometric normal vs the ray; outward shading normals; self-hits
//    ignored with tnear = kSelfHitEpsilon · max(1, |origin|∞).
//  - Batched forms for renderers (IntersectCamera, AddLightIrradiance: 8-ray packets;
//    RecordHitRadiance / EvalTape: the full tree with its diffuse shading deferred) give the
//    same bits as the one-ray-at-a-time functions.
// Camera: raster/camera.h PixelRay; k×k supersamples per pixel on a regular grid at
// (x + (i + ½)/k, y + (j + ½)/k) (k = 1: the pixel centre).
// Not here: images and files (render.h, pipeline/trace_job.h), layers (layers.h).
#pragma once

#include <cstdint>
#include <deque>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <vector>

#include "raster/camera.h"
#include "trace/embree_scene.h"
#include "trace/fresnel.h"
#include "trace/ray_path.h"
#include "trace/scene.h"

namespace pem::trace {

constexpr float kSelfHitEpsilon = 1e-5f;

struct TraceOptions {
    int fullTreeDepth = 6;    // interface events along a branch, shared across lens groups
    double minWeight = 1e-3;  // branches / paths below this absolute weight stop
    FresnelModel fresnel = FresnelModel::Exact;
    glm::vec3 ambient{0.05f};  // ambient radiance reflected by a unit-albedo diffuse surface
    bool operator==(const TraceOptions&) const = default;
};

// Rays cast, by kind (each EmbreeScene call is one ray).
struct RayCounts {
    uint64_t primary = 0;    // camera rays
    uint64_t secondary = 0;  // reflected, refracted, exit and continued rays (Intersect[All])
    uint64_t shadow = 0;     // Occluded
    uint64_t Total() const { return primary + secondary + shadow; }
    RayCounts& operator+=(const RayCounts& o) {
        primary += o.primary, secondary += o.secondary, shadow += o.shadow;
        return *this;
    }
};

// One term of the greedy model for one camera sample.
struct TermSample {
    bool escaped = false;  // the path has an exit ray (else it was cut: b = 0)
    Ray exit;              // the exit ray (origin, unit dir)
    Hit exitHit;           // what the exit ray hits first (invalid: the environment)
    glm::vec3 F{0.0f}, G{1.0f};
    glm::vec3 b{0.0f};  // the exit ray's radiance
    int events = 0;     // interface events along the path
    glm::vec3 Weighted() const { return F * G * b; }
};

struct GreedySample {
    TermSample reflection, refraction;
    glm::vec3 Radiance() const { return reflection.Weighted() + refraction.Weighted(); }
};

// k×k sample s (row-major in the pixel) of pixel (x, y), in continuous image coordinates:
// (x, y) + SampleOffset(k, s) (so a renderer may compute the k² offsets once).
glm::vec2 SampleOffset(int k, int s);
glm::vec2 SamplePosition(int x, int y, int k, int s);

class Tracer {
  public:
    // Keeps references: the Scene and EmbreeScene must outlive the Tracer.
    Tracer(const Scene& scene, const EmbreeScene& embree, const TraceOptions& options = {});

    const Scene& scene() const { return scene_; }
    const TraceOptions& options() const { return options_; }
    // Lens group index, -1 for non-lens objects.
    int GroupOf(int object) const { return groupOf_[static_cast<size_t>(object)]; }
    bool GroupHasGlass(int group) const;

    // Ray queries that count themselves (tnear from the self-hit epsilon unless given).
    Hit Intersect(const Ray& ray, RayCounts& counts, bool primary = false) const;
    // Camera rays in packets of 8 (EmbreeScene::IntersectPacket8): hits[i] is bit for bit
    // Intersect(rays[i], counts, true); counted as primary rays.
    void IntersectCamera(std::span<const Ray> rays, std::span<Hit> hits, RayCounts& counts) const;
    std::vector<Hit> IntersectAll(const Ray& ray, RayCounts& counts) const;

    // Reference radiance along a camera ray (full tree).
    glm::vec3 Radiance(const Ray& cameraRay, RayCounts& counts) const;
    // Radiance along a camera ray with the greedy model at lens objects (first hit only;
    // lenses seen through exit rays are traced fully).
    glm::vec3 GreedyRadiance(const Ray& cameraRay, RayCounts& counts) const;

    // The radiance leaving `hit` back along `ray` (a miss: the environment): diffuse shading,
    // or the full tree of the hit's lens group with `depthBudget` events left (0: black).
    glm::vec3 HitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                          RayCounts& counts) const;

    // Greedy paths for lens group `group` from its hit `first` along `ray` (which may lie
    // behind occluders: continued incoming rays).
    GreedySample TraceGreedy(const Ray& ray, const Hit& first, int group, RayCounts& counts) const;
    // The same two greedy paths without their exit radiance (run-time texgen needs only the
    // exit rays and F, G); nullopt when `first` is not a hit of the group.
    std::optional<GreedyPaths> GreedyPathsAt(const Ray& ray, const Hit& first, int group,
                                             RayCounts& counts) const;

    // The surface of a lens hit as ray_path.h sees it.
    SurfaceHit MakeSurfaceHit(const Ray& ray, const Hit& hit) const;

    // Diffuse shading in steps, so a renderer can trace one light's shadow rays for many hits
    // in a row (coherent work): ShadeDiffuse = Finish(point, Σ_lights LightIrradiance).
    struct DiffusePoint {
        glm::vec3 base{0.0f};  // emission + albedo · ambient
        glm::vec3 albedo{0.0f};
        glm::vec3 p{0.0f};             // shadow-ray origin (offset off the surface)
        glm::vec3 ns{0.0f}, ng{0.0f};  // shading and geometric normals on the ray's side
    };
    DiffusePoint DiffuseAt(const Ray& ray, const Hit& hit) const;
    glm::vec3 LightIrradiance(const Light& light, const DiffusePoint& dp, RayCounts& counts) const;
    // One light for many points, the shadow rays in packets of 8 (EmbreeScene::OccludedPacket8):
    // irradiance[j] += LightIrradiance(light, points[j], counts), the same values and additions.
    void AddLightIrradiance(const Light& light, std::span<const DiffusePoint> points,
                            std::span<glm::vec3> irradiance, RayCounts& counts) const;
    static glm::vec3 Finish(const DiffusePoint& dp, const glm::vec3& irradiance);
    glm::vec3 ShadeDiffuse(const Ray& ray, const Hit& hit, RayCounts& counts) const;

    // HitRadiance with its diffuse shading deferred, so a renderer can trace the shadow rays of
    // many samples' tree leaves together (RenderFrame's rows). RecordHitRadiance appends to the
    // tape the ops of one HitRadiance call (the same rays, in the same order) and one
    // DiffusePoint per diffuse hit; once `irradiance[j]` holds Σ_lights LightIrradiance for
    // points[j] (summed light by light), EvalTape over that call's ops returns HitRadiance's
    // value bit for bit (the same additions and products in the same order).
    struct RadianceTape {
        enum class Op : uint8_t { Value, Diffuse, BeginSum, AddWeighted };
        struct Entry {
            Op op;
            uint32_t point = 0;  // Diffuse: index into points
            glm::vec3 v{0.0f};   // Value: the radiance; AddWeighted: the leaf weight
        };
        std::vector<Entry> ops;
        std::vector<DiffusePoint> points;
        void Clear() { ops.clear(), points.clear(); }

        // Scratch per lens-group nesting level (buffers reused across calls; a deque so that
        // deeper levels never move the ones in use).
        struct Exit {
            Ray ray;
            Hit hit;
        };
        struct Level {
            std::vector<ExitRay> leaves;
            std::vector<Exit> exits;
        };
        std::deque<Level> levels;
    };
    void RecordHitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                           RadianceTape& tape, RayCounts& counts) const;
    // `stack` is scratch (reused to avoid allocations).
    static glm::vec3 EvalTape(std::span<const RadianceTape::Entry> ops,
                              std::span<const DiffusePoint> points,
                              std::span<const glm::vec3> irradiance, std::vector<glm::vec3>& stack);

  private:
    void RecordHitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                           RadianceTape& tape, size_t level, RayCounts& counts) const;

    // LightIrradiance before its shadow ray: false when the light cannot contribute (no ray);
    // otherwise `value` (E·cosθ) counts iff `shadow` is unoccluded. Writes through pointers (a
    // returned struct was copied through the stack with store-forwarding stalls).
    bool PrepareLight(const Light& light, const DiffusePoint& dp, RayQuery* shadow,
                      glm::vec3* value) const;

    glm::vec3 LensRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                           RayCounts& counts) const;

    const Scene& scene_;
    const EmbreeScene& embree_;
    TraceOptions options_;
    std::vector<int> groupOf_;              // per object
    std::vector<SurfaceMaterial> surface_;  // per object (lens objects only meaningful)
    std::vector<std::vector<TriangleCorners>> lensCorners_;  // per object, lens objects only
    std::vector<bool> groupHasGlass_;
};

}  // namespace pem::trace
