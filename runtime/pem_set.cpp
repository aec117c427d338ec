// SPDX-License-Identifier: MIT
// pem_set.cpp — manifest.json and the 8-bit maps (pem_set.h).
#include "runtime/pem_set.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "infer/cube_map.h"
#include "infer/pem_file.h"
#include "viewer_tty/input_error.h"

namespace pem::runtime {
namespace {

using nlohmann::json;

glm::dvec3 Vec3(const json& j) {
    return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

trace::Shell ShellFrom(const json& j) {
    const std::string type = j.at("type").get<std::string>();
    if (type == "sphere")
        return trace::SphereShell{Vec3(j.at("centre")), j.at("radius").get<double>()};
    if (type == "ellipsoid")
        return trace::EllipsoidShell{Vec3(j.at("centre")), Vec3(j.at("radii"))};
    if (type == "box") return trace::BoxShell{Vec3(j.at("min")), Vec3(j.at("max"))};
    if (type == "quad") {
        trace::QuadShell q;
        q.centre = Vec3(j.at("centre"));
        q.normal = Vec3(j.at("normal"));
        q.u = Vec3(j.at("u"));
        q.v = Vec3(j.at("v"));
        q.halfExtent = {j.at("half_extent").at(0).get<double>(),
                        j.at("half_extent").at(1).get<double>()};
        return q;
    }
    throw std::runtime_error("unknown shell type \"" + type + "\"");
}

}  // namespace

trace::SphereShell SingleLayerShell(const glm::dvec3& emOrigin, const std::vector<double>& radii,
                                    const std::vector<int64_t>& records) {
    double sum = 0.0, weight = 0.0;
    for (size_t l = 0; l < radii.size(); ++l) {
        sum += static_cast<double>(records[l]) * radii[l];
        weight += static_cast<double>(records[l]);
    }
    const double radius = weight > 0.0 ? sum / weight : (radii.empty() ? 1.0 : radii[0]);
    return {emOrigin, radius};
}

trace::Shell ShellFromJson(const std::string& jsonText) {
    return ShellFrom(json::parse(jsonText));
}

const raster::Texture* PemSet::Map(int view, int group, const std::string& name) const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "/view_%03d/group_%d/", view, group);
    const std::string path = dir + buf + name + ".exr";
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

PemSet LoadPemSet(const std::string& dir) {
    const std::string path = dir + "/manifest.json";
    std::ifstream f(path);
    if (!f) throw InputError(path, "cannot open (run pemref infer first)");
    PemSet set;
    set.dir = dir;
    try {
        const json j = json::parse(f);
        if (j.at("format").get<std::string>() != "pemref_pem/1")
            throw std::runtime_error("not a pemref_pem/1 manifest");
        set.scenePath = j.at("scene").get<std::string>();
        set.traceDir = j.at("trace_dir").get<std::string>();
        set.width = j.at("size").at(0).get<int>();
        set.height = j.at("size").at(1).get<int>();
        set.spp = j.at("spp").get<int>();
        set.res = j.at("res").get<int>();
        for (const json& v : j.at("views")) {
            raster::Camera c;
            c.eye = glm::vec3(Vec3(v.at("eye")));
            c.target = glm::vec3(Vec3(v.at("target")));
            set.views.push_back(c);
        }
        if (j.at("inferred_views").is_null()) {
            for (int v = 0; v < static_cast<int>(set.views.size()); ++v) set.inferred.push_back(v);
        } else {
            set.inferred = j.at("inferred_views").get<std::vector<int>>();
        }
        int index = 0;
        for (const json& g : j.at("lens_groups")) {
            PemGroup pg;
            pg.index = index++;
            pg.glass = g.at("glass").get<bool>();
            pg.emOrigin = glm::vec3(Vec3(g.at("em_origin")));
            std::vector<double> radii;
            std::vector<int64_t> records;
            for (const json& l : g.at("layers")) {
                pg.layers.push_back(ShellFrom(l.at("shell")));
                radii.push_back(l.at("radius").get<double>());
                records.push_back(l.at("records").get<int64_t>());
                pg.layerEmpty.push_back(records.back() == 0 ? 1 : 0);
            }
            pg.singleShell = SingleLayerShell(glm::dvec3(pg.emOrigin), radii, records);
            if (g.contains("pem_local_distant")) {
                pg.pem = true;
                pg.localShell = ShellFrom(g.at("pem_local_distant").at("local"));
                pg.distantShell = ShellFrom(g.at("pem_local_distant").at("distant"));
            }
            set.groups.push_back(std::move(pg));
        }
    } catch (const json::exception& e) {
        throw InputError(path, std::string("malformed manifest: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw InputError(path, e.what());
    }
    if (set.views.empty() || set.inferred.empty()) throw InputError(path, "no viewpoint samples");
    return set;
}

}  // namespace pem::runtime
