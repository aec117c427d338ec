// SPDX-License-Identifier: MIT
// cmd_golden.h — `pemref golden`: golden images made with a hardware profile, which never drift
// (viewer_tty/golden/golden_job.h).
//   pemref golden generate SUITE --out DIR [--profile P] [--hashes-only] [--threads N]
//   pemref golden check SUITE DIR [--junit FILE] [--diff-dir D] [--threads N]
//   pemref golden update SUITE DIR [--threads N]
//   pemref golden compare A.png B.png [--fuzzy D,N] [--diff OUT.png]
//   pemref golden compare --bounds SUITE/TEST IMAGE.png [--lsb N]
// compare --bounds accepts IMAGE when every channel lies within the range the modelled profiles
// span for that suite test (a raster case file may be named directly), widened by N LSB
// (default: the test's bounds_lsb, else 1).
// Output: one line per test (PASS/FAIL, rule, what differed, ꟻLIP mean), the failures'
// picture paths, a summary. Exit code: 0 all pass (compare: accepted), 1 some fail, 2 could
// not run (bad suite, missing files, bad arguments) — one line naming the file and the cause.
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddGoldenCommand(CLI::App& app);
int RunGoldenCommand(const CLI::App& app);

}  // namespace pem::cli
