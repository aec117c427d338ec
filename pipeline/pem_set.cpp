// SPDX-License-Identifier: MIT
// pem_set.cpp — PEM directories for drawing (pem_set.h).
#include "pipeline/pem_set.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include "base/input_error.h"
#include "infer/env_map.h"
#include "infer/pem_file.h"
#include "pipeline/layout.h"
#include "pipeline/pem_pack.h"

namespace pem::pipeline {
namespace {

// Maps by path, loaded on first use; a missing file is remembered as nullptr.
class MapCache {
  public:
    explicit MapCache(const PemManifest& manifest)
        : manifest_(manifest), sampler_(MapSampler(manifest)) {}

    const raster::Texture* Get(int view, int group, const std::string& name) {
        const std::string path = MapPath(manifest_.dir, view, group, name);
        auto it = cache_.find(path);
        if (it == cache_.end()) {
            std::unique_ptr<std::vector<raster::Texture>> tex;
            if (std::filesystem::exists(path))
                tex = std::make_unique<std::vector<raster::Texture>>(Load(path));
            it = cache_.emplace(path, std::move(tex)).first;
        }
        return it->second ? it->second->data() : nullptr;
    }

  private:
    // The map's hardware copy (one texture per chart): inside the directory, a readable map of the
    // manifest's layout at a size it allows (a power of two in [res, max_res]).
    std::vector<raster::Texture> Load(const std::string& path) const {
        CheckInside(manifest_.dir, path);
        infer::EnvMapF map;
        try {
            map = infer::ReadEnvMapExr(path);
        } catch (const base::InputError&) {
            throw;
        } catch (const std::exception& e) {
            throw base::InputError(path, std::string("cannot read the map: ") + e.what());
        }
        CheckMapShape(manifest_, map.kind, map.size, map.LevelHeight(0), map.charts, path);
        return infer::ToTextures(map, sampler_, manifest_.hardware.format);
    }

    PemManifest manifest_;
    raster::SamplerState sampler_;
    std::map<std::string, std::unique_ptr<std::vector<raster::Texture>>> cache_;
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
    set.tessT = m.tessT;
    set.topologyT = m.topologyT;
    set.hardware = m.hardware;
    set.parameterization = m.parameterization;
    TraceManifest tracing;  // the tracer's options, as the trace read them
    tracing.fullTreeDepth = m.fullTreeDepth, tracing.minWeight = m.minWeight;
    tracing.fresnel = m.fresnel;
    set.tracing = tracing.Tracing();
    auto cache = std::make_shared<MapCache>(m);
    set.map = [cache](int view, int group, const std::string& name) {
        return cache->Get(view, group, name);
    };
    return set;
}

trace::Scene LoadPemScene(const PemManifest& m, const std::string& source) {
    const std::string path = ResolveScene(m.dir, m.scene, m.sceneGiven);
    if (!std::filesystem::exists(path))
        throw base::InputError(
            source.empty() ? m.dir + "/" + kManifestJson : source,
            "scene not found (" + m.scene + " relative to the directory, or " + m.sceneGiven + ")");
    return trace::LoadScene(path);
}

runtime::MapSet PackMapSet(PemPack pack, const std::string& packFile) {
    runtime::MapSet set = LoadMapSet(pack.manifest);
    set.name = packFile;
    auto maps =
        std::make_shared<std::map<MapKey, std::vector<raster::Texture>>>(std::move(pack.maps));
    set.map = [maps](int view, int group, const std::string& name) -> const raster::Texture* {
        auto it = maps->find({view, group, name});
        return it == maps->end() ? nullptr : it->second.data();
    };
    return set;
}

std::unique_ptr<runtime::Renderer> OpenPemDirectory(const std::string& pemDir, int threads,
                                                    const std::string& embreeIsa) {
    PemManifest m;
    runtime::MapSet maps;
    const bool packed = IsPemPack(pemDir);
    if (packed) {
        PemPack pack = ReadPemPack(pemDir);
        m = pack.manifest;
        maps = PackMapSet(std::move(pack), pemDir);
    } else {
        m = ReadPemManifest(pemDir);
        maps = LoadMapSet(m);
    }
    trace::Scene scene = LoadPemScene(m, packed ? pemDir : "");
    return std::make_unique<runtime::Renderer>(std::move(scene), std::move(maps), threads,
                                               embreeIsa);
}

raster::Camera ViewCamera(const runtime::Renderer& renderer, const std::string& spec, int width,
                          int height) {
    raster::Camera c;
    int index = 0;
    double az = 0, el = 0, dist = 1;
    char extra = 0;
    if (spec == "camera") {
        if (!renderer.scene().camera)
            throw base::InputError("--view camera", "the scene has no camera");
        c = trace::CameraForSize(*renderer.scene().camera, width, height);
    } else if (std::sscanf(spec.c_str(), "sample:%d%c", &index, &extra) == 1) {
        if (index < 0 || index >= static_cast<int>(renderer.maps().samples.size()))
            throw base::InputError("--view " + spec, "no such viewpoint sample");
        c = renderer.SampleCamera(index);
    } else if (std::sscanf(spec.c_str(), "orbit:%lf:%lf:%lf%c", &az, &el, &dist, &extra) == 3 &&
               std::isfinite(az) && std::isfinite(el) && std::isfinite(dist) && dist > 0.0) {
        c = renderer.Orbit(az, el, dist);
    } else {
        throw base::InputError("--view " + spec, "expected sample:I, orbit:AZ:EL:DIST or camera");
    }
    c.width = width;
    c.height = height;
    return c;
}

}  // namespace pem::pipeline
