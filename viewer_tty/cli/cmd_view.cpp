// SPDX-License-Identifier: MIT
// cmd_view.cpp — the renderer behind `pemref view` (cmd_view.h).
#include "viewer_tty/cli/cmd_view.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "base/display_image.h"
#include "base/input_error.h"
#include "pipeline/pem_set.h"
#include "runtime/renderer.h"
#include "trace/render.h"
#include "viewer_tty/tty/viewer.h"

namespace pem::cli {
namespace {

struct ViewArgs {
    std::string pemDir, keys, mode = "hybrid";
    int threads = 2, frames = 0, cols = 0, rows = 0;
    double t = 5.0;
    bool quiet = false;
};

ViewArgs& Args() {
    static ViewArgs args;
    return args;
}

runtime::Method MethodOf(tty::ViewMode mode) {
    switch (mode) {
        case tty::ViewMode::Pem:
            return runtime::Method::Pem;
        case tty::ViewMode::StaticEm:
            return runtime::Method::StaticEm;
        case tty::ViewMode::RayTraced:
            return runtime::Method::RayTraced;
        default:
            return runtime::Method::Hybrid;
    }
}

tty::ViewMode ModeOf(const std::string& name) {
    for (int m = 0; m < tty::kNumViewModes; ++m)
        if (name == tty::ToString(static_cast<tty::ViewMode>(m)))
            return static_cast<tty::ViewMode>(m);
    if (name == "static") return tty::ViewMode::StaticEm;
    if (name == "traced") return tty::ViewMode::RayTraced;
    throw base::InputError("--mode " + name, "expected hybrid, pem, static, traced or difference");
}

}  // namespace

void AddViewCommand(CLI::App& app) {
    ViewArgs& a = Args();
    CLI::App* sub = app.add_subcommand("view", "interactive terminal viewer of inferred PEMs");
    sub->add_option("pem_dir", a.pemDir, "output directory of pemref infer")->required();
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--t", a.t, "initial tessellation threshold")->check(CLI::Range(1.0, 64.0));
    sub->add_option("--mode", a.mode, "initial mode");
    sub->add_option("--keys", a.keys, "scripted: keys to apply, one frame each (no terminal)");
    sub->add_option("--frames", a.frames, "scripted: number of frames")
        ->check(CLI::Range(0, 100000));
    sub->add_option("--cols", a.cols, "screen columns (default: the terminal's)")
        ->check(CLI::Range(0, 2000));
    sub->add_option("--rows", a.rows, "screen rows incl. the status line")
        ->check(CLI::Range(0, 1000));
    sub->add_flag("--quiet", a.quiet, "scripted: status lines only");
}

int RunViewCommand() {
    const ViewArgs& a = Args();
    tty::ViewState initial;
    initial.mode = ModeOf(a.mode);
    initial.t = a.t;
    std::unique_ptr<runtime::Renderer> owned = pipeline::OpenPemDirectory(a.pemDir, a.threads);
    runtime::Renderer& renderer = *owned;
    const tty::RenderViewFn render = [&](const tty::ViewState& st, int w, int h) {
        raster::Camera cam =
            renderer.Orbit(st.azimuthDeg, st.elevationDeg + st.heightOffsetDeg, st.distanceScale);
        cam.width = std::max(1, w);
        cam.height = std::max(1, h);
        runtime::RenderSettings s;
        s.method = MethodOf(st.mode);
        s.t = st.t;
        s.spp = 1;
        s.subpixels = 1;  // one sample per pixel: t is in pixels of the picture shown
        s.threads = a.threads;
        runtime::RenderedFrame f = renderer.Render(cam, s);
        char info[160];
        const runtime::FrameStats& fs = f.stats;
        if (st.mode == tty::ViewMode::Difference) {
            runtime::RenderSettings rs = s;
            rs.method = runtime::Method::RayTraced;
            const runtime::RenderedFrame ref = renderer.Render(cam, rs);
            trace::FloatImage mask(cam.width, cam.height, 1);
            for (size_t p = 0; p < f.lensMask.size(); ++p)
                mask.data[p] = f.lensMask[p] ? 1.0f : 0.0f;
            const trace::ImageError e = trace::CompareImages(f.image, ref.image, mask);
            for (size_t k = 0; k < f.image.data.size(); ++k)
                f.image.data[k] = 4.0f * std::fabs(std::clamp(f.image.data[k], 0.0f, 1.0f) -
                                                   std::clamp(ref.image.data[k], 0.0f, 1.0f));
            std::snprintf(info, sizeof info, "|hybrid-traced|x4  lens PSNR %.1f dB", e.psnr);
        } else if (st.mode == tty::ViewMode::RayTraced) {
            std::snprintf(info, sizeof info, "ray traced 1 spp, %llu rays",
                          static_cast<unsigned long long>(fs.tracerRays));
        } else {
            std::string samples;
            for (size_t k = 0; k < fs.samples.size(); ++k)
                samples += (k ? " " : "") + std::to_string(fs.samples[k]) + ":" +
                           std::to_string(fs.sampleWeights[k]).substr(0, 4);
            std::snprintf(info, sizeof info, "samples %s  lens %.0f ms  %llu rays  %zu tris",
                          samples.c_str(), 1e3 * fs.lensSeconds,
                          static_cast<unsigned long long>(fs.vertexRays), fs.trianglesOut);
        }
        return tty::ViewFrame{
            base::ToDisplayImage(f.image.data, cam.width, cam.height, 3, 1.0f, a.threads), info};
    };
    tty::ViewerOptions o;
    o.keys = a.keys;
    o.frames = a.frames;
    o.cols = a.cols;
    o.rows = a.rows;
    o.quiet = a.quiet;
    return tty::RunViewer(o, initial, render);
}

}  // namespace pem::cli
