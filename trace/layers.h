// SPDX-License-Identifier: MIT
// layers.h — layered EM geometry per lens group (hybrid §4.1–4.2, PEM §4) and the layer images.
//
// Layers: cluster.h's LBG over the hit records of ALL viewpoints (distance from the group's EM
// origin = shell.h EmOrigin over the group's triangles), whole objects to one layer. An object
// without records is put, hit by hit, into the layer of nearest radius.
// Shell per layer: the candidate with the least parallax (ShellParallax) over the layer's
// records — the frontmost record of each ray, as (exit ray origin, hit point): a sphere at the
// EM origin with the cluster's radius, a box of that half size and one bounding the records,
// an ellipsoid fit, two vertical cylinders (bounding, and of the cluster's radius), and for a
// sparsely occupied layer (fewer than `sparseOccupancy` of the 6·16·16 cube-direction cells
// hold a record) a quad impostor; boxes and cylinders stand on the floor when the group rests on
// the lowest geometry of the scene (the PEM paper's box for objects on a surface). Without ray
// origins: the sphere, or the quad for a sparse layer. Mirror-only groups also get the PEM
// split's shells: for the local layer the candidate with the least parallax over the group's self
// hits (ChooseLocalShell; the PEM paper's ellipsoid over the group's vertices among them), and a
// box for the distant layer (half size = mean distance of the distant hits, bottom on the floor
// when the group rests on the lowest geometry of the scene).
// Layer images (per term, per layer, RGBA premultiplied, box-filtered like segment.h): for each
// sample's exit ray, every front-facing hit outside the group in order of distance; the first hit
// in each layer gives that layer its colour (the hit's radiance seen along the exit ray) and
// coverage 1. A ray with no hit in the outermost layer gives the outermost layer the environment
// (radiance at infinity) along its direction.
// Not here: the records themselves (segment.h), EM inference (infer/).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "trace/cluster.h"
#include "trace/image.h"
#include "trace/shell.h"
#include "trace/tracer.h"

namespace pem::trace {

struct LayerShell {
    std::string kind;  // "sphere", "box", "cylinder", "ellipsoid" or "quad"
    Shell shell;
    double occupancy = 0.0;  // fraction of direction cells holding a record
    // The parallax of the shell (degrees): the mean angle, seen from the EM origin, between
    // where a record's exit ray meets the shell and where it met the scene (0: the shell passes
    // through what the layer shows). NaN when the records carry no ray origins.
    double parallaxDeg = 0.0;
    std::vector<std::pair<std::string, double>> candidates;  // every kind tried, its parallax
};

struct GroupLayers {
    int group = -1;
    glm::vec3 emOrigin{0.0f};
    LayerClustering clustering;
    std::vector<LayerShell> shells;  // per layer
    std::vector<int> objectLayer;    // per scene object: its layer, -1 = no records
    bool mirror = false;             // the PEM shells below are set
    Shell localShell;
    double localParallaxDeg = 0.0;  // its parallax over the self hits (NaN: none recorded)
    BoxShell distantShell;
    double distantMeanDistance = 0.0;
};

glm::vec3 GroupEmOrigin(const Scene& scene, int group);

struct LayerInput {
    std::span<const HitRecord> records;
    std::span<const glm::vec3> points;  // one per record
    int layers = 2;
    double sparseOccupancy = 0.15;
    double distantDistanceSum = 0.0;  // mirror-only groups (segment.h)
    size_t distantCount = 0;
    std::span<const glm::vec3> origins;  // per record: its exit ray's origin (may be empty)
    // Mirror-only groups: the self hits (segment.h localOrigins, localPoints), may be empty.
    std::span<const glm::vec3> localOrigins, localPoints;
};

GroupLayers BuildLayers(const Scene& scene, int group, bool mirror, const LayerInput& input);

// An exit ray (from `origin`) and the scene point it met.
struct RayHit {
    glm::dvec3 origin, point;
};
// A shell's parallax over such hits: the mean angle (degrees), seen from the EM origin, between
// where each ray meets the shell and the scene point it met (a miss counts 90°). Zero for a
// shell through every point, and for rays that leave from the EM origin itself.
double ShellParallax(const Shell& shell, std::span<const RayHit> hits, const glm::dvec3& emOrigin);

// The PEM split's local shell: the candidate with the least parallax over the group's self hits
// (each a first reflected ray that meets the group again: its origin, the point it met): the
// minimum-volume ellipsoid over the group's vertices (first, so it wins ties; the choice without
// self hits, parallax NaN), the ellipsoid fit and the box around the hit points, and spheres at
// the deciles of their distance from the EM origin.
struct LocalShellChoice {
    Shell shell;
    double parallaxDeg = 0.0;
};
LocalShellChoice ChooseLocalShell(std::span<const glm::dvec3> vertices,
                                  std::span<const RayHit> selfHits, const glm::dvec3& emOrigin);

// The layer of a hit on `object` at `distance` from the EM origin.
int LayerOf(const GroupLayers& layers, int object, double distance);

// The layers' colours along a ray leaving the lens group (an exit ray, or a ray from the EM
// origin: the direct images of the environment, hybrid §4.3), as RenderLayers gives them: per
// layer the radiance of its first front-facing hit seen along the ray and alpha 1; the outermost
// layer without a hit the environment along the ray; the others (0, 0, 0, 0). `depthBudget`: the
// ray tree depth left for the hits' shading.
std::vector<glm::vec4> LayerColours(const Tracer& tracer, const GroupLayers& layers, const Ray& ray,
                                    int depthBudget, RayCounts& counts);

struct LayerImages {
    std::vector<FloatImage> term[2];     // [τ][layer], RGBA
    std::vector<FloatImage> samples[2];  // the same as K× sample images (image.h SampleCell)
    RayCounts counts;
};

LayerImages RenderLayers(const Tracer& tracer, const raster::Camera& camera, int k,
                         const GroupLayers& layers, int threads,
                         const std::function<void(int, int)>& progress = {});

}  // namespace pem::trace
