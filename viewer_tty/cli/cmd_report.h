// SPDX-License-Identifier: MIT
// cmd_report.h — `pemref report`: error against run time for every method on a bake directory
// (viewer_tty/report/report_job.h).
//   pemref report DIR [--reference-spp K] [--threads N] [--no-stability] [--no-packs] [--quiet]
// Outputs: DIR/report.md, report.svg, report.json, budget.svg, packs.svg and DIR/views/*.png.
#pragma once

#include <CLI/CLI.hpp>

#include "viewer_tty/report/report_job.h"

namespace pem::cli {

void AddReportCommand(CLI::App& app);
int RunReportCommand();

// Runs a report with this build's facts filled in (also `pemref demo`'s second step).
void RunReport(report::ReportJobOptions options, bool quiet);

}  // namespace pem::cli
