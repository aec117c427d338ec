// SPDX-License-Identifier: MIT
// bake_job.cpp — the resumable trace → infer pipeline (bake_job.h).
#include "pipeline/bake_job.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <vector>

#include "base/atomic_file.h"
#include "base/directory_lock.h"
#include "base/input_error.h"
#include "base/worker_pool.h"
#include "pipeline/layout.h"
#include "pipeline/pem_manifest.h"
#include "raster/frame.h"
#include "runtime/lens_paths.h"
#include "runtime/parameterization.h"

namespace pem::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kBakeFormat = "pemref_bake";
constexpr int kBakeVersion = 1;

// The options a bake's files depend on (not jobs or threads), named as `pemref bake` spells
// them: bake.json's "settings", its one writer and reader below.
json BakeSettings(const BakeJobOptions& o) {
    std::error_code ec;
    const fs::path scene = fs::weakly_canonical(o.trace.scene, ec);
    const runtime::MapHardware& hw = o.infer.hardware;
    json s = {
        {"scene", ec ? o.trace.scene : scene.string()},
        {"views", o.trace.views},
        {"size", std::to_string(o.trace.width) + "x" + std::to_string(o.trace.height)},
        {"spp", o.trace.spp},
        {"layers", o.trace.layers},
        {"res", o.infer.res},
        {"max-res", o.infer.maxRes},
        {"parameterization", std::string(runtime::ParameterizationName(o.infer.parameterization))},
        {"neighbours", o.infer.neighbours},
        {"profile", hw.profile},
        {"anisotropy", hw.maxAnisotropy},
        {"lod-bias", hw.lodBias},
        {"radiance-scale", hw.radianceScale}};
    // Settings added later, recorded only when not their default (older bake.json files stay
    // valid): the maps' format, the tessellation t, the further t the maps also fit and the
    // topology threshold.
    if (hw.format != raster::TexelFormat::Rgba8)
        for (const auto& [name, format] : raster::kTexelFormatNames)
            if (format == hw.format) s["map-format"] = std::string(name);
    if (o.infer.tessT != runtime::kDefaultTessT) s["t"] = o.infer.tessT;
    if (!o.infer.alsoTessT.empty()) s["also-t"] = o.infer.alsoTessT;
    if (o.infer.topologyT != runtime::kDefaultTopologyT) s["t-topology"] = o.infer.topologyT;
    return s;
}

// Step 0: a new bake records its settings; a resumed one must have been started with the same
// (else its samples would mix two settings): one error naming bake.json and the first option
// that differs. A bake directory from before bake.json existed gets one.
void CheckSettings(const BakeJobOptions& o) {
    const std::string path = BakeJsonPath(o.outDir);
    const json now = BakeSettings(o);
    if (fs::exists(path)) {
        json was;
        try {
            std::ifstream in(path);
            was = json::parse(in);
            if (was.at("format") != kBakeFormat || was.at("version") != kBakeVersion)
                throw std::runtime_error("not a pemref_bake 1 file");
            was = was.at("settings");
        } catch (const std::exception& e) {
            throw base::InputError(path, std::string("unreadable: ") + e.what());
        }
        for (const auto& [key, value] : was.items())  // a setting given then, not now
            if (!now.contains(key))
                throw base::InputError(path, "this bake was started with --" + key + " " +
                                                 value.dump() + ", resumed without it");
        // --map-format first: it sets --lod-bias's default, so the message names what was given.
        std::vector<std::string> keys;
        if (now.contains("map-format")) keys.push_back("map-format");
        for (const auto& [key, value] : now.items())
            if (key != "map-format") keys.push_back(key);
        for (const std::string& key : keys)
            if (!was.contains(key) || was.at(key) != now.at(key))
                throw base::InputError(
                    path, "this bake was started with --" + key + " " +
                              (was.contains(key) ? was.at(key).dump() : std::string("(none)")) +
                              ", resumed with " + now.at(key).dump() +
                              " (resume with the same options, or bake into a new directory)");
        return;
    }
    const json file = {{"format", kBakeFormat}, {"version", kBakeVersion}, {"settings", now}};
    base::WriteTextAtomic(path, file.dump(2) + "\n");
}

// Step 1: the trace, unless a finished one is there.
TraceManifest TraceOnce(const BakeJobOptions& o) {
    const std::string traceDir = BakeTraceDir(o.outDir);
    if (!fs::exists(traceDir + "/" + kTraceJson)) {
        TraceJobOptions t = o.trace;
        t.outDir = traceDir;
        t.threads = o.threads * o.jobs;
        if (o.log) o.log("tracing " + t.scene);
        RunTraceJob(t);
    }
    return ReadTraceManifest(traceDir);
}

// Step 2: the samples without sample.json, `jobs` at a time on the worker pool.
void InferSamples(const BakeJobOptions& o, int n, const std::vector<int>& todo) {
    const std::string pemDir = BakePemDir(o.outDir);
    const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(todo.size())));
    std::atomic<int> next{0};
    std::mutex mutex;  // progress calls, one at a time
    std::vector<double> partial(static_cast<size_t>(jobs), 0.0);
    int done = n - static_cast<int>(todo.size());
    auto report = [&](int job, double fraction, bool finished) {
        const std::lock_guard<std::mutex> lock(mutex);
        partial[static_cast<size_t>(job)] = finished ? 0.0 : fraction;
        if (finished) ++done;
        double f = done;
        for (double p : partial) f += p;
        if (o.progress) o.progress(f / n);
    };
    std::atomic<bool> failed{false};  // a failed sample stops the others at their next one
    base::RunOnWorkers(jobs, [&](int job) {
        for (int k = next++; k < static_cast<int>(todo.size()) && !failed; k = next++) {
            InferJobOptions io = o.infer;
            io.traceDir = BakeTraceDir(o.outDir);
            io.outDir = pemDir;
            io.threads = o.threads;
            io.views = {todo[static_cast<size_t>(k)]};
            io.progress = [&, job](const std::string&, double f) { report(job, f, false); };
            try {
                const InferJobResult r = RunInferJob(io);
                WriteSampleJson(pemDir, {r.samples.at(0), r.maps, r.leftOut});
            } catch (...) {
                failed = true;
                throw;
            }
            report(job, 1.0, true);
        }
    });
}

// Step 3: infer.json and manifest.json over every sample.
size_t WriteOutputs(const BakeJobOptions& o, const TraceManifest& trace, int n) {
    InferRecord rec;
    rec.dir = BakePemDir(o.outDir);
    rec.traceDir = BakeTraceDir(o.outDir);
    rec.res = o.infer.res, rec.threads = o.threads, rec.jobs = o.jobs;
    rec.neighbours = o.infer.neighbours, rec.hdr = o.infer.hdr, rec.lambda = o.infer.weights;
    for (int v = 0; v < n; ++v) {
        const SampleRecord s = ReadSampleJson(rec.dir, v);
        rec.seconds += s.sample.seconds;
        rec.samples.push_back(s.sample);
        rec.maps.insert(rec.maps.end(), s.maps.begin(), s.maps.end());
        rec.leftOut.insert(rec.leftOut.end(), s.leftOut.begin(), s.leftOut.end());
    }
    WriteInferJson(rec);
    PemManifest m = PemManifestFor(trace, rec.dir, o.infer.res, o.infer.hdr, {}, o.infer.hardware,
                                   std::max(o.infer.res, o.infer.maxRes), o.infer.parameterization);
    m.tessT = o.infer.tessT;
    m.alsoTessT = o.infer.alsoTessT;
    WritePemManifest(m);
    return rec.maps.size();
}

}  // namespace

BakeJobOptions DefaultBakeOptions() {
    BakeJobOptions o;
    o.trace.views = "circle:3:10";
    o.infer.single = true;  // the report compares the single-layer PEM
    return o;
}

BakeJobOptions DemoBakeOptions() {
    BakeJobOptions o = DefaultBakeOptions();
    o.infer.res = 256;
    o.infer.maxRes = 512;
    o.infer.tessT = 1.0;
    o.infer.alsoTessT = {runtime::kDefaultTessT};
    o.infer.hardware.format = raster::TexelFormat::Rgba32F;
    o.infer.weights.smooth = DefaultSmooth(o.infer.hardware.format);
    o.infer.hardware.lodBias = DefaultLodBias(o.infer.hardware.format);
    return o;
}

BakeJobResult RunBakeJob(const BakeJobOptions& o) {
    const std::string pemDir = BakePemDir(o.outDir);
    std::error_code ec;
    fs::create_directories(pemDir, ec);
    if (ec) throw base::InputError(o.outDir, "cannot create the directory: " + ec.message());
    const base::DirectoryLock lock(o.outDir);  // one bake per directory at a time
    base::RemoveTemporaries(o.outDir);
    // A new bake that fails before its trace is done leaves no bake.json (nothing with data).
    const bool fresh = !fs::exists(BakeJsonPath(o.outDir)) &&
                       !fs::exists(BakeTraceDir(o.outDir) + "/" + kTraceJson);
    CheckSettings(o);
    TraceManifest trace;
    try {
        trace = TraceOnce(o);
    } catch (...) {
        if (fresh) fs::remove(BakeJsonPath(o.outDir), ec);
        throw;
    }
    const int n = static_cast<int>(trace.views.size());
    std::vector<int> todo;
    for (int v = 0; v < n; ++v)
        if (!fs::exists(SampleJsonPath(pemDir, v))) todo.push_back(v);
    if (!todo.empty()) InferSamples(o, n, todo);
    return {n, WriteOutputs(o, trace, n)};
}

}  // namespace pem::pipeline
