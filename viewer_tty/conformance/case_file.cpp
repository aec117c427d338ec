// SPDX-License-Identifier: MIT
// case_file.cpp — the case reader: JSON text -> validated pem::raster::Frame.
// Conventions: every helper takes `where`, the JSON key path of the value it reads ("passes[2].
// vertices[7][4]"), and reports problems by throwing CaseError("<where>: <cause>"); the public
// entry points turn that into pem::base::InputError with the file path in front.
// Not here: the writer (case_file_write.cpp), byte codecs and generators (case_codec.h).
#include "viewer_tty/conformance/case_file.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "viewer_tty/conformance/case_codec.h"
#include "viewer_tty/conformance/case_names.h"
#include "viewer_tty/conformance/case_values.h"

namespace pem::conformance {

namespace {

using nlohmann::json;
using raster::Frame;
using raster::Pass;
using raster::Texture;
using raster::TextureKind;

constexpr int kMaxSize = 8192;
constexpr const char* kFormatName = "gl_ref_case/1";

// Texture sizes --------------------------------------------------------------------------------

int PowerOfTwoSize(const json& obj, const std::string& where, const char* key) {
    const int size =
        static_cast<int>(AsInt(Require(obj, where, key), Key(where, key), 1, kMaxSize));
    if (!std::has_single_bit(static_cast<unsigned>(size)))
        Fail(Key(where, key), std::to_string(size) + " is not a power of two");
    return size;
}

int MaxLevels(int width, int height) {
    return std::bit_width(static_cast<unsigned>(std::max(width, height)));
}

// Sampler state ---------------------------------------------------------------------------------

raster::SamplerState ParseSampler(const json& obj, const std::string& where, TextureKind kind) {
    raster::SamplerState s;
    if (const json* v = Find(obj, "min_filter")) {
        const std::string name = AsString(*v, Key(where, "min_filter"));
        const auto* it = std::find_if(kMinFilterNames.begin(), kMinFilterNames.end(),
                                      [&](const MinFilterName& n) { return n.name == name; });
        if (it == kMinFilterNames.end())
            Fail(Key(where, "min_filter"), "unknown filter \"" + name + "\"");
        s.minFilter = it->filter;
        s.mipFilter = it->mip;
    }
    s.magFilter = EnumOr(obj, where, "mag_filter", kMagFilterNames, s.magFilter);
    if (kind == TextureKind::Cube) {
        s.seamless = BoolOr(obj, where, "seamless", true);
    } else {
        s.wrapS = EnumOr(obj, where, "wrap_s", kWrapNames, s.wrapS);
        s.wrapT = EnumOr(obj, where, "wrap_t", kWrapNames, s.wrapT);
    }
    s.lodBias = FloatOr(obj, where, "lod_bias", s.lodBias);
    s.minLod = FloatOr(obj, where, "min_lod", s.minLod);
    s.maxLod = FloatOr(obj, where, "max_lod", s.maxLod);
    if (const json* v = Find(obj, "max_anisotropy")) {
        // glTexParameterf(GL_TEXTURE_MAX_ANISOTROPY) rejects values below 1.
        s.maxAnisotropy = AsFloat(*v, Key(where, "max_anisotropy"));
        if (!(s.maxAnisotropy >= 1.0f)) Fail(Key(where, "max_anisotropy"), v->dump() + " below 1");
    }
    return s;
}

// Texels ------------------------------------------------------------------------------------------

TexelGen ParseTexelGen(const json& obj, const std::string& where) {
    TexelGen gen;
    const std::string name = AsString(*Find(obj, "gen"), Key(where, "gen"));
    if (name == "random" || name == "random_box") {
        gen.kind = name == "random" ? TexelGenKind::Random : TexelGenKind::RandomBox;
        gen.seed = AsSeed(Require(obj, where, "seed"), Key(where, "seed"));
        gen.alpha = 255;
        const json* alpha = Find(obj, "alpha");
        if (alpha && alpha->is_string() && alpha->get<std::string>() == "random")
            gen.alpha = -1;
        else if (alpha)
            gen.alpha = static_cast<int>(AsInt(*alpha, Key(where, "alpha"), 0, 255));
    } else if (name == "gradient") {
        gen.kind = TexelGenKind::Gradient;
        gen.alpha = IntOr(obj, where, "alpha", -1, 0, 255);
    } else {
        Fail(Key(where, "gen"), "unknown generator \"" + name + "\"");
    }
    return gen;
}

// Every float of an RGBA32F level is finite.
void CheckFinite(const std::vector<uint8_t>& level, const std::string& where) {
    const std::vector<float> values = raster::FloatsFromBytes(level);
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            Fail(where, "texel " + std::to_string(i / 4) + " component " + std::to_string(i % 4) +
                            " is not a finite float");
}

// One explicit image string, decoded and checked against its expected byte count.
std::vector<uint8_t> DecodeImage(const json& v, const std::string& where, bool base64,
                                 size_t expectedBytes) {
    const std::string text = AsString(v, where);
    DecodeResult decoded = base64 ? Base64Decode(text) : HexDecode(text);
    if (!decoded.error.empty()) Fail(where, decoded.error);
    if (decoded.bytes.size() != expectedBytes)
        Fail(where, "expected " + std::to_string(expectedBytes) + " bytes, got " +
                        std::to_string(decoded.bytes.size()));
    return decoded.bytes;
}

std::vector<std::vector<uint8_t>> ParseExplicitTexels(const json& obj, const std::string& where,
                                                      const Texture& tex, int numLevels) {
    const std::string encoding = AsString(*Find(obj, "encoding"), Key(where, "encoding"));
    if (encoding != "hex" && encoding != "base64")
        Fail(Key(where, "encoding"), "unknown encoding \"" + encoding + "\"");
    const std::string imagesWhere = Key(where, "images");
    const json& images = AsArray(Require(obj, where, "images"), imagesWhere);
    if (images.size() != size_t(numLevels))
        Fail(imagesWhere, "expected " + std::to_string(numLevels) + " levels, got " +
                              std::to_string(images.size()));
    std::vector<std::vector<uint8_t>> levels;
    for (int l = 0; l < numLevels; ++l) {
        const std::string levelWhere = Index(imagesWhere, size_t(l));
        const size_t faceBytes =
            size_t(tex.LevelWidth(l)) * size_t(tex.LevelHeight(l)) * size_t(tex.TexelBytes());
        const json& entry = images[size_t(l)];
        if (tex.kind == TextureKind::Tex2D && entry.is_string()) {
            levels.push_back(DecodeImage(entry, levelWhere, encoding == "base64", faceBytes));
            continue;
        }
        const json& faces = AsArray(entry, levelWhere);
        if (faces.size() != size_t(tex.Faces()))
            Fail(levelWhere, "expected " + std::to_string(tex.Faces()) + " face strings, got " +
                                 std::to_string(faces.size()));
        std::vector<uint8_t> level;
        for (size_t f = 0; f < faces.size(); ++f) {
            std::vector<uint8_t> face =
                DecodeImage(faces[f], Index(levelWhere, f), encoding == "base64", faceBytes);
            level.insert(level.end(), face.begin(), face.end());
        }
        levels.push_back(std::move(level));
    }
    if (tex.format == raster::TexelFormat::Rgba32F)
        for (size_t l = 0; l < levels.size(); ++l) CheckFinite(levels[l], Index(imagesWhere, l));
    return levels;
}

std::vector<std::vector<uint8_t>> ParseTexels(const json& v, const std::string& where,
                                              const Texture& tex, int numLevels) {
    const json& obj = AsObject(v, where);
    if (Find(obj, "gen")) {
        std::vector<std::vector<uint8_t>> levels =
            GenerateTexels(tex.kind, tex.width, tex.height, numLevels, ParseTexelGen(obj, where));
        if (tex.format == raster::TexelFormat::Rgba32F)
            for (std::vector<uint8_t>& level : levels) level = FloatLevelFromBytes(level);
        return levels;
    }
    if (Find(obj, "encoding")) return ParseExplicitTexels(obj, where, tex, numLevels);
    Fail(where, "missing key \"gen\" or \"encoding\"");
}

// Textures -------------------------------------------------------------------------------------

Texture ParseTexture(const json& v, const std::string& where, TextureKind kind) {
    const json& obj = AsObject(v, where);
    Texture tex;
    tex.kind = kind;
    // Step 1: level-0 size (cubes are square) and the number of levels given.
    if (kind == TextureKind::Cube) {
        tex.width = tex.height = PowerOfTwoSize(obj, where, "size");
    } else {
        tex.width = PowerOfTwoSize(obj, where, "width");
        tex.height = PowerOfTwoSize(obj, where, "height");
    }
    const int maxLevels = MaxLevels(tex.width, tex.height);
    const int numLevels = IntOr(obj, where, "levels", maxLevels, 1, maxLevels);
    // Step 2: sampler state and texels.
    tex.sampler = ParseSampler(obj, where, kind);
    tex.format = EnumOr(obj, where, "internal_format", kTexelFormatNames, tex.format);
    tex.levels = ParseTexels(Require(obj, where, "texels"), Key(where, "texels"), tex, numLevels);
    return tex;
}

// Passes ----------------------------------------------------------------------------------------

// The file's cube count and texture list, to resolve unit references.
struct TextureTable {
    int numCubes = 0;
    const std::vector<Texture>* textures = nullptr;
};

int ResolveUnit(const json& v, const std::string& where, const TextureTable& table) {
    const json& obj = AsObject(v, where);
    const json* cube = Find(obj, "cube");
    const json* tex2d = Find(obj, "tex2d");
    if ((cube == nullptr) == (tex2d == nullptr))
        Fail(where, "expected exactly one of \"cube\" or \"tex2d\"");
    const int num2d = static_cast<int>(table.textures->size()) - table.numCubes;
    if (cube) {
        const int64_t i = AsInt(*cube, Key(where, "cube"), 0, std::numeric_limits<int>::max());
        if (i >= table.numCubes)
            Fail(Key(where, "cube"), "cube " + std::to_string(i) + " out of range (" +
                                         std::to_string(table.numCubes) + " cubemaps)");
        return static_cast<int>(i);
    }
    const int64_t i = AsInt(*tex2d, Key(where, "tex2d"), 0, std::numeric_limits<int>::max());
    if (i >= num2d)
        Fail(Key(where, "tex2d"), "2D texture " + std::to_string(i) + " out of range (" +
                                      std::to_string(num2d) + " textures2d)");
    return table.numCubes + static_cast<int>(i);
}

// Fills pass->numUnits and pass->texture from `units`, or the legacy `cubemap` key.
void ParseUnits(const json& obj, const std::string& where, const TextureTable& table, Pass* pass) {
    const json* units = Find(obj, "units");
    if (!units) {
        const int cube = IntOr(obj, where, "cubemap", 0, 0, std::numeric_limits<int>::max());
        if (cube >= table.numCubes)
            Fail(Key(where, "cubemap"), "cube " + std::to_string(cube) + " out of range (" +
                                            std::to_string(table.numCubes) + " cubemaps)");
        pass->numUnits = 1;
        pass->texture = {cube, 0};
        return;
    }
    const std::string unitsWhere = Key(where, "units");
    const json& list = AsArray(*units, unitsWhere);
    if (list.size() > size_t(raster::kMaxUnits))
        Fail(unitsWhere, std::to_string(list.size()) + " units (at most 2)");
    pass->numUnits = static_cast<int>(list.size());
    for (size_t u = 0; u < list.size(); ++u)
        pass->texture[u] = ResolveUnit(list[u], Index(unitsWhere, u), table);
}

// Two cube maps with different `seamless` flags cannot be sampled in one draw (global GL state).
void CheckSeamless(const Pass& pass, const std::string& where, const TextureTable& table) {
    int seamless = -1;
    for (int u = 0; u < pass.numUnits; ++u) {
        const Texture& tex = (*table.textures)[size_t(pass.texture[size_t(u)])];
        if (tex.kind != TextureKind::Cube) continue;
        const int flag = tex.sampler.seamless ? 1 : 0;
        if (seamless >= 0 && flag != seamless)
            Fail(Key(where, "units"), "the pass samples cube maps with different \"seamless\"");
        seamless = flag;
    }
}

raster::BlendState ParseBlendObject(const json& obj, const std::string& where) {
    raster::BlendState b;
    b.enabled = true;
    b.srcRgb = EnumOr(obj, where, "src_rgb", kBlendFactorNames, raster::BlendFactor::One);
    b.dstRgb = EnumOr(obj, where, "dst_rgb", kBlendFactorNames, raster::BlendFactor::Zero);
    b.srcAlpha = EnumOr(obj, where, "src_alpha", kBlendFactorNames, b.srcRgb);
    b.dstAlpha = EnumOr(obj, where, "dst_alpha", kBlendFactorNames, b.dstRgb);
    b.eqRgb = EnumOr(obj, where, "equation_rgb", kBlendEquationNames, raster::BlendEquation::Add);
    b.eqAlpha =
        EnumOr(obj, where, "equation_alpha", kBlendEquationNames, raster::BlendEquation::Add);
    return b;
}

raster::BlendState ParseBlend(const json& obj, const std::string& where) {
    const json* v = Find(obj, "blend");
    if (!v) return raster::BlendState::None();
    const std::string blendWhere = Key(where, "blend");
    if (v->is_object()) return ParseBlendObject(*v, blendWhere);
    const std::string name = AsString(*v, blendWhere);
    if (name == "none") return raster::BlendState::None();
    if (name == "over") return raster::BlendState::Over();
    if (name == "add") return raster::BlendState::Additive();
    if (name == "multiply") return raster::BlendState::Multiply();
    Fail(blendWhere, "unknown blend mode \"" + name + "\"");
}

// The pass's `depth_test` (absent: GL_DEPTH_TEST disabled); it needs the case's depth buffer.
std::optional<raster::DepthTest> ParseDepthTest(const json& obj, const std::string& where,
                                                bool haveDepth) {
    const json* v = Find(obj, "depth_test");
    if (!v) return std::nullopt;
    const std::string testWhere = Key(where, "depth_test");
    const json& test = AsObject(*v, testWhere);
    if (!haveDepth) Fail(testWhere, "the case has no \"depth\" buffer");
    raster::DepthTest t;
    t.func = EnumOr(test, testWhere, "func", kDepthFuncNames, t.func);
    t.write = BoolOr(test, testWhere, "write", t.write);
    return t;
}

Pass ParsePass(const json& v, const std::string& where, const TextureTable& table, bool haveDepth) {
    const json& obj = AsObject(v, where);
    Pass pass;
    // Step 1: texture units, blending and the depth test.
    ParseUnits(obj, where, table, &pass);
    CheckSeamless(pass, where, table);
    pass.blend = ParseBlend(obj, where);
    pass.depthTest = ParseDepthTest(obj, where, haveDepth);
    // Step 2: geometry, then the triangle-list checks.
    pass.vertices = ParseVertices(obj, where, pass.numUnits);
    pass.indices = ParseIndices(obj, where);
    CheckTriangles(pass, where);
    return pass;
}

// Frame -------------------------------------------------------------------------------------------

std::array<uint8_t, 4> ParseClear(const json& obj) {
    std::array<uint8_t, 4> clear{0, 0, 0, 0};
    const json* v = Find(obj, "clear");
    if (!v) return clear;
    const json& list = AsArray(*v, "clear");
    if (list.size() != 4) Fail("clear", "expected 4 numbers [R,G,B,A]");
    for (size_t c = 0; c < 4; ++c)
        clear[c] = static_cast<uint8_t>(AsInt(list[c], Index("clear", c), 0, 255));
    return clear;
}

// The top-level `depth` buffer (absent: none): a required format and a clear value in [0, 1].
std::optional<raster::DepthBuffer> ParseDepth(const json& root) {
    const json* v = Find(root, "depth");
    if (!v) return std::nullopt;
    const json& obj = AsObject(*v, "depth");
    raster::DepthBuffer depth;
    Require(obj, "depth", "format");
    depth.format = EnumOr(obj, "depth", "format", kDepthFormatNames, depth.format);
    if (const json* clear = Find(obj, "clear")) {
        depth.clear = AsFloat(*clear, "depth.clear");
        if (!(depth.clear >= 0.0f && depth.clear <= 1.0f))
            Fail("depth.clear", clear->dump() + " outside [0, 1]");
    }
    return depth;
}

// Appends the textures of array `key` (absent = none) of `kind` to frame->textures.
void ParseTextureList(const json& root, const char* key, TextureKind kind, Frame* frame) {
    const json* v = Find(root, key);
    if (!v) return;
    const json& list = AsArray(*v, key);
    for (size_t i = 0; i < list.size(); ++i)
        frame->textures.push_back(ParseTexture(list[i], Index(key, i), kind));
}

Frame ParseFrame(const json& root) {
    AsObject(root, "(top level)");
    if (const json* format = Find(root, "format");
        format && AsString(*format, "format") != kFormatName)
        Fail("format", "unsupported format \"" + format->get<std::string>() + "\"");
    Frame frame;
    // Step 1: framebuffer.
    frame.width = static_cast<int>(AsInt(Require(root, "", "width"), "width", 1, kMaxSize));
    frame.height = static_cast<int>(AsInt(Require(root, "", "height"), "height", 1, kMaxSize));
    frame.colorFormat = EnumOr(root, "", "color_format", kColorFormatNames, frame.colorFormat);
    frame.clear = ParseClear(root);
    frame.depthClamp = BoolOr(root, "", "depth_clamp", false);
    frame.depth = ParseDepth(root);
    // Step 2: textures, cube maps first.
    ParseTextureList(root, "cubemaps", TextureKind::Cube, &frame);
    TextureTable table{static_cast<int>(frame.textures.size()), &frame.textures};
    ParseTextureList(root, "textures2d", TextureKind::Tex2D, &frame);
    // Step 3: passes.
    if (const json* passes = Find(root, "passes")) {
        const json& list = AsArray(*passes, "passes");
        for (size_t i = 0; i < list.size(); ++i)
            frame.passes.push_back(
                ParsePass(list[i], Index("passes", i), table, frame.depth.has_value()));
    }
    return frame;
}

std::string ReadWholeFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw base::InputError(path, "is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw base::InputError(path, std::string("cannot open: ") + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw base::InputError(path, "read error");
    return text.str();
}

}  // namespace

Frame ParseCaseJson(const std::string& text, const std::string& path) {
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) {  // syntax, and numbers beyond double (out_of_range)
        throw base::InputError(path, std::string("invalid JSON: ") + e.what());
    }
    try {
        return ParseFrame(root);
    } catch (const CaseError& e) {
        throw base::InputError(path, e.what());
    } catch (const json::exception& e) {
        throw base::InputError(path, e.what());
    }
}

Frame LoadCaseFile(const std::string& path) {
    return ParseCaseJson(ReadWholeFile(path), path);
}

}  // namespace pem::conformance
