// SPDX-License-Identifier: MIT
// cmd_view.h — `pemref view`: the interactive terminal viewer (viewer.h) on the run-time
// renderer (runtime/renderer.h).
//   pemref view PEM_DIR [--threads N] [--t T] [--keys KEYS --frames N] [--cols C --rows R]
//                [--mode hybrid|pem|static|traced|difference] [--quiet]
// Keys (viewer.h): h/l or ←/→ azimuth, k/j or ↑/↓ elevation, +/- zoom, u/d off the sample
// circle, 1..5 or m modes, [ ] t, r reset, q quit. The ray-traced mode uses one sample per pixel;
// "difference" shows |hybrid − ray traced| × 4 and puts the lens PSNR in the status line.
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddViewCommand(CLI::App& app);
int RunViewCommand();

}  // namespace pem::cli
