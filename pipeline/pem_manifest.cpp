// SPDX-License-Identifier: MIT
// pem_manifest.cpp — manifest.json (pem_manifest.h).
#include "pipeline/pem_manifest.h"

#include <algorithm>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "pipeline/json_values.h"
#include "pipeline/layout.h"

namespace pem::pipeline {
namespace {

constexpr const char* kFormat = "pemref_pem";
constexpr int kVersion = 2;

json ManifestJson(const PemManifest& m) {
    json views = json::array(), groups = json::array();
    for (const raster::Camera& c : m.views) views.push_back(CameraJson(c));
    for (const runtime::LensGroupEm& g : m.groups) groups.push_back(LensGroupJson(g));
    json j = {{"format", kFormat},
              {"version", kVersion},
              {"scene", m.scene},
              {"scene_given", m.sceneGiven},
              {"trace_dir", m.traceDir},
              {"trace_dir_given", m.traceDirGiven},
              {"size", {m.width, m.height}},
              {"spp", m.spp},
              {"res", m.res},
              {"max_res", m.maxRes},
              {"profile", m.hardware.profile},
              {"max_anisotropy", m.hardware.maxAnisotropy},
              {"radiance_scale", m.hardware.radianceScale},
              {"lod_bias", m.hardware.lodBias},
              {"parameterization", runtime::ParameterizationName(m.parameterization)},
              {"full_tree_depth", m.fullTreeDepth},
              {"min_weight", m.minWeight},
              {"fresnel", m.fresnel},
              {"hdr", m.hdr},
              {"t", m.tessT},
              {"views", views},
              {"inferred_views", m.inferred},
              {"lens_groups", groups}};
    // Only when given (absent: none, as directories written before the key).
    if (!m.alsoTessT.empty()) j["also_t"] = m.alsoTessT;
    // Only when there is one (absent: t alone, as directories written before the key).
    if (m.topologyT > 0.0) j["t_topology"] = m.topologyT;
    // RGBA32F maps only (absent: RGBA8, as directories written before the key).
    if (m.hardware.format != raster::TexelFormat::Rgba8)
        for (const auto& [name, format] : raster::kTexelFormatNames)
            if (format == m.hardware.format) j["map_format"] = std::string(name);
    return j;
}

void CheckFormat(const json& j) {
    if (j.value("format", "") == "pemref_pem/1")
        throw std::runtime_error("written by an older pemref (pemref_pem/1): infer again");
    if (j.value("format", "") != kFormat) throw std::runtime_error("not a pemref manifest.json");
    if (j.at("version") != kVersion)
        throw std::runtime_error("version " + j.at("version").dump() + ", expected " +
                                 std::to_string(kVersion) + ": infer again");
}

PemManifest ManifestFromJson(const json& j) {
    CheckFormat(j);
    PemManifest m;
    m.scene = j.at("scene").get<std::string>();
    m.sceneGiven = j.at("scene_given").get<std::string>();
    m.traceDir = j.at("trace_dir").get<std::string>();
    m.traceDirGiven = j.at("trace_dir_given").get<std::string>();
    m.width = IntFromJson<int>(j.at("size").at(0), "size");
    m.height = IntFromJson<int>(j.at("size").at(1), "size");
    m.spp = IntAt<int>(j, "spp");
    m.res = IntAt<int>(j, "res");
    if (j.at("size").size() != 2 || m.width < 1 || m.height < 1 || m.spp < 1)
        throw std::runtime_error("bad size or spp");
    if (m.res < 1 || m.res > 4096 || (m.res & (m.res - 1)) != 0)
        throw std::runtime_error("res " + std::to_string(m.res) + " is not a power of two");
    m.maxRes = IntAtOr<int>(j, "max_res", m.res);  // absent in older directories: every map at res
    if (m.maxRes < m.res || m.maxRes > 4096 || (m.maxRes & (m.maxRes - 1)) != 0)
        throw std::runtime_error("max_res " + std::to_string(m.maxRes) +
                                 " is not a power of two in [res, 4096]");
    m.hardware.profile = ProfileAt(j, "profile");
    m.hardware.maxAnisotropy = j.value("max_anisotropy", 1.0f);  // absent in older directories: off
    if (!(m.hardware.maxAnisotropy >= 1.0f && m.hardware.maxAnisotropy <= 16.0f))
        throw std::runtime_error("max_anisotropy must lie in [1, 16]");
    m.hardware.radianceScale = j.value("radiance_scale", 1.0f);  // absent in older directories
    if (!runtime::IsRadianceScale(m.hardware.radianceScale))
        throw std::runtime_error("radiance_scale must be a power of two in [1, 64]");
    m.hardware.lodBias = j.value("lod_bias", 0.0f);  // absent in older directories: none
    if (!(m.hardware.lodBias >= -runtime::kMaxLodBias &&
          m.hardware.lodBias <= runtime::kMaxLodBias))
        throw std::runtime_error("lod_bias must lie in [-4, 4]");
    const std::string format = j.value("map_format", "rgba8");  // absent in older directories
    const auto* named =
        std::find_if(raster::kTexelFormatNames.begin(), raster::kTexelFormatNames.end(),
                     [&](const auto& n) { return n.first == format; });
    if (named == raster::kTexelFormatNames.end())
        throw std::runtime_error("unknown map_format '" + format + "' (rgba8 or rgba32f)");
    m.hardware.format = named->second;
    const std::string layout = j.value("parameterization", "cube");  // absent in older directories
    const auto parameterization = runtime::ParseParameterization(layout);
    if (!parameterization) throw std::runtime_error("unknown parameterization '" + layout + "'");
    m.parameterization = *parameterization;
    if (m.parameterization != runtime::Parameterization::Cube && m.res < 2)
        throw std::runtime_error("res must be >= 2 for a 2D layout");
    m.fullTreeDepth = IntAt<int>(j, "full_tree_depth");
    m.minWeight = j.at("min_weight").get<double>();
    m.fresnel = j.at("fresnel").get<std::string>();
    m.hdr = j.at("hdr").get<bool>();
    m.tessT = j.value("t", runtime::kDefaultTessT);  // absent in older directories
    if (!(m.tessT >= 0.25 && m.tessT <= 1e4)) throw std::runtime_error("t must lie in [0.25, 1e4]");
    if (j.contains("also_t")) m.alsoTessT = j.at("also_t").get<std::vector<double>>();
    for (double t : m.alsoTessT)
        if (!(t >= 0.25 && t <= 1e4)) throw std::runtime_error("also_t must lie in [0.25, 1e4]");
    m.topologyT = j.value("t_topology", 0.0);
    if (!(m.topologyT == 0.0 || (m.topologyT >= 0.25 && m.topologyT <= 1e4)))
        throw std::runtime_error("t_topology must be 0 or lie in [0.25, 1e4]");
    for (const json& v : j.at("views")) m.views.push_back(CameraFromJson(v));
    m.inferred = IntsAt<int>(j, "inferred_views");
    int index = 0;
    for (const json& g : j.at("lens_groups")) m.groups.push_back(LensGroupFromJson(g, index++));
    if (m.views.empty() || m.inferred.empty()) throw std::runtime_error("no viewpoint samples");
    for (int v : m.inferred)
        if (v < 0 || v >= static_cast<int>(m.views.size()))
            throw std::runtime_error("inferred_views names a sample that does not exist");
    return m;
}

}  // namespace

PemManifest PemManifestFor(const TraceManifest& trace, const std::string& pemDir, int res, bool hdr,
                           const std::vector<int>& inferred, const runtime::MapHardware& hardware,
                           int maxRes, runtime::Parameterization parameterization) {
    PemManifest m;
    m.dir = pemDir;
    const std::string scene = ResolveScene(trace.dir, trace.scene, trace.sceneGiven);
    m.scene = SceneForStorage(pemDir, scene);
    m.sceneGiven = trace.sceneGiven;
    m.traceDir = SceneForStorage(pemDir, trace.dir);
    m.traceDirGiven = AbsolutePath(trace.dir);
    m.width = trace.width;
    m.height = trace.height;
    m.spp = trace.spp;
    m.res = res;
    m.maxRes = std::max(res, maxRes);
    m.hdr = hdr;
    m.hardware = hardware;
    m.parameterization = parameterization;
    m.fullTreeDepth = trace.fullTreeDepth;
    m.minWeight = trace.minWeight;
    m.fresnel = trace.fresnel;
    m.views = trace.Cameras();
    m.inferred = inferred;
    if (m.inferred.empty())
        for (int v = 0; v < static_cast<int>(m.views.size()); ++v) m.inferred.push_back(v);
    m.groups = trace.groups;
    return m;
}

void WritePemManifest(const PemManifest& m) {
    base::WriteTextAtomic(m.dir + "/" + kManifestJson, PemManifestText(m));
}

void CheckMapSize(const PemManifest& m, int size, const std::string& path) {
    if (size < m.res || size > m.maxRes || (size & (size - 1)) != 0)
        throw base::InputError(path,
                               "face size " + std::to_string(size) + ", the manifest says " +
                                   std::to_string(m.res) +
                                   (m.maxRes > m.res ? " to " + std::to_string(m.maxRes) : ""));
}

raster::SamplerState MapSampler(const PemManifest& m) {
    // The wrap modes are the layout's at any size.
    return runtime::LayoutSampler(runtime::LayoutOf(m.parameterization, 2), m.hardware.Sampler());
}

int CheckMapShape(const PemManifest& m, raster::TextureKind kind, int width, int height, int charts,
                  const std::string& path) {
    const bool cube = m.parameterization == runtime::Parameterization::Cube;
    const std::string name(runtime::ParameterizationName(m.parameterization));
    if (cube != (kind == raster::TextureKind::Cube))
        throw base::InputError(
            path, std::string(cube ? "a 2D map" : "a cube map") + ", the manifest says " + name);
    if (cube) {
        CheckMapSize(m, width, path);
        return width;
    }
    // Step: the layout's size (a power of two in [res, max_res]) whose textures have this shape.
    for (int size = std::max(2, m.res); size <= m.maxRes; size *= 2) {
        const runtime::MapLayout layout = runtime::LayoutOf(m.parameterization, size);
        if (layout.width == width && layout.height == height && layout.textures == charts)
            return size;
    }
    const runtime::MapLayout smallest = runtime::LayoutOf(m.parameterization, std::max(2, m.res));
    throw base::InputError(
        path, std::to_string(charts) + " x " + std::to_string(width) + " x " +
                  std::to_string(height) + " is not a " + name + " map of the manifest's sizes (" +
                  std::to_string(smallest.textures) + " x " + std::to_string(smallest.width) +
                  " x " + std::to_string(smallest.height) + " at size " +
                  std::to_string(std::max(2, m.res)) + ")");
}

std::string PemManifestText(const PemManifest& m) {
    return ManifestJson(m).dump(2) + "\n";
}

PemManifest PemManifestFromText(const std::string& text, const std::string& dir,
                                const std::string& source) {
    PemManifest m;
    try {
        m = ManifestFromJson(json::parse(text));
    } catch (const json::exception& e) {
        throw base::InputError(source, std::string("malformed manifest: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw base::InputError(source, e.what());
    }
    m.dir = dir;
    return m;
}

PemManifest RelocatedPemManifest(const PemManifest& m, const std::string& dir) {
    PemManifest out = m;
    out.dir = dir;
    out.scene = SceneForStorage(dir, ResolveScene(m.dir, m.scene, m.sceneGiven));
    out.traceDir = SceneForStorage(dir, ResolveScene(m.dir, m.traceDir, m.traceDirGiven));
    return out;
}

PemManifest ReadPemManifest(const std::string& dir) {
    PemManifest m =
        ReadJsonFile(dir + "/" + kManifestJson, "run pemref infer first", ManifestFromJson);
    m.dir = dir;
    return m;
}

}  // namespace pem::pipeline
