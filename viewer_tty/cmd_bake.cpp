// SPDX-License-Identifier: MIT
// cmd_bake.cpp — the resumable trace → infer pipeline (cmd_bake.h).
#include "viewer_tty/cmd_bake.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "infer/infer_run.h"
#include "viewer_tty/cmd_infer.h"
#include "viewer_tty/cmd_trace.h"
#include "viewer_tty/infer_json.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/progress.h"

namespace pem::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

BakeJob& Args() {
    static BakeJob args;
    return args;
}

std::string SampleDir(const std::string& pemDir, int v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/view_%03d", v);
    return pemDir + buf;
}

// Temporaries a killed run left behind ("<file>.tmp" and "<file>.tmp.<pid>").
void RemoveTemporaries(const std::string& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return;
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().filename().string().find(".tmp") != std::string::npos)
            stale.push_back(e.path());
    for (const fs::path& p : stale) fs::remove(p, ec);
}

}  // namespace

void AddBakeCommand(CLI::App& app) {
    BakeJob& a = Args();
    CLI::App* sub =
        app.add_subcommand("bake", "trace and infer every viewpoint sample of a scene (resumable)");
    sub->add_option("scene", a.scene, "scene (.gltf/.glb)")->required();
    sub->add_option("--out", a.out, "output directory (DIR/trace, DIR/pem)")->required();
    sub->add_option("--views", a.views, "camera | circle:N:STEP_DEG");
    sub->add_option("--res", a.res, "cube face size N (power of two)");
    sub->add_option("--size", a.size, "image size WxH");
    sub->add_option("--spp", a.spp, "K: K×K supersamples per pixel")->check(CLI::Range(1, 16));
    sub->add_option("--layers", a.layers, "EM layers (LBG)")->check(CLI::Range(1, 16));
    sub->add_option("--neighbours", a.neighbours,
                    "samples on each side in the simultaneous solve (hybrid §4.3)")
        ->check(CLI::Range(0, 8));
    sub->add_option("--jobs", a.jobs, "viewpoint samples inferred at once")
        ->check(CLI::Range(1, 64));
    sub->add_option("--threads", a.threads, "threads per job")->check(CLI::Range(1, 256));
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunBakeCommand() {
    return RunBakeJob(Args());
}

int RunBakeJob(const BakeJob& a) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string traceDir = a.out + "/trace", pemDir = a.out + "/pem";
    std::error_code ec;
    fs::create_directories(pemDir, ec);
    if (ec) throw InputError(a.out, "cannot create the directory: " + ec.message());
    RemoveTemporaries(a.out);

    // Step 1: the trace (one step: its layers span every viewpoint).
    if (!fs::exists(traceDir + "/trace.json")) {
        TraceJob t;
        t.scene = a.scene;
        t.views = a.views;
        t.size = a.size;
        t.out = traceDir;
        t.spp = a.spp;
        t.layers = a.layers;
        t.threads = a.threads * a.jobs;
        t.quiet = true;
        if (!a.quiet) std::fprintf(stderr, "pemref bake: tracing %s\n", a.scene.c_str());
        RunTraceJob(t);
    }
    const infer::TraceManifest trace = infer::ReadTraceManifest(traceDir);

    // Step 2: the samples not done yet, `jobs` at a time.
    const int n = static_cast<int>(trace.views.size());
    std::vector<int> todo;
    for (int v = 0; v < n; ++v)
        if (!fs::exists(SampleDir(pemDir, v) + "/sample.json")) todo.push_back(v);
    ProgressLine line("pemref bake", a.quiet);
    const int jobs = std::max(1, std::min<int>(a.jobs, static_cast<int>(todo.size())));
    std::atomic<int> next{0};
    std::atomic<int> done{n - static_cast<int>(todo.size())};
    std::vector<std::atomic<double>> partial(static_cast<size_t>(jobs));
    for (std::atomic<double>& p : partial) p = 0.0;
    std::mutex mutex;
    std::exception_ptr failure;
    auto worker = [&](int job) {
        for (int k = next++; k < static_cast<int>(todo.size()); k = next++) {
            try {
                const int v = todo[static_cast<size_t>(k)];
                infer::InferRunOptions o;
                o.traceDir = traceDir;
                o.outDir = pemDir;
                o.res = a.res;
                o.threads = a.threads;
                o.views = {v};
                o.neighbours = a.neighbours;
                o.single = true;  // the report compares the single-layer PEM
                o.solve.maxIterations = 150;
                o.solve.logEvery = 25;
                o.solve.atol = 1e-4;
                o.progress = [&partial, job](const std::string&, double f) {
                    partial[static_cast<size_t>(job)] = f;
                };
                const infer::InferRunReport r = infer::RunInfer(o);
                json maps = json::array();
                for (const infer::MapReport& m : r.maps) maps.push_back(MapJson(m));
                const json sample = {{"sample", SampleJson(r.samples.at(0))},
                                     {"maps", maps},
                                     {"left_out", LeftOutJson(r.leftOut)}};
                WriteTextAtomic(SampleDir(pemDir, v) + "/sample.json", sample.dump(2) + "\n");
                partial[static_cast<size_t>(job)] = 0.0;
                ++done;
            } catch (...) {
                const std::lock_guard<std::mutex> lock(mutex);
                if (!failure) failure = std::current_exception();
                return;
            }
        }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < jobs && !todo.empty(); ++j) pool.emplace_back(worker, j);
    // The calling thread shows the progress: finished samples plus the running ones' fractions.
    for (;;) {
        double f = done;
        for (const std::atomic<double>& p : partial) f += p;
        line.Update(f / n);
        bool all = true;
        {
            const std::lock_guard<std::mutex> lock(mutex);
            all = failure != nullptr;
        }
        if (all || done >= n || todo.empty()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    for (std::thread& t : pool) t.join();
    line.Finish();
    if (failure) std::rethrow_exception(failure);

    // Step 3: infer.json and manifest.json over every sample.
    json maps = json::array(), samples = json::array(), leftOut = json::array();
    for (int v = 0; v < n; ++v) {
        std::ifstream f(SampleDir(pemDir, v) + "/sample.json");
        const json s = json::parse(f);
        samples.push_back(s.at("sample"));
        for (const json& m : s.at("maps")) maps.push_back(m);
        for (const json& l : s.at("left_out")) leftOut.push_back(l);
    }
    const json inferJson = {{"trace_dir", traceDir},
                            {"res", a.res},
                            {"threads", a.threads},
                            {"jobs", a.jobs},
                            {"neighbours", a.neighbours},
                            {"samples", samples},
                            {"maps", maps},
                            {"left_out", leftOut}};
    WriteTextAtomic(pemDir + "/infer.json", inferJson.dump(2) + "\n");
    WriteTextAtomic(pemDir + "/manifest.json",
                    ManifestJson(trace, traceDir, a.res, false, {}).dump(2) + "\n");
    if (!a.quiet)
        std::printf("baked %d viewpoint sample(s) (%zu maps) in %.1f s -> %s\n", n, maps.size(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                    pemDir.c_str());
    return 0;
}

}  // namespace pem::cli
