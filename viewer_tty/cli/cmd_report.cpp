// SPDX-License-Identifier: MIT
// cmd_report.cpp — options of `pemref report` (cmd_report.h).
#include "viewer_tty/cli/cmd_report.h"

#include <cstdio>
#include <string>

#ifndef PEM_BUILD_FLAGS
#define PEM_BUILD_FLAGS "unknown"
#endif
#ifndef PEM_COMPILER
#define PEM_COMPILER "unknown"
#endif
#ifndef PEM_SOURCE_DIR
#define PEM_SOURCE_DIR ""
#endif

namespace pem::cli {
namespace {

struct ReportArgs {
    report::ReportJobOptions job;
    bool quiet = false;
};

ReportArgs& Args() {
    static ReportArgs args;
    return args;
}

}  // namespace

void AddReportCommand(CLI::App& app) {
    ReportArgs& a = Args();
    CLI::App* sub = app.add_subcommand("report", "error against run time for every method");
    sub->add_option("dir", a.job.dir, "a pemref bake directory")->required();
    sub->add_option("--reference-spp", a.job.referenceSpp, "K: the reference's K×K samples")
        ->check(CLI::Range(1, 16));
    sub->add_option("--threads", a.job.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_flag(
        "--no-stability", [&a](int64_t) { a.job.stability = false; },
        "leave out the stability suite");
    sub->add_flag(
        "--no-packs", [&a](int64_t) { a.job.packs = false; },
        "leave out the packed PEMs' rate-distortion table");
    sub->add_flag("--quiet", a.quiet, "no progress lines");
}

int RunReportCommand() {
    RunReport(Args().job, Args().quiet);
    return 0;
}

void RunReport(report::ReportJobOptions o, bool quiet) {
    o.buildFlags = PEM_BUILD_FLAGS;
    o.compiler = PEM_COMPILER;
    if (!std::string(PEM_SOURCE_DIR).empty())
        o.dataDir = std::string(PEM_SOURCE_DIR) + "/tests/data";
    if (!quiet)
        o.log = [](const std::string& line) {
            std::fprintf(stderr, "pemref report: %s\n", line.c_str());
        };
    report::RunReportJob(o);
    if (!quiet)
        std::printf("report: %s/report.md, report.svg, report.json; images in %s/views\n",
                    o.dir.c_str(), o.dir.c_str());
}

}  // namespace pem::cli
