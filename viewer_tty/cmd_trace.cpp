// SPDX-License-Identifier: MIT
// cmd_trace.cpp — argument parsing, viewpoints, PNG previews, progress and trace.json for
// `pemref trace` (cmd_trace.h). The work itself is trace::RunTrace.
#include "viewer_tty/cmd_trace.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "trace/scene.h"
#include "trace/trace_run.h"
#include "viewer_tty/display.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/png_io.h"
#include "viewer_tty/progress.h"

namespace pem::cli {

namespace {

using nlohmann::json;

TraceJob& Args() {
    static TraceJob args;
    return args;
}

std::vector<raster::Camera> ParseViews(const trace::Scene& scene, const std::string& spec, int w,
                                       int h) {
    if (!scene.camera) throw InputError(scene.path, "no camera node (needed by --views)");
    const raster::Camera cam = trace::CameraForSize(*scene.camera, w, h);
    if (spec == "camera") return {cam};
    int n = 0;
    double step = 0.0;
    char extra = 0;
    if (std::sscanf(spec.c_str(), "circle:%d:%lf%c", &n, &step, &extra) != 2 || n < 1 ||
        n > 100000 || !std::isfinite(step))
        throw InputError("--views " + spec, "expected camera or circle:N:STEP_DEG");
    return trace::CircleViews(cam, trace::LensCentre(scene), n, step);
}

void WritePreview(const std::string& exrPath, const trace::FloatImage& img, float exposure) {
    const raster::Image8 out =
        ToDisplayImage(img.data, img.width, img.height, img.channels, exposure);
    WritePng(exrPath.substr(0, exrPath.size() - 4) + ".png", out);
}

bool WantsPreview(const std::string& path) {
    for (const char* name :
         {"/reference.exr", "/greedy.exr", "/b_R.exr", "/b_T.exr", "/local.exr", "/distant.exr"}) {
        const std::string n(name);
        if (path.size() >= n.size() && path.compare(path.size() - n.size(), n.size(), n) == 0)
            return true;
    }
    return false;
}

json Vec(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

json ShellJson(const trace::Shell& shell) {
    if (const auto* s = std::get_if<trace::SphereShell>(&shell))
        return {{"type", "sphere"}, {"centre", Vec(s->centre)}, {"radius", s->radius}};
    if (const auto* q = std::get_if<trace::QuadShell>(&shell))
        return {{"type", "quad"},           {"centre", Vec(q->centre)},
                {"normal", Vec(q->normal)}, {"u", Vec(q->u)},
                {"v", Vec(q->v)},           {"half_extent", {q->halfExtent.x, q->halfExtent.y}}};
    if (const auto* e = std::get_if<trace::EllipsoidShell>(&shell))
        return {{"type", "ellipsoid"}, {"centre", Vec(e->centre)}, {"radii", Vec(e->radii)}};
    if (const auto* b = std::get_if<trace::BoxShell>(&shell))
        return {{"type", "box"}, {"min", Vec(b->min)}, {"max", Vec(b->max)}};
    return {{"type", "cylinder"}};
}

json RaysJson(const trace::RayCounts& c) {
    return {{"total", c.Total()},
            {"primary", c.primary},
            {"secondary", c.secondary},
            {"shadow", c.shadow}};
}

json ErrorJson(const trace::ImageError& e) {
    return {{"rmse", e.rmse}, {"psnr_db", e.psnr}, {"pixels", e.pixels}};
}

json GroupJson(const trace::Scene& scene, const trace::GroupReport& g) {
    const trace::GroupLayers& l = g.layers;
    json layers = json::array();
    for (size_t i = 0; i < l.clustering.layers.size(); ++i) {
        const trace::LayerCluster& c = l.clustering.layers[i];
        json objects = json::array();
        for (uint32_t o : c.objects) objects.push_back(scene.objects[o].name);
        layers.push_back({{"radius", c.radius},
                          {"records", c.recordCount},
                          {"objects", objects},
                          {"occupancy", l.shells[i].occupancy},
                          {"shell", ShellJson(l.shells[i].shell)}});
    }
    json j = {{"objects", g.objects},
              {"glass", g.glass},
              {"terms", g.glass ? json::array({"R", "T"}) : json::array({"R"})},
              {"em_origin", Vec(glm::dvec3(l.emOrigin))},
              {"records", g.records},
              {"lbg_iterations", l.clustering.iterations},
              {"lbg_converged", l.clustering.converged},
              {"layers", layers}};
    if (l.mirror)
        j["pem_local_distant"] = {{"local", ShellJson(l.localShell)},
                                  {"distant", ShellJson(l.distantShell)},
                                  {"distant_mean_distance", l.distantMeanDistance}};
    return j;
}

json ReportJson(const trace::Scene& scene, const TraceJob& a, const trace::TraceRunReport& r,
                const std::vector<raster::Camera>& views) {
    json jviews = json::array();
    for (size_t v = 0; v < r.views.size(); ++v) {
        const trace::ViewReport& vr = r.views[v];
        jviews.push_back({{"eye", Vec(glm::dvec3(views[v].eye))},
                          {"target", Vec(glm::dvec3(views[v].target))},
                          {"reference_seconds", vr.referenceSeconds},
                          {"greedy_seconds", vr.greedySeconds},
                          {"rays_reference", RaysJson(vr.reference)},
                          {"rays_greedy", RaysJson(vr.greedy)},
                          {"rays_segmentation", RaysJson(vr.segmentation)},
                          {"rays_layers", RaysJson(vr.layers)},
                          {"greedy_vs_reference",
                           {{"frame", ErrorJson(vr.frame)},
                            {"lens", ErrorJson(vr.lens)},
                            {"frame_hdr", ErrorJson(vr.frameHdr)},
                            {"lens_hdr", ErrorJson(vr.lensHdr)}}}});
    }
    json groups = json::array();
    for (const trace::GroupReport& g : r.groups) groups.push_back(GroupJson(scene, g));
    return {{"scene", a.scene},
            {"rays", r.total.Total()},
            {"rays_by_kind", RaysJson(r.total)},
            {"seconds", r.seconds},
            {"bvh_seconds", r.buildSeconds},
            {"triangles", r.triangles},
            {"viewpoints", r.views.size()},
            {"size", a.size},
            {"spp", a.spp},
            {"threads", a.threads},
            {"full_tree_depth", a.depth},
            {"min_weight", 1e-3},
            {"fresnel", a.fresnel},
            {"embree_config", r.embreeConfig},
            {"views", jviews},
            {"lens_groups", groups},
            {"left_out",
             {"T-term images for mirror-only groups", "local/distant split for groups with glass",
              "caustics and light through glass (shadow rays are opaque)"}}};
}

void WriteJson(const std::string& path, const json& j) {
    const std::string tmp = path + ".tmp." + std::to_string(getpid());
    {
        std::ofstream f(tmp);
        f << j.dump(2) << "\n";
        if (!f) {
            std::remove(tmp.c_str());
            throw InputError(path, "cannot write");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw InputError(path, "cannot rename");
}

}  // namespace

std::pair<int, int> ParseSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 ||
        h < 1 || w > 16384 || h > 16384)
        throw InputError("--size " + text, "expected WxH, e.g. 640x480");
    return {w, h};
}

void AddTraceCommand(CLI::App& app) {
    TraceJob& a = Args();
    CLI::App* sub = app.add_subcommand("trace",
                                       "ray-trace a glTF scene: reference, segmented "
                                       "two-term images, layers (OpenEXR + PNG)");
    sub->add_option("scene", a.scene, "scene (.gltf/.glb)")->required();
    sub->add_option("--out", a.out, "output directory")->required();
    sub->add_option("--views", a.views, "camera | circle:N:STEP_DEG");
    sub->add_option("--spp", a.spp, "K: K×K supersamples per pixel")->check(CLI::Range(1, 16));
    sub->add_option("--size", a.size, "image size WxH");
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--layers", a.layers, "number of EM layers (LBG)")->check(CLI::Range(1, 16));
    sub->add_option("--full-tree-depth", a.depth, "interface events per branch")
        ->check(CLI::Range(1, 32));
    sub->add_option("--fresnel", a.fresnel, "dielectric Fresnel")
        ->check(CLI::IsMember({"exact", "schlick"}));
    sub->add_option("--exposure", a.exposure, "PNG preview exposure")->check(CLI::Range(0.0, 1e6));
    sub->add_flag("--frames-only", a.framesOnly, "only the reference and greedy frames");
    sub->add_flag("--quiet", a.quiet, "no progress line");
}

int RunTraceCommand() {
    return RunTraceJob(Args());
}

int RunTraceJob(const TraceJob& a) {
    const auto [w, h] = ParseSize(a.size);
    const trace::Scene scene = trace::LoadScene(a.scene);
    trace::TraceRunOptions o;
    o.views = ParseViews(scene, a.views, w, h);
    o.k = a.spp;
    o.threads = a.threads;
    o.layers = a.layers;
    o.trace.fullTreeDepth = a.depth;
    o.trace.fresnel =
        a.fresnel == "schlick" ? trace::FresnelModel::Schlick : trace::FresnelModel::Exact;
    o.outDir = a.out;
    o.segment = !a.framesOnly;
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec) throw InputError(a.out, "cannot create the directory: " + ec.message());
    ProgressLine line("pemref trace", a.quiet);  // only on a terminal (progress.h)
    if (line.Enabled()) o.progress = [&line](const std::string&, double f) { line.Update(f); };
    o.written = [&a](const std::string& path, const trace::FloatImage& img) {
        if (WantsPreview(path)) WritePreview(path, img, a.exposure);
    };
    const trace::TraceRunReport report = trace::RunTrace(scene, o);
    line.Finish();
    WriteJson(a.out + "/trace.json", ReportJson(scene, a, report, o.views));
    if (!a.quiet)
        std::printf("traced %zu viewpoint(s): %llu rays in %.2f s -> %s\n", report.views.size(),
                    static_cast<unsigned long long>(report.total.Total()), report.seconds,
                    a.out.c_str());
    return 0;
}

}  // namespace pem::cli
