// SPDX-License-Identifier: MIT
// infer_run.h — the whole `pemref infer` job: a `pemref trace` directory in, one PEM per
// (viewpoint, lens group, layer) out, with infer.json's figures (issue 4).
//
//   InferRunOptions o;  o.traceDir = "out/trace";  o.outDir = "out/pem";  o.res = 256;
//   InferRunReport r = RunInfer(o);
//
// For each viewpoint sample and lens group (trace.json): the group's mesh adaptively tessellated
// at the sample (runtime/lens_paths.h), and per layer l one map `layer_l` for both terms
// (hybrid §4.3: [A_R; A_T] x = [b_R; b_T]): per term τ the texgen pass (runtime/texgen.h) that
// looks the layer's cube map up at each vertex's exit-ray hit on the layer's shell; raster/'s
// rendering matrix of that pass (linear profile: llvmpipe's texel selection and weights), the
// target = the traced layer image layer_l_τ un-premultiplied by the lens coverage (b_τ's
// alpha), weighted by confidence_τ × coverage; the terms' rows stacked; BuildSystem with the
// active texels (observed + rings), LSMR with bounds ([0, 1] or HDR), FillUnobserved, files.
// `single`: one more map, `single`, from the whole exit radiance b_τ on one sphere.
// With `neighbours` = k, the layer maps' systems also hold the rows of the k samples on each side
// (their own vertex paths, texgen and traced layer images, confidence × neighbourWeight): the
// simultaneous solve of hybrid §4.3, so a map also fits what is seen just off its sample.
// Mirror-only groups also get the PEM paper's split (PEM mode texgen: the eye ray reflected off
// each vertex normal): `local` on the ellipsoid shell and `distant` on the box.
// Figures per map: rows, cols, nnz, seconds to build and solve, iterations, rmse (the linear
// model, float texels), rmse_8bit (raster/'s llvmpipe profile with the 8-bit copy), texel range,
// filled texels; with `direct` also the direct solver's rmse_8bit (when it fits).
// Files under outDir: view_v/group_g/<name>.exr (tiled mip-mapped cube, pem_file.h),
// <name>.png (the 8-bit copy: level l's six faces side by side, levels stacked), <name>.csv (the
// solve log); manifest.json and infer.json are written by the caller (viewer_tty/cmd_infer.cpp)
// from the report. --export-system writes per map <dir>/<name>_{K,h,x}.mtx + .json.
// Not here: argument parsing and JSON (viewer_tty/cmd_infer.cpp), rendering with PEMs
// (runtime/renderer.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "infer/problem.h"
#include "infer/solver.h"
#include "raster/camera.h"
#include "trace/shell.h"

namespace pem::infer {

// What `pemref trace` wrote (trace.json), as inference needs it.
struct TracedLayer {
    trace::Shell shell;
    std::string kind;  // "sphere", "quad", ...
    double radius = 0.0;
    int64_t records = 0;
};
struct TracedGroup {
    int index = 0;
    std::vector<std::string> objects;
    bool glass = false;
    glm::vec3 emOrigin{0.0f};
    std::vector<TracedLayer> layers;
    bool pem = false;  // mirror-only: local/distant shells below
    trace::Shell localShell, distantShell;
    trace::Shell singleShell;  // runtime/pem_set.h SingleLayerShell
};
struct TraceManifest {
    std::string dir, scenePath;
    int width = 0, height = 0, spp = 1;
    std::vector<raster::Camera> views;
    std::vector<TracedGroup> groups;
};
TraceManifest ReadTraceManifest(const std::string& traceDir);

struct InferRunOptions {
    std::string traceDir, outDir, exportDir;
    int res = 256;
    int threads = 1;
    bool hdr = false;              // float radiance, bounds [0, inf)
    double tessT = 5.0;            // tessellation t in subpixels (1 / spp pixels)
    std::vector<int> views;        // empty: all
    bool single = false;           // also the single-layer map (`single`, both terms)
    int neighbours = 0;            // samples on each side in the simultaneous solve (hybrid §4.3)
    double neighbourWeight = 0.5;  // their rows' confidence factor
    bool direct = false;           // also solve with the direct oracle (when it fits)
    int64_t directMaxCols = 400000;  // unknowns (4 per texel) the direct solver may take
    RegularizerWeights weights;
    SystemOptions system{2};
    SolveOptions solve;
    std::function<void(const std::string& stage, double fraction)> progress;
};

struct MapReport {
    int view = 0, group = 0, layer = 0;
    std::string term;  // "R", "T", or "pem" (local/distant split)
    std::string name;  // file stem under view_v/group_g/
    int64_t rows = 0, cols = 0, nnz = 0;
    int64_t observedTexels = 0, filledTexels = 0;
    double buildSeconds = 0.0, solveSeconds = 0.0;
    int iterations = 0;
    std::string stop;
    double rmse = 0.0, rmse8 = 0.0, objective = 0.0;
    double texelMin = 0.0, texelMax = 0.0;
    double directRmse8 = -1.0, directSeconds = 0.0;  // < 0: not run
    // Where the time goes (seconds): raster's rendering matrix (part of buildSeconds), one
    // forward render of the same pass (the rmse_8bit render), FillUnobserved and the files.
    double matrixSeconds = 0.0, renderSeconds = 0.0, fillSeconds = 0.0, writeSeconds = 0.0;
};

struct SampleReport {
    int view = 0;
    double seconds = 0.0;      // the whole sample: paths, every map
    double pathSeconds = 0.0;  // vertex rays and tessellation
    uint64_t vertexRays = 0;
    size_t triangles = 0;
};

// Work the job decided not to do (issue 6: "leave out what the scene does not need").
struct LeftOut {
    int view = 0, group = 0;
    std::string what, why;
};

struct InferRunReport {
    TraceManifest trace;
    std::vector<MapReport> maps;
    std::vector<SampleReport> samples;
    std::vector<LeftOut> leftOut;
    double seconds = 0.0;
};

InferRunReport RunInfer(const InferRunOptions& options);

}  // namespace pem::infer
