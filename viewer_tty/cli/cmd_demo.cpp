// SPDX-License-Identifier: MIT
// cmd_demo.cpp — bake + report of the bundled scene (cmd_demo.h).
#include "viewer_tty/cli/cmd_demo.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "base/input_error.h"
#include "viewer_tty/cli/args.h"
#include "viewer_tty/cli/cmd_bake.h"
#include "viewer_tty/cli/cmd_report.h"

#ifndef PEM_SOURCE_DIR
#define PEM_SOURCE_DIR "."
#endif

namespace pem::cli {
namespace {

struct DemoArgs {
    std::string out = "out/demo", scene, size = "640x480";
    int res = pipeline::DemoBakeOptions().infer.res,
        maxRes = pipeline::DemoBakeOptions().infer.maxRes;
    int threads = 2;
    bool quiet = false;
};

DemoArgs& Args() {
    static DemoArgs args;
    return args;
}

}  // namespace

void AddDemoCommand(CLI::App& app) {
    DemoArgs& a = Args();
    CLI::App* sub = app.add_subcommand("demo", "bake the bundled scene (a) and write the report");
    sub->add_option("--out", a.out, "output directory");
    sub->add_option("--scene", a.scene, "scene (default: the bundled scene (a))");
    sub->add_option("--size", a.size, "image size WxH");
    AddMapSizeOptions(sub, &a.res, &a.maxRes);
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_flag("--quiet", a.quiet, "no progress lines");
}

int RunDemoCommand() {
    const DemoArgs& a = Args();
    const auto t0 = std::chrono::steady_clock::now();
    pipeline::BakeJobOptions bake = pipeline::DemoBakeOptions();
    bake.trace.scene = a.scene.empty()
                           ? std::string(PEM_SOURCE_DIR) + "/data/scenes/hybrid_glass_teapot.gltf"
                           : a.scene;
    if (!std::filesystem::exists(bake.trace.scene))
        throw base::InputError(bake.trace.scene, "scene not found");
    bake.outDir = a.out;
    std::tie(bake.trace.width, bake.trace.height) = ParseSize(a.size);
    bake.infer.res = a.res;
    bake.infer.maxRes = a.maxRes;
    bake.threads = a.threads;
    RunBake(bake, a.quiet);
    report::ReportJobOptions report;
    report.dir = a.out;
    report.threads = a.threads;
    RunReport(report, a.quiet);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf(
        "\npemref demo done in %.0f s. Outputs under %s/:\n"
        "  report.md, report.svg, report.json   error against run time, left-out work, stability\n"
        "  budget.svg, packs.svg                the error budget; packed PEMs' size against PSNR\n"
        "  views/<position>_<method>.png        the frames compared (reference = 6x6 ray traced)\n"
        "  trace/                               ray-traced images, layers, trace.json\n"
        "  pem/                                 the inferred maps (EXR + 8-bit PNG), infer.json\n"
        "Look around: pemref view %s/pem   (q quits)\n",
        seconds, a.out.c_str(), a.out.c_str());
    return 0;
}

}  // namespace pem::cli
