// SPDX-License-Identifier: MIT
// cmd_stability.h — `pemref stability`: run the numerical stability suite (stability.h) and
// print one row per case.
//   pemref stability [--json FILE] [--data DIR] [--threads N] [--verbose]
// Output: a table (name, category, PASS/FAIL, residual, condition, seconds, outcome); with
// --verbose each row is followed by the case's expected outcome and detail. --json writes every
// field of every case (NaN figures as null). --data is the repository's tests/data (for
// tests/data/bad_scenes; without it only generated inputs are used).
// Exit code: 0 when every case passes, 1 otherwise. Errors: one line (main.cpp prints what()).
// Not here: the cases themselves (stability*.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

// Adds the `stability` subcommand (its arguments live in cmd_stability.cpp).
void AddStabilityCommand(CLI::App& app);
// Runs it; call when app.got_subcommand("stability"). Returns the exit code.
int RunStabilityCommand();

}  // namespace pem::cli
