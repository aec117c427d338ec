// SPDX-License-Identifier: MIT
// cmd_demo.h — `pemref demo`: the main job on the bundled default scene (a).
//   pemref demo [--out DIR] [--scene SCENE.gltf] [--size WxH] [--res N] [--threads N] [--quiet]
// Bakes scene (a) (3 viewpoint samples 10° apart, 3×3 supersampling; `pemref bake`), renders
// it on the sample circle, between two samples and 10° above the circle with every method and
// writes the error-against-run-time report (`pemref report`), then prints where everything is.
// Resumable like bake: started again, it reuses what is done.
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddDemoCommand(CLI::App& app);
int RunDemoCommand();

}  // namespace pem::cli
