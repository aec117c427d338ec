// SPDX-License-Identifier: MIT
// ray_path.h — the hybrid paper's two-term greedy ray-path model (Hakura & Snyder 2001, §3) and,
// for comparison, the full binary ray tree, both traced against an abstract `SurfaceHitFn` (the
// Embree tracer implements it; tests use analytic spheres and slabs).
//
// Model: the primary ray's first hit spawns two paths, one starting with a reflection and one with
// a refraction; each is continued, at every further interface, by the child with the larger
// Fresnel coefficient (mean over channels; ties go to reflection) until it leaves the local system
// (no further hit). F multiplies the chosen coefficients; G multiplies exp(-sigma * length) for
// every segment travelled inside an object (length = distance between the two hit positions).
// Radiance = T·F_T·G_T + R·F_R·G_R.
//
// Conventions: normals in SurfaceHit are unit and point out of the object; `entering` is true when
// the ray crosses from outside to inside. Media are not nested: a segment is inside an object iff
// it leaves a hit by refraction while entering, or by reflection while exiting, and is then
// attenuated by that hit's material. Continued rays start a small step along their own direction
// (so a path stays on its exact polyline; see kRayOffset in ray_path.cpp); the tracer should still
// ignore hits at t ~ 0. Directions of traced rays are unit.
//
// Not here: scenes, Embree, radiance lookups, tessellation (which will call PathsDiffer).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <iosfwd>
#include <optional>
#include <vector>

#include "trace/fresnel.h"
#include "trace/ray.h"

namespace pem::trace {

enum class Event : uint8_t { Reflect, Refract };

enum class SurfaceKind : uint8_t {
    Dielectric,  // glass: Fresnel reflection and refraction
    Mirror,      // mirror or metal: Schlick with a per-channel F0, no transmission
};

struct SurfaceMaterial {
    SurfaceKind kind = SurfaceKind::Dielectric;
    double ior = 1.5;            // index of refraction inside the object
    double outsideIor = 1.0;     // index of refraction of the medium outside
    glm::dvec3 absorption{0.0};  // sigma per unit length inside, per channel: G = exp(-sigma d)
    glm::dvec3 mirrorF0{1.0};    // Mirror: Schlick F0 per channel (1 = perfect mirror)
    FresnelModel fresnel = FresnelModel::Exact;  // Dielectric: exact or Schlick

    bool operator==(const SurfaceMaterial&) const = default;
};

// What the tracer reports for the nearest surface along a ray.
struct SurfaceHit {
    float t = 0.0f;  // distance along the (unit) ray direction
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f};  // unit, outward
    glm::vec3 shadingNormal{0.0f, 1.0f, 0.0f};    // unit, outward (interpolated vertex normal)
    SurfaceMaterial material;
    bool entering = true;  // dot(ray.dir, geometricNormal) < 0
    uint32_t objectId = 0;
    uint32_t primId = 0;

    bool operator==(const SurfaceHit&) const = default;
};

// The tracer's side of the contract: the nearest hit along `ray` (t > 0), or nullopt if the ray
// leaves the local system.
struct SurfaceHitFn {
    virtual ~SurfaceHitFn() = default;
    virtual std::optional<SurfaceHit> Next(const Ray& ray) = 0;
};

// Both children of one interface: coefficients per channel and directions.
struct Interaction {
    glm::dvec3 reflectance{0.0};
    glm::dvec3 transmittance{0.0};  // 0 for mirrors and under total internal reflection
    glm::dvec3 reflectDir{0.0};
    std::optional<glm::dvec3>
        refractDir;  // nullopt for mirrors and under total internal reflection
};

// Scatter a unit incident direction at a hit (the shading normal, flipped to the geometric side).
Interaction Scatter(const glm::dvec3& dir, const SurfaceHit& hit);
// The greedy rule: the child with the larger coefficient (channel mean); reflection on ties.
Event GreedyChoice(const Interaction& interaction);

struct PathVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};  // shading normal, outward
    Event event = Event::Reflect;
    bool entering = true;
    uint32_t objectId = 0;
    uint32_t primId = 0;

    bool operator==(const PathVertex&) const = default;
};

struct RayPath {
    std::vector<PathVertex> vertices;  // one per interface event, in order
    glm::vec3 exitOrigin{0.0f};        // the last continued ray
    glm::vec3 exitDir{0.0f};
    glm::dvec3 F{1.0};     // product of the chosen Fresnel coefficients
    glm::dvec3 G{1.0};     // product of exp(-sigma d) over inside segments
    bool escaped = false;  // true: the exit ray leaves the local system; false: cut off by depth,
                           // weight, or an impossible first event (then F = 0)

    glm::dvec3 Weight() const { return F * G; }
    bool operator==(const RayPath&) const = default;
};

struct GreedyPaths {
    RayPath reflection;  // the R term: first event a reflection
    RayPath refraction;  // the T term: first event a refraction (F = 0 for mirrors)
};

// The two greedy paths of a primary ray, or nullopt if the primary ray hits nothing. maxDepth
// bounds the number of interface events per path; a path whose weight max(F G) drops below
// minWeight stops.
std::optional<GreedyPaths> TraceGreedyPaths(const Ray& primary, SurfaceHitFn& hits, int maxDepth,
                                            double minWeight);

// One leaf of the full ray tree.
struct ExitRay {
    Ray ray;                 // origin and unit direction of the leaf ray
    glm::dvec3 weight{0.0};  // product of coefficients and attenuations along the branch
    int depth = 0;           // interface events along the branch
    bool escaped = false;    // false: cut off by depth or weight (kept so the weights sum to 1)

    bool operator==(const ExitRay&) const = default;
};

// Every leaf of the full binary tree, reflection child before refraction child (depth first).
// Children with zero coefficient are not spawned. A primary ray that hits nothing is one escaped
// leaf.
std::vector<ExitRay> TraceFullTree(const Ray& primary, SurfaceHitFn& hits, int maxDepth,
                                   double minWeight);
// The same leaves into `leaves` (cleared first; its capacity is reused across calls).
void TraceFullTree(const Ray& primary, SurfaceHitFn& hits, int maxDepth, double minWeight,
                   std::vector<ExitRay>& leaves);

// Whether two paths differ in topology: path length, the event at some interface, or escape
// status (a discontinuity between them that no interpolation bridges).
bool TopologyDiffers(const RayPath& a, const RayPath& b);
// Adaptive-tessellation criterion (hybrid §5): TopologyDiffers, or exit directions more than
// maxAngleDeg apart.
bool PathsDiffer(const RayPath& a, const RayPath& b, double maxAngleDeg = 3.0);

std::ostream& operator<<(std::ostream& os, Event event);
std::ostream& operator<<(std::ostream& os, const PathVertex& vertex);
std::ostream& operator<<(std::ostream& os, const RayPath& path);

}  // namespace pem::trace
