// SPDX-License-Identifier: MIT
// cmd_trace.h — `pemref trace`: ray-trace a glTF scene from one or more viewpoints and write the
// reference images, the segmented two-term images, layers and shells (trace/trace_run.h).
//   pemref trace SCENE.gltf --out DIR [--views camera|circle:N:STEP_DEG] [--spp K]
//                [--size WxH] [--threads N] [--layers N] [--full-tree-depth D]
//                [--fresnel exact|schlick] [--exposure E] [--frames-only] [--quiet]
// Outputs: the EXR files of trace_run.h, PNG previews (tone-mapped: ×exposure, clamp, sRGB)
// of reference, greedy, b_τ, local and distant images, and DIR/trace.json. Errors: one line
// `pemref: <file>: <cause>` (main.cpp prints what() of the exception).
// A progress line with an ETA goes to stderr only when stderr is a TTY and --quiet is not set.
// Not here: the tracer (trace/), the interactive viewer.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

namespace pem::cli {

// Everything `pemref trace` takes (its command-line options).
struct TraceJob {
    std::string scene, views = "camera", size = "640x480", out, fresnel = "exact";
    int spp = 3, threads = 1, layers = 2, depth = 6;
    float exposure = 1.0f;
    bool quiet = false, framesOnly = false;
};

// "WxH" → (W, H), both in [1, 16384] (InputError naming --size otherwise).
std::pair<int, int> ParseSize(const std::string& text);

// Runs a trace job (also used by `pemref bake`); trace.json is written last.
int RunTraceJob(const TraceJob& job);

// Adds the `trace` subcommand (its arguments live in cmd_trace.cpp).
void AddTraceCommand(CLI::App& app);
// Runs it; call when app.got_subcommand("trace"). Returns the exit code.
int RunTraceCommand();

}  // namespace pem::cli
