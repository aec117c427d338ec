// SPDX-License-Identifier: MIT
// cmd_infer.cpp — options, progress and summary of `pemref infer` (cmd_infer.h).
#include "viewer_tty/cli/cmd_infer.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

#include "base/directory_lock.h"
#include "base/input_error.h"
#include "pipeline/infer_job.h"
#include "viewer_tty/cli/args.h"

namespace pem::cli {
namespace {

struct InferArgs {
    pipeline::InferJobOptions job;
    std::string views;
    bool quiet = false;
    CLI::Option* smooth = nullptr;   // given or not: the default depends on --map-format
    CLI::Option* lodBias = nullptr;  // the same
};

InferArgs& Args() {
    static InferArgs args;
    return args;
}

std::vector<int> ParseViewList(const std::string& text) {
    std::vector<int> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < 0 || v > 1000000)
            throw base::InputError("--views " + text, "expected a comma-separated list of indices");
        out.push_back(static_cast<int>(v));
    }
    return out;
}

void CreateDirectory(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw base::InputError(dir, "cannot create the directory: " + ec.message());
}

}  // namespace

void AddInferCommand(CLI::App& app) {
    InferArgs& a = Args();
    pipeline::InferJobOptions& o = a.job;
    CLI::App* sub = app.add_subcommand(
        "infer", "infer layered environment maps (all MIP levels) from a pemref trace directory");
    sub->add_option("trace_dir", o.traceDir, "output directory of pemref trace")->required();
    sub->add_option("--out", o.outDir, "PEM directory")->required();
    AddMapSizeOptions(sub, &o.res, &o.maxRes);
    AddParameterizationOption(sub, &o.parameterization);
    sub->add_option("--threads", o.threads, "worker threads")->check(CLI::Range(1, 256));
    a.lodBias = AddMapHardwareOptions(sub, &o.hardware);
    sub->add_option("--views", a.views, "viewpoint samples to infer, e.g. 0,2 (default: all)");
    sub->add_option("--neighbours", o.neighbours,
                    "samples on each side in the simultaneous solve (hybrid §4.3)")
        ->check(CLI::Range(0, 8));
    AddTessellationOptions(sub, &o.tessT, &o.alsoTessT, &o.topologyT);
    sub->add_option("--max-iterations", o.solve.maxIterations, "LSMR iterations per map")
        ->check(CLI::Range(1, 100000));
    char smoothHelp[96];
    std::snprintf(smoothHelp, sizeof smoothHelp, "lambda_s (default %g; float maps %g)",
                  pipeline::DefaultSmooth(raster::TexelFormat::Rgba8),
                  pipeline::DefaultSmooth(raster::TexelFormat::Rgba32F));
    a.smooth =
        sub->add_option("--smooth", o.weights.smooth, smoothHelp)->check(CLI::Range(0.0, 1e6));
    sub->add_option("--pyramid", o.weights.pyramid, "lambda_p")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--prior", o.weights.prior, "lambda_0")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--export-system", o.exportDir, "write K, h, x in Matrix Market format");
    sub->add_flag("--hdr", o.hdr, "float maps bounded below by 0 only (default: 8-bit [0, 1])");
    sub->add_flag("--single", o.single, "also the single-layer map per term (for comparisons)");
    sub->add_flag("--direct", o.direct, "also run the direct solver (small systems)");
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunInferCommand() {
    const InferArgs& a = Args();
    pipeline::InferJobOptions o = a.job;
    if (a.smooth->count() == 0) o.weights.smooth = pipeline::DefaultSmooth(o.hardware.format);
    if (a.lodBias->count() == 0) o.hardware.lodBias = pipeline::DefaultLodBias(o.hardware.format);
    o.views = a.views.empty() ? std::vector<int>{} : ParseViewList(a.views);
    CreateDirectory(o.outDir);
    if (!o.exportDir.empty()) CreateDirectory(o.exportDir);
    const base::DirectoryLock lock(o.outDir);
    tty::ProgressLine line("pemref infer", a.quiet);
    o.progress = ProgressTo(&line);
    const pipeline::InferJobResult r = pipeline::RunInferJob(o);
    line.Finish();
    pipeline::WriteInferOutputs(o, r);
    if (!a.quiet)
        std::printf("inferred %zu map(s) for %zu sample(s) in %.2f s -> %s\n", r.maps.size(),
                    r.samples.size(), r.seconds, o.outDir.c_str());
    return 0;
}

}  // namespace pem::cli
