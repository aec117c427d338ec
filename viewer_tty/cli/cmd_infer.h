// SPDX-License-Identifier: MIT
// cmd_infer.h — `pemref infer`: layered EMs for every viewpoint sample of a trace directory
// (pipeline/infer_job.h).
//   pemref infer TRACE_DIR --out PEM_DIR [--res N] [--threads N] [--views I,J,...] [--hdr]
//                [--t T] [--neighbours K] [--single] [--direct] [--export-system DIR]
//                [--max-iterations N] [--smooth L] [--pyramid L] [--prior L] [--quiet]
// Outputs: the maps (pipeline/layout.h), manifest.json (pipeline/pem_manifest.h) and infer.json
// (pipeline/infer_report.h). Errors: one line, exit 1 (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddInferCommand(CLI::App& app);
int RunInferCommand();

}  // namespace pem::cli
