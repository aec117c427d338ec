// SPDX-License-Identifier: MIT
// cmd_trace.cpp — options and summary line of `pemref trace` (cmd_trace.h).
#include "viewer_tty/cli/cmd_trace.h"

#include <cstdio>
#include <filesystem>
#include <string>

#include "base/directory_lock.h"
#include "base/input_error.h"
#include "pipeline/trace_job.h"
#include "viewer_tty/cli/args.h"

namespace pem::cli {
namespace {

struct TraceArgs {
    pipeline::TraceJobOptions job;
    std::string size = "640x480", fresnel = "exact";
    bool quiet = false, framesOnly = false;
};

TraceArgs& Args() {
    static TraceArgs args;
    return args;
}

}  // namespace

void AddTraceCommand(CLI::App& app) {
    TraceArgs& a = Args();
    pipeline::TraceJobOptions& o = a.job;
    CLI::App* sub = app.add_subcommand("trace",
                                       "ray-trace a glTF scene: reference, segmented "
                                       "two-term images, layers (OpenEXR + PNG)");
    sub->add_option("scene", o.scene, "scene (.gltf/.glb)")->required();
    sub->add_option("--out", o.outDir, "output directory")->required();
    sub->add_option("--views", o.views, "camera | circle:N:STEP_DEG");
    sub->add_option("--spp", o.spp, "K: K×K supersamples per pixel")->check(CLI::Range(1, 16));
    sub->add_option("--size", a.size, "image size WxH");
    sub->add_option("--threads", o.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--layers", o.layers, "number of EM layers (LBG)")->check(CLI::Range(1, 16));
    sub->add_option("--full-tree-depth", o.trace.fullTreeDepth, "interface events per branch")
        ->check(CLI::Range(1, 32));
    sub->add_option("--fresnel", a.fresnel, "dielectric Fresnel")
        ->check(CLI::IsMember({"exact", "schlick"}));
    sub->add_option("--exposure", o.exposure, "PNG preview exposure")->check(CLI::Range(0.0, 1e6));
    sub->add_flag("--frames-only", a.framesOnly, "only the reference and greedy frames");
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunTraceCommand() {
    const TraceArgs& a = Args();
    pipeline::TraceJobOptions o = a.job;
    std::tie(o.width, o.height) = ParseSize(a.size);
    o.trace.fresnel =
        a.fresnel == "schlick" ? trace::FresnelModel::Schlick : trace::FresnelModel::Exact;
    o.segment = !a.framesOnly;
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    if (ec) throw base::InputError(o.outDir, "cannot create the directory: " + ec.message());
    const base::DirectoryLock lock(o.outDir);
    tty::ProgressLine line("pemref trace", a.quiet);  // only on a terminal
    o.progress = ProgressTo(&line);
    const pipeline::TraceManifest m = pipeline::RunTraceJob(o);
    line.Finish();
    if (!a.quiet)
        std::printf("traced %zu viewpoint(s): %llu rays in %.2f s -> %s\n", m.views.size(),
                    static_cast<unsigned long long>(m.rays.Total()), m.seconds, o.outDir.c_str());
    return 0;
}

}  // namespace pem::cli
