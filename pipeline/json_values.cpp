// SPDX-License-Identifier: MIT
// json_values.cpp — JSON forms of cameras, shells and lens groups (json_values.h).
#include "pipeline/json_values.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/profile.h"

namespace pem::pipeline {
namespace {

double Finite(const json& j) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw std::runtime_error("a number is not finite");
    return v;
}

// NaN and infinities as null (JSON has neither), and back.
json Number(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}
double NumberOr(const json& j, double ifNull) {
    return j.is_null() ? ifNull : j.get<double>();
}

json LayerJson(const runtime::EmLayer& l) {
    json candidates = json::array();
    for (const auto& [kind, parallax] : l.candidates)
        candidates.push_back({{"shell", kind}, {"parallax_deg", Number(parallax)}});
    return {{"radius", l.radius},          {"records", l.records},
            {"objects", l.objects},        {"occupancy", l.occupancy},
            {"shell", ShellJson(l.shell)}, {"parallax_deg", Number(l.parallaxDeg)},
            {"candidates", candidates}};
}

runtime::EmLayer LayerFromJson(const json& j) {
    runtime::EmLayer l;
    l.shell = ShellFromJson(j.at("shell"));
    l.kind = j.at("shell").at("type").get<std::string>();
    l.radius = Finite(j.at("radius"));
    l.records = IntAt<int64_t>(j, "records");
    l.objects = j.at("objects").get<std::vector<std::string>>();
    l.occupancy = Finite(j.at("occupancy"));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    l.parallaxDeg = NumberOr(j.at("parallax_deg"), nan);
    for (const json& c : j.at("candidates"))
        l.candidates.emplace_back(c.at("shell").get<std::string>(),
                                  NumberOr(c.at("parallax_deg"), nan));
    return l;
}

}  // namespace

json Vec3Json(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

glm::dvec3 Vec3FromJson(const json& j) {
    if (!j.is_array() || j.size() != 3) throw std::runtime_error("expected [x, y, z]");
    return {Finite(j.at(0)), Finite(j.at(1)), Finite(j.at(2))};
}

json CameraJson(const raster::Camera& c) {
    return {{"eye", Vec3Json(glm::dvec3(c.eye))},
            {"target", Vec3Json(glm::dvec3(c.target))},
            {"up", Vec3Json(glm::dvec3(c.up))},
            {"fov_y_radians", static_cast<double>(c.fovYRadians)},
            {"size", {c.width, c.height}}};
}

raster::Camera CameraFromJson(const json& j) {
    raster::Camera c;
    c.eye = glm::vec3(Vec3FromJson(j.at("eye")));
    c.target = glm::vec3(Vec3FromJson(j.at("target")));
    c.up = glm::vec3(Vec3FromJson(j.at("up")));
    c.fovYRadians = static_cast<float>(Finite(j.at("fov_y_radians")));
    c.width = IntFromJson<int>(j.at("size").at(0), "size");
    c.height = IntFromJson<int>(j.at("size").at(1), "size");
    if (c.width < 1 || c.height < 1 || c.width > 16384 || c.height > 16384)
        throw std::runtime_error("camera size out of range");
    if (!(c.fovYRadians > 0.0f && c.fovYRadians < 3.14159f))
        throw std::runtime_error("camera field of view out of range");
    if (!(glm::length(c.target - c.eye) > 0.0f)) throw std::runtime_error("camera eye = target");
    return c;
}

json ShellJson(const trace::Shell& shell) {
    if (const auto* s = std::get_if<trace::SphereShell>(&shell))
        return {{"type", "sphere"}, {"centre", Vec3Json(s->centre)}, {"radius", s->radius}};
    if (const auto* q = std::get_if<trace::QuadShell>(&shell))
        return {{"type", "quad"},
                {"centre", Vec3Json(q->centre)},
                {"normal", Vec3Json(q->normal)},
                {"u", Vec3Json(q->u)},
                {"v", Vec3Json(q->v)},
                {"half_extent", {q->halfExtent.x, q->halfExtent.y}}};
    if (const auto* e = std::get_if<trace::EllipsoidShell>(&shell))
        return {
            {"type", "ellipsoid"}, {"centre", Vec3Json(e->centre)}, {"radii", Vec3Json(e->radii)}};
    if (const auto* b = std::get_if<trace::BoxShell>(&shell))
        return {{"type", "box"}, {"min", Vec3Json(b->min)}, {"max", Vec3Json(b->max)}};
    const auto& c = std::get<trace::CylinderShell>(shell);  // infinite ends as null
    return {{"type", "cylinder"},
            {"axis_xz", {c.axisXZ.x, c.axisXZ.y}},
            {"radius", c.radius},
            {"y_min", Number(c.yMin)},
            {"y_max", Number(c.yMax)}};
}

trace::Shell ShellFromJson(const json& j) {
    const std::string type = j.at("type").get<std::string>();
    if (type == "sphere")
        return trace::SphereShell{Vec3FromJson(j.at("centre")), Finite(j.at("radius"))};
    if (type == "ellipsoid")
        return trace::EllipsoidShell{Vec3FromJson(j.at("centre")), Vec3FromJson(j.at("radii"))};
    if (type == "box") return trace::BoxShell{Vec3FromJson(j.at("min")), Vec3FromJson(j.at("max"))};
    if (type == "quad") {
        trace::QuadShell q;
        q.centre = Vec3FromJson(j.at("centre"));
        q.normal = Vec3FromJson(j.at("normal"));
        q.u = Vec3FromJson(j.at("u"));
        q.v = Vec3FromJson(j.at("v"));
        q.halfExtent = {Finite(j.at("half_extent").at(0)), Finite(j.at("half_extent").at(1))};
        return q;
    }
    if (type == "cylinder") {
        trace::CylinderShell c;
        c.axisXZ = {Finite(j.at("axis_xz").at(0)), Finite(j.at("axis_xz").at(1))};
        c.radius = Finite(j.at("radius"));
        c.yMin = NumberOr(j.at("y_min"), -std::numeric_limits<double>::infinity());
        c.yMax = NumberOr(j.at("y_max"), std::numeric_limits<double>::infinity());
        if (!(c.radius > 0.0) || !(c.yMin < c.yMax)) throw std::runtime_error("bad cylinder");
        return c;
    }
    throw std::runtime_error("unknown shell type \"" + type + "\"");
}

json LensGroupJson(const runtime::LensGroupEm& g) {
    json layers = json::array();
    for (const runtime::EmLayer& l : g.layers) layers.push_back(LayerJson(l));
    json j = {{"objects", g.objects},
              {"glass", g.glass},
              {"terms", g.glass ? json::array({"R", "T"}) : json::array({"R"})},
              {"em_origin", Vec3Json(glm::dvec3(g.emOrigin))},
              {"records", g.records},
              {"lbg_iterations", g.lbgIterations},
              {"lbg_converged", g.lbgConverged},
              {"layers", layers}};
    if (g.pem)
        j["pem_local_distant"] = {{"local", ShellJson(g.localShell)},
                                  {"local_parallax_deg", Number(g.localParallaxDeg)},
                                  {"distant", ShellJson(g.distantShell)},
                                  {"distant_mean_distance", g.distantMeanDistance}};
    return j;
}

std::string ProfileAt(const json& j, const char* key) {
    const std::string name = j.at(key).get<std::string>();
    try {
        raster::ProfileNamed(name);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string(key) + ": " + e.what());
    }
    return name;
}

runtime::LensGroupEm LensGroupFromJson(const json& j, int index) {
    runtime::LensGroupEm g;
    g.index = index;
    g.objects = j.at("objects").get<std::vector<std::string>>();
    g.glass = j.at("glass").get<bool>();
    g.emOrigin = glm::vec3(Vec3FromJson(j.at("em_origin")));
    g.records = IntAt<int64_t>(j, "records");
    g.lbgIterations = IntAt<int>(j, "lbg_iterations");
    g.lbgConverged = j.at("lbg_converged").get<bool>();
    for (const json& l : j.at("layers")) g.layers.push_back(LayerFromJson(l));
    if (j.contains("pem_local_distant")) {
        const json& p = j.at("pem_local_distant");
        g.pem = true;
        g.localShell = ShellFromJson(p.at("local"));
        const double nan = std::numeric_limits<double>::quiet_NaN();  // absent: older traces
        g.localParallaxDeg =
            p.contains("local_parallax_deg") ? NumberOr(p.at("local_parallax_deg"), nan) : nan;
        g.distantShell = ShellFromJson(p.at("distant"));
        g.distantMeanDistance = Finite(p.at("distant_mean_distance"));
    }
    return g;
}

}  // namespace pem::pipeline
