// SPDX-License-Identifier: MIT
// gltf_mesh.cpp — one glTF mesh instance → world-space trace::Objects (one per primitive).
// Steps per primitive: read attributes → assemble triangles (list/strip/fan) → transform to
// world → drop zero-area triangles → normals (transformed, or flat when absent) → bounds.
// Not here: materials (gltf_material.cpp), node traversal (scene.cpp).
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

#include "trace/gltf_internal.h"

namespace pem::trace::gltf {

namespace {

constexpr double kMaxCoordinate = 1e15;  // beyond this float BVHs and t values are meaningless

struct RawPrimitive {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::uvec3> triangles;
};

std::vector<glm::uvec3> AssembleTriangles(const std::vector<uint32_t>& idx, int mode) {
    std::vector<glm::uvec3> tris;
    const size_t n = idx.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (size_t i = 0; i + 2 < n; i += 3) tris.push_back({idx[i], idx[i + 1], idx[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < n; ++i)  // odd triangles swap to keep the winding
            tris.push_back(i % 2 == 0 ? glm::uvec3{idx[i], idx[i + 1], idx[i + 2]}
                                      : glm::uvec3{idx[i + 1], idx[i], idx[i + 2]});
    } else {  // TINYGLTF_MODE_TRIANGLE_FAN
        for (size_t i = 1; i + 1 < n; ++i) tris.push_back({idx[0], idx[i], idx[i + 1]});
    }
    return tris;
}

// Reads the attributes and indices of one primitive (local space, indices checked).
RawPrimitive ReadPrimitive(const Context& ctx, const tinygltf::Primitive& prim,
                           const std::string& where) {
    RawPrimitive raw;
    auto attr = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attr("POSITION") < 0) Fail(ctx, where + ": primitive has no POSITION attribute");
    raw.positions = ReadVec3(ctx, attr("POSITION"), where + ".POSITION");
    const size_t n = raw.positions.size();
    if (n > 0xFFFFFFF0u) Fail(ctx, where + ": too many vertices");
    if (attr("NORMAL") >= 0) raw.normals = ReadVec3(ctx, attr("NORMAL"), where + ".NORMAL");
    if (attr("TEXCOORD_0") >= 0)
        raw.uvs = ReadTexcoord(ctx, attr("TEXCOORD_0"), where + ".TEXCOORD_0");
    if ((!raw.normals.empty() && raw.normals.size() != n) ||
        (!raw.uvs.empty() && raw.uvs.size() != n))
        Fail(ctx, where + ": attribute counts differ from POSITION's " + std::to_string(n));
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        idx = ReadIndices(ctx, prim.indices, where + ".indices");
        for (size_t i = 0; i < idx.size(); ++i)
            if (idx[i] >= n)
                Fail(ctx, where + ".indices[" + std::to_string(i) + "]: index " +
                              std::to_string(idx[i]) + " out of range (" + std::to_string(n) +
                              " vertices)");
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = static_cast<uint32_t>(i);
    }
    raw.triangles = AssembleTriangles(idx, prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode);
    return raw;
}

glm::vec3 ToWorldPoint(const Context& ctx, const glm::dmat4& m, const glm::vec3& p,
                       const std::string& where) {
    const glm::dvec3 w = glm::dvec3(m * glm::dvec4(glm::dvec3(p), 1.0));
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(w[c]) || std::abs(w[c]) > kMaxCoordinate)
            Fail(ctx, where + ": world-space position out of range (node transform?)");
    return glm::vec3(w);
}

glm::dvec3 FaceNormal(const std::vector<glm::vec3>& p, const glm::uvec3& t) {
    const glm::dvec3 a(p[t.x]), b(p[t.y]), c(p[t.z]);
    return glm::cross(b - a, c - a);
}

// Transformed vertex normals; a normal that degenerates (zero input or singular transform)
// is replaced by the area-weighted mean of the face normals around its vertex.
std::vector<glm::vec3> WorldNormals(const RawPrimitive& raw, const glm::dmat3& normalMatrix,
                                    bool usable, const std::vector<glm::vec3>& worldPos) {
    std::vector<glm::dvec3> n(raw.normals.size(), glm::dvec3(0.0));
    std::vector<bool> bad(n.size(), !usable);
    for (size_t i = 0; i < n.size() && usable; ++i) {
        n[i] = normalMatrix * glm::dvec3(raw.normals[i]);
        bad[i] = !(glm::length(n[i]) > 1e-30);
    }
    std::vector<glm::dvec3> fallback(n.size(), glm::dvec3(0.0));
    for (const glm::uvec3& t : raw.triangles)
        for (int k = 0; k < 3; ++k) fallback[t[k]] += FaceNormal(worldPos, t);
    std::vector<glm::vec3> out(n.size());
    for (size_t i = 0; i < n.size(); ++i) {
        glm::dvec3 d = bad[i] ? fallback[i] : n[i];
        const double len = glm::length(d);
        out[i] = len > 0.0 ? glm::vec3(d / len) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return out;
}

// Splits vertices per triangle and gives each the unit face normal (NORMAL absent).
void MakeFlat(Object* obj, const std::vector<glm::vec2>& uvs) {
    Object flat;
    for (const glm::uvec3& t : obj->triangles) {
        const glm::vec3 n = glm::vec3(glm::normalize(FaceNormal(obj->positions, t)));
        const uint32_t base = static_cast<uint32_t>(flat.positions.size());
        for (int k = 0; k < 3; ++k) {
            flat.positions.push_back(obj->positions[t[k]]);
            flat.normals.push_back(n);
            if (!uvs.empty()) flat.uvs.push_back(uvs[t[k]]);
        }
        flat.triangles.push_back({base, base + 1, base + 2});
    }
    obj->positions = std::move(flat.positions);
    obj->normals = std::move(flat.normals);
    obj->uvs = std::move(flat.uvs);
    obj->triangles = std::move(flat.triangles);
}

// Builds one world-space object; returns false when no triangle survives.
bool BuildObject(const Context& ctx, const RawPrimitive& raw, const glm::dmat4& world,
                 const std::string& where, Object* obj, int* dropped) {
    // Step 1: positions to world space.
    obj->positions.resize(raw.positions.size());
    for (size_t i = 0; i < raw.positions.size(); ++i)
        obj->positions[i] = ToWorldPoint(ctx, world, raw.positions[i], where + ".POSITION");
    // Step 2: keep non-degenerate triangles (area measured on the float world positions that
    // the intersectors see); mirroring transforms swap the winding.
    const double det = glm::determinant(glm::dmat3(world));
    for (glm::uvec3 t : raw.triangles) {
        if (glm::length(FaceNormal(obj->positions, t)) == 0.0) {
            ++*dropped;
            continue;
        }
        obj->triangles.push_back(det < 0.0 ? glm::uvec3{t.x, t.z, t.y} : t);
    }
    if (obj->triangles.empty()) return false;
    // Step 3: normals and uvs.
    if (raw.normals.empty()) {
        MakeFlat(obj, raw.uvs);
    } else {
        RawPrimitive kept = raw;
        kept.triangles = obj->triangles;
        const glm::dmat3 nm =
            det != 0.0 ? glm::inverseTranspose(glm::dmat3(world)) : glm::dmat3(0.0);
        obj->normals = WorldNormals(kept, nm, det != 0.0, obj->positions);
        obj->uvs = raw.uvs;
    }
    // Step 4: bounds of the vertices in use.
    for (const glm::uvec3& t : obj->triangles)
        for (int k = 0; k < 3; ++k) obj->bounds.Extend(obj->positions[t[k]]);
    return true;
}

}  // namespace

void AppendMeshObjects(const Context& ctx, int nodeIndex, int meshIndex, const glm::dmat4& world,
                       Scene* scene) {
    const auto& model = ctx.model;
    const std::string nodeWhere = "nodes[" + std::to_string(nodeIndex) + "]";
    if (meshIndex < 0 || static_cast<size_t>(meshIndex) >= model.meshes.size())
        Fail(ctx, nodeWhere + ".mesh: mesh " + std::to_string(meshIndex) + " out of range");
    const tinygltf::Node& node = model.nodes[static_cast<size_t>(nodeIndex)];
    const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(meshIndex)];
    if (node.skin >= 0 || (!mesh.primitives.empty() && !mesh.primitives[0].targets.empty()))
        Note(ctx, nodeWhere + ": skin/morph targets ignored (bind pose used)");
    const std::string baseName = node.name.empty() ? "node" + std::to_string(nodeIndex) : node.name;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = mesh.primitives[p];
        const std::string where =
            "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(p) + "]";
        if (prim.mode >= 0 && prim.mode < TINYGLTF_MODE_TRIANGLES) {
            Note(ctx, where + ": points/lines (mode " + std::to_string(prim.mode) + ") skipped");
            continue;
        }
        if (prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            Fail(ctx, where + ": invalid primitive mode " + std::to_string(prim.mode));
        if (prim.material >= static_cast<int>(model.materials.size()))
            Fail(ctx, where + ".material: " + std::to_string(prim.material) + " out of range");
        Object obj;
        obj.name = mesh.primitives.size() > 1 ? baseName + "#" + std::to_string(p) : baseName;
        obj.node = nodeIndex;
        obj.mesh = meshIndex;
        obj.primitive = static_cast<int>(p);
        obj.lensRole =
            StringOr(ctx, node.extras, "pemref_role", "", nodeWhere + ".extras") == "lens";
        // The default material is the last entry of Scene::materials (ConvertMaterials).
        obj.material =
            prim.material >= 0 ? prim.material : static_cast<int>(scene->materials.size()) - 1;
        if (BuildObject(ctx, ReadPrimitive(ctx, prim, where), world, where, &obj,
                        &scene->droppedDegenerate))
            scene->objects.push_back(std::move(obj));
        else
            Note(ctx, where + ": no non-degenerate triangles, skipped");
    }
}

}  // namespace pem::trace::gltf
