// SPDX-License-Identifier: MIT
// exact_fit.h — the error budget's "best maps on these shells" stage: each layer's map fitted to
// the traced layer images through EXACT lookups — every subpixel's own exit ray met with the
// layer's shell, the finest level sampled bilinearly, no per-vertex interpolation, no MIP
// filtering — unregularized; unbounded, nonnegative, or RGB in the 8-bit maps' range
// [0, radiance scale]. Unbounded at twice the maps' resolution, what stays is what no map on
// these shells can show (parallax, view and path dependence); nonnegative, what the negative
// texels of that fit bought (a least-squares fit sharpens with them); in the maps' range, what
// clamping the incident radiance costs; at the maps' own resolution, what the resolution costs;
// what the hardware adds on top of it is the cost of its texgen and filtering. The subpixels
// are traced once and the rows built once per resolution; the nonnegative fit starts from the
// unbounded one clamped, the fit in range from the nonnegative one.
//
//   ExactStages st = ExactLookupStages(tracer, camera, k, group, targets, coverage, 128, 2.0,
//                                      /*bounded=*/true, 2);
//
// Conventions: targets[τ][l] is layer_l_τ with the lens coverage divided out (RGBA, the maps'
// premultiplied values); each stage has Renderer::LayerImages' layout ([term][layer] RGBA per
// pixel, the layers that have records). Face coordinates from raster's cube lookup; bilinear
// taps clamped to their face.
// Not here: the stage table (error_budget.h).
#pragma once

#include <vector>

#include "raster/camera.h"
#include "raster/frame.h"
#include "runtime/lens_group_em.h"
#include "trace/image.h"
#include "trace/tracer.h"

namespace pem::report {

// The fits the budget compares, each in Renderer::LayerImages' layout.
// `bounded` false (float maps, MapHardware::format RGBA32F): the maps have no bounds, so there
// are no nonnegative and in-range fits (left empty) and the fit at the maps' resolution is
// unbounded too.
struct ExactStages {
    std::vector<std::vector<raster::ImageF>> unbounded;      // twice the maps' resolution
    std::vector<std::vector<raster::ImageF>> nonnegative;    // the same, texels >= 0
    std::vector<std::vector<raster::ImageF>> inRange;        // RGB in [0, maxRadiance], alpha <= 1
    std::vector<std::vector<raster::ImageF>> ownResolution;  // in range at the maps' resolution
};

ExactStages ExactLookupStages(const trace::Tracer& tracer, const raster::Camera& camera, int k,
                              const runtime::LensGroupEm& group,
                              const std::vector<std::vector<trace::FloatImage>>& targets,
                              const trace::FloatImage& coverage, int res, double maxRadiance,
                              bool bounded, int threads);

}  // namespace pem::report
