// SPDX-License-Identifier: MIT
// cli_bad_case_test.cpp — every category of bad case input throws pem::base::InputError whose
// what() is one line `<path>: <key path>: <cause>`; plus the files in tests/data/bad_cases/.
// Conventions: each case mutates one value of a valid base case through a JSON pointer.
// Not here: valid-case semantics (case_file_test.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "viewer_tty/conformance/case_codec.h"
#include "viewer_tty/conformance/case_file.h"

namespace pem::conformance {
namespace {

using nlohmann::json;

constexpr const char* kPath = "bad.json";

json BaseCase() {
    return json::parse(R"({"width": 4, "height": 4,
      "cubemaps": [{"size": 2, "texels": {"gen": "random", "seed": 5}},
                   {"size": 2, "seamless": false, "texels": {"encoding": "hex",
                    "images": [["00000000000000000000000000000000", "00000000000000000000000000000000",
                                "00000000000000000000000000000000", "00000000000000000000000000000000",
                                "00000000000000000000000000000000", "00000000000000000000000000000000"],
                               ["00000000", "00000000", "00000000", "00000000", "00000000", "00000000"]]}}],
      "textures2d": [{"width": 2, "height": 1, "texels": {"encoding": "base64",
                      "images": ["AAAAAAAAAAA=", "AAAAAA=="]}}],
      "passes": [{"units": [{"cube": 0}, {"tex2d": 0}], "vertices": [
        [-1, -1, 0, 1,  1, 0, 0,  0, 0, 0,  1, 1, 1, 1],
        [ 3, -1, 0, 1,  1, 0, 0,  0, 0, 0,  1, 1, 1, 1],
        [-1,  3, 0, 1,  1, 0, 0,  0, 0, 0,  1, 1, 1, 1]], "indices": [0, 1, 2]}]})");
}

// The message of the base::InputError thrown for `text`, or "" if none.
std::string ErrorOf(const std::string& text) {
    try {
        ParseCaseJson(text, kPath);
    } catch (const base::InputError& e) {
        return e.what();
    }
    return "";
}

std::string ErrorWith(const std::string& pointer, const json& value) {
    json j = BaseCase();
    j[json::json_pointer(pointer)] = value;
    return ErrorOf(j.dump());
}

std::string ErrorWithout(const std::string& pointer) {
    json j = BaseCase();
    const json::json_pointer p(pointer);
    json& parent = j[p.parent_pointer()];
    if (parent.is_array())
        parent.erase(std::stoul(p.back()));
    else
        parent.erase(p.back());
    return ErrorOf(j.dump());
}

void ExpectError(const std::string& message, const std::string& keyAndCause) {
    EXPECT_EQ(message.rfind(std::string(kPath) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(keyAndCause), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

std::string B64Floats(const std::vector<float>& floats) {
    std::vector<uint8_t> bytes(floats.size() * 4);
    std::memcpy(bytes.data(), floats.data(), bytes.size());  // little-endian host
    return Base64Encode(bytes);
}

TEST(BadCase, BaseCaseIsValid) {
    EXPECT_EQ(ErrorOf(BaseCase().dump()), "");
}

TEST(BadCase, FileAndJson) {
    try {
        LoadCaseFile("/nonexistent/case.json");
        FAIL();
    } catch (const base::InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/case.json: cannot open", 0), 0u);
    }
    EXPECT_THROW(LoadCaseFile("/"), base::InputError);
    ExpectError(ErrorOf("{\"width\": 4,\n"), "invalid JSON");
    ExpectError(ErrorOf("[1, 2]"), "(top level): expected an object");
    ExpectError(ErrorWith("/format", "gl_ref_case/2"), "format: unsupported");
}

TEST(BadCase, MissingKeys) {
    ExpectError(ErrorWithout("/width"), "width: missing key");
    ExpectError(ErrorWithout("/cubemaps/0/size"), "cubemaps[0].size: missing key");
    ExpectError(ErrorWithout("/textures2d/0/height"), "textures2d[0].height: missing key");
    ExpectError(ErrorWithout("/cubemaps/0/texels"), "cubemaps[0].texels: missing key");
    ExpectError(ErrorWithout("/cubemaps/0/texels/seed"), "cubemaps[0].texels.seed: missing key");
    ExpectError(ErrorWithout("/passes/0/vertices"), "passes[0].vertices: missing key");
    ExpectError(ErrorWithout("/cubemaps/1/texels/encoding"), "cubemaps[1].texels: missing key");
}

TEST(BadCase, MistypedKeys) {
    ExpectError(ErrorWith("/width", "4"), "width: expected an integer");
    ExpectError(ErrorWith("/height", 4.5), "height: expected an integer");
    ExpectError(ErrorWith("/passes", json::object()), "passes: expected an array");
    ExpectError(ErrorWith("/passes/0/vertices", 3), "passes[0].vertices: expected an array");
    ExpectError(ErrorWith("/passes/0/vertices/0/5", true),
                "passes[0].vertices[0][5]: expected a number");
    ExpectError(ErrorWith("/passes/0/blend", 5), "passes[0].blend: expected a string");
    ExpectError(ErrorWith("/cubemaps/0/seamless", "yes"),
                "cubemaps[0].seamless: expected a boolean");
    ExpectError(ErrorWith("/cubemaps/0/texels/seed", "-1"),
                "cubemaps[0].texels.seed: not an unsigned");
    ExpectError(ErrorWith("/cubemaps/0/texels/seed", -1), "cubemaps[0].texels.seed: negative");
    ExpectError(ErrorWith("/passes/0/vertices/1/2", "1.5x"),
                "passes[0].vertices[1][2]: not a number");
}

TEST(BadCase, UnknownValues) {
    ExpectError(ErrorWith("/cubemaps/0/min_filter", "bilinear"), "cubemaps[0].min_filter: unknown");
    ExpectError(ErrorWith("/cubemaps/0/mag_filter", "cubic"), "cubemaps[0].mag_filter: unknown");
    ExpectError(ErrorWith("/textures2d/0/wrap_t", "clamp"), "textures2d[0].wrap_t: unknown");
    ExpectError(ErrorWith("/passes/0/blend", "screen"), "passes[0].blend: unknown");
    ExpectError(ErrorWith("/passes/0/blend", json{{"dst_alpha", "two"}}),
                "passes[0].blend.dst_alpha: unknown");
    ExpectError(ErrorWith("/cubemaps/0/texels/gen", "noise"), "cubemaps[0].texels.gen: unknown");
    ExpectError(ErrorWith("/cubemaps/1/texels/encoding", "b32"),
                "cubemaps[1].texels.encoding: unknown");
    ExpectError(ErrorWith("/passes/0/units/0", json{{"cube", 0}, {"tex2d", 0}}),
                "passes[0].units[0]: expected exactly one");
}

TEST(BadCase, Sizes) {
    ExpectError(ErrorWith("/cubemaps/0/size", 3), "cubemaps[0].size: 3 is not a power of two");
    ExpectError(ErrorWith("/cubemaps/0/size", 16384), "cubemaps[0].size: 16384 out of range");
    ExpectError(ErrorWith("/cubemaps/0/size", 0), "cubemaps[0].size: 0 out of range");
    ExpectError(ErrorWith("/textures2d/0/width", 6), "textures2d[0].width: 6 is not a power");
    ExpectError(ErrorWith("/width", 0), "width: 0 out of range");
    ExpectError(ErrorWith("/height", 8193), "height: 8193 out of range");
    ExpectError(ErrorWith("/cubemaps/0/levels", 3), "cubemaps[0].levels: 3 out of range 1..2");
    ExpectError(ErrorWith("/cubemaps/0/levels", 0), "cubemaps[0].levels: 0 out of range");
    ExpectError(ErrorWith("/clear", json{1, 2, 3}), "clear: expected 4");
    ExpectError(ErrorWith("/clear", json{1, 2, 3, 256}), "clear[3]: 256 out of range");
    ExpectError(ErrorWith("/cubemaps/0/texels/alpha", 300), "cubemaps[0].texels.alpha: 300");
}

TEST(BadCase, NonFiniteNumbers) {
    ExpectError(ErrorWith("/passes/0/vertices/1/4", "nan"), "passes[0].vertices[1][4]: NaN");
    ExpectError(ErrorWith("/passes/0/vertices/2/0", "-inf"), "passes[0].vertices[2][0]: infinite");
    ExpectError(ErrorWith("/passes/0/vertices/2/0", 1e39), "passes[0].vertices[2][0]: beyond");
    ExpectError(ErrorWith("/cubemaps/0/lod_bias", "0x1p+200"), "cubemaps[0].lod_bias: beyond");
    std::vector<float> floats(3 * 14, 0.5f);
    floats[14 + 3] = std::numeric_limits<float>::quiet_NaN();
    json j = BaseCase();
    j["passes"][0].erase("vertices");
    j["passes"][0]["vertices_b64"] = B64Floats(floats);
    ExpectError(ErrorOf(j.dump()), "passes[0].vertices_b64[1][3]: NaN");
    floats[14 + 3] = std::numeric_limits<float>::infinity();
    j["passes"][0]["vertices_b64"] = B64Floats(floats);
    ExpectError(ErrorOf(j.dump()), "passes[0].vertices_b64[1][3]: infinite");
}

TEST(BadCase, EncodingsAndByteCounts) {
    ExpectError(ErrorWith("/textures2d/0/texels/images/0", "AAAAAAAAAAA"),
                "textures2d[0].texels.images[0]: base64 length");
    ExpectError(ErrorWith("/textures2d/0/texels/images/0", "AAAAAAAA*AA="),
                "textures2d[0].texels.images[0]: invalid base64");
    ExpectError(ErrorWith("/textures2d/0/texels/images/1", "AAAA"),
                "textures2d[0].texels.images[1]: expected 4 bytes, got 3");
    ExpectError(ErrorWith("/cubemaps/1/texels/images/1/5", "0000000"),
                "cubemaps[1].texels.images[1][5]: hex length is odd");
    ExpectError(ErrorWith("/cubemaps/1/texels/images/1/5", "0000000g"),
                "cubemaps[1].texels.images[1][5]: invalid hex");
    ExpectError(ErrorWith("/cubemaps/1/texels/images/1/5", "000000"),
                "cubemaps[1].texels.images[1][5]: expected 4 bytes, got 3");
    ExpectError(ErrorWith("/cubemaps/1/texels/images/1", json{"00000000"}),
                "cubemaps[1].texels.images[1]: expected 6 face strings");
    ExpectError(ErrorWithout("/cubemaps/1/texels/images/1"),
                "cubemaps[1].texels.images: expected 2 levels, got 1");
    json j = BaseCase();
    j["passes"][0].erase("vertices");
    j["passes"][0]["vertices_b64"] = B64Floats(std::vector<float>(40, 0.0f));
    ExpectError(ErrorOf(j.dump()), "passes[0].vertices_b64: 160 bytes, not a multiple of 56");
    j["passes"][0]["vertices_b64"] = "AAA";
    ExpectError(ErrorOf(j.dump()), "passes[0].vertices_b64: base64 length");
}

TEST(BadCase, Geometry) {
    ExpectError(ErrorWith("/passes/0/indices/2", 3), "passes[0].indices[2]: index 3 out of range");
    ExpectError(ErrorWith("/passes/0/indices", json{0, 1}), "passes[0].indices: 2 indices");
    ExpectError(ErrorWith("/passes/0/indices/0", -1), "passes[0].indices[0]: -1 out of range");
    ExpectError(ErrorWithout("/passes/0/indices/2"), "passes[0].indices: 2 indices");
    json j = BaseCase();
    j["passes"][0].erase("indices");
    j["passes"][0]["vertices"].erase(2);
    ExpectError(ErrorOf(j.dump()), "passes[0].vertices: 2 vertices without indices");
    ExpectError(ErrorWith("/passes/0/vertices/1", json{1, 2, 3}),
                "passes[0].vertices[1]: expected 14 numbers, got 3");
    ExpectError(ErrorWith("/passes/0/vertices", json(std::vector<int>(13, 0))),
                "passes[0].vertices: 13 numbers, not a multiple of 14");
}

TEST(BadCase, Units) {
    ExpectError(ErrorWith("/passes/0/units", json{{{"cube", 0}}, {{"cube", 0}}, {{"cube", 0}}}),
                "passes[0].units: 3 units (at most 2)");
    ExpectError(ErrorWith("/passes/0/units/0/cube", 2),
                "passes[0].units[0].cube: cube 2 out of range");
    ExpectError(ErrorWith("/passes/0/units/1/tex2d", 1),
                "passes[0].units[1].tex2d: 2D texture 1 out of range");
    ExpectError(ErrorWith("/passes/0/units/1", json{{"cube", 1}}),
                "passes[0].units: the pass samples cube maps with different \"seamless\"");
    json j = BaseCase();
    j["passes"][0].erase("units");
    j["passes"][0]["cubemap"] = 7;
    ExpectError(ErrorOf(j.dump()), "passes[0].cubemap: cube 7 out of range (2 cubemaps)");
}

TEST(BadCase, Formats) {
    ExpectError(ErrorWith("/color_format", "rgb10"), "color_format: unknown value \"rgb10\"");
    ExpectError(ErrorWith("/cubemaps/0/internal_format", "rgba16f"),
                "cubemaps[0].internal_format: unknown value \"rgba16f\"");
    // Explicit RGBA32F texels: 16 bytes a texel, each float finite.
    ExpectError(ErrorWith("/textures2d/0/internal_format", "rgba32f"),
                "textures2d[0].texels.images[0]: expected 32 bytes, got 8");
    json j = BaseCase();
    j["textures2d"][0]["internal_format"] = "rgba32f";
    j["textures2d"][0]["height"] = 1;
    j["textures2d"][0]["width"] = 1;
    j["textures2d"][0]["texels"]["images"] = {"AAAAAAAAAAAAAIB/AAAAAA=="};  // +Inf in component 2
    ExpectError(ErrorOf(j.dump()),
                "textures2d[0].texels.images[0]: texel 0 component 2 is not a finite float");
}

TEST(BadCase, Depth) {
    ExpectError(ErrorWith("/depth", "z24"), "depth: expected an object");
    ExpectError(ErrorWith("/depth", json{{"clear", 0.5}}), "depth.format: missing key");
    ExpectError(ErrorWith("/depth", json{{"format", "z8"}}), "depth.format: unknown value \"z8\"");
    ExpectError(ErrorWith("/depth", json{{"format", "z24"}, {"clear", 1.5}}),
                "depth.clear: 1.5 outside [0, 1]");
    ExpectError(ErrorWith("/depth", json{{"format", "z16"}, {"clear", -0.25}}),
                "depth.clear: -0.25 outside [0, 1]");
    ExpectError(ErrorWith("/depth", json{{"format", "z32f"}, {"clear", "nan"}}),
                "depth.clear: NaN");
    ExpectError(ErrorWith("/depth", json{{"format", "z32f"}, {"clear", true}}),
                "depth.clear: expected a number");
    ExpectError(ErrorWith("/passes/0/depth_test", json{{"func", "less"}}),
                "passes[0].depth_test: the case has no \"depth\" buffer");
    json j = BaseCase();
    j["depth"] = {{"format", "z24"}};
    j["passes"][0]["depth_test"] = {{"func", "lesser"}};
    ExpectError(ErrorOf(j.dump()), "passes[0].depth_test.func: unknown value \"lesser\"");
    j["passes"][0]["depth_test"] = {{"write", 1}};
    ExpectError(ErrorOf(j.dump()), "passes[0].depth_test.write: expected a boolean");
    j["passes"][0]["depth_test"] = true;
    ExpectError(ErrorOf(j.dump()), "passes[0].depth_test: expected an object");
    j["passes"][0]["depth_test"] = json::object();
    EXPECT_EQ(ErrorOf(j.dump()), "");
}

TEST(BadCase, MaxAnisotropy) {
    ExpectError(ErrorWith("/cubemaps/0/max_anisotropy", 0.5),
                "cubemaps[0].max_anisotropy: 0.5 below 1");
    ExpectError(ErrorWith("/textures2d/0/max_anisotropy", -16),
                "textures2d[0].max_anisotropy: -16 below 1");
    ExpectError(ErrorWith("/textures2d/0/max_anisotropy", 0),
                "textures2d[0].max_anisotropy: 0 below 1");
    ExpectError(ErrorWith("/cubemaps/1/max_anisotropy", "nan"), "cubemaps[1].max_anisotropy: NaN");
    ExpectError(ErrorWith("/cubemaps/0/max_anisotropy", "inf"),
                "cubemaps[0].max_anisotropy: infinite");
    ExpectError(ErrorWith("/cubemaps/0/max_anisotropy", true),
                "cubemaps[0].max_anisotropy: expected a number");
    ExpectError(ErrorWith("/cubemaps/0/max_anisotropy", 1e40),
                "cubemaps[0].max_anisotropy: beyond float32 range");
    // 1 (off), fractions and values above the driver's 16 are valid GL values.
    for (const json& ok : {json(1), json(1.5), json(16), json(1000), json("0x1.8p+1")})
        EXPECT_EQ(ErrorWith("/cubemaps/0/max_anisotropy", ok), "") << ok.dump();
}

TEST(BadCase, MinLodAboveMaxLodIsAllowed) {
    json j = BaseCase();
    j["cubemaps"][0]["min_lod"] = 5;
    j["cubemaps"][0]["max_lod"] = -5;
    j["note"] = "unknown keys are ignored";
    EXPECT_EQ(ErrorOf(j.dump()), "");
}

TEST(BadCase, DataFiles) {
    const std::filesystem::path dir = std::filesystem::path(PEM_TEST_DATA_DIR) / "bad_cases";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        ++count;
        const std::string path = entry.path().string();
        try {
            LoadCaseFile(path);
            ADD_FAILURE() << path << " loaded without error";
        } catch (const base::InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
        }
    }
    EXPECT_GE(count, 5);
}

}  // namespace
}  // namespace pem::conformance
