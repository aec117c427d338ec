// SPDX-License-Identifier: MIT
// cmd_trace.h — `pemref trace`: ray-trace a glTF scene from one or more viewpoints and write the
// reference images, the segmented two-term images, layers and shells (pipeline/trace_job.h).
//   pemref trace SCENE.gltf --out DIR [--views camera|circle:N:STEP_DEG] [--spp K]
//                [--size WxH] [--threads N] [--layers N] [--full-tree-depth D]
//                [--fresnel exact|schlick] [--exposure E] [--frames-only] [--quiet]
// Outputs: pipeline/layout.h. PNG previews are tone-mapped (×exposure, clamp, sRGB).
// A progress line with an ETA goes to stderr only when stderr is a TTY and --quiet is not set.
// Errors: one line `pemref: <file>: <cause>` (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddTraceCommand(CLI::App& app);
int RunTraceCommand();

}  // namespace pem::cli
