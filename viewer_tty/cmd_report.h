// SPDX-License-Identifier: MIT
// cmd_report.h — `pemref report`: error against run time for every method on a baked scene.
//   pemref report DIR [--reference-spp K] [--threads N] [--no-stability] [--quiet]
// DIR is a `pemref bake` directory (DIR/trace, DIR/pem). Three camera positions: on the sample
// circle (a viewpoint sample), between two samples (half the azimuth step), and 10° above the
// circle there. Methods: static EM, single-layer PEM, layered PEM, hybrid t = 3 and t = 5, the
// ray tracer at 1, 4, 9 and 16 samples per pixel. Reference: the ray tracer at K×K (default 6,
// converged for this deterministic tracer up to pixel aliasing). Scores (RMSE, PSNR, SSIM, in
// float and after 8-bit) over the pixels where the reference sees a lens object; run time is the
// whole frame, measured warm (maps loaded). Also: what the pipeline left out (from DIR's
// trace.json and infer.json and a hybrid frame's statistics) and the stability suite.
// Outputs DIR/report.md, DIR/report.svg, DIR/report.json and DIR/views/<position>_<method>.png.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pem::cli {

struct ReportJob {
    std::string dir;
    int referenceSpp = 6, threads = 1;
    bool stability = true, quiet = false;
};

void AddReportCommand(CLI::App& app);
int RunReportCommand();
int RunReportJob(const ReportJob& job);

}  // namespace pem::cli
