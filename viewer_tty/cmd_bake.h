// SPDX-License-Identifier: MIT
// cmd_bake.h — `pemref bake`: the whole pipeline for a scene, resumable.
//   pemref bake SCENE.gltf --out DIR [--views camera|circle:N:STEP_DEG] [--res N] [--size WxH]
//               [--spp K] [--layers L] [--neighbours K] [--jobs J] [--threads T] [--quiet]
// Steps: DIR/trace (pemref trace over every viewpoint: layers are clustered over all of them, so
// it is one step, skipped when DIR/trace/trace.json exists — written last), then per viewpoint
// sample the inference (with K samples on each side in the simultaneous solve) into
// DIR/pem/view_<v>/ (J samples at a time, T threads each), closed by
// DIR/pem/view_<v>/sample.json (written last: the sample is done), then DIR/pem/infer.json and
// manifest.json for all samples. Every file is written to a temporary name and renamed; a
// bake killed at any moment and started again removes the temporaries, skips what is done and
// produces the same bytes as an uninterrupted bake. A progress line with an ETA on a terminal.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pem::cli {

struct BakeJob {
    std::string scene, out, views = "circle:3:10", size = "640x480";
    int res = 128, spp = 3, layers = 2, jobs = 1, threads = 1, neighbours = 1;
    bool quiet = false;
};

void AddBakeCommand(CLI::App& app);
int RunBakeCommand();
int RunBakeJob(const BakeJob& job);

}  // namespace pem::cli
