// SPDX-License-Identifier: MIT
// case_file_write.cpp — CaseToJson: a Frame as a gl_ref_case/1 (superset) file.
// Conventions: every key written explicitly (`depth` and `depth_test` only when present, their
// absence being meaningful; `color_format` and `internal_format` only when not rgba8, so a
// plain gl_ref_case/1 frame is written as before); texels as base64; floats as JSON numbers holding
// the float's exact double value, printed as the shortest repr that reads back to that double;
// arrays of scalars on one line, everything else indented by 2.
// Not here: reading (case_file.cpp).
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "viewer_tty/conformance/case_codec.h"
#include "viewer_tty/conformance/case_file.h"
#include "viewer_tty/conformance/case_names.h"

namespace pem::conformance {

namespace {

using Json = nlohmann::ordered_json;
using raster::Texture;
using raster::TextureKind;

double Exact(float f) {
    return static_cast<double>(f);
}

std::string_view MinFilterNameOf(const raster::SamplerState& s) {
    for (const MinFilterName& entry : kMinFilterNames)
        if (entry.filter == s.minFilter && entry.mip == s.mipFilter) return entry.name;
    return {};
}

Json TextureJson(const Texture& tex) {
    Json j;
    // Step 1: size and level count.
    if (tex.kind == TextureKind::Cube) {
        j["size"] = tex.width;
    } else {
        j["width"] = tex.width;
        j["height"] = tex.height;
    }
    j["levels"] = tex.NumLevels();
    // Step 2: sampler state.
    const raster::SamplerState& s = tex.sampler;
    j["min_filter"] = MinFilterNameOf(s);
    j["mag_filter"] = NameOf(kMagFilterNames, s.magFilter);
    if (tex.kind == TextureKind::Cube) {
        j["seamless"] = s.seamless;
    } else {
        j["wrap_s"] = NameOf(kWrapNames, s.wrapS);
        j["wrap_t"] = NameOf(kWrapNames, s.wrapT);
    }
    j["lod_bias"] = Exact(s.lodBias);
    j["min_lod"] = Exact(s.minLod);
    j["max_lod"] = Exact(s.maxLod);
    j["max_anisotropy"] = Exact(s.maxAnisotropy);
    if (tex.format != raster::TexelFormat::Rgba8)
        j["internal_format"] = NameOf(kTexelFormatNames, tex.format);
    // Step 3: texels, one base64 string per (level, face).
    Json images = Json::array();
    for (int l = 0; l < tex.NumLevels(); ++l) {
        const std::vector<uint8_t>& level = tex.levels[size_t(l)];
        const size_t faceBytes = level.size() / size_t(tex.Faces());
        Json faces = Json::array();
        for (size_t f = 0; f < size_t(tex.Faces()); ++f)
            faces.push_back(Base64Encode({level.begin() + std::ptrdiff_t(f * faceBytes),
                                          level.begin() + std::ptrdiff_t((f + 1) * faceBytes)}));
        images.push_back(tex.kind == TextureKind::Cube ? faces : faces[0]);
    }
    j["texels"] = {{"encoding", "base64"}, {"images", images}};
    return j;
}

Json BlendJson(const raster::BlendState& b) {
    if (!b.enabled) return "none";
    if (b == raster::BlendState::Over()) return "over";
    if (b == raster::BlendState::Additive()) return "add";
    if (b == raster::BlendState::Multiply()) return "multiply";
    Json j;
    j["src_rgb"] = NameOf(kBlendFactorNames, b.srcRgb);
    j["dst_rgb"] = NameOf(kBlendFactorNames, b.dstRgb);
    j["src_alpha"] = NameOf(kBlendFactorNames, b.srcAlpha);
    j["dst_alpha"] = NameOf(kBlendFactorNames, b.dstAlpha);
    j["equation_rgb"] = NameOf(kBlendEquationNames, b.eqRgb);
    j["equation_alpha"] = NameOf(kBlendEquationNames, b.eqAlpha);
    return j;
}

// A unit reference {"cube": i} or {"tex2d": i} for Frame texture index `t`.
Json UnitJson(const raster::Frame& frame, int t) {
    if (t < 0 || size_t(t) >= frame.textures.size())
        throw std::invalid_argument("CaseToJson: texture index out of range");
    int cubesBefore = 0, tex2dBefore = 0;
    for (int k = 0; k < t; ++k)
        (frame.textures[size_t(k)].kind == TextureKind::Cube ? cubesBefore : tex2dBefore)++;
    if (frame.textures[size_t(t)].kind == TextureKind::Cube) return {{"cube", cubesBefore}};
    return {{"tex2d", tex2dBefore}};
}

Json VertexJson(const raster::Vertex& v, int numUnits) {
    Json numbers = Json::array();
    for (int c = 0; c < 4; ++c) numbers.push_back(Exact(v.pos[c]));
    for (int u = 0; u < numUnits; ++u)
        for (int c = 0; c < 3; ++c) numbers.push_back(Exact(v.coord[size_t(u)][c]));
    for (int c = 0; c < 4; ++c) numbers.push_back(Exact(v.color[c]));
    return numbers;
}

Json PassJson(const raster::Frame& frame, const raster::Pass& pass) {
    Json j;
    j["units"] = Json::array();
    for (int u = 0; u < pass.numUnits; ++u)
        j["units"].push_back(UnitJson(frame, pass.texture[size_t(u)]));
    j["blend"] = BlendJson(pass.blend);
    if (pass.depthTest)
        j["depth_test"] = {{"func", NameOf(kDepthFuncNames, pass.depthTest->func)},
                           {"write", pass.depthTest->write}};
    j["vertices"] = Json::array();
    for (const raster::Vertex& v : pass.vertices)
        j["vertices"].push_back(VertexJson(v, pass.numUnits));
    if (!pass.indices.empty()) j["indices"] = pass.indices;
    return j;
}

// Pretty printer: scalars and arrays of scalars on one line, containers expanded.
bool IsFlat(const Json& j) {
    if (!j.is_array()) return !j.is_object();
    for (const Json& e : j)
        if (e.is_structured()) return false;
    return true;
}

void Print(const Json& j, int indent, std::ostringstream* out) {
    if (IsFlat(j)) {
        *out << j.dump(-1, ' ', false, Json::error_handler_t::strict);
        return;
    }
    const std::string pad(size_t(indent + 2), ' ');
    *out << (j.is_object() ? "{\n" : "[\n");
    size_t k = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++k) {
        *out << pad;
        if (j.is_object()) *out << Json(it.key()).dump() << ": ";
        Print(*it, indent + 2, out);
        *out << (k + 1 < j.size() ? ",\n" : "\n");
    }
    *out << std::string(size_t(indent), ' ') << (j.is_object() ? "}" : "]");
}

}  // namespace

std::string CaseToJson(const raster::Frame& frame) {
    // Step 1: the framebuffer (the case format has no scissor test).
    if (frame.scissor)
        throw std::invalid_argument("CaseToJson: the case format has no scissor box");
    Json j;
    j["format"] = "gl_ref_case/1";
    j["width"] = frame.width;
    j["height"] = frame.height;
    if (frame.colorFormat != raster::ColorFormat::Rgba8)
        j["color_format"] = NameOf(kColorFormatNames, frame.colorFormat);
    j["clear"] = frame.clear;
    j["depth_clamp"] = frame.depthClamp;
    if (frame.depth)
        j["depth"] = {{"format", NameOf(kDepthFormatNames, frame.depth->format)},
                      {"clear", Exact(frame.depth->clear)}};
    // Step 2: textures, split by kind (file order = Frame order within each kind).
    j["cubemaps"] = Json::array();
    j["textures2d"] = Json::array();
    for (const Texture& tex : frame.textures)
        j[tex.kind == TextureKind::Cube ? "cubemaps" : "textures2d"].push_back(TextureJson(tex));
    // Step 3: passes.
    j["passes"] = Json::array();
    for (const raster::Pass& pass : frame.passes) j["passes"].push_back(PassJson(frame, pass));
    std::ostringstream out;
    Print(j, 0, &out);
    out << "\n";
    return out.str();
}

}  // namespace pem::conformance
