// SPDX-License-Identifier: MIT
// cmd_infer.cpp — argument parsing, progress, manifest.json and infer.json for `pemref infer`.
#include "viewer_tty/cmd_infer.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "infer/infer_run.h"
#include "viewer_tty/infer_json.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/progress.h"

namespace pem::cli {
namespace {

using nlohmann::json;

struct InferArgs {
    std::string traceDir, out, views, exportDir;
    int res = 256, threads = 1, neighbours = 0, maxIterations = 150;
    double t = 5.0, smooth = 1e-3, pyramid = 1e-3, prior = 1e-6;
    bool hdr = false, direct = false, single = false, quiet = false;
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
            throw InputError("--views " + text, "expected a comma-separated list of indices");
        out.push_back(static_cast<int>(v));
    }
    return out;
}

}  // namespace

void WriteTextAtomic(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp." + std::to_string(getpid());
    {
        std::ofstream f(tmp);
        f << text;
        if (!f) {
            std::remove(tmp.c_str());
            throw InputError(path, "cannot write");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw InputError(path, "cannot rename");
}

void AddInferCommand(CLI::App& app) {
    InferArgs& a = Args();
    CLI::App* sub = app.add_subcommand(
        "infer", "infer layered environment maps (all MIP levels) from a pemref trace directory");
    sub->add_option("trace_dir", a.traceDir, "output directory of pemref trace")->required();
    sub->add_option("--out", a.out, "PEM directory")->required();
    sub->add_option("--res", a.res, "cube face size N (power of two)");
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--views", a.views, "viewpoint samples to infer, e.g. 0,2 (default: all)");
    sub->add_option("--neighbours", a.neighbours,
                    "samples on each side in the simultaneous solve (hybrid §4.3)")
        ->check(CLI::Range(0, 8));
    sub->add_option("--t", a.t, "tessellation t (subpixels)")->check(CLI::Range(0.25, 1e4));
    sub->add_option("--max-iterations", a.maxIterations, "LSMR iterations per map")
        ->check(CLI::Range(1, 100000));
    sub->add_option("--smooth", a.smooth, "lambda_s")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--pyramid", a.pyramid, "lambda_p")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--prior", a.prior, "lambda_0")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--export-system", a.exportDir, "write K, h, x in Matrix Market format");
    sub->add_flag("--hdr", a.hdr, "float maps bounded below by 0 only (default: 8-bit [0, 1])");
    sub->add_flag("--single", a.single, "also the single-layer map per term (for comparisons)");
    sub->add_flag("--direct", a.direct, "also run the direct solver (small systems)");
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunInferCommand() {
    const InferArgs& a = Args();
    infer::InferRunOptions o;
    o.traceDir = a.traceDir;
    o.outDir = a.out;
    o.exportDir = a.exportDir;
    o.res = a.res;
    o.threads = a.threads;
    o.hdr = a.hdr;
    o.tessT = a.t;
    o.direct = a.direct;
    o.neighbours = a.neighbours;
    o.single = a.single;
    o.views = a.views.empty() ? std::vector<int>{} : ParseViewList(a.views);
    o.weights.smooth = a.smooth;
    o.weights.pyramid = a.pyramid;
    o.weights.prior = a.prior;
    o.solve.maxIterations = a.maxIterations;
    o.solve.logEvery = 25;
    o.solve.atol = 1e-4;
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec) throw InputError(a.out, "cannot create the directory: " + ec.message());
    if (!a.exportDir.empty()) {
        std::filesystem::create_directories(a.exportDir, ec);
        if (ec) throw InputError(a.exportDir, "cannot create the directory: " + ec.message());
    }
    ProgressLine line("pemref infer", a.quiet);
    if (line.Enabled()) o.progress = [&line](const std::string&, double f) { line.Update(f); };
    const infer::InferRunReport r = infer::RunInfer(o);
    line.Finish();

    // infer.json (every figure) and manifest.json (what a renderer needs), infer_json.h.
    json maps = json::array(), samples = json::array();
    for (const infer::MapReport& m : r.maps) maps.push_back(MapJson(m));
    for (const infer::SampleReport& s : r.samples) samples.push_back(SampleJson(s));
    const json inferJson = {
        {"trace_dir", a.traceDir},
        {"res", a.res},
        {"threads", a.threads},
        {"hdr", a.hdr},
        {"lambda", {{"smooth", a.smooth}, {"pyramid", a.pyramid}, {"prior", a.prior}}},
        {"seconds", r.seconds},
        {"samples", samples},
        {"maps", maps},
        {"left_out", LeftOutJson(r.leftOut)}};
    WriteTextAtomic(a.out + "/infer.json", inferJson.dump(2) + "\n");
    WriteTextAtomic(a.out + "/manifest.json",
                    ManifestJson(r.trace, a.traceDir, a.res, a.hdr, o.views).dump(2) + "\n");
    if (!a.quiet)
        std::printf("inferred %zu map(s) for %zu sample(s) in %.2f s -> %s\n", r.maps.size(),
                    r.samples.size(), r.seconds, a.out.c_str());
    return 0;
}

}  // namespace pem::cli
