// SPDX-License-Identifier: MIT
// gltf_material.cpp — glTF materials → trace::Material (the mapping is in material.h), and the
// images they reference → linear float Texture2D (8- or 16-bit, 1–4 channels, sRGB decoded:
// base colour and emissive textures are sRGB in glTF). Each glTF texture is converted once.
// Not here: texture sampling (material.cpp), KHR_texture_transform (noted, ignored).
#include <cmath>
#include <map>

#include "trace/gltf_internal.h"

namespace pem::trace::gltf {

namespace {

float SrgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

Texture2D ConvertImage(const Context& ctx, int textureIndex, const std::string& where) {
    const auto& m = ctx.model;
    if (textureIndex < 0 || static_cast<size_t>(textureIndex) >= m.textures.size())
        Fail(ctx, where + ": texture " + std::to_string(textureIndex) + " out of range");
    const int source = m.textures[static_cast<size_t>(textureIndex)].source;
    if (source < 0 || static_cast<size_t>(source) >= m.images.size())
        Fail(ctx, where + ": texture " + std::to_string(textureIndex) + " has no valid image");
    const tinygltf::Image& img = m.images[static_cast<size_t>(source)];
    const int bytes = img.bits == 16 ? 2 : 1;
    const size_t expected =
        static_cast<size_t>(std::max(img.width, 0)) * static_cast<size_t>(std::max(img.height, 0)) *
        static_cast<size_t>(std::max(img.component, 0)) * static_cast<size_t>(bytes);
    if (img.width <= 0 || img.height <= 0 || img.component < 1 || img.component > 4 ||
        (img.bits != 8 && img.bits != 16) || img.image.size() != expected)
        Fail(ctx, where + ": image " + std::to_string(source) + " was not decoded (unsupported)");
    Texture2D tex;
    tex.name = img.name.empty() ? img.uri : img.name;
    tex.width = img.width;
    tex.height = img.height;
    tex.rgb.resize(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
    const size_t pixels = tex.rgb.size() / 3;
    const float scale = bytes == 2 ? 1.0f / 65535.0f : 1.0f / 255.0f;
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
            // Grey (1–2 channels) replicates channel 0.
            const int ch = img.component >= 3 ? c : 0;
            const size_t at = (i * static_cast<size_t>(img.component) + static_cast<size_t>(ch)) *
                              static_cast<size_t>(bytes);
            const unsigned value = bytes == 2
                                       ? unsigned(img.image[at]) | unsigned(img.image[at + 1]) << 8
                                       : unsigned(img.image[at]);
            tex.rgb[3 * i + static_cast<size_t>(c)] =
                SrgbToLinear(static_cast<float>(value) * scale);
        }
    return tex;
}

// The glTF sampler of a texture (absent: LINEAR, REPEAT); unknown enum values are errors.
TextureSampler ConvertSampler(const Context& ctx, int samplerIndex, const std::string& where) {
    TextureSampler s;
    if (samplerIndex < 0) return s;
    const auto& m = ctx.model;
    if (static_cast<size_t>(samplerIndex) >= m.samplers.size())
        Fail(ctx, where + ": sampler " + std::to_string(samplerIndex) + " out of range");
    const tinygltf::Sampler& g = m.samplers[static_cast<size_t>(samplerIndex)];
    if (g.magFilter != -1 && g.magFilter != 9728 && g.magFilter != 9729)
        Fail(ctx, where + ": sampler magFilter " + std::to_string(g.magFilter) + " is not valid");
    if (g.minFilter != -1 &&
        (g.minFilter < 9728 || g.minFilter > 9987 || (g.minFilter > 9729 && g.minFilter < 9984)))
        Fail(ctx, where + ": sampler minFilter " + std::to_string(g.minFilter) + " is not valid");
    s.nearest = g.magFilter == 9728;
    s.minFilter = g.minFilter;
    auto wrap = [&](int v, const char* name) {
        if (v == 10497) return TexWrap::Repeat;
        if (v == 33071) return TexWrap::ClampToEdge;
        if (v == 33648) return TexWrap::MirroredRepeat;
        Fail(ctx, where + ": sampler " + name + " " + std::to_string(v) + " is not valid");
        return TexWrap::Repeat;
    };
    s.wrapS = wrap(g.wrapS, "wrapS");
    s.wrapT = wrap(g.wrapT, "wrapT");
    return s;
}

// The Scene::textures index for a glTF texture, converting it on first use.
int TextureSlot(const Context& ctx, const tinygltf::TextureInfo& info, const std::string& where,
                std::map<int, int>* cache, Scene* scene) {
    if (info.index < 0) return -1;
    if (Extension(info.extensions, "KHR_texture_transform"))
        Note(ctx, where + ": KHR_texture_transform ignored");
    if (info.texCoord != 0)
        Note(ctx, where + ": texCoord " + std::to_string(info.texCoord) +
                      " not supported, TEXCOORD_0 used");
    auto it = cache->find(info.index);
    if (it != cache->end()) return it->second;
    scene->textures.push_back(ConvertImage(ctx, info.index, where));
    scene->textures.back().sampler =
        ConvertSampler(ctx, ctx.model.textures[static_cast<size_t>(info.index)].sampler, where);
    const int slot = static_cast<int>(scene->textures.size()) - 1;
    (*cache)[info.index] = slot;
    return slot;
}

glm::vec3 Factor3(const Context& ctx, const std::vector<double>& f, size_t expected,
                  const std::string& where) {
    if (f.size() != expected)
        Fail(ctx, where + ": expected " + std::to_string(expected) + " numbers");
    for (double x : f)
        if (!std::isfinite(x) || x < 0.0)
            Fail(ctx, where + ": expected non-negative finite numbers");
    return glm::vec3(static_cast<float>(f[0]), static_cast<float>(f[1]), static_cast<float>(f[2]));
}

// Glass parameters from KHR_materials_transmission / _ior / _volume.
void ApplyGlass(const Context& ctx, const tinygltf::Material& src, const std::string& where,
                Material* mat) {
    const tinygltf::Value* tr = Extension(src.extensions, "KHR_materials_transmission");
    const double transmission =
        tr ? NumberOr(ctx, *tr, "transmissionFactor", 0.0, where + ".KHR_materials_transmission")
           : 0.0;
    if (transmission <= 0.0) return;
    if (transmission > 1.0) Fail(ctx, where + ": transmissionFactor > 1");
    mat->kind = MaterialKind::Glass;
    mat->transmission = static_cast<float>(transmission);
    if (const tinygltf::Value* ior = Extension(src.extensions, "KHR_materials_ior")) {
        const double v = NumberOr(ctx, *ior, "ior", 1.5, where + ".KHR_materials_ior");
        if (v < 1.0 || v > 10.0) Fail(ctx, where + ".KHR_materials_ior.ior: must be in [1, 10]");
        mat->ior = static_cast<float>(v);
    }
    if (const tinygltf::Value* vol = Extension(src.extensions, "KHR_materials_volume")) {
        const std::string w = where + ".KHR_materials_volume";
        const glm::dvec3 c = Vec3Or(ctx, *vol, "attenuationColor", glm::dvec3(1.0), w);
        const double d = NumberOr(ctx, *vol, "attenuationDistance", HUGE_VAL, w);
        if (d <= 0.0) Fail(ctx, w + ".attenuationDistance: must be > 0");
        for (int k = 0; k < 3; ++k) {
            if (c[k] < 0.0 || c[k] > 1.0) Fail(ctx, w + ".attenuationColor: must be in [0, 1]");
            // σ = −ln(c)/d; c = 0 would be infinitely dark, so it is clamped to 1e-6.
            mat->absorption[k] =
                std::isinf(d) ? 0.0f : static_cast<float>(-std::log(std::max(c[k], 1e-6)) / d);
        }
    }
}

Material ConvertMaterial(const Context& ctx, const tinygltf::Material& src,
                         const std::string& where, std::map<int, int>* cache, Scene* scene) {
    Material mat;
    mat.name = src.name;
    const auto& pbr = src.pbrMetallicRoughness;
    // Step 1: base colour and emission (+ textures).
    mat.baseColor = Factor3(ctx, pbr.baseColorFactor, 4, where + ".baseColorFactor");
    mat.baseColorTexture =
        TextureSlot(ctx, pbr.baseColorTexture, where + ".baseColorTexture", cache, scene);
    mat.emission =
        Factor3(ctx, src.emissiveFactor.empty() ? std::vector<double>{0, 0, 0} : src.emissiveFactor,
                3, where + ".emissiveFactor");
    if (const tinygltf::Value* es = Extension(src.extensions, "KHR_materials_emissive_strength")) {
        const double s =
            NumberOr(ctx, *es, "emissiveStrength", 1.0, where + ".KHR_materials_emissive_strength");
        if (s < 0.0) Fail(ctx, where + ".emissiveStrength: must be >= 0");
        mat.emission *= static_cast<float>(s);
    }
    mat.emissiveTexture =
        TextureSlot(ctx, src.emissiveTexture, where + ".emissiveTexture", cache, scene);
    // Step 2: the kind.
    ApplyGlass(ctx, src, where, &mat);
    if (mat.kind == MaterialKind::Glass) return mat;
    if (pbr.metallicFactor == 1.0 && pbr.roughnessFactor == 0.0) {
        mat.kind = MaterialKind::Mirror;
    } else if (pbr.metallicFactor > 0.0) {
        Note(ctx, where + " (" + src.name + "): metallic " + std::to_string(pbr.metallicFactor) +
                      ", roughness " + std::to_string(pbr.roughnessFactor) +
                      " approximated as diffuse");
    }
    return mat;
}

}  // namespace

void ConvertMaterials(const Context& ctx, Scene* scene) {
    std::map<int, int> cache;  // glTF texture index → Scene::textures index
    for (size_t i = 0; i < ctx.model.materials.size(); ++i)
        scene->materials.push_back(ConvertMaterial(
            ctx, ctx.model.materials[i], "materials[" + std::to_string(i) + "]", &cache, scene));
    Material fallback;  // for primitives without a material (glTF's default is white)
    fallback.name = "default";
    scene->materials.push_back(fallback);
}

}  // namespace pem::trace::gltf
