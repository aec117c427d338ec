// SPDX-License-Identifier: MIT
// cmd_report.cpp — the measurements behind `pemref report` (cmd_report.h).
#include "viewer_tty/cmd_report.h"

#include <sys/utsname.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "runtime/renderer.h"
#include "trace/trace_run.h"
#include "viewer_tty/display.h"
#include "viewer_tty/image_metrics.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/png_io.h"
#include "viewer_tty/report_writer.h"
#include "viewer_tty/stability.h"

#ifndef PEM_BUILD_FLAGS
#define PEM_BUILD_FLAGS "unknown"
#endif
#ifndef PEM_COMPILER
#define PEM_COMPILER "unknown"
#endif
#ifndef PEM_SOURCE_DIR
#define PEM_SOURCE_DIR ""
#endif

namespace pem::cli {
namespace {

using nlohmann::json;

ReportJob& Args() {
    static ReportJob args;
    return args;
}

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

MetricImage ToMetric(const trace::FloatImage& img) {
    MetricImage m{img.width, img.height, {}};
    m.rgb.reserve(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
    for (size_t p = 0; p < static_cast<size_t>(img.width) * static_cast<size_t>(img.height); ++p)
        for (size_t c = 0; c < 3; ++c)
            m.rgb.push_back(img.data[p * static_cast<size_t>(img.channels) + c]);
    return m;
}

struct Position {
    std::string name, file;
    raster::Camera camera;
};

// Azimuth of an eye about the lens centre (radians, from +Z toward +X).
double Azimuth(const glm::vec3& eye, const glm::vec3& centre) {
    return std::atan2(static_cast<double>(eye.x - centre.x), static_cast<double>(eye.z - centre.z));
}

struct MethodRun {
    std::string method, setting, file;
    runtime::RenderSettings settings;
};

}  // namespace

void AddReportCommand(CLI::App& app) {
    ReportJob& a = Args();
    CLI::App* sub = app.add_subcommand("report", "error against run time for every method");
    sub->add_option("dir", a.dir, "a pemref bake directory")->required();
    sub->add_option("--reference-spp", a.referenceSpp, "K: the reference's K×K samples")
        ->check(CLI::Range(1, 16));
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_flag(
        "--no-stability", [&a](int64_t) { a.stability = false; }, "leave out the stability suite");
    sub->add_flag("--quiet", a.quiet, "no progress lines");
}

int RunReportCommand() {
    return RunReportJob(Args());
}

int RunReportJob(const ReportJob& a) {
    runtime::Renderer renderer(runtime::LoadPemSet(a.dir + "/pem"), a.threads);
    const runtime::PemSet& pems = renderer.pems();
    ReportData data;
    data.title = "pemref report";
    data.scene = pems.scenePath;
    data.machine = Machine();
    data.threads = a.threads;
    data.buildFlags = PEM_BUILD_FLAGS;
    data.compiler = PEM_COMPILER;

    // Step 1: the three camera positions.
    const glm::vec3 centre = trace::LensCentre(renderer.scene());
    const int s0 = pems.inferred.front();
    double step = 10.0;
    if (pems.inferred.size() > 1) {
        const double d = Azimuth(pems.views[static_cast<size_t>(pems.inferred[1])].eye, centre) -
                         Azimuth(pems.views[static_cast<size_t>(s0)].eye, centre);
        step = glm::degrees(std::remainder(d, 2.0 * M_PI));
    }
    std::vector<Position> positions = {
        {"on circle", "on_circle", renderer.SampleCamera(s0)},
        {"between samples", "between", renderer.Orbit(step / 2.0, 0.0, 1.0)},
        {"10° above", "above", renderer.Orbit(step / 2.0, 10.0, 1.0)}};

    // Step 2: the methods.
    std::vector<MethodRun> runs;
    auto add = [&](std::string method, std::string setting, std::string file, runtime::Method m,
                   double t, int spp, int layers) {
        runtime::RenderSettings s;
        s.method = m;
        s.t = t;
        s.spp = spp;
        s.layers = layers;
        s.threads = a.threads;
        runs.push_back({std::move(method), std::move(setting), std::move(file), s});
    };
    add("static EM", "", "static", runtime::Method::StaticEm, 5.0, 1, 0);
    add("single-layer PEM", "", "pem1", runtime::Method::Pem, 5.0, 1, 1);
    add("layered PEM", "", "pem", runtime::Method::Pem, 5.0, 1, 0);
    add("hybrid", "t=3", "hybrid_t3", runtime::Method::Hybrid, 3.0, 1, 0);
    add("hybrid", "t=5", "hybrid_t5", runtime::Method::Hybrid, 5.0, 1, 0);
    for (int k = 1; k <= 4; ++k)
        add("ray tracer", std::to_string(k * k) + " spp", "traced_" + std::to_string(k * k),
            runtime::Method::RayTraced, 5.0, k, 0);

    const std::string viewsDir = a.dir + "/views";
    std::filesystem::create_directories(viewsDir);
    for (const Position& pos : positions) {
        if (!a.quiet) std::fprintf(stderr, "pemref report: %s: reference\n", pos.name.c_str());
        runtime::RenderSettings ref;
        ref.method = runtime::Method::RayTraced;
        ref.spp = a.referenceSpp;
        ref.threads = a.threads;
        const runtime::RenderedFrame reference = renderer.Render(pos.camera, ref);
        const MetricImage refImage = ToMetric(reference.image);
        const std::vector<uint8_t>& mask = reference.lensMask;
        WritePng(viewsDir + "/" + pos.file + "_reference.png",
                 ToDisplayImage(reference.image.data, reference.image.width, reference.image.height,
                                3, 1.0f));
        for (const MethodRun& run : runs) {
            if (!a.quiet)
                std::fprintf(stderr, "pemref report: %s: %s %s\n", pos.name.c_str(),
                             run.method.c_str(), run.setting.c_str());
            // Warm: maps loaded and prepared by a first frame (not for the ray tracer).
            if (run.settings.method != runtime::Method::RayTraced)
                renderer.Render(pos.camera, run.settings);
            const runtime::RenderedFrame f = renderer.Render(pos.camera, run.settings);
            const MetricImage img = ToMetric(f.image);
            MethodResult r;
            r.method = run.method;
            r.setting = run.setting;
            r.position = pos.name;
            r.seconds = f.stats.totalSeconds;
            r.rays = f.stats.tracerRays + f.stats.vertexRays + f.stats.backgroundRays;
            r.floatScores = CompareFloat(img, refImage, &mask);
            r.scores8 = Compare8Bit(img, refImage, &mask);
            data.results.push_back(r);
            WritePng(viewsDir + "/" + pos.file + "_" + run.file + ".png",
                     ToDisplayImage(f.image.data, f.image.width, f.image.height, 3, 1.0f));
        }
    }

    // Step 3: what the pipeline left out (trace.json, infer.json).
    std::ifstream traceJson(a.dir + "/trace/trace.json"), inferJson(a.dir + "/pem/infer.json");
    if (traceJson && inferJson) {
        const json tj = json::parse(traceJson), ij = json::parse(inferJson);
        for (size_t g = 0; g < tj.at("lens_groups").size(); ++g) {
            const json& grp = tj.at("lens_groups")[g];
            const std::string name = grp.at("objects").dump();
            double rSeconds = 0.0, solveSeconds = 0.0;
            int64_t filled = 0, observed = 0;
            for (const json& m : ij.at("maps")) {
                if (m.at("group").get<size_t>() != g) continue;
                const double sec =
                    m.at("build_seconds").get<double>() + m.at("solve_seconds").get<double>();
                if (m.at("term") == "R") rSeconds += sec;
                solveSeconds += m.at("solve_seconds").get<double>();
                filled += m.at("filled_texels").get<int64_t>();
                observed += m.at("observed_texels").get<int64_t>();
            }
            // Decisions of the inference (empty clusters, convex reflectors), per sample.
            for (const json& l : ij.value("left_out", json::array())) {
                if (l.at("group").get<size_t>() != g) continue;
                double sum = 0.0;
                int count = 0;
                for (const json& m : ij.at("maps"))
                    if (m.at("group").get<size_t>() == g && m.at("view") == l.at("view")) {
                        sum += m.at("build_seconds").get<double>() +
                               m.at("solve_seconds").get<double>();
                        ++count;
                    }
                data.leftOut.push_back({name,
                                        l.at("what").get<std::string>() + " (sample " +
                                            std::to_string(l.at("view").get<int>()) + ")",
                                        l.at("why").get<std::string>(), count ? sum / count : 0.0});
            }
            if (!grp.at("glass").get<bool>())
                data.leftOut.push_back({name,
                                        "refraction (T) term: no trace images, no maps, no passes",
                                        "no object of the group transmits light",
                                        rSeconds});  // estimate: as much as the R term cost
            for (size_t l = 0; l < grp.at("layers").size(); ++l)
                if (grp.at("layers")[l].at("records").get<int64_t>() == 0)
                    data.leftOut.push_back(
                        {name, "layer " + std::to_string(l), "its cluster is empty", 0.0});
            if (observed > 0)
                data.leftOut.push_back(
                    {name,
                     std::to_string(filled) + " texels (incl. whole MIP levels) out of the solves",
                     "no pixel of the sample samples them: filled afterwards",
                     solveSeconds * static_cast<double>(filled) / static_cast<double>(observed)});
        }
    }
    // What the run-time renderer leaves out, from a hybrid t = 5 frame on the circle.
    {
        runtime::RenderSettings hs;
        hs.method = runtime::Method::Hybrid;
        hs.threads = a.threads;
        const runtime::FrameStats st = renderer.Render(positions[0].camera, hs).stats;
        const double perVertex =
            st.tracedVertices > 0 ? st.traceSeconds / static_cast<double>(st.tracedVertices) : 0.0;
        data.leftOut.push_back(
            {"all lens groups",
             std::to_string(st.backFacingTriangles) + " back-facing triangles, " +
                 std::to_string(st.untracedVertices) + " vertices (hybrid t=5, on circle)",
             "facing away from the eye: no vertex rays, no refinement, not drawn",
             perVertex * static_cast<double>(st.untracedVertices)});
        if (st.groupsSkipped > 0)
            data.leftOut.push_back({"all lens groups",
                                    std::to_string(st.groupsSkipped) + " lens group(s) (on circle)",
                                    "no pixel sees them: no rays, no passes", 0.0});
    }
    data.notes.push_back(
        "Scores over the pixels where the reference sees a lens object; run time "
        "is the whole frame (the rest of the scene: one ray-traced sample per "
        "pixel for the EM methods), warm.");
    data.notes.push_back("Reference: the ray tracer (full tree) at " +
                         std::to_string(a.referenceSpp) + "×" + std::to_string(a.referenceSpp) +
                         " samples per pixel.");
    data.notes.push_back(
        "Left-out seconds are estimates: the R term's cost for a T term; the mean cost of one "
        "of the group's maps for a map left out; solve time scaled by the left-out/solved texel "
        "ratio for unsampled texels; seconds per traced vertex times the untraced vertices for "
        "back-facing parts.");

    // Step 4: the stability suite.
    if (a.stability) {
        StabilityOptions so;
        so.dataDir =
            std::string(PEM_SOURCE_DIR).empty() ? "" : std::string(PEM_SOURCE_DIR) + "/tests/data";
        if (!so.dataDir.empty() && !std::filesystem::exists(so.dataDir)) so.dataDir.clear();
        so.threads = a.threads;
        for (const StabilityCase& c : RunStabilitySuite(so))
            data.stability.push_back({c.name, c.category, c.expected, c.outcome, c.passed,
                                      c.residual, c.condition, c.detail});
    }
    WriteReport(data, a.dir);
    if (!a.quiet)
        std::printf("report: %s/report.md, report.svg, report.json; images in %s\n", a.dir.c_str(),
                    viewsDir.c_str());
    return 0;
}

}  // namespace pem::cli
