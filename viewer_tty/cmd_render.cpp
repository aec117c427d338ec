// SPDX-License-Identifier: MIT
// cmd_render.cpp — argument parsing, output and statistics for `pemref render`.
#include "viewer_tty/cmd_render.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <tuple>
#include <vector>

#include "trace/render.h"
#include "viewer_tty/cmd_infer.h"
#include "viewer_tty/cmd_trace.h"
#include "viewer_tty/display.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/png_io.h"

namespace pem::cli {
namespace {

using nlohmann::json;

struct RenderArgs {
    std::string pemDir, view = "sample:0", size, out, method = "hybrid", stats;
    double t = 5.0;
    int spp = 3, subpixels = 0, layers = 0, threads = 1, repeat = 0;
    float exposure = 1.0f;
    bool quiet = false;
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

runtime::Method ParseMethod(const std::string& name) {
    if (name == "hybrid") return runtime::Method::Hybrid;
    if (name == "pem") return runtime::Method::Pem;
    if (name == "static") return runtime::Method::StaticEm;
    if (name == "traced") return runtime::Method::RayTraced;
    throw InputError("--method " + name, "expected hybrid, pem, static or traced");
}

raster::Camera ParseViewSpec(const runtime::Renderer& renderer, const std::string& spec, int width,
                             int height) {
    raster::Camera c;
    int index = 0;
    double az = 0, el = 0, dist = 1;
    char extra = 0;
    if (spec == "camera") {
        c = renderer.SampleCamera(0);
        const raster::Camera sc = trace::CameraForSize(*renderer.scene().camera, width, height);
        c.eye = sc.eye, c.target = sc.target;
    } else if (std::sscanf(spec.c_str(), "sample:%d%c", &index, &extra) == 1) {
        if (index < 0 || index >= static_cast<int>(renderer.pems().views.size()))
            throw InputError("--view " + spec, "no such viewpoint sample");
        c = renderer.SampleCamera(index);
    } else if (std::sscanf(spec.c_str(), "orbit:%lf:%lf:%lf%c", &az, &el, &dist, &extra) == 3 &&
               std::isfinite(az) && std::isfinite(el) && std::isfinite(dist) && dist > 0.0) {
        c = renderer.Orbit(az, el, dist);
    } else {
        throw InputError("--view " + spec, "expected sample:I, orbit:AZ:EL:DIST or camera");
    }
    c.width = width;
    c.height = height;
    return c;
}

void AddRenderCommand(CLI::App& app) {
    RenderArgs& a = Args();
    CLI::App* sub = app.add_subcommand("render", "render a frame from inferred layered EMs");
    sub->add_option("pem_dir", a.pemDir, "output directory of pemref infer")->required();
    sub->add_option("-o,--out", a.out, "output image (.png or .exr)")->required();
    sub->add_option("--view", a.view, "sample:I | orbit:AZ:EL:DIST | camera");
    sub->add_option("--size", a.size, "image size WxH (default: the PEMs')");
    sub->add_option("--method", a.method, "hybrid | pem | static | traced");
    sub->add_option("--t", a.t, "tessellation threshold (subpixels)")->check(CLI::Range(0.25, 1e4));
    sub->add_option("--subpixels", a.subpixels,
                    "K: t is in 1/K pixel (default 0: the PEMs' supersampling)")
        ->check(CLI::Range(0, 16));
    sub->add_option("--spp", a.spp, "K for the ray tracer: K×K samples")->check(CLI::Range(1, 16));
    sub->add_option("--layers", a.layers, "0: all layers, 1: the outermost only")
        ->check(CLI::Range(0, 1));
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--stats", a.stats, "per-frame statistics (JSON)");
    sub->add_option("--exposure", a.exposure, "PNG exposure")->check(CLI::Range(0.0, 1e6));
    sub->add_option("--repeat", a.repeat, "render N more times and report the median times")
        ->check(CLI::Range(0, 1000));
    sub->add_flag("--quiet", a.quiet, "no summary line");
}

int RunRenderCommand() {
    const RenderArgs& a = Args();
    if (!EndsWith(a.out, ".png") && !EndsWith(a.out, ".exr"))
        throw InputError(a.out, "output must end in .png or .exr");
    runtime::Renderer renderer(runtime::LoadPemSet(a.pemDir), a.threads);
    int w = renderer.pems().width, h = renderer.pems().height;
    if (!a.size.empty()) std::tie(w, h) = ParseSize(a.size);
    const raster::Camera camera = ParseViewSpec(renderer, a.view, w, h);
    runtime::RenderSettings s;
    s.method = ParseMethod(a.method);
    s.t = a.t;
    s.spp = a.spp;
    s.subpixels = a.subpixels;
    s.layers = a.layers;
    s.threads = a.threads;
    runtime::RenderedFrame f = renderer.Render(camera, s);
    if (a.repeat > 0) {
        // Warm frames (maps loaded and prepared): the median of each time.
        std::vector<runtime::FrameStats> runs;
        for (int r = 0; r < a.repeat; ++r) runs.push_back(renderer.Render(camera, s).stats);
        auto median = [&](double runtime::FrameStats::*field) {
            std::vector<double> v;
            for (const runtime::FrameStats& st : runs) v.push_back(st.*field);
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        for (double runtime::FrameStats::*field :
             {&runtime::FrameStats::traceSeconds, &runtime::FrameStats::tessSeconds,
              &runtime::FrameStats::texgenSeconds, &runtime::FrameStats::rasterSeconds,
              &runtime::FrameStats::backgroundSeconds, &runtime::FrameStats::lensSeconds,
              &runtime::FrameStats::totalSeconds})
            f.stats.*field = median(field);
    }
    if (EndsWith(a.out, ".exr"))
        trace::WriteExr(a.out, f.image);
    else
        WritePng(a.out, ToDisplayImage(f.image.data, w, h, 3, a.exposure));
    if (!a.stats.empty()) {
        // The paper's comparison: the same frame ray traced at K×K with the same Embree code.
        runtime::RenderSettings rs = s;
        rs.method = runtime::Method::RayTraced;
        const runtime::RenderedFrame ref = renderer.Render(camera, rs);
        trace::FloatImage mask(w, h, 1);
        for (size_t p = 0; p < f.lensMask.size(); ++p) mask.data[p] = f.lensMask[p] ? 1.0f : 0.0f;
        const trace::ImageError frameErr = trace::CompareImages(f.image, ref.image, {});
        const trace::ImageError lensErr = trace::CompareImages(f.image, ref.image, mask);
        const runtime::FrameStats& st = f.stats;
        const json j = {
            {"method", a.method},
            {"view", a.view},
            {"size", {w, h}},
            {"t", a.t},
            {"threads", a.threads},
            {"samples", st.samples},
            {"sample_weights", st.sampleWeights},
            {"vertex_rays", st.vertexRays},
            {"traced_vertices", st.tracedVertices},
            {"triangles_in", st.trianglesIn},
            {"triangles_after_tessellation", st.trianglesOut},
            {"ray_tracing_seconds", st.traceSeconds},
            {"tessellation_seconds", st.tessSeconds},
            {"texgen_seconds", st.texgenSeconds},
            {"rasterization_seconds", st.rasterSeconds},
            {"lens_seconds", st.lensSeconds},
            {"background_seconds", st.backgroundSeconds},
            {"background_rays", st.backgroundRays},
            {"frame_seconds", st.totalSeconds},
            {"ray_tracer",
             {{"spp", a.spp}, {"seconds", ref.stats.totalSeconds}, {"rays", ref.stats.tracerRays}}},
            {"time_reduction", st.lensSeconds > 0 ? ref.stats.totalSeconds / st.lensSeconds : 0.0},
            {"time_reduction_whole_frame",
             st.totalSeconds > 0 ? ref.stats.totalSeconds / st.totalSeconds : 0.0},
            {"ray_reduction", st.vertexRays > 0 ? static_cast<double>(ref.stats.tracerRays) /
                                                      static_cast<double>(st.vertexRays)
                                                : 0.0},
            {"ray_reduction_whole_frame",
             st.vertexRays + st.backgroundRays > 0
                 ? static_cast<double>(ref.stats.tracerRays) /
                       static_cast<double>(st.vertexRays + st.backgroundRays)
                 : 0.0},
            {"vs_ray_tracer",
             {{"frame_rmse", frameErr.rmse},
              {"frame_psnr_db", frameErr.psnr},
              {"lens_rmse", lensErr.rmse},
              {"lens_psnr_db", lensErr.psnr},
              {"lens_pixels", lensErr.pixels}}}};
        WriteTextAtomic(a.stats, j.dump(2) + "\n");
    }
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
