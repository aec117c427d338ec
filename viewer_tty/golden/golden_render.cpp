// SPDX-License-Identifier: MIT
// golden_render.cpp — golden tests drawn (golden_render.h).
#include "viewer_tty/golden/golden_render.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "base/display_image.h"
#include "base/input_error.h"
#include "base/sha256.h"
#include "pipeline/json_values.h"
#include "pipeline/pem_set.h"
#include "raster/profile.h"
#include "runtime/renderer.h"
#include "trace/embree_scene.h"
#include "trace/layers.h"
#include "trace/render.h"
#include "trace/scene.h"
#include "viewer_tty/conformance/case_file.h"

namespace pem::golden {
namespace {

// Embree's ISA for every golden: SSE2, which every x86-64 CPU runs, so a traced golden does not
// depend on the machine that made it (Embree's results differ across ISAs on ties).
constexpr const char* kEmbreeIsa = "sse2";

std::string FileBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw base::InputError(path, "cannot open");
    return std::string((std::istreambuf_iterator<char>(f)), {});
}

std::string Sha(const std::string& bytes) {
    return base::Sha256Hex(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

// The settings that change the picture, as text (part of the input's hash).
std::string Settings(const GoldenTest& t, const std::string& profile) {
    return t.camera + "|" + t.view + "|" + t.method + "|" + std::to_string(t.width) + "x" +
           std::to_string(t.height) + "|" + std::to_string(t.spp) + "|" + profile;
}

base::Image8 Display(const trace::FloatImage& img) {
    return base::ToDisplayImage(img.data, img.width, img.height, img.channels, 1.0f);
}

raster::Camera SceneCamera(const trace::Scene& scene, const GoldenTest& t) {
    if (t.camera != "scene") {
        raster::Camera c = pipeline::CameraFromJson(nlohmann::json::parse(t.camera));
        c.width = t.width, c.height = t.height;
        return c;
    }
    if (!scene.camera) throw base::InputError(t.input, "no camera node (the test asks for it)");
    return trace::CameraForSize(*scene.camera, t.width, t.height);
}

// The static EM needs no maps: a map set with the groups' EM origins and one sample.
runtime::MapSet StaticMapSet(const trace::Scene& scene, const raster::Camera& cam,
                             const std::string& profile) {
    runtime::MapSet m;
    m.name = scene.path;
    m.samples = {cam};
    m.inferred = {0};
    for (size_t g = 0; g < scene.lensGroups.size(); ++g) {
        runtime::LensGroupEm em;
        em.index = int(g);
        em.emOrigin = trace::GroupEmOrigin(scene, int(g));
        for (int o : scene.lensGroups[g].objects)
            em.glass =
                em.glass || scene.materials[size_t(scene.objects[size_t(o)].material)].kind ==
                                trace::MaterialKind::Glass;
        m.groups.push_back(em);
    }
    m.res = 128;
    m.hardware.profile = profile;
    m.map = [](int, int, const std::string&) -> const raster::Texture* { return nullptr; };
    return m;
}

base::Image8 RenderScene(const GoldenTest& t, const std::string& profile, int threads) {
    trace::Scene scene = trace::LoadScene(t.input);
    const raster::Camera cam = SceneCamera(scene, t);
    if (t.method == "traced") {
        const trace::EmbreeDevice device({threads, kEmbreeIsa});
        const trace::EmbreeScene embree(device, scene);
        const trace::Tracer tracer(scene, embree);
        return Display(
            trace::RenderFrame(tracer, cam, t.spp, trace::Model::FullTree, threads).image);
    }
    runtime::MapSet maps = StaticMapSet(scene, cam, profile);
    runtime::Renderer r(std::move(scene), std::move(maps), threads, kEmbreeIsa);
    runtime::RenderSettings s;
    s.method = runtime::Method::StaticEm;
    s.threads = threads;
    return Display(r.Render(cam, s).image);
}

base::Image8 RenderPem(const GoldenTest& t, const std::string& profile, int threads) {
    const std::unique_ptr<runtime::Renderer> r =
        pipeline::OpenPemDirectory(t.input, threads, kEmbreeIsa);
    const raster::Camera first = r->SampleCamera(0);
    const raster::Camera cam = pipeline::ViewCamera(*r, t.view, t.width ? t.width : first.width,
                                                    t.height ? t.height : first.height);
    runtime::RenderSettings s;
    s.method = t.method == "pem"      ? runtime::Method::Pem
               : t.method == "static" ? runtime::Method::StaticEm
               : t.method == "traced" ? runtime::Method::RayTraced
                                      : runtime::Method::Hybrid;
    s.spp = t.spp;
    s.threads = threads;
    s.profile = profile;
    return Display(r->Render(cam, s).image);
}

}  // namespace

Rendered RenderTest(const GoldenTest& t, const std::string& profile, int threads) {
    Rendered out;
    const std::string settings = Settings(t, profile);
    switch (t.kind) {
        case GoldenTest::Kind::Case: {
            raster::RenderOptions o = raster::ProfileNamed(profile).options;
            o.threads = threads;
            out.image =
                raster::Render(raster::PreparedFrame(conformance::LoadCaseFile(t.input)), o).image8;
            out.inputSha256 = Sha(FileBytes(t.input) + settings);
            break;
        }
        case GoldenTest::Kind::Scene:
            out.image = RenderScene(t, profile, threads);
            out.inputSha256 = Sha(FileBytes(t.input) + settings);
            break;
        case GoldenTest::Kind::Pem:
            out.image = RenderPem(t, profile, threads);
            out.inputSha256 = Sha(FileBytes(t.input + "/manifest.json") + settings);
            break;
    }
    return out;
}

}  // namespace pem::golden
