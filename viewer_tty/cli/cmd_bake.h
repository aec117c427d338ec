// SPDX-License-Identifier: MIT
// cmd_bake.h — `pemref bake`: the whole pipeline for a scene, resumable (pipeline/bake_job.h).
//   pemref bake SCENE.gltf --out DIR [--views camera|circle:N:STEP_DEG] [--res N] [--size WxH]
//               [--spp K] [--layers L] [--neighbours K] [--jobs J] [--threads T] [--quiet]
// DIR/trace (pemref trace over every viewpoint), then per viewpoint sample the inference (with
// K samples on each side in the simultaneous solve) into DIR/pem/view_<v>/ (J samples at a time,
// T threads each), closed by its sample.json, then DIR/pem/infer.json and manifest.json. A bake
// killed at any moment and started again produces the same bytes as an uninterrupted bake.
// A progress line with an ETA on a terminal.
#pragma once

#include <CLI/CLI.hpp>

#include "pipeline/bake_job.h"

namespace pem::cli {

void AddBakeCommand(CLI::App& app);
int RunBakeCommand();

// Runs a bake with a progress line and a summary (also `pemref demo`'s first step).
void RunBake(pipeline::BakeJobOptions options, bool quiet);

}  // namespace pem::cli
