// SPDX-License-Identifier: MIT
// trace_job.h — the whole `pemref trace` job: viewpoint samples → reference and greedy frames,
// per-lens-group segmented images, layers over all viewpoints, layer images, all as float
// OpenEXR files (with PNG previews) under one directory, and trace.json.
//
//   TraceJobOptions o;  o.scene = "data/scenes/x.gltf";  o.outDir = "out/trace";
//   o.views = "circle:3:10";  TraceManifest t = RunTraceJob(o);
//
// Files: layout.h. Order of work: for each viewpoint the frames and segmentation, then the
// layers (all viewpoints' records at once), then every viewpoint's layer images. The bytes of
// every image are independent of the thread count.
// Not here: argument parsing (viewer_tty/cli/cmd_trace.cpp).
#pragma once

#include <functional>
#include <string>

#include "pipeline/trace_manifest.h"
#include "trace/tracer.h"

namespace pem::pipeline {

struct TraceJobOptions {
    std::string scene, outDir;
    std::string views = "camera";  // camera | circle:N:STEP_DEG (viewpoints.h)
    int width = 640, height = 480;
    int spp = 3;  // K×K supersamples per pixel
    int threads = 1;
    int layers = 2;  // N for the LBG clustering
    trace::TraceOptions trace;
    float exposure = 1.0f;  // of the PNG previews
    bool segment = true;    // false: only the reference and greedy frames
    // Progress: the stage's name and the fraction of the whole job done.
    std::function<void(const std::string& stage, double fraction)> progress;
};

TraceManifest RunTraceJob(const TraceJobOptions& options);

}  // namespace pem::pipeline
