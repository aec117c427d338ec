// SPDX-License-Identifier: MIT
// cmd_render.h — `pemref render`: one frame at any viewpoint from a PEM directory
// (runtime/renderer.h), with the hybrid paper's per-frame statistics.
//   pemref render PEM_DIR [--view sample:I|orbit:AZ:EL:DIST|camera] [--size WxH] -o OUT.png|exr
//                 [--method hybrid|pem|static|traced] [--t T] [--spp K] [--layers 0|1]
//                 [--threads N] [--stats FILE.json] [--exposure E] [--quiet]
// orbit: degrees added to the first sample's azimuth and elevation about the lens centre, DIST
// scales its distance. --stats also ray-traces the same frame at K×K (the paper's comparison)
// and reports times, rays, reduction factors and the error against it.
// Errors: one line, exit 1 (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddRenderCommand(CLI::App& app);
int RunRenderCommand();

}  // namespace pem::cli
