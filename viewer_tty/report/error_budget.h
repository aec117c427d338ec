// SPDX-License-Identifier: MIT
// error_budget.h — where the method loses against the ray tracer, stage by stage, per lens group:
// the teaching table of `pemref report`. Each stage swaps one part of the method for its exact
// version; its cost is the PSNR it takes away from the frame before it.
//
//   std::vector<GroupBudget> b = ErrorBudget(renderer, trace, bakeDirOffPositions, threads);
//
// At the first viewpoint sample (the report's "on circle"), against the trace's full-tree
// reference there (same K×K sampling) and against its two-term frame (greedy: the frame the maps
// are fitted to, so the method's own measure), on the group's pixels (coverage > 0.5), PSNR of
// the 8-bit sRGB display images (as the PNG files):
//   two-term model      the greedy R + T paths instead of the full ray tree (traced)
//   layered EM          the traced layer images composited with premultiplied over, times the
//                       traced F·G: what perfect maps on these layers could give
//   best maps, exact    each layer's map fitted through exact per-subpixel lookups at twice
//   lookups             the maps' resolution, unbounded (exact_fit.h): what no map on these
//                       shells can show (parallax, view and path dependence)
//   nonnegative maps    the same fit with texels ≥ 0: what the negative texels of the unbounded
//                       fit bought (sharpening; no radiance is negative)
//   maps' range         the same fit in the 8-bit maps' range, [0, radiance scale]
//                       (runtime/map_set.h): what clamping the incident radiance costs
//                       (float maps, runtime/map_set.h MapHardware::format: neither of these
//                       two stages; the maps are unbounded)
//   map resolution      the same fit in that range at the maps' own resolution (float maps:
//                       unbounded)
//   texgen, filtering,  the inferred maps drawn through their texgen passes alone (linear
//   solve               profile, exact texel weights), composited and modulated as above: what
//                       per-vertex lookups, MIP filtering and the regularized solve cost
//   hardware frame      the hybrid frame as drawn: per-vertex F·G, the maps and framebuffer in
//                       their formats (8-bit, or float), the hardware's compositing
//   hardware frame at   when the maps were fitted at another t: the same frame tessellated at the
//   t=5                 renderers' default t (runtime::kDefaultTessT), what interactive rendering
//                       costs
// Off the samples (between two samples, 10° above): the hybrid frame against the ray tracer at
// the same K×K there (full tree, and the two-term model traced there), on the pixels that see
// the group, compared with the same measures at the sample: the cost of being away from it (and,
// when the maps were fitted at another t, at the renderers' default t there as well).
// Not here: the documents (report_writer.h: GroupBudget, the table and budget.svg).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pipeline/trace_manifest.h"
#include "raster/camera.h"
#include "runtime/renderer.h"
#include "viewer_tty/report/report_writer.h"

namespace pem::report {

struct BudgetPosition {
    std::string name;
    raster::Camera camera;
    // Frames the caller drew there already, else drawn here: the hybrid frame at the maps' t
    // (RenderSettings t = 0), at the renderers' default t, and the full-tree ray tracer at the
    // trace's K×K.
    std::optional<runtime::RenderedFrame> hybrid, hybridDefaultT, traced;
};

// positions[0] is the first inferred sample; the others are off the samples.
std::vector<GroupBudget> ErrorBudget(runtime::Renderer& renderer,
                                     const pipeline::TraceManifest& trace,
                                     const std::vector<BudgetPosition>& positions, int threads);

}  // namespace pem::report
