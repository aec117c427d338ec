// SPDX-License-Identifier: MIT
// cmd_render.cpp — argument parsing, output and statistics for `pemref render`.
#include "viewer_tty/cli/cmd_render.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <tuple>
#include <vector>

#include "base/atomic_file.h"
#include "base/display_image.h"
#include "base/input_error.h"
#include "base/png_io.h"
#include "pipeline/pem_set.h"
#include "trace/render.h"
#include "viewer_tty/cli/args.h"

namespace pem::cli {
namespace {

using nlohmann::json;

struct RenderArgs {
    std::string pemDir, view = "sample:0", size, out, method = "hybrid", stats, profile;
    double t = 0.0;                   // 0: the maps' own (the inference's t)
    std::optional<double> topologyT;  // nullopt: the maps' own
    int spp = 3, subpixels = 0, layers = 0, threads = 1, repeat = 0;
    float exposure = 1.0f;
    bool quiet = false;
    runtime::Parameterization layout = runtime::Parameterization::Cube;
    CLI::Option* layoutOption = nullptr;  // given: --parameterization
};

RenderArgs& Args() {
    static RenderArgs args;
    return args;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

void AddRenderCommand(CLI::App& app) {
    RenderArgs& a = Args();
    CLI::App* sub = app.add_subcommand("render", "render a frame from inferred layered EMs");
    sub->add_option("pem_dir", a.pemDir, "output directory of pemref infer")->required();
    sub->add_option("-o,--out", a.out, "output image (.png or .exr)")->required();
    sub->add_option("--view", a.view, "sample:I | orbit:AZ:EL:DIST | camera");
    sub->add_option("--size", a.size, "image size WxH (default: the PEMs')");
    sub->add_option("--method", a.method, "hybrid | pem | static | traced");
    sub->add_option("--t", a.t,
                    "tessellation threshold (subpixels; default: the t the maps were inferred "
                    "with, manifest.json)")
        ->check(CLI::Range(0.25, 1e4));
    AddTopologyOption(sub, &a.topologyT);
    sub->add_option("--subpixels", a.subpixels,
                    "K: t is in 1/K pixel (default 0: the PEMs' supersampling)")
        ->check(CLI::Range(0, 16));
    sub->add_option("--spp", a.spp, "K for the ray tracer: K×K samples")->check(CLI::Range(1, 16));
    sub->add_option("--layers", a.layers, "0: all layers, 1: the outermost only")
        ->check(CLI::Range(0, 1));
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    AddProfileOption(sub, &a.profile);
    a.layoutOption = AddParameterizationOption(sub, &a.layout);
    a.layoutOption->description(
        "the static EM's layout (--method static; the PEM methods draw the maps' own, which "
        "this must then name)");
    sub->add_option("--stats", a.stats, "per-frame statistics (JSON)");
    sub->add_option("--exposure", a.exposure, "PNG exposure")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--repeat", a.repeat, "render N more times and report the median times")
        ->check(CLI::Range(0, 1000));
    sub->add_flag("--quiet", a.quiet, "no summary line");
}

namespace {

// The stage times of a frame, by their --stats names.
const std::pair<const char*, double runtime::FrameStats::*> kStageTimes[] = {
    {"ray_tracing_seconds", &runtime::FrameStats::traceSeconds},
    {"tessellation_seconds", &runtime::FrameStats::tessSeconds},
    {"texgen_seconds", &runtime::FrameStats::texgenSeconds},
    {"rasterization_seconds", &runtime::FrameStats::rasterSeconds},
    {"lens_seconds", &runtime::FrameStats::lensSeconds},
    {"background_seconds", &runtime::FrameStats::backgroundSeconds},
    {"frame_seconds", &runtime::FrameStats::totalSeconds}};

// --repeat: the median of each stage's time over warm frames (maps loaded and prepared).
void MedianTimes(runtime::Renderer& renderer, const raster::Camera& camera,
                 const runtime::RenderSettings& s, int repeat, runtime::FrameStats* stats) {
    std::vector<runtime::FrameStats> runs;
    for (int r = 0; r < repeat; ++r) runs.push_back(renderer.Render(camera, s).stats);
    auto median = [&](double runtime::FrameStats::*field) {
        std::vector<double> v;
        for (const runtime::FrameStats& st : runs) v.push_back(st.*field);
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    for (const auto& [name, field] : kStageTimes) stats->*field = median(field);
}

double Ratio(double a, double b) {
    return b > 0 ? a / b : 0.0;
}

// --stats: the hybrid paper's table, with the same frame ray traced at K×K (the paper's
// comparison, the same Embree code) and the error against it.
json StatsJson(const RenderArgs& a, runtime::Renderer& renderer, const raster::Camera& camera,
               const runtime::RenderSettings& s, const runtime::RenderedFrame& f) {
    runtime::RenderSettings rs = s;
    rs.method = runtime::Method::RayTraced;
    const runtime::RenderedFrame ref = renderer.Render(camera, rs);
    trace::FloatImage mask(camera.width, camera.height, 1);
    for (size_t p = 0; p < f.lensMask.size(); ++p) mask.data[p] = f.lensMask[p] ? 1.0f : 0.0f;
    const trace::ImageError frameErr = trace::CompareImages(f.image, ref.image, {});
    const trace::ImageError lensErr = trace::CompareImages(f.image, ref.image, mask);
    const runtime::FrameStats& st = f.stats;
    const double rays = static_cast<double>(ref.stats.tracerRays);
    json j = {
        {"method", a.method},
        {"view", a.view},
        {"size", {camera.width, camera.height}},
        {"t", s.t > 0.0 ? s.t : renderer.maps().tessT},
        {"t_topology", s.topologyT.value_or(renderer.maps().topologyT)},
        {"threads", a.threads},
        {"samples", st.samples},
        {"sample_weights", st.sampleWeights},
        {"vertex_rays", st.vertexRays},
        {"traced_vertices", st.tracedVertices},
        {"triangles_in", st.trianglesIn},
        {"triangles_after_tessellation", st.trianglesOut},
        {"background_rays", st.backgroundRays},
        {"ray_tracer",
         {{"spp", a.spp}, {"seconds", ref.stats.totalSeconds}, {"rays", ref.stats.tracerRays}}},
        {"time_reduction", Ratio(ref.stats.totalSeconds, st.lensSeconds)},
        {"time_reduction_whole_frame", Ratio(ref.stats.totalSeconds, st.totalSeconds)},
        {"ray_reduction", Ratio(rays, static_cast<double>(st.vertexRays))},
        {"ray_reduction_whole_frame",
         Ratio(rays, static_cast<double>(st.vertexRays + st.backgroundRays))},
        {"vs_ray_tracer",
         {{"frame_rmse", frameErr.rmse},
          {"frame_psnr_db", frameErr.psnr},
          {"lens_rmse", lensErr.rmse},
          {"lens_psnr_db", lensErr.psnr},
          {"lens_pixels", lensErr.pixels}}}};
    for (const auto& [name, field] : kStageTimes) j[name] = st.*field;
    return j;
}

// --parameterization: any layout for the static EM; for the PEM methods the maps' own.
runtime::Parameterization CheckedLayout(const RenderArgs& a, const runtime::Renderer& renderer,
                                        runtime::Method method) {
    const runtime::Parameterization own = renderer.maps().parameterization;
    if (method != runtime::Method::StaticEm && method != runtime::Method::RayTraced &&
        a.layout != own)
        throw base::InputError(
            "--parameterization " + std::string(runtime::ParameterizationName(a.layout)),
            a.pemDir + " holds " + std::string(runtime::ParameterizationName(own)) +
                " maps (its manifest.json); only --method static draws another layout (or "
                "infer again with this one)");
    return a.layout;
}

}  // namespace

int RunRenderCommand() {
    const RenderArgs& a = Args();
    if (!EndsWith(a.out, ".png") && !EndsWith(a.out, ".exr"))
        throw base::InputError(a.out, "output must end in .png or .exr");
    std::unique_ptr<runtime::Renderer> renderer = pipeline::OpenPemDirectory(a.pemDir, a.threads);
    const raster::Camera first = renderer->SampleCamera(0);
    int w = first.width, h = first.height;
    if (!a.size.empty()) std::tie(w, h) = ParseSize(a.size);
    const raster::Camera camera = pipeline::ViewCamera(*renderer, a.view, w, h);
    runtime::RenderSettings s;
    s.method = ParseMethod(a.method);
    s.t = a.t, s.spp = a.spp, s.subpixels = a.subpixels, s.layers = a.layers;
    s.topologyT = a.topologyT;
    s.threads = a.threads;
    s.profile = a.profile;
    if (a.layoutOption->count() > 0) s.staticLayout = CheckedLayout(a, *renderer, s.method);
    runtime::RenderedFrame f = renderer->Render(camera, s);
    if (a.repeat > 0) MedianTimes(*renderer, camera, s, a.repeat, &f.stats);
    if (EndsWith(a.out, ".exr"))
        trace::WriteExr(a.out, f.image);
    else
        base::WritePng(a.out, base::ToDisplayImage(f.image.data, w, h, 3, a.exposure));
    if (!a.stats.empty())
        base::WriteTextAtomic(a.stats, StatsJson(a, *renderer, camera, s, f).dump(2) + "\n");
    if (!a.quiet)
        std::printf(
            "%s frame %dx%d in %.1f ms (lens %.1f ms: rays %.1f, tessellation %.1f, texgen "
            "%.1f, raster %.1f; %llu vertex rays, %zu triangles) -> %s\n",
            a.method.c_str(), w, h, 1e3 * f.stats.totalSeconds, 1e3 * f.stats.lensSeconds,
            1e3 * f.stats.traceSeconds, 1e3 * f.stats.tessSeconds, 1e3 * f.stats.texgenSeconds,
            1e3 * f.stats.rasterSeconds, static_cast<unsigned long long>(f.stats.vertexRays),
            f.stats.trianglesOut, a.out.c_str());
    return 0;
}

}  // namespace pem::cli
