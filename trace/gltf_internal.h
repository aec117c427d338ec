// SPDX-License-Identifier: MIT
// gltf_internal.h — INTERNAL to trace/ (scene.cpp, gltf_*.cpp): checked access to a parsed
// tinygltf::Model. Every helper validates indices, sizes and types and reports a violation as
// pem::base::InputError("<gltf path>: <where>: <cause>") through Fail().
// Uses Debian's shared libtinygltf (docs/deps.md route A): <tiny_gltf.h> WITHOUT
// TINYGLTF_IMPLEMENTATION. Nothing outside trace/*.cpp may include this header.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "trace/scene.h"

namespace pem::trace::gltf {

// What every helper needs: the model, the file name for messages, the notes list.
struct Context {
    const tinygltf::Model& model;
    std::string path;
    std::vector<std::string>* notes;
};

[[noreturn]] void Fail(const Context& ctx, const std::string& cause);
void Note(const Context& ctx, const std::string& note);

// JSON values (extras/extensions). Missing keys give the default; a present key of the wrong
// type or a non-finite number fails with `where` in the message.
const tinygltf::Value* Member(const tinygltf::Value& object, const std::string& key);
double NumberOr(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                double fallback, const std::string& where);
std::string StringOr(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                     const std::string& fallback, const std::string& where);
glm::dvec3 Vec3Or(const Context& ctx, const tinygltf::Value& object, const std::string& key,
                  const glm::dvec3& fallback, const std::string& where);
const tinygltf::Value* Extension(const tinygltf::ExtensionMap& map, const std::string& name);

// Accessors (bounds-checked, sparse and bufferView-less accessors rejected).
std::vector<glm::vec3> ReadVec3(const Context& ctx, int accessor, const std::string& where);
std::vector<glm::vec2> ReadTexcoord(const Context& ctx, int accessor, const std::string& where);
std::vector<uint32_t> ReadIndices(const Context& ctx, int accessor, const std::string& where);

// Materials and the textures they use (Scene::textures), in glTF order.
void ConvertMaterials(const Context& ctx, Scene* scene);

// Appends the objects of mesh `meshIndex` instanced by node `nodeIndex` with world matrix
// `world` (column-major, double).
void AppendMeshObjects(const Context& ctx, int nodeIndex, int meshIndex, const glm::dmat4& world,
                       Scene* scene);

}  // namespace pem::trace::gltf
