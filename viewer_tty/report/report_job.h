// SPDX-License-Identifier: MIT
// report_job.h — the measurements behind `pemref report` on a bake directory: every method at
// three camera positions (on the sample circle, between two samples, 10° above), error against a
// K×K ray-traced reference and run time; what the pipeline left out and what that saved; the
// stability suite; the rate–distortion of packed PEMs. Written by report_writer.h as report.md,
// report.svg, report.json, with the frames in DIR/views/<position>_<method>.png.
//
//   ReportJobOptions o;  o.dir = "out/demo";  o.threads = 2;
//   RunReportJob(o);
//
// Not here: argument parsing (viewer_tty/cli/cmd_report.cpp), the documents (report_writer.h).
#pragma once

#include <functional>
#include <string>

namespace pem::report {

struct ReportJobOptions {
    std::string dir;       // a bake directory (dir/trace, dir/pem)
    int referenceSpp = 6;  // the reference's K×K samples
    int threads = 1;
    bool stability = true;  // run the stability suite
    bool packs = true;      // measure packed PEMs (pack_study.h)
    std::string dataDir;    // tests/data for the stability suite's bad scenes ("" = none)
    std::string buildFlags, compiler;                  // what the report records about the build
    std::function<void(const std::string& line)> log;  // one line per frame started
};

void RunReportJob(const ReportJobOptions& options);

}  // namespace pem::report
