// SPDX-License-Identifier: MIT
// bake_job.h — trace and infer every viewpoint sample of a scene, resumable: killed at any
// moment and started again, it produces the same bytes as an uninterrupted run.
//
//   BakeJobOptions o;  o.trace.scene = "scene.gltf";  o.outDir = "out/bake";
//   RunBakeJob(o);     // out/bake/trace, out/bake/pem (layout.h)
//
// Steps: the directory is locked (a second bake into it refuses: base/directory_lock.h);
// temporaries a killed run left are removed; bake.json records the options the files depend on
// (scene, views, size, spp, layers, res, max-res, parameterization, neighbours, the map
// hardware; not jobs or threads), and a bake resumed with other ones is refused
// (base::InputError naming bake.json and the option; a directory from before bake.json is
// trusted and gets one); the trace (one step: its layers span every
// viewpoint) unless trace.json exists; every sample without its sample.json, `jobs` samples at
// a time, each written whole before its sample.json; infer.json and manifest.json over every
// sample. The maps do not depend on `jobs` or the thread counts.
// Not here: argument parsing (viewer_tty/cli/cmd_bake.cpp).
#pragma once

#include <functional>
#include <string>

#include "pipeline/infer_job.h"
#include "pipeline/trace_job.h"

namespace pem::pipeline {

struct BakeJobOptions {
    std::string outDir;
    TraceJobOptions trace;  // scene, views, size, spp, layers (outDir and threads are set here)
    InferJobOptions infer;  // res, neighbours, solver (dirs, views and threads are set here)
    int jobs = 1;           // samples inferred at once
    int threads = 1;        // threads per job (the trace uses jobs × threads)
    // Progress: fraction of the samples done; called from the job threads, one at a time.
    std::function<void(double fraction)> progress;
    std::function<void(const std::string& line)> log;  // one line per step started
};

struct BakeJobResult {
    int samples = 0;
    size_t maps = 0;
};

// Bake defaults: three samples 10° apart, 640×480, 3×3 samples, each sample's maps from its own
// images (neighbours = 0: fitted sample by sample, the neighbours' rows cost twice the time and
// memory and gave 0.1 dB 10° above the circle, on the circle 0.1 dB less), the single-layer
// maps too (the report compares them).
BakeJobOptions DefaultBakeOptions();
// The demo's bake (`pemref demo`): the defaults with maps as close to the traced frame as the
// hardware draws them — float maps (highlights above white, negative texels; RGBA32F), each
// map's face size from its test rendering between 256 and 512 (PEM §4), tessellation t = 1
// subpixel (hybrid §5) and also the renderers' default t (alsoTessT: fitted at t = 1 alone, the
// hybrid at t = 5 lost 5 dB at the samples of the PEM teapot), the float maps' smoothing
// (DefaultSmooth) — about four times the inference time of the defaults.
BakeJobOptions DemoBakeOptions();

BakeJobResult RunBakeJob(const BakeJobOptions& options);

}  // namespace pem::pipeline
