// SPDX-License-Identifier: MIT
// pem_set.cpp — PEM directories for drawing (pem_set.h).
#include "pipeline/pem_set.h"

#include <filesystem>
#include <map>

#include "base/input_error.h"
#include "infer/cube_map.h"
#include "infer/pem_file.h"
#include "pipeline/layout.h"

namespace pem::pipeline {
namespace {

// Maps by path, loaded on first use; a missing file is remembered as nullptr.
class MapCache {
  public:
    explicit MapCache(std::string dir) : dir_(std::move(dir)) {}

    const raster::Texture* Get(int view, int group, const std::string& name) {
        const std::string path = MapPath(dir_, view, group, name);
        auto it = cache_.find(path);
        if (it == cache_.end()) {
            std::unique_ptr<raster::Texture> tex;
            if (std::filesystem::exists(path))
                tex = std::make_unique<raster::Texture>(
                    infer::ToTexture8(infer::ReadCubeMapExr(path), raster::SamplerState{}));
            it = cache_.emplace(path, std::move(tex)).first;
        }
        return it->second.get();
    }

  private:
    std::string dir_;
    std::map<std::string, std::unique_ptr<raster::Texture>> cache_;
};

}  // namespace

runtime::MapSet LoadMapSet(const PemManifest& m) {
    runtime::MapSet set;
    set.name = m.dir;
    set.samples = m.views;
    set.inferred = m.inferred;
    set.groups = m.groups;
    set.spp = m.spp;
    set.res = m.res;
    TraceManifest tracing;  // the tracer's options, as the trace read them
    tracing.fullTreeDepth = m.fullTreeDepth, tracing.minWeight = m.minWeight;
    tracing.fresnel = m.fresnel;
    set.tracing = tracing.Tracing();
    auto cache = std::make_shared<MapCache>(m.dir);
    set.map = [cache](int view, int group, const std::string& name) {
        return cache->Get(view, group, name);
    };
    return set;
}

trace::Scene LoadPemScene(const PemManifest& m) {
    const std::string path = ResolveScene(m.dir, m.scene, m.sceneGiven);
    if (!std::filesystem::exists(path))
        throw base::InputError(
            m.dir + "/" + kManifestJson,
            "scene not found (" + m.scene + " relative to the directory, or " + m.sceneGiven + ")");
    return trace::LoadScene(path);
}

std::unique_ptr<runtime::Renderer> OpenPemDirectory(const std::string& pemDir, int threads) {
    const PemManifest m = ReadPemManifest(pemDir);
    trace::Scene scene = LoadPemScene(m);
    runtime::MapSet maps = LoadMapSet(m);
    return std::make_unique<runtime::Renderer>(std::move(scene), std::move(maps), threads);
}

}  // namespace pem::pipeline
