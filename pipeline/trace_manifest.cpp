// SPDX-License-Identifier: MIT
// trace_manifest.cpp — trace.json (trace_manifest.h).
#include "pipeline/trace_manifest.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "pipeline/json_values.h"
#include "pipeline/layout.h"

namespace pem::pipeline {
namespace {

constexpr const char* kFormat = "pemref_trace";
constexpr int kVersion = 2;

json RaysJson(const trace::RayCounts& c) {
    return {{"total", c.Total()},
            {"primary", c.primary},
            {"secondary", c.secondary},
            {"shadow", c.shadow}};
}

trace::RayCounts RaysFromJson(const json& j) {
    trace::RayCounts c;
    c.primary = IntAt<uint64_t>(j, "primary");
    c.secondary = IntAt<uint64_t>(j, "secondary");
    c.shadow = IntAt<uint64_t>(j, "shadow");
    return c;
}

json ErrorJson(const trace::ImageError& e) {
    return {{"rmse", e.rmse}, {"psnr_db", e.psnr}, {"pixels", e.pixels}};
}

// psnr_db is null for equal images (+inf).
trace::ImageError ErrorFromJson(const json& j) {
    trace::ImageError e;
    e.rmse = j.at("rmse").get<double>();
    e.psnr = j.at("psnr_db").is_null() ? std::numeric_limits<double>::infinity()
                                       : j.at("psnr_db").get<double>();
    e.pixels = IntAt<size_t>(j, "pixels");
    return e;
}

json ViewJson(const TracedView& v) {
    return {{"camera", CameraJson(v.camera)},
            {"reference_seconds", v.referenceSeconds},
            {"greedy_seconds", v.greedySeconds},
            {"rays_reference", RaysJson(v.reference)},
            {"rays_greedy", RaysJson(v.greedy)},
            {"rays_segmentation", RaysJson(v.segmentation)},
            {"rays_layers", RaysJson(v.layers)},
            {"greedy_vs_reference",
             {{"frame", ErrorJson(v.frame)},
              {"lens", ErrorJson(v.lens)},
              {"frame_hdr", ErrorJson(v.frameHdr)},
              {"lens_hdr", ErrorJson(v.lensHdr)}}}};
}

TracedView ViewFromJson(const json& j) {
    TracedView v;
    v.camera = CameraFromJson(j.at("camera"));
    v.referenceSeconds = j.at("reference_seconds").get<double>();
    v.greedySeconds = j.at("greedy_seconds").get<double>();
    v.reference = RaysFromJson(j.at("rays_reference"));
    v.greedy = RaysFromJson(j.at("rays_greedy"));
    v.segmentation = RaysFromJson(j.at("rays_segmentation"));
    v.layers = RaysFromJson(j.at("rays_layers"));
    const json& e = j.at("greedy_vs_reference");
    v.frame = ErrorFromJson(e.at("frame"));
    v.lens = ErrorFromJson(e.at("lens"));
    v.frameHdr = ErrorFromJson(e.at("frame_hdr"));
    v.lensHdr = ErrorFromJson(e.at("lens_hdr"));
    return v;
}

json ManifestJson(const TraceManifest& m) {
    json views = json::array(), groups = json::array();
    for (const TracedView& v : m.views) views.push_back(ViewJson(v));
    for (const runtime::LensGroupEm& g : m.groups) groups.push_back(LensGroupJson(g));
    return {{"format", kFormat},
            {"version", kVersion},
            {"scene", m.scene},
            {"scene_given", m.sceneGiven},
            {"rays", m.rays.Total()},
            {"rays_by_kind", RaysJson(m.rays)},
            {"seconds", m.seconds},
            {"bvh_seconds", m.bvhSeconds},
            {"triangles", m.triangles},
            {"viewpoints", m.views.size()},
            {"size", {m.width, m.height}},
            {"spp", m.spp},
            {"threads", m.threads},
            {"full_tree_depth", m.fullTreeDepth},
            {"min_weight", m.minWeight},
            {"fresnel", m.fresnel},
            {"embree_config", m.embreeConfig},
            {"views", views},
            {"lens_groups", groups},
            {"left_out", m.leftOut}};
}

void CheckFormat(const json& j) {
    if (!j.contains("format"))
        throw std::runtime_error("written by an older pemref (no format field): trace again");
    if (j.at("format") != kFormat) throw std::runtime_error("not a pemref trace.json");
    if (j.at("version") != kVersion)
        throw std::runtime_error("version " + j.at("version").dump() + ", expected " +
                                 std::to_string(kVersion) + ": trace again");
}

TraceManifest ManifestFromJson(const json& j) {
    CheckFormat(j);
    TraceManifest m;
    m.scene = j.at("scene").get<std::string>();
    m.sceneGiven = j.at("scene_given").get<std::string>();
    if (j.at("size").size() != 2) throw std::runtime_error("size is not [width, height]");
    m.width = IntFromJson<int>(j.at("size").at(0), "size");
    m.height = IntFromJson<int>(j.at("size").at(1), "size");
    m.spp = IntAt<int>(j, "spp");
    if (m.width < 1 || m.height < 1 || m.spp < 1) throw std::runtime_error("bad size or spp");
    m.threads = IntAt<int>(j, "threads");
    m.fullTreeDepth = IntAt<int>(j, "full_tree_depth");
    m.minWeight = j.at("min_weight").get<double>();
    m.fresnel = j.at("fresnel").get<std::string>();
    if (m.fresnel != "exact" && m.fresnel != "schlick") throw std::runtime_error("unknown fresnel");
    m.embreeConfig = j.at("embree_config").get<std::string>();
    m.seconds = j.at("seconds").get<double>();
    m.bvhSeconds = j.at("bvh_seconds").get<double>();
    m.triangles = IntAt<size_t>(j, "triangles");
    m.rays = RaysFromJson(j.at("rays_by_kind"));
    for (const json& v : j.at("views")) m.views.push_back(ViewFromJson(v));
    int index = 0;
    for (const json& g : j.at("lens_groups")) m.groups.push_back(LensGroupFromJson(g, index++));
    m.leftOut = j.at("left_out").get<std::vector<std::string>>();
    return m;
}

}  // namespace

std::vector<raster::Camera> TraceManifest::Cameras() const {
    std::vector<raster::Camera> cameras;
    for (const TracedView& v : views) cameras.push_back(v.camera);
    return cameras;
}

trace::TraceOptions TraceManifest::Tracing() const {
    trace::TraceOptions o;
    o.fullTreeDepth = fullTreeDepth;
    o.minWeight = minWeight;
    o.fresnel = fresnel == "schlick" ? trace::FresnelModel::Schlick : trace::FresnelModel::Exact;
    return o;
}

void WriteTraceManifest(const TraceManifest& m) {
    base::WriteTextAtomic(m.dir + "/" + kTraceJson, ManifestJson(m).dump(2) + "\n");
}

TraceManifest ReadTraceManifest(const std::string& dir) {
    TraceManifest m =
        ReadJsonFile(dir + "/" + kTraceJson, "run pemref trace first", ManifestFromJson);
    m.dir = dir;
    return m;
}

namespace {

// An image of the trace's size times `k` (k = K for sample images).
trace::FloatImage ReadChecked(const TraceManifest& m, const std::string& path, int channels,
                              int k = 1) {
    CheckInside(m.dir, path);
    trace::FloatImage img = trace::ReadExr(path);
    const int w = k * m.width, h = k * m.height;
    if (img.width != w || img.height != h || img.channels != channels)
        throw base::InputError(path, std::to_string(img.width) + "x" + std::to_string(img.height) +
                                         " with " + std::to_string(img.channels) + " channels; " +
                                         std::to_string(w) + "x" + std::to_string(h) + " with " +
                                         std::to_string(channels) +
                                         " channels expected for this trace");
    return img;
}

}  // namespace

trace::FloatImage ReadFrameImage(const TraceManifest& m, int view, const std::string& name) {
    return ReadChecked(m, FrameImagePath(m.dir, view, name), 3);
}

trace::FloatImage ReadGroupImage(const TraceManifest& m, int view, int group,
                                 const std::string& name, int channels) {
    return ReadChecked(m, GroupImagePath(m.dir, view, group, name), channels);
}

trace::FloatImage ReadGroupSamples(const TraceManifest& m, int view, int group,
                                   const std::string& name) {
    if (m.spp == 1) return ReadGroupImage(m, view, group, name);
    const std::string path = GroupSampleImagePath(m.dir, view, group, name);
    if (!std::filesystem::exists(path))
        throw base::InputError(path, "missing: the trace keeps no sample images (trace again)");
    return ReadChecked(m, path, 4, m.spp);
}

std::string ResolveScene(const std::string& dir, const std::string& stored,
                         const std::string& given) {
    namespace fs = std::filesystem;
    const fs::path p(stored);
    const fs::path resolved = (p.is_absolute() ? p : fs::path(dir) / p).lexically_normal();
    std::error_code ec;
    if (fs::exists(resolved, ec)) return resolved.string();
    return given;
}

std::string AbsolutePath(const std::string& path) {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::absolute(path, ec);
    return (ec ? std::filesystem::path(path) : p).lexically_normal().string();
}

std::string SceneForStorage(const std::string& dir, const std::string& scenePath) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path scene = fs::absolute(scenePath, ec);
    const fs::path base = fs::absolute(dir, ec);
    const fs::path relative = scene.lexically_normal().lexically_relative(base.lexically_normal());
    return relative.empty() ? scene.lexically_normal().string() : relative.string();
}

}  // namespace pem::pipeline
