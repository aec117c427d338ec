// SPDX-License-Identifier: MIT
// report_job.cpp — measurements of `pemref report` (report_job.h).
#include "viewer_tty/report/report_job.h"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "base/display_image.h"
#include "base/png_io.h"
#include "pipeline/infer_report.h"
#include "pipeline/layout.h"
#include "pipeline/pem_set.h"
#include "pipeline/trace_manifest.h"
#include "viewer_tty/report/error_budget.h"
#include "viewer_tty/report/pack_study.h"
#include "viewer_tty/report/positions.h"
#include "viewer_tty/report/report_writer.h"
#include "viewer_tty/stability/stability.h"

namespace pem::report {
namespace {

std::string Machine() {
    std::string model = "unknown CPU";
    std::ifstream cpu("/proc/cpuinfo");
    for (std::string line; std::getline(cpu, line);)
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    utsname u{};
    uname(&u);
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) +
           " hardware threads, " + u.sysname + " " + u.release;
}

void WriteFramePng(const std::string& path, const trace::FloatImage& image) {
    base::WritePng(path, base::ToDisplayImage(image.data, image.width, image.height, 3, 1.0f));
}

struct MethodRun {
    std::string method, setting, file;
    runtime::RenderSettings settings;
};

// Every method the report compares; hybrid at the t its maps were inferred on (mapsT, what they
// fit) and at the renderers' default t (kDefaultTessT, faster when coarser), or at t = 3 and 5
// when the maps' t is the default.
std::vector<MethodRun> Methods(double mapsT, int threads) {
    std::vector<MethodRun> runs;
    auto add = [&](std::string method, std::string setting, std::string file, runtime::Method m,
                   double t, int spp, int layers) {
        runtime::RenderSettings s;
        s.method = m, s.t = t, s.spp = spp, s.layers = layers, s.threads = threads;
        runs.push_back({std::move(method), std::move(setting), std::move(file), s});
    };
    add("static EM", "", "static", runtime::Method::StaticEm, 5.0, 1, 0);
    add("single-layer PEM", "", "pem1", runtime::Method::Pem, 5.0, 1, 1);
    add("layered PEM", "", "pem", runtime::Method::Pem, 5.0, 1, 0);
    const double def = runtime::kDefaultTessT;
    for (double t : {mapsT == def ? 3.0 : mapsT, def}) {
        std::string label = TessSetting(t), file = "hybrid_" + label;
        file.erase(std::remove(file.begin(), file.end(), '='), file.end());
        add("hybrid", label, file, runtime::Method::Hybrid, t, 1, 0);
    }
    for (int k = 1; k <= 4; ++k)
        add("ray tracer", std::to_string(k * k) + " spp", "traced_" + std::to_string(k * k),
            runtime::Method::RayTraced, 5.0, k, 0);
    return runs;
}

// A quarter-size frame of the same view: it draws the same maps at a sixteenth of the cost.
raster::Camera WarmCamera(raster::Camera camera) {
    camera.width = std::max(1, camera.width / 4);
    camera.height = std::max(1, camera.height / 4);
    return camera;
}

// Every method at one position against the reference, frames written to viewsDir; the reference
// and its lens pixels returned (for the packed PEMs), the frames the error budget compares kept
// in `budget` (budgetSpp: the trace's K×K; 0 without a trace).
PackReference MeasurePosition(runtime::Renderer& renderer, const Position& pos,
                              const std::vector<MethodRun>& runs, const ReportJobOptions& o,
                              const std::string& viewsDir, int budgetSpp, BudgetPosition* budget,
                              ReportData* data) {
    if (o.log) o.log(pos.name + ": reference");
    runtime::RenderSettings ref;
    ref.method = runtime::Method::RayTraced;
    ref.spp = o.referenceSpp;
    ref.threads = o.threads;
    const runtime::RenderedFrame reference = renderer.Render(pos.camera, ref);
    const MetricImage refImage = ToMetric(reference.image);
    const std::vector<uint8_t>& mask = reference.lensMask;
    WriteFramePng(viewsDir + "/" + pos.file + "_reference.png", reference.image);
    for (const MethodRun& run : runs) {
        if (o.log) o.log(pos.name + ": " + run.method + " " + run.setting);
        // Warm: the maps the frame draws prepared by a first, quarter-size frame of the same
        // view (not for the ray tracer).
        if (run.settings.method != runtime::Method::RayTraced)
            renderer.Render(WarmCamera(pos.camera), run.settings);
        const runtime::RenderedFrame f = renderer.Render(pos.camera, run.settings);
        const MetricImage img = ToMetric(f.image);
        MethodResult r;
        r.method = run.method, r.setting = run.setting, r.position = pos.name;
        r.seconds = f.stats.totalSeconds;
        r.rays = f.stats.tracerRays + f.stats.vertexRays + f.stats.backgroundRays;
        r.floatScores = CompareFloat(img, refImage, &mask);
        r.scores8 = Compare8Bit(img, refImage, &mask);
        data->results.push_back(r);
        WriteFramePng(viewsDir + "/" + pos.file + "_" + run.file + ".png", f.image);
        const runtime::RenderSettings& rs = run.settings;
        if (rs.method == runtime::Method::Hybrid && rs.t == renderer.maps().tessT)
            budget->hybrid = f;
        if (rs.method == runtime::Method::Hybrid && rs.t == runtime::kDefaultTessT)
            budget->hybridDefaultT = f;
        if (rs.method == runtime::Method::RayTraced && rs.spp == budgetSpp) budget->traced = f;
    }
    return {pos.name, pos.camera, refImage, mask};
}

// Mean build + solve seconds of a group's maps at one sample.
double MeanMapSeconds(const pipeline::InferRecord& ir, int group, int view) {
    double sum = 0.0;
    int count = 0;
    for (const pipeline::MapReport& m : ir.maps)
        if (m.group == group && m.view == view) sum += m.buildSeconds + m.solveSeconds, ++count;
    return count ? sum / count : 0.0;
}

// What the trace and the inference left out, per group, with the time it saved (estimates).
void PipelineLeftOut(const pipeline::TraceManifest& tm, const pipeline::InferRecord& ir,
                     ReportData* data) {
    for (const runtime::LensGroupEm& grp : tm.groups) {
        const int g = grp.index;
        const std::string name = nlohmann::json(grp.objects).dump();
        double rSeconds = 0.0, solveSeconds = 0.0;
        int64_t filled = 0, observed = 0;
        for (const pipeline::MapReport& m : ir.maps) {
            if (m.group != g) continue;
            if (m.term == "R") rSeconds += m.buildSeconds + m.solveSeconds;
            solveSeconds += m.solveSeconds;
            filled += m.filledTexels;
            observed += m.observedTexels;
        }
        for (const pipeline::LeftOut& l : ir.leftOut)  // empty clusters, convex reflectors
            if (l.group == g)
                data->leftOut.push_back({name, l.what + " (sample " + std::to_string(l.view) + ")",
                                         l.why, MeanMapSeconds(ir, g, l.view)});
        if (!grp.glass)
            data->leftOut.push_back({name,
                                     "refraction (T) term: no trace images, no maps, no passes",
                                     "no object of the group transmits light",
                                     rSeconds});  // estimate: as much as the R term cost
        for (size_t l = 0; l < grp.layers.size(); ++l)
            if (grp.layers[l].Empty())
                data->leftOut.push_back(
                    {name, "layer " + std::to_string(l), "its cluster is empty", 0.0});
        if (observed > 0)
            data->leftOut.push_back(
                {name,
                 std::to_string(filled) + " texels (incl. whole MIP levels) out of the solves",
                 "no pixel of the sample samples them: filled afterwards (cube layer and "
                 "single-layer maps: from the direct images of the environment)",
                 solveSeconds * static_cast<double>(filled) / static_cast<double>(observed)});
    }
}

// What the run-time renderer leaves out, from a hybrid frame on the circle (the maps' t).
void RunTimeLeftOut(runtime::Renderer& renderer, const raster::Camera& camera, int threads,
                    ReportData* data) {
    runtime::RenderSettings hs;
    hs.method = runtime::Method::Hybrid;
    hs.threads = threads;
    const runtime::FrameStats st = renderer.Render(camera, hs).stats;
    const double perVertex =
        st.tracedVertices > 0 ? st.traceSeconds / static_cast<double>(st.tracedVertices) : 0.0;
    data->leftOut.push_back({"all lens groups",
                             std::to_string(st.backFacingTriangles) + " back-facing triangles, " +
                                 std::to_string(st.untracedVertices) + " vertices (hybrid " +
                                 TessSetting(renderer.maps().tessT) + ", on circle)",
                             "facing away from the eye: no vertex rays, no refinement, not drawn",
                             perVertex * static_cast<double>(st.untracedVertices)});
    if (st.groupsSkipped > 0)
        data->leftOut.push_back({"all lens groups",
                                 std::to_string(st.groupsSkipped) + " lens group(s) (on circle)",
                                 "no pixel sees them: no rays, no passes", 0.0});
}

void AddNotes(int referenceSpp, ReportData* data) {
    data->notes.push_back(
        "Scores over the pixels where the reference sees a lens object; run time "
        "is the whole frame (the rest of the scene: one ray-traced sample per "
        "pixel for the EM methods), warm.");
    data->notes.push_back("Reference: the ray tracer (full tree) at " +
                          std::to_string(referenceSpp) + "×" + std::to_string(referenceSpp) +
                          " samples per pixel.");
    data->notes.push_back(
        "Left-out seconds are estimates: the R term's cost for a T term; the mean cost of one "
        "of the group's maps for a map left out; solve time scaled by the left-out/solved texel "
        "ratio for unsampled texels; seconds per traced vertex times the untraced vertices for "
        "back-facing parts.");
}

void AddStability(const ReportJobOptions& o, ReportData* data) {
    stability::StabilityOptions so;
    so.dataDir = o.dataDir;
    if (!so.dataDir.empty() && !std::filesystem::exists(so.dataDir)) so.dataDir.clear();
    so.threads = o.threads;
    for (const stability::StabilityCase& c : stability::RunStabilitySuite(so))
        data->stability.push_back({c.name, c.category, c.expected, c.outcome, c.passed, c.residual,
                                   c.condition, c.detail});
}

}  // namespace

void RunReportJob(const ReportJobOptions& o) {
    const std::string pemDir = pipeline::BakePemDir(o.dir);
    std::unique_ptr<runtime::Renderer> renderer = pipeline::OpenPemDirectory(pemDir, o.threads);
    ReportData data;
    data.title = "pemref report";
    data.scene = pipeline::ReadPemManifest(pemDir).sceneGiven;
    data.machine = Machine();
    data.threads = o.threads;
    data.buildFlags = o.buildFlags;
    data.compiler = o.compiler;
    // Step 1: every method at the three positions.
    const std::vector<Position> positions = Positions(*renderer);
    const std::string viewsDir = o.dir + "/views";
    std::filesystem::create_directories(viewsDir);
    const std::string traceDir = pipeline::BakeTraceDir(o.dir);
    std::optional<pipeline::TraceManifest> trace;
    if (std::filesystem::exists(traceDir + "/" + pipeline::kTraceJson))
        trace = pipeline::ReadTraceManifest(traceDir);
    std::vector<PackReference> references;
    std::vector<BudgetPosition> at;
    for (const Position& pos : positions) {
        at.push_back({pos.name, pos.camera, {}, {}, {}});
        references.push_back(MeasurePosition(*renderer, pos,
                                             Methods(renderer->maps().tessT, o.threads), o,
                                             viewsDir, trace ? trace->spp : 0, &at.back(), &data));
    }
    // Step 2: what the pipeline and the run time left out.
    if (trace && std::filesystem::exists(pemDir + "/" + pipeline::kInferJson))
        PipelineLeftOut(*trace, pipeline::ReadInferJson(pemDir), &data);
    RunTimeLeftOut(*renderer, positions[0].camera, o.threads, &data);
    // Step 3: the error budget (with the trace's images at the first sample).
    if (trace) {
        if (o.log) o.log("error budget");
        data.budget = ErrorBudget(*renderer, *trace, at, o.threads);
    }
    // Step 4: packed PEMs, their size against the frames drawn from them.
    // (A pack holds 8-bit maps: a PEM of float maps is not packed, and the report says so.)
    const bool floatMaps = renderer->maps().hardware.format != raster::TexelFormat::Rgba8;
    if (o.packs && floatMaps)
        data.leftOut.push_back({"all lens groups", "the packed PEMs (packs.svg)",
                                "the maps are rgba32f; a pack holds 8-bit maps", 0.0});
    if (o.packs && !floatMaps)
        data.packs = StudyPacks(pemDir, o.dir, references, data.results, o.threads, o.log);
    AddNotes(o.referenceSpp, &data);
    // Step 5: the stability suite; the documents.
    if (o.stability) AddStability(o, &data);
    WriteReport(data, o.dir);
}

}  // namespace pem::report
