// SPDX-License-Identifier: MIT
// scene.cpp — LoadScene: tinygltf parse → extension checks → node traversal (world matrices,
// meshes, camera, lights) → scene extras (environment, viewpoints) → lens groups.
// Conventions and errors: scene.h. Not here: accessors (gltf_accessor.cpp), meshes
// (gltf_mesh.cpp), materials (gltf_material.cpp), lookups (scene_query.cpp).
#include "trace/scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <iterator>
#include <numbers>
#include <set>

#include "base/input_error.h"
#include "trace/gltf_internal.h"

namespace pem::trace {

namespace {

using gltf::Context;
using gltf::Fail;

const std::set<std::string> kSupportedExtensions = {
    "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
    "KHR_materials_emissive_strength", "KHR_lights_punctual"};
const std::set<std::string> kCompressionExtensions = {
    "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};

std::string ReadFileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string CompressionHint(const std::string& name) {
    return "requires " + name +
           ", which pemref does not support (Debian's tinygltf has no decoder; decompress the "
           "file offline)";
}

// Step 1: parse with tinygltf. Errors and warnings both reject the file; a failed parse of a
// compressed file names the extension rather than tinygltf's follow-on error.
tinygltf::Model ParseGltf(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw pem::base::InputError(path, "cannot open file (missing or not a regular file)");
    const std::string bytes = ReadFileBytes(path);
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool glb = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    const bool ok = glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                        : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok || !err.empty() || !warn.empty()) {
        for (const std::string& ext : kCompressionExtensions)
            if (bytes.find(ext) != std::string::npos)
                throw pem::base::InputError(path, CompressionHint(ext));
        std::string cause = !err.empty()    ? err
                            : !warn.empty() ? warn
                                            : "tinygltf failed to parse the file";
        while (!cause.empty() && (cause.back() == '\n' || cause.back() == ' ')) cause.pop_back();
        throw pem::base::InputError(path, "glTF parse error: " + cause);
    }
    return model;
}

// Step 2: required extensions must be ones we implement; unknown used ones are noted.
void CheckExtensions(const Context& ctx) {
    for (const std::string& ext : ctx.model.extensionsRequired) {
        if (kCompressionExtensions.count(ext)) Fail(ctx, CompressionHint(ext));
        if (!kSupportedExtensions.count(ext))
            Fail(ctx, "requires extension " + ext + ", which pemref does not support");
    }
    for (const std::string& ext : ctx.model.extensionsUsed)
        if (!kSupportedExtensions.count(ext)) gltf::Note(ctx, "extension " + ext + " ignored");
}

glm::dmat4 LocalMatrix(const Context& ctx, const tinygltf::Node& node, const std::string& where) {
    auto finite = [&](const std::vector<double>& v, size_t n, const char* what) {
        if (!v.empty() && v.size() != n) Fail(ctx, where + "." + what + ": wrong number of values");
        for (double x : v)
            if (!std::isfinite(x))
                Fail(ctx, where + "." + what + ": non-finite value (NaN or Inf)");
    };
    finite(node.matrix, 16, "matrix");
    finite(node.translation, 3, "translation");
    finite(node.rotation, 4, "rotation");
    finite(node.scale, 3, "scale");
    if (!node.matrix.empty()) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<size_t>(4 * c + r)];
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!node.translation.empty())
        t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    if (!node.rotation.empty()) {  // glTF quaternion order x, y, z, w
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double len = glm::length(q);
        if (!(len > 0.0)) Fail(ctx, where + ".rotation: zero quaternion");
        r = glm::mat4_cast(q / len);
    }
    if (!node.scale.empty())
        s = glm::scale(glm::dmat4(1.0), glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return t * r * s;
}

SceneCamera MakeCamera(const Context& ctx, const tinygltf::Node& node, const glm::dmat4& world,
                       const std::string& where) {
    const tinygltf::Camera& cam = ctx.model.cameras[static_cast<size_t>(node.camera)];
    const auto& p = cam.perspective;
    if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi))
        Fail(ctx, where + ": camera yfov must be in (0, pi)");
    if (!(p.aspectRatio >= 0.0) || !std::isfinite(p.aspectRatio) || p.aspectRatio > 100.0)
        Fail(ctx, where + ": camera aspectRatio invalid");
    SceneCamera out;
    out.name = node.name.empty() ? cam.name : node.name;
    out.aspect = p.aspectRatio > 0.0 ? static_cast<float>(p.aspectRatio) : 1.0f;
    out.zNear = p.znear > 0.0 && std::isfinite(p.znear) ? static_cast<float>(p.znear) : 0.05f;
    out.zFar =
        p.zfar > p.znear && std::isfinite(p.zfar) ? static_cast<float>(p.zfar) : 1e4f * out.zNear;
    const glm::dvec3 eye(world[3]);
    const glm::dvec3 forward = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0);
    if (!(glm::length(forward) > 0.0) || !(glm::length(glm::cross(forward, up)) > 0.0))
        Fail(ctx, where + ": camera transform is singular");
    double distance = 1.0;
    if (gltf::Member(node.extras, "pemref_look_at"))
        distance = glm::length(
            gltf::Vec3Or(ctx, node.extras, "pemref_look_at", eye, where + ".extras") - eye);
    if (!(distance > 0.0)) distance = 1.0;
    raster::Camera& c = out.camera;
    c.eye = glm::vec3(eye);
    c.target = glm::vec3(eye + glm::normalize(forward) * distance);
    c.up = glm::vec3(glm::normalize(up));
    c.fovYRadians = static_cast<float>(p.yfov);
    c.height = 480;
    c.width = std::max(1, static_cast<int>(std::lround(480.0 * static_cast<double>(out.aspect))));
    return out;
}

Light MakeLight(const Context& ctx, int index, const glm::dmat4& world, const std::string& where) {
    if (index < 0 || static_cast<size_t>(index) >= ctx.model.lights.size())
        Fail(ctx, where + ": light " + std::to_string(index) + " out of range");
    const tinygltf::Light& src = ctx.model.lights[static_cast<size_t>(index)];
    Light l;
    l.name = src.name;
    if (src.type == "point")
        l.kind = Light::Kind::Point;
    else if (src.type == "spot")
        l.kind = Light::Kind::Spot;
    else if (src.type == "directional")
        l.kind = Light::Kind::Directional;
    else
        Fail(ctx, where + ": unknown light type \"" + src.type + "\"");
    glm::dvec3 color(1.0);
    if (!src.color.empty()) {
        if (src.color.size() != 3) Fail(ctx, where + ": light color needs 3 numbers");
        color = glm::dvec3(src.color[0], src.color[1], src.color[2]);
    }
    const glm::dvec3 power = color * src.intensity;
    if (!std::isfinite(power.x + power.y + power.z) ||
        glm::min(power.x, glm::min(power.y, power.z)) < 0.0 || !std::isfinite(src.range) ||
        src.range < 0.0)
        Fail(ctx, where + ": light color/intensity/range invalid");
    l.intensity = glm::vec3(power);
    l.range = static_cast<float>(src.range);
    l.innerCone = static_cast<float>(src.spot.innerConeAngle);
    l.outerCone = static_cast<float>(src.spot.outerConeAngle);
    l.position = glm::vec3(glm::dvec3(world[3]));
    const glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    if (l.kind != Light::Kind::Point && !(glm::length(dir) > 0.0))
        Fail(ctx, where + ": light transform is singular");
    if (glm::length(dir) > 0.0) l.direction = glm::vec3(glm::normalize(dir));
    return l;
}

// Step 3: depth-first traversal from the scene roots. Each node may be reached once (glTF
// requires a tree), which also rejects cycles.
struct Traversal {
    const Context& ctx;
    Scene* scene;
    std::vector<char> visited;

    void Visit(int index, const glm::dmat4& parent) {
        const auto& nodes = ctx.model.nodes;
        const std::string where = "nodes[" + std::to_string(index) + "]";
        if (index < 0 || static_cast<size_t>(index) >= nodes.size())
            Fail(ctx, where + ": node index out of range");
        if (visited[static_cast<size_t>(index)])
            Fail(ctx, where + ": reached twice (node cycle or shared child; glTF requires a tree)");
        visited[static_cast<size_t>(index)] = 1;
        const tinygltf::Node& node = nodes[static_cast<size_t>(index)];
        const glm::dmat4 world = parent * LocalMatrix(ctx, node, where);
        if (node.mesh >= 0) gltf::AppendMeshObjects(ctx, index, node.mesh, world, scene);
        if (node.camera >= static_cast<int>(ctx.model.cameras.size()))
            Fail(ctx, where + ".camera: out of range");
        if (node.camera >= 0 && !scene->camera) {
            if (ctx.model.cameras[static_cast<size_t>(node.camera)].type == "perspective")
                scene->camera = MakeCamera(ctx, node, world, where);
            else
                gltf::Note(ctx, where + ": non-perspective camera ignored");
        }
        if (const tinygltf::Value* ext = gltf::Extension(node.extensions, "KHR_lights_punctual")) {
            const double li =
                gltf::NumberOr(ctx, *ext, "light", -1.0, where + ".KHR_lights_punctual");
            scene->lights.push_back(MakeLight(ctx, static_cast<int>(li), world, where));
        }
        for (int child : node.children) Visit(child, world);
    }
};

std::vector<int> RootNodes(const Context& ctx) {
    const auto& m = ctx.model;
    if (m.scenes.empty()) {  // no scene: every node that is nobody's child
        std::vector<char> isChild(m.nodes.size(), 0);
        for (const auto& n : m.nodes)
            for (int c : n.children)
                if (c >= 0 && static_cast<size_t>(c) < m.nodes.size())
                    isChild[static_cast<size_t>(c)] = 1;
        std::vector<int> roots;
        for (size_t i = 0; i < m.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
        return roots;
    }
    const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
    if (static_cast<size_t>(s) >= m.scenes.size())
        Fail(ctx, "scene " + std::to_string(s) + " out of range");
    return m.scenes[static_cast<size_t>(s)].nodes;
}

const tinygltf::Value& SceneExtras(const Context& ctx) {
    static const tinygltf::Value kNone;
    const auto& m = ctx.model;
    if (m.scenes.empty()) return kNone;
    return m.scenes[static_cast<size_t>(m.defaultScene >= 0 ? m.defaultScene : 0)].extras;
}

// Step 4: scene extras (data/README.md).
void ReadEnvironment(const Context& ctx, Scene* scene) {
    const tinygltf::Value* env = gltf::Member(SceneExtras(ctx), "pemref_environment");
    if (!env) return;
    const std::string where = "scenes.extras.pemref_environment";
    if (!env->IsObject()) Fail(ctx, where + ": expected an object");
    const std::string uri = gltf::StringOr(ctx, *env, "uri", "", where);
    if (uri.empty()) Fail(ctx, where + ".uri: missing");
    const std::string mapping = gltf::StringOr(ctx, *env, "mapping", "latlong", where);
    if (mapping != "latlong" && mapping != "cube")
        Fail(ctx, where + ".mapping: \"" + mapping + "\" (expected latlong or cube)");
    const double intensity = gltf::NumberOr(ctx, *env, "intensity", 1.0, where);
    if (intensity < 0.0) Fail(ctx, where + ".intensity: must be >= 0");
    const std::string exr =
        (std::filesystem::path(ctx.path).parent_path() / uri).lexically_normal().string();
    try {
        scene->environment = LoadEnvironment(
            exr, mapping == "cube" ? Environment::Mapping::Cube : Environment::Mapping::LatLong,
            static_cast<float>(intensity));
    } catch (const pem::base::InputError& e) {
        Fail(ctx, where + ": " + e.what());
    }
}

void ReadViewpoints(const Context& ctx, Scene* scene) {
    const tinygltf::Value* vp = gltf::Member(SceneExtras(ctx), "pemref_viewpoints");
    if (!vp) return;
    const std::string where = "scenes.extras.pemref_viewpoints";
    if (gltf::StringOr(ctx, *vp, "kind", "", where) != "circle")
        Fail(ctx, where + ".kind: expected \"circle\"");
    Viewpoints& v = scene->viewpoints;
    v.center = glm::vec3(gltf::Vec3Or(ctx, *vp, "center", glm::dvec3(0.0), where));
    v.radius = static_cast<float>(gltf::NumberOr(ctx, *vp, "radius", 0.0, where));
    v.height = static_cast<float>(gltf::NumberOr(ctx, *vp, "height", 0.0, where));
    v.startDeg = static_cast<float>(gltf::NumberOr(ctx, *vp, "start_deg", 0.0, where));
    v.stepDeg = static_cast<float>(gltf::NumberOr(ctx, *vp, "step_deg", 0.0, where));
    const double count = gltf::NumberOr(ctx, *vp, "count", 0.0, where);
    if (count < 0.0 || count > 1e6 || count != std::floor(count))
        Fail(ctx, where + ".count: invalid");
    v.count = static_cast<int>(count);
}

}  // namespace

Scene LoadScene(const std::string& gltfPath) {
    const tinygltf::Model model = ParseGltf(gltfPath);
    Scene scene;
    scene.path = gltfPath;
    const Context ctx{model, gltfPath, &scene.notes};
    CheckExtensions(ctx);
    gltf::ConvertMaterials(ctx, &scene);
    Traversal walk{ctx, &scene, std::vector<char>(model.nodes.size(), 0)};
    for (int root : RootNodes(ctx)) walk.Visit(root, glm::dmat4(1.0));
    if (scene.objects.empty())
        Fail(ctx, scene.droppedDegenerate > 0 ? "all " + std::to_string(scene.droppedDegenerate) +
                                                    " triangles are degenerate (zero area)"
                                              : "the scene has no triangles");
    if (scene.droppedDegenerate > 0)
        scene.notes.push_back(std::to_string(scene.droppedDegenerate) +
                              " zero-area triangles dropped");
    ReadEnvironment(ctx, &scene);
    ReadViewpoints(ctx, &scene);
    scene.lensGroups = FindLensGroups(scene.objects, scene.materials);
    return scene;
}

}  // namespace pem::trace
