// SPDX-License-Identifier: MIT
// segment.h — per viewpoint and lens group, the ray tracer's images that EM inference needs
// (hybrid §3–4, PEM §4), and the hit records that layer clustering needs.
//
// Incoming rays: every k×k camera sample whose ray meets the group's bounding box; its first
// hit on the group is taken even behind occluders ("incoming rays continued through
// occluders", hybrid §4.1: IntersectAll when the nearest hit is another object). From that hit
// the greedy two-term paths are traced (tracer.h).
// Images (box filter = sum over the pixel's samples / k²; RGBA premultiplied, A = coverage, the
// fraction of samples whose incoming ray hits the group):
//  - b[τ]:  the exit ray's radiance of term τ (0 = R, 1 = T; a cut path contributes 0),
//  - fg[τ]: the modulation F·G per channel,
//  - confidence[τ] (one channel): confidence.h over the pixel's exit directions, θc = 5°.
//  T images only for groups with glass. b, local and distant are also kept sample by sample
//  (K× images, image.h SampleCell; A = 1 where the sample's ray hits the group): inference fits
//  its maps to the samples. Mirror-only groups also get the PEM split along the
//  FIRST reflected ray: `local` (A = fraction whose first reflected ray hits the group again,
//  rgb its full-tree radiance), `distant` (the first reflected ray continued through the group
//  to the first other surface or the environment; A = coverage) and `fresnel1` (the first
//  bounce's Schlick F). Then (αL·L + (1−αL)·D)·F1 is the reference on covered pixels.
// Records (for cluster.h): for the FIRST sample of each pixel and each term with an exit ray,
// every front-facing hit (EmbreeScene::IntersectAll; equal-t repeats merged) on objects outside
// the group, with distance from the group's EM origin; rayId = 2·pixel + τ. For mirror-only groups
// also the first sample's self hits (localOrigins, localPoints).
// Not here: clustering and layer images (layers.h).
#pragma once

#include <functional>
#include <vector>

#include "trace/cluster.h"
#include "trace/image.h"
#include "trace/tracer.h"

namespace pem::trace {

struct GroupSegmentation {
    int group = -1;
    int terms = 1;                        // 1 (mirror-only group: R) or 2 (R, T)
    FloatImage b[2];                      // RGBA
    FloatImage fg[2];                     // RGBA
    FloatImage confidence[2];             // Y
    bool mirror = false;                  // the PEM split below is filled
    FloatImage local, distant, fresnel1;  // RGBA
    // The K× sample images of b[τ], local and distant (BoxFilter gives the images above).
    FloatImage bSamples[2], localSamples, distantSamples;
    std::vector<HitRecord> records;
    std::vector<glm::vec3> recordPoints;   // world position of each record's hit
    std::vector<glm::vec3> recordOrigins;  // the exit ray's origin of each record
    double distantDistanceSum = 0.0;       // distance of distant hits from the EM origin
    size_t distantCount = 0;
    // Mirror-only groups, the FIRST sample of each pixel whose first reflected ray hits the group
    // again: that ray's origin and the point it met (the local layer's shell choice, layers.h).
    std::vector<glm::vec3> localOrigins, localPoints;
    RayCounts counts;
};

// Front-facing hits along `ray` on objects outside `group`, nearest first, equal-t repeats of
// one object merged (continued outgoing rays, hybrid §4.1).
std::vector<Hit> EnvironmentHits(const Tracer& tracer, const Ray& ray, int group,
                                 RayCounts& counts);

// The group's hit along a camera ray, continued through occluders; invalid if none.
Hit IncomingHit(const Tracer& tracer, const Ray& ray, int group, RayCounts& counts);

GroupSegmentation SegmentGroup(const Tracer& tracer, const raster::Camera& camera, int k, int group,
                               uint32_t viewpoint, const glm::vec3& emOrigin, int threads,
                               const std::function<void(int, int)>& progress = {});

}  // namespace pem::trace
