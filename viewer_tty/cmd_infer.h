// SPDX-License-Identifier: MIT
// cmd_infer.h — `pemref infer`: layered EMs for every viewpoint sample of a trace directory
// (infer/infer_run.h).
//   pemref infer TRACE_DIR --out PEM_DIR [--res N] [--threads N] [--views I,J,...] [--hdr]
//                [--t T] [--direct] [--export-system DIR] [--max-iterations N]
//                [--smooth L] [--pyramid L] [--prior L] [--quiet]
// Outputs: the PEM files of infer_run.h, PEM_DIR/manifest.json (scene, views, groups, shells,
// EM origins, resolution, profile, file of every map) and PEM_DIR/infer.json (per map: rows,
// cols, nnz, build_seconds, solve_seconds, iterations, rmse, rmse_8bit, texel_min, texel_max,
// ...; per sample: seconds). Errors: one line, exit 1 (main.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pem::cli {

void AddInferCommand(CLI::App& app);
int RunInferCommand();

// Writes JSON text to path through a temporary file and a rename (InputError on failure).
void WriteTextAtomic(const std::string& path, const std::string& text);

}  // namespace pem::cli
