// SPDX-License-Identifier: MIT
// cmd_bake.cpp — options, progress and summary of `pemref bake` (cmd_bake.h).
#include "viewer_tty/cli/cmd_bake.h"

#include <chrono>
#include <cstdio>
#include <string>

#include "pipeline/layout.h"
#include "viewer_tty/cli/args.h"

namespace pem::cli {
namespace {

struct BakeArgs {
    pipeline::BakeJobOptions job = pipeline::DefaultBakeOptions();
    std::string size = "640x480";
    bool quiet = false;
    CLI::Option* lodBias = nullptr;  // given or not: the default depends on --map-format
};

BakeArgs& Args() {
    static BakeArgs args;
    return args;
}

}  // namespace

void AddBakeCommand(CLI::App& app) {
    BakeArgs& a = Args();
    pipeline::BakeJobOptions& o = a.job;
    CLI::App* sub =
        app.add_subcommand("bake", "trace and infer every viewpoint sample of a scene (resumable)");
    sub->add_option("scene", o.trace.scene, "scene (.gltf/.glb)")->required();
    sub->add_option("--out", o.outDir, "output directory (DIR/trace, DIR/pem)")->required();
    sub->add_option("--views", o.trace.views, "camera | circle:N:STEP_DEG");
    AddMapSizeOptions(sub, &o.infer.res, &o.infer.maxRes);
    AddParameterizationOption(sub, &o.infer.parameterization);
    sub->add_option("--size", a.size, "image size WxH");
    sub->add_option("--spp", o.trace.spp, "K: K×K supersamples per pixel")
        ->check(CLI::Range(1, 16));
    sub->add_option("--layers", o.trace.layers, "EM layers (LBG)")->check(CLI::Range(1, 16));
    sub->add_option("--neighbours", o.infer.neighbours,
                    "samples on each side in the simultaneous solve (hybrid §4.3)")
        ->check(CLI::Range(0, 8));
    sub->add_option("--jobs", o.jobs, "viewpoint samples inferred at once")
        ->check(CLI::Range(1, 64));
    sub->add_option("--threads", o.threads, "threads per job")->check(CLI::Range(1, 256));
    a.lodBias = AddMapHardwareOptions(sub, &o.infer.hardware);
    AddTessellationOptions(sub, &o.infer.tessT, &o.infer.alsoTessT, &o.infer.topologyT);
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunBakeCommand() {
    const BakeArgs& a = Args();
    pipeline::BakeJobOptions o = a.job;
    std::tie(o.trace.width, o.trace.height) = ParseSize(a.size);
    o.infer.weights.smooth = pipeline::DefaultSmooth(o.infer.hardware.format);
    if (a.lodBias->count() == 0)
        o.infer.hardware.lodBias = pipeline::DefaultLodBias(o.infer.hardware.format);
    RunBake(o, a.quiet);
    return 0;
}

void RunBake(pipeline::BakeJobOptions o, bool quiet) {
    const auto t0 = std::chrono::steady_clock::now();
    tty::ProgressLine line("pemref bake", quiet);
    if (line.Enabled()) o.progress = [&line](double f) { line.Update(f); };
    if (!quiet)
        o.log = [](const std::string& s) { std::fprintf(stderr, "pemref bake: %s\n", s.c_str()); };
    const pipeline::BakeJobResult r = pipeline::RunBakeJob(o);
    line.Finish();
    if (!quiet)
        std::printf("baked %d viewpoint sample(s) (%zu maps) in %.1f s -> %s\n", r.samples, r.maps,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                    pipeline::BakePemDir(o.outDir).c_str());
}

}  // namespace pem::cli
