// SPDX-License-Identifier: MIT
// material.h — pemref's three materials and the 2D textures they may reference.
//
// Mapping from glTF metallic-roughness (scene.cpp applies it, data/README.md documents it):
//  - Glass:   KHR_materials_transmission.transmissionFactor > 0. ior from KHR_materials_ior
//             (default 1.5); absorption σ = −ln(attenuationColor)/attenuationDistance per channel
//             (KHR_materials_volume; 0 when absent or the distance is infinite).
//  - Mirror:  metallicFactor == 1 and roughnessFactor == 0; baseColor is F0.
//  - Diffuse: everything else; baseColor is the albedo (rough metals are approximated as
//             diffuse; LoadScene adds a note when it does so).
//  - Any material may emit: emission = emissiveFactor × KHR_materials_emissive_strength.
// Textures are stored in linear float RGB (sRGB decoded at load), rows top-down as in the image
// file; glTF uv (0, 0) is the top-left corner of the image. Sampling is bilinear with REPEAT
// wrapping; the glTF sampler object is ignored.
// Not here: Fresnel (the math modules), texture transforms, normal/occlusion maps.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace pem::trace {

enum class MaterialKind { Diffuse, Mirror, Glass };

const char* MaterialKindName(MaterialKind kind);

// A glTF sampler as the tracer honours it (glTF 2.0 §3.8.4). The tracer samples the finest
// level — a ray has no footprint — which is where GL uses the magnification filter; so
// magFilter (NEAREST or LINEAR, LINEAR when undefined) picks the filter and minFilter (kept for
// the record) does not apply. Wraps as GL defines them on texel coordinates.
enum class TexWrap { Repeat, ClampToEdge, MirroredRepeat };
struct TextureSampler {
    bool nearest = false;  // magFilter NEAREST (9728); LINEAR (9729) or undefined otherwise
    int minFilter = -1;    // the glTF value, -1 undefined (not used: see above)
    TexWrap wrapS = TexWrap::Repeat, wrapT = TexWrap::Repeat;
    bool operator==(const TextureSampler&) const = default;
};

struct Texture2D {
    std::string name;
    int width = 0, height = 0;
    std::vector<float> rgb;  // width · height · 3, linear, rows top-down
    TextureSampler sampler;
    bool operator==(const Texture2D&) const = default;
};

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Diffuse;
    glm::vec3 baseColor{1.0f};   // diffuse albedo / mirror F0 / glass surface tint (unused)
    int baseColorTexture = -1;   // Scene::textures index, multiplies baseColor (diffuse only)
    glm::vec3 emission{0.0f};    // radiance scale: emissiveFactor × emissive strength
    int emissiveTexture = -1;    // Scene::textures index, multiplies emission
    float transmission = 0.0f;   // KHR_materials_transmission factor (glass only)
    float ior = 1.5f;            // glass only
    glm::vec3 absorption{0.0f};  // σ per world unit, per channel (glass only)
    bool operator==(const Material&) const = default;

    bool IsLens() const { return kind != MaterialKind::Diffuse; }  // mirror or glass
};

// The texture at glTF uv (texel centres at (i + 0.5)/width, v down the image) with its sampler:
// nearest texel floor(u·w) or bilinear between floor(u·w − 0.5) and the next, each texel
// coordinate wrapped by the sampler's wrap mode.
glm::vec3 SampleTexture(const Texture2D& texture, glm::vec2 uv);

}  // namespace pem::trace
