// SPDX-License-Identifier: MIT
// cmd_study.cpp — options of `pemref study` (cmd_study.h).
#include "viewer_tty/cli/cmd_study.h"

#include <chrono>
#include <cstdio>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "viewer_tty/cli/args.h"
#include "viewer_tty/report/layout_study.h"
#include "viewer_tty/report/layout_study_writer.h"

namespace pem::cli {
namespace {

struct StudyArgs {
    report::LayoutStudyOptions job;
    std::vector<std::string> layouts;
    std::string size = "320x240";
    bool quiet = false;
};

StudyArgs& Args() {
    static StudyArgs args;
    return args;
}

std::vector<runtime::Parameterization> ParseLayouts(const std::vector<std::string>& names) {
    std::vector<runtime::Parameterization> out;
    for (const std::string& n : names) {
        const auto p = runtime::ParseParameterization(n);
        if (!p) throw base::InputError("--layouts " + n, "unknown parameterization");
        out.push_back(*p);
    }
    return out;
}

}  // namespace

void AddStudyCommand(CLI::App& app) {
    StudyArgs& a = Args();
    report::LayoutStudyOptions& o = a.job;
    CLI::App* sub = app.add_subcommand(
        "study", "the five environment-map parameterizations inferred and compared");
    sub->add_option("scenes", o.scenes, "scenes (.gltf/.glb)")->required();
    sub->add_option("--out", o.outDir, "output directory")->required();
    sub->add_option("--layouts", a.layouts, "cube,latlong,sphere,paraboloid,tennis (default all)")
        ->delimiter(',');
    sub->add_option("--sizes", o.sizes, "map sizes (LayoutOf's n), e.g. 8,16,32,64")
        ->delimiter(',');
    sub->add_option("--views", o.views, "circle:N:STEP_DEG");
    sub->add_option("--size", a.size, "image size WxH");
    sub->add_option("--spp", o.spp, "K: the trace's K×K samples per pixel")
        ->check(CLI::Range(1, 16));
    sub->add_option("--reference-spp", o.referenceSpp, "K: the reference's K×K samples")
        ->check(CLI::Range(1, 16));
    sub->add_option("--threads", o.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunStudyCommand() {
    StudyArgs& a = Args();
    report::LayoutStudyOptions o = a.job;
    std::tie(o.width, o.height) = ParseSize(a.size);
    if (!a.layouts.empty()) o.layouts = ParseLayouts(a.layouts);
    const auto t0 = std::chrono::steady_clock::now();
    tty::ProgressLine line("pemref study", a.quiet);
    if (line.Enabled()) o.progress = [&line](const std::string&, double f) { line.Update(f); };
    // The whole study in a temporary directory that replaces DIR when it is done.
    const std::string outDir = o.outDir;
    base::WriteDirectoryAtomically(outDir, "study.json", [&](const std::string& tmp) {
        o.outDir = tmp;
        report::WriteLayoutStudy(report::RunLayoutStudy(o), tmp);
    });
    line.Finish();
    if (!a.quiet)
        std::printf(
            "study of %zu layout(s) x %zu size(s) on %zu scene(s) in %.1f s -> "
            "%s/study.md, study.svg, study.json\n",
            o.layouts.size(), o.sizes.size(), o.scenes.size(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            o.outDir.c_str());
    return 0;
}

}  // namespace pem::cli
