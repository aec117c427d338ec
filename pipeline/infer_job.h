// SPDX-License-Identifier: MIT
// infer_job.h — the whole `pemref infer` job: a trace directory in, one environment map per
// (viewpoint sample, lens group, layer) out, every MIP level, with the figures infer.json
// reports (infer_report.h).
//
//   InferJobOptions o;  o.traceDir = "out/trace";  o.outDir = "out/pem";
//   InferJobResult r = RunInferJob(o);       // the maps
//   WriteInferOutputs(o, r);                 // + infer.json and manifest.json
//
// For each viewpoint sample and lens group: the group's mesh adaptively tessellated at the
// sample (runtime/lens_paths.h), and per layer l one map `layer_l` for both terms (hybrid §4.3:
// [A_R; A_T] x = [b_R; b_T]): per term τ the texgen pass (runtime/texgen.h) that looks the
// layer's cube map up at each vertex's exit-ray hit on the layer's shell; raster/'s rendering
// matrix of that pass (linear profile: llvmpipe's texel selection and weights) drawn with the
// trace's K×K subpixels per pixel, one row per covered subpixel; the target = that camera
// sample of the traced layer image layer_l_τ (trace/image.h sample images) un-premultiplied by
// its lens coverage (b_τ's alpha), weighted by the coverage (a sample has one exit ray: the
// hybrid paper's confidence is 1); the terms' rows stacked; infer::BuildSystem with the
// active texels (observed + rings), LSMR with bounds ([0, 1] or HDR), FillUnobserved, files.
// `single`: one more map, `single`, from the whole exit radiance b_τ on one sphere.
// With maxRes > res, each map's face size comes from a test rendering (PEM §4 "EM Resolution"):
// its sample's passes drawn at face size maxRes without LOD bias; the size whose level 0 is the
// finest level 10 % of the covered subpixels read, within [res, maxRes].
// With `alsoTessT`, the layer maps' systems also hold the rows of the sample's view tessellated at
// each further t (the renderers' interactive t beside a finer bake t): maps that the hardware
// draws close to the traced frame at either.
// With `neighbours` = k, the layer maps' systems also hold the rows of the k samples on each side
// (their own vertex paths, texgen and traced layer images, weight × neighbourWeight): the
// simultaneous solve of hybrid §4.3, so a map also fits what is seen just off its sample.
// Mirror-only groups also get the PEM paper's split (runtime/mirror_geometry.h): `local` on the
// local shell (trace/layers.h ChooseLocalShell) and `distant` on the box; each fitted as the
// renderer draws it (`local` only on the polygons off the convex hull, EQUAL after a depth pass
// of every polygon).
// Files per map under outDir (layout.h): <map>.exr (tiled mip-mapped cube, infer/pem_file.h),
// <map>.png (the 8-bit copy: level l's six faces side by side, levels stacked), <map>.csv (the
// solve log); --export-system writes per map <dir>/v<vvv>_g<g>_<map>_{K,h,x}.mtx + .json.
// Not here: argument parsing (viewer_tty/cli/cmd_infer.cpp), rendering (runtime/renderer.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "infer/problem.h"
#include "infer/solver.h"
#include "pipeline/infer_report.h"
#include "pipeline/trace_manifest.h"
#include "runtime/map_set.h"

namespace pem::pipeline {

// The lens maps when none is asked for (infer, bake, demo), chosen on scene (a) at the demo's
// settings: hybrid and PEM frames at sample 0 against the traced two-term frame, lens pixels
// (docs/method.md §5).
//  - Face size 128. At 256 (with radiance scale 4) the mirror cup gains 3.4 dB more (hybrid
//    28.6, PEM mode 31.7), but inference takes 1.5 times and the report (its error budget)
//    twice as long, and the demo no longer finishes in 5 minutes. `--max-res 256` chooses 256
//    for every map of scene (a) but the cup's local one (the teapot's refraction magnifies
//    more than the cup's reflection), and costs 1.7-2.2 times the inference: teapot +0.9 dB.
//  - LOD bias (DefaultLodBias) -4: every subpixel is a row of the fit, so the fit can use texels
//    finer than the footprint, which the hardware's MIP filter would otherwise blur (teapot
//    +0.3 dB, cup +1.5, cup in PEM mode +2.0).
//  - Radiance scale 2: 8-bit maps reach twice the unit radiance (teapot +0.35 dB, cup +0.35;
//    4 gives the teapot +0.2 dB more and costs the cup 0.45 dB).
inline constexpr int kDefaultMapResolution = 128;
inline constexpr float kDefaultRadianceScale = 2.0f;

// LSMR with at most 150 iterations and atol 1e-4, a log line every 25 iterations: what every
// pipeline solve uses unless told otherwise.
infer::SolveOptions DefaultSolveOptions();

// The smoothness weight λs for maps of `format` when none is given (--smooth): the solver's
// default (infer::RegularizerWeights) for 8-bit maps, 10× it for float maps — without bounds,
// texels that a single view constrains overshoot into speckles off the samples. The demo's
// report (scene (a), lens pixels against the 6×6 reference): hybrid 10° above the circle
// 20.20 → 20.41 dB, between the samples 21.52 → 21.94 dB; at the samples the outside check
// loses 0.3–0.75 dB (teapot 32.38 → 31.63 at sample 0).
double DefaultSmooth(raster::TexelFormat format);

// The maps' LOD bias for maps of `format` when none is given (--lod-bias): -4 for 8-bit maps
// (above), -2.5 for float maps, whose negative texels undo part of the MIP filter's blur
// themselves: off the samples the finest levels then alias less (speckles where a lookup sweeps
// across texels). The demo's report (scene (a), lens pixels against the 6×6 reference, with the
// topology threshold runtime::kDefaultTopologyT), hybrid at t = 5, -4 / -3 / -2.5 / -2: 10°
// above the circle 20.24 / 20.35 / 20.55 / 20.54 dB, between the samples 21.81 / 21.92 /
// 21.99 / 22.00; the outside check at the three samples (hybrid at t = 1, lowest of the three)
// glass teapot 30.81 / 30.26 / 30.53 / 29.96, mirror cup 34.06 / 31.29 / 30.54 / 29.58 dB.
float DefaultLodBias(raster::TexelFormat format);

// The weight of the rows of a further tessellation (InferJobOptions::alsoTessT), the maps' own
// t's being 1. Scene (a) at the demo's settings with --also-t 5, the glass teapot's hybrid at
// the three samples against the traced two-term frame (the outside check): at 1 the frames at
// t = 1 lose 0.6-1.1 dB to maps fitted at t = 1 alone, 0.3-0.8 at 0.5 (which gives up 0.4-0.6
// of the gain at t = 5: 25.0-25.3 dB alone, 28.5-29.9 at 1, 28.0-29.3 at 0.5).
inline constexpr double kAlsoTessWeight = 0.5;

struct InferJobOptions {
    std::string traceDir, outDir, exportDir;
    int res = kDefaultMapResolution;
    // > res: each map's face size from a test rendering of its sample (the finest MIP level
    // its subpixels read at this size, PEM §4 "EM Resolution"), between res and maxRes.
    int maxRes = 0;
    int threads = 1;
    // The target hardware: profile, the maps' sampler and radiance scale.
    runtime::MapHardware hardware{.radianceScale = kDefaultRadianceScale,
                                  .lodBias = DefaultLodBias(raster::TexelFormat::Rgba8)};
    // The maps' layout (runtime/parameterization.h); a 2D layout needs res >= 2.
    runtime::Parameterization parameterization = runtime::Parameterization::Cube;
    bool hdr = false;                       // float radiance, bounds [0, inf)
    double tessT = runtime::kDefaultTessT;  // tessellation t in subpixels (1 / spp pixels)
    // Further tessellations of the sample the layer maps also fit, each with the rows of its
    // own texgen pass at weight kAlsoTessWeight (t = tessT is skipped): maps fitted at one t
    // alone are tuned to its vertices and show speckles where a coarser t interpolates other
    // lookups.
    std::vector<double> alsoTessT;
    // Every tessellation's topology threshold (trace/tessellate.h; 0: t alone), kept in the
    // manifest so that the renderers refine as the maps were fitted.
    double topologyT = runtime::kDefaultTopologyT;
    std::vector<int> views;        // empty: all
    bool single = false;           // also the single-layer map (`single`, both terms)
    int neighbours = 0;            // samples on each side in the simultaneous solve (hybrid §4.3)
    double neighbourWeight = 0.5;  // their rows' weight factor
    bool direct = false;           // also solve with the direct oracle (when it fits)
    int64_t directMaxCols = 400000;  // unknowns (4 per texel) the direct solver may take
    infer::RegularizerWeights weights;
    infer::SystemOptions system{2};
    infer::SolveOptions solve = DefaultSolveOptions();
    std::function<void(const std::string& stage, double fraction)> progress;
};

struct InferJobResult {
    TraceManifest trace;
    std::vector<MapReport> maps;
    std::vector<SampleReport> samples;
    std::vector<LeftOut> leftOut;
    double seconds = 0.0;
};

InferJobResult RunInferJob(const InferJobOptions& options);

// infer.json and manifest.json of a finished `pemref infer`.
void WriteInferOutputs(const InferJobOptions& options, const InferJobResult& result);

}  // namespace pem::pipeline
