// SPDX-License-Identifier: MIT
// case_file_test.cpp — case files: gl_ref_case/1 meaning (legacy 11-number vertices, blend names,
// generators), the superset (2D textures, 0..2 units), exact round trip Load(Save(f)) == f for
// random frames, and one base::InputError (with the path in front) per bad-input category.
// Not here: codecs and hashing (codec_test.cpp), rendering.
#include "viewer_tty/conformance/case_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>

#include "viewer_tty/conformance/case_codec.h"

namespace pem::conformance {
namespace {

using raster::Frame;
using raster::TextureKind;

constexpr const char* kPath = "mem.json";

// A 1-triangle legacy case with one 2x2 gradient cube, `extra` spliced into the pass.
std::string LegacyCase(const std::string& passExtra = "", const std::string& cubeExtra = "") {
    return R"({"width": 4, "height": 4, "clear": [1, 2, 3, 4],
      "cubemaps": [{"size": 2, "texels": {"gen": "gradient"})" +
           cubeExtra + R"(}],
      "passes": [{"blend": "over", "vertices": [
        [-1, -1, 0, 1,  1, 0, 0,  1, 1, 1, 1],
        [ 3, -1, 0, 1,  1, 0, 0,  1, 1, 1, 1],
        [-1,  3, 0, 1,  1, 0, 0,  1, 1, 1, "0x1p-1"]])" +
           passExtra + "}]}";
}

TEST(CaseFile, LegacyFormat) {
    const Frame f = ParseCaseJson(LegacyCase(), kPath);
    EXPECT_EQ(f.width, 4);
    EXPECT_EQ(f.clear, (std::array<uint8_t, 4>{1, 2, 3, 4}));
    ASSERT_EQ(f.textures.size(), 1u);
    EXPECT_EQ(f.textures[0].NumLevels(), 2);
    EXPECT_EQ(f.textures[0].sampler, raster::SamplerState{});
    ASSERT_EQ(f.passes.size(), 1u);
    EXPECT_EQ(f.passes[0].numUnits, 1);
    EXPECT_EQ(f.passes[0].texture[0], 0);
    EXPECT_EQ(f.passes[0].blend, raster::BlendState::Over());
    EXPECT_EQ(f.passes[0].vertices[1].pos.x, 3.0f);
    EXPECT_EQ(f.passes[0].vertices[2].color.a, 0.5f);
    EXPECT_EQ(f.passes[0].NumTriangles(), 1);
}

TEST(CaseFile, NumbersRoundDoubleToNearestFloat) {
    const Frame f = ParseCaseJson(LegacyCase(R"(, "cubemap": 0)", R"(, "lod_bias": 0.1)"), kPath);
    EXPECT_EQ(f.textures[0].sampler.lodBias, static_cast<float>(0.1));
}

TEST(CaseFile, UnitsAndTextures2d) {
    const std::string text = R"({"width": 2, "height": 2,
      "cubemaps": [{"size": 1, "seamless": false, "texels": {"gen": "random", "seed": "0x5EED0001"}}],
      "textures2d": [{"width": 4, "height": 2, "wrap_s": "repeat", "min_filter": "nearest",
        "levels": 2, "texels": {"encoding": "hex",
          "images": ["00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff", ["0a0b0c0d0e0f1011"]]}}],
      "passes": [
        {"units": [{"tex2d": 0}, {"cube": 0}], "vertices": [0,0,0,1, 0.5,0.5,9, 1,0,0, 1,1,1,1,
          0,0,0,1, 0,0,0, 1,0,0, 1,1,1,1,  0,0,0,1, 0,0,0, 1,0,0, 1,1,1,1]},
        {"units": [], "blend": {"src_rgb": "one", "dst_rgb": "one", "equation_rgb": "max"},
         "vertices": [[0,0,0,1, 1,1,1,1], [0,0,0,1, 1,1,1,1], [0,0,0,1, 1,1,1,1]],
         "indices": [0, 1, 2, 2, 1, 0]}]})";
    const Frame f = ParseCaseJson(text, kPath);
    ASSERT_EQ(f.textures.size(), 2u);
    EXPECT_EQ(f.textures[1].kind, TextureKind::Tex2D);
    EXPECT_EQ(f.textures[1].sampler.wrapS, raster::Wrap::Repeat);
    EXPECT_EQ(f.textures[1].sampler.mipFilter, raster::MipFilter::None);
    EXPECT_EQ(f.textures[1].levels[1].size(), 8u);
    EXPECT_EQ(f.passes[0].numUnits, 2);
    EXPECT_EQ(f.passes[0].texture, (std::array<int, 2>{1, 0}));
    EXPECT_EQ(f.passes[0].vertices[0].coord[0], glm::vec3(0.5f, 0.5f, 9.0f));
    EXPECT_EQ(f.passes[1].numUnits, 0);
    EXPECT_EQ(f.passes[1].blend.eqRgb, raster::BlendEquation::Max);
    EXPECT_EQ(f.passes[1].blend.eqAlpha, raster::BlendEquation::Add);
    EXPECT_EQ(f.passes[1].blend.dstAlpha, raster::BlendFactor::One);
    EXPECT_EQ(f.passes[1].NumTriangles(), 2);
}

// Random canonical frames ---------------------------------------------------------------------

float RandomFloat(std::mt19937_64* rng) {
    // Any finite float bit pattern, including subnormals and -0.
    for (;;) {
        const float f = std::bit_cast<float>(static_cast<uint32_t>((*rng)()));
        if (std::isfinite(f)) return f;
    }
}

raster::Texture RandomTexture(std::mt19937_64* rng, TextureKind kind) {
    raster::Texture tex;
    tex.kind = kind;
    tex.width = 1 << ((*rng)() % 4);
    tex.height = kind == TextureKind::Cube ? tex.width : 1 << ((*rng)() % 4);
    const int maxLevels = std::bit_width(unsigned(std::max(tex.width, tex.height)));
    const int numLevels = 1 + int((*rng)() % unsigned(maxLevels));
    tex.sampler.minFilter = raster::Filter((*rng)() % 2);
    tex.sampler.mipFilter = raster::MipFilter((*rng)() % 3);
    tex.sampler.magFilter = raster::Filter((*rng)() % 2);
    if (kind == TextureKind::Tex2D) tex.sampler.wrapS = raster::Wrap((*rng)() % 3);
    if (kind == TextureKind::Tex2D) tex.sampler.wrapT = raster::Wrap((*rng)() % 3);
    if (kind == TextureKind::Cube) tex.sampler.seamless = (*rng)() % 2;
    tex.sampler.lodBias = RandomFloat(rng);
    tex.sampler.minLod = RandomFloat(rng);
    if ((*rng)() % 2) tex.sampler.maxAnisotropy = 1.0f + float((*rng)() % 80) / 4.0f;
    tex.levels = GenerateTexels(kind, tex.width, tex.height, numLevels,
                                {TexelGenKind::Random, (*rng)(), -1});
    return tex;
}

raster::Pass RandomPass(std::mt19937_64* rng, const Frame& frame, int numCubes) {
    raster::Pass pass;
    pass.numUnits = int((*rng)() % 3);
    for (int u = 0; u < pass.numUnits; ++u)  // cube units all use cube 0: one seamless flag
        pass.texture[size_t(u)] = (*rng)() % 2 ? 0 : numCubes + int((*rng)() % 2);
    const raster::BlendState presets[] = {raster::BlendState::None(), raster::BlendState::Over(),
                                          raster::BlendState::Additive(),
                                          raster::BlendState::Multiply()};
    pass.blend = presets[(*rng)() % 4];
    if ((*rng)() % 3 == 0) {
        pass.blend.srcAlpha = raster::BlendFactor::SrcAlphaSaturate;
        pass.blend.eqAlpha = raster::BlendEquation::ReverseSubtract;
        pass.blend.enabled = true;
    }
    const int numVertices = 3 * int(1 + (*rng)() % 3);
    for (int k = 0; k < numVertices; ++k) {
        raster::Vertex v;
        for (int c = 0; c < 4; ++c) v.pos[c] = RandomFloat(rng);
        for (int u = 0; u < pass.numUnits; ++u)
            for (int c = 0; c < 3; ++c) v.coord[size_t(u)][c] = RandomFloat(rng);
        for (int c = 0; c < 4; ++c) v.color[c] = RandomFloat(rng);
        pass.vertices.push_back(v);
    }
    if ((*rng)() % 2)
        for (int k = 0; k < 6; ++k)
            pass.indices.push_back(uint32_t((*rng)() % unsigned(numVertices)));
    if (frame.depth && (*rng)() % 3 != 0)
        pass.depthTest = raster::DepthTest{raster::DepthFunc((*rng)() % 8), (*rng)() % 2 == 0};
    return pass;
}

Frame RandomFrame(uint64_t seed) {
    std::mt19937_64 rng(seed);
    Frame f;
    f.width = 1 + int(rng() % 64);
    f.height = 1 + int(rng() % 64);
    for (auto& c : f.clear) c = uint8_t(rng());
    f.depthClamp = rng() % 2;
    if (rng() % 3 != 0)  // clear: a random float in [0, 1] (odd values included)
        f.depth = raster::DepthBuffer{raster::DepthFormat(rng() % 3),
                                      float(rng() >> 40) / float(1 << 24)};
    f.textures.push_back(RandomTexture(&rng, TextureKind::Cube));
    f.textures.push_back(RandomTexture(&rng, TextureKind::Cube));
    f.textures.push_back(RandomTexture(&rng, TextureKind::Tex2D));
    f.textures.push_back(RandomTexture(&rng, TextureKind::Tex2D));
    for (int p = 0; p < 4; ++p) f.passes.push_back(RandomPass(&rng, f, 2));
    return f;
}

TEST(CaseFile, DepthKeysAndDefaults) {
    const std::string text = R"({"width": 4, "height": 4,
      "depth": {"format": "z16"},
      "passes": [
        {"units": [], "depth_test": {}, "vertices": [[-1,-1,0,1, 1,1,1,1], [3,-1,0,1, 1,1,1,1],
                                                      [-1,3,0,1, 1,1,1,1]]},
        {"units": [], "depth_test": {"func": "gequal", "write": false},
         "vertices": [[-1,-1,0,1, 1,1,1,1], [3,-1,0,1, 1,1,1,1], [-1,3,0,1, 1,1,1,1]]},
        {"units": [], "vertices": [[-1,-1,0,1, 1,1,1,1], [3,-1,0,1, 1,1,1,1], [-1,3,0,1, 1,1,1,1]]}]})";
    const Frame f = ParseCaseJson(text, kPath);
    ASSERT_TRUE(f.depth.has_value());
    EXPECT_EQ(f.depth->format, raster::DepthFormat::Z16);
    EXPECT_EQ(f.depth->clear, 1.0f);
    EXPECT_EQ(f.passes[0].depthTest, (raster::DepthTest{raster::DepthFunc::Less, true}));
    EXPECT_EQ(f.passes[1].depthTest, (raster::DepthTest{raster::DepthFunc::GEqual, false}));
    EXPECT_FALSE(f.passes[2].depthTest.has_value());
    const Frame g = ParseCaseJson(R"({"width": 1, "height": 1,
      "depth": {"format": "z32f", "clear": 0.3}, "passes": []})",
                                  kPath);
    EXPECT_EQ(g.depth->clear, 0.3f);
    EXPECT_FALSE(ParseCaseJson(LegacyCase(), kPath).depth.has_value());
}

TEST(CaseFile, MaxAnisotropyKeyAndDefault) {
    const std::string text = R"({"width": 2, "height": 2,
      "cubemaps": [{"size": 1, "max_anisotropy": 16, "texels": {"gen": "gradient"}},
                   {"size": 1, "texels": {"gen": "gradient"}}],
      "textures2d": [{"width": 1, "height": 1, "max_anisotropy": "0x1.4p+1",
                      "texels": {"gen": "gradient"}}]})";
    const Frame f = ParseCaseJson(text, kPath);
    EXPECT_EQ(f.textures[0].sampler.maxAnisotropy, 16.0f);
    EXPECT_EQ(f.textures[1].sampler.maxAnisotropy, 1.0f);  // default: off
    EXPECT_EQ(f.textures[2].sampler.maxAnisotropy, 2.5f);
    const std::string written = CaseToJson(f);
    EXPECT_NE(written.find("\"max_anisotropy\": 2.5"), std::string::npos);
    EXPECT_TRUE(ParseCaseJson(written, kPath) == f);
}

TEST(CaseFile, RoundTripRandomFrames) {
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        const Frame f = RandomFrame(seed);
        const std::string text = CaseToJson(f);
        const Frame g = ParseCaseJson(text, kPath);
        EXPECT_TRUE(f == g) << "seed " << seed;
        EXPECT_EQ(CaseToJson(g), text) << "seed " << seed;
    }
}

// The case format has no scissor test: a frame with a scissor box is not written as if whole.
TEST(CaseFile, AScissoredFrameIsRefused) {
    Frame f = RandomFrame(1);
    f.scissor = raster::PixelBox{0, 0, 1, 1};
    EXPECT_THROW(CaseToJson(f), std::invalid_argument);
}

TEST(CaseFile, RoundTripKeepsNegativeZeroAndSubnormals) {
    Frame f = ParseCaseJson(LegacyCase(), kPath);
    f.passes[0].vertices[0].pos.x = -0.0f;
    f.passes[0].vertices[0].color.r = std::numeric_limits<float>::denorm_min();
    f.passes[0].vertices[0].color.g = std::numeric_limits<float>::max();
    const Frame g = ParseCaseJson(CaseToJson(f), kPath);
    EXPECT_TRUE(std::signbit(g.passes[0].vertices[0].pos.x));
    EXPECT_TRUE(f == g);
}

}  // namespace
}  // namespace pem::conformance
