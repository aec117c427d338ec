// SPDX-License-Identifier: MIT
// cmd_raster.h — `pemref raster`: render a raster case file (gl_ref_case/1 and pemref's
// superset, docs/raster-case-format.md) with raster/ and print the SHA-256 of its RGBA8 pixels.
//   pemref raster CASE.json [-o out.png] [--profile llvmpipe|linear] [--threads N] [--repeat N]
//                 [--matrix out.mtx] [--rounding rne|d3d] [--cube-lod llvmpipe|exact]
// --repeat N adds frame_ms_median (rendering only); --matrix writes the rendering matrix A,
// the rendered frame (out.rendered.mtx) and the constant term (out.offset.mtx).
// Errors: one line, exit 1 (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddRasterCommand(CLI::App& app);
int RunRasterCommand();

}  // namespace pem::cli
