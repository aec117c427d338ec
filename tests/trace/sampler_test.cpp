// SPDX-License-Identifier: MIT
// sampler_test.cpp — glTF samplers as the tracer honours them: NEAREST and LINEAR, REPEAT,
// CLAMP_TO_EDGE and MIRRORED_REPEAT, against texel values worked out by hand, and read from a
// glTF file (bad enum values refused naming the sampler).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "base/input_error.h"
#include "base/png_io.h"
#include "trace/material.h"
#include "trace/scene.h"

namespace pem::trace {
namespace {

// 4×2 texels; texel (i, j) has red = i, green = j, blue = 10 i + j.
Texture2D Grid(TextureSampler s) {
    Texture2D t;
    t.width = 4, t.height = 2;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i)
            t.rgb.insert(t.rgb.end(), {float(i), float(j), float(10 * i + j)});
    t.sampler = s;
    return t;
}

TextureSampler Nearest(TexWrap wrap) {
    TextureSampler s;
    s.nearest = true;
    s.wrapS = s.wrapT = wrap;
    return s;
}

TEST(Sampler, NearestPicksTheTexelUnderUv) {
    const Texture2D t = Grid(Nearest(TexWrap::Repeat));
    EXPECT_EQ(SampleTexture(t, {0.0f, 0.0f}), glm::vec3(0, 0, 0));
    EXPECT_EQ(SampleTexture(t, {0.49f, 0.51f}), glm::vec3(1, 1, 11));  // u·4 = 1.96, v·2 = 1.02
    EXPECT_EQ(SampleTexture(t, {0.99f, 0.0f}), glm::vec3(3, 0, 30));
}

TEST(Sampler, WrapModesOnTexelCoordinates) {
    // u = 1.3 → texel coordinate floor(5.2) = 5; u = -0.3 → floor(-1.2) = -2.
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::Repeat)), {1.3f, 0.2f}).x, 1.0f);   // 5 mod 4
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::Repeat)), {-0.3f, 0.2f}).x, 2.0f);  // -2 mod 4
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::ClampToEdge)), {1.3f, 0.2f}).x, 3.0f);  // edge
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::ClampToEdge)), {-0.3f, 0.2f}).x, 0.0f);
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::MirroredRepeat)), {1.3f, 0.2f}).x, 2.0f);  // 7-5
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::MirroredRepeat)), {-0.3f, 0.2f}).x,
              1.0f);  // -2 → 1
    // v: 1.8 → floor(3.6) = 3: repeat 1, clamp 1, mirrored 2·2−1−3 = 0.
    EXPECT_EQ(SampleTexture(Grid(Nearest(TexWrap::MirroredRepeat)), {0.1f, 1.8f}).y, 0.0f);
}

TEST(Sampler, LinearBlendsTheFourNearestCentres) {
    TextureSampler s;
    s.wrapS = s.wrapT = TexWrap::ClampToEdge;
    const Texture2D t = Grid(s);
    // Centre of texel (1, 0): exactly it.
    EXPECT_EQ(SampleTexture(t, {1.5f / 4, 0.5f / 2}), glm::vec3(1, 0, 10));
    // Halfway between the centres of (1, 0), (2, 0), (1, 1), (2, 1).
    const glm::vec3 mid = SampleTexture(t, {2.0f / 4, 1.0f / 2});
    EXPECT_FLOAT_EQ(mid.x, 1.5f);
    EXPECT_FLOAT_EQ(mid.y, 0.5f);
    EXPECT_FLOAT_EQ(mid.z, 15.5f);
    // Left of the first centre, clamped: texel 0 on both sides.
    EXPECT_FLOAT_EQ(SampleTexture(t, {0.05f, 0.25f}).x, 0.0f);
    // The same point with REPEAT blends texel 3 (to the left) and texel 0: 0.3·3 + 0.7·0.
    s.wrapS = TexWrap::Repeat;
    EXPECT_NEAR(SampleTexture(Grid(s), {0.05f, 0.25f}).x, 0.9f, 1e-6f);
}

// A one-triangle glTF whose emissive texture (2×2 checker PNG) uses sampler `samplerJson`.
std::string WriteTexturedTriangle(const std::string& samplerJson) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("pem_sampler_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    base::WritePng(
        (dir / "checker.png").string(),
        base::Image8{2, 2, {255, 255, 255, 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 255}});
    std::ifstream tri(std::string(PEM_SOURCE_DIR) + "/tests/data/trace_scenes/triangle.gltf");
    std::string text((std::istreambuf_iterator<char>(tri)), {});
    const size_t end = text.rfind('}');
    text = text.substr(0, end) +
           R"(, "materials": [{"emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}}],
           "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "checker.png"}],
           "samplers": [)" +
           samplerJson + "]}";
    const std::string path = (dir / "scene.gltf").string();
    std::ofstream(path) << text;
    return path;
}

TEST(Sampler, ReadFromGltf) {
    const Scene s = LoadScene(WriteTexturedTriangle(
        R"({"magFilter": 9728, "minFilter": 9986, "wrapS": 33648, "wrapT": 33071})"));
    ASSERT_EQ(s.textures.size(), 1u);
    const TextureSampler& t = s.textures[0].sampler;
    EXPECT_TRUE(t.nearest);
    EXPECT_EQ(t.minFilter, 9986);
    EXPECT_EQ(t.wrapS, TexWrap::MirroredRepeat);
    EXPECT_EQ(t.wrapT, TexWrap::ClampToEdge);
    // NEAREST: between texel centres the colour is one texel's, never a blend.
    EXPECT_EQ(SampleTexture(s.textures[0], {0.49f, 0.2f}), glm::vec3(1.0f));
    EXPECT_EQ(SampleTexture(s.textures[0], {0.51f, 0.2f}), glm::vec3(0.0f));
}

TEST(Sampler, InvalidValuesNameTheSampler) {
    for (const char* bad :
         {R"({"magFilter": 9985})", R"({"wrapS": 1234})", R"({"minFilter": 9730})"}) {
        try {
            LoadScene(WriteTexturedTriangle(bad));
            FAIL() << bad;
        } catch (const base::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("sampler"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace pem::trace
