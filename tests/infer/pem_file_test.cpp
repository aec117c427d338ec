// SPDX-License-Identifier: MIT
// pem_file_test.cpp — OpenEXR cube and 2D maps: exact round trip of every level, the full level
// chain (degenerate tail included), the face layout as a bijection, the 8-bit copy.
#include "infer/pem_file.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfTiledOutputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <tuple>

namespace pem::infer {
namespace {

std::string OutputPath(const std::string& name) {
    std::filesystem::create_directories(PEM_TEST_OUTPUT_DIR);
    return std::string(PEM_TEST_OUTPUT_DIR) + "/" + name;
}

// Values spanning 1e-6 .. 1e6 with random signs and mantissas (bit patterns must survive).
EnvMapF RandomMap(int size, int levels, uint64_t seed) {
    EnvMapF map;
    map.size = size;
    uint64_t s = seed;
    for (int l = 0; l < levels; ++l) {
        const int n = map.LevelSize(l);
        std::vector<float> v(static_cast<size_t>(6 * n * n * 4));
        for (float& x : v) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            const double u = static_cast<double>(s >> 11) / 9007199254740992.0;
            x = static_cast<float>(std::pow(10.0, 12.0 * u - 6.0) * ((s >> 7) & 1 ? 1.0 : -1.0));
        }
        map.levels.push_back(std::move(v));
    }
    return map;
}

// The files the EXR fuzzer found (tests/data/fuzz_regressions/exr): refused with an exception,
// no crash; under the sanitizer jobs, no undefined behaviour and no huge allocation either.
TEST(PemFile, FuzzRegressionsAreRefused) {
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(std::string(PEM_SOURCE_DIR) +
                                                             "/tests/data/fuzz_regressions/exr")) {
        EXPECT_THROW(ReadEnvMapExr(e.path().string()), std::exception) << e.path();
        ++files;
    }
    EXPECT_GE(files, 2);
}

TEST(PemFile, ExrLevelCount) {
    EXPECT_EQ(ExrLevelCount(16), 7);  // 16x96 .. 1x6, 1x3, 1x1
    EXPECT_EQ(ExrLevelCount(1), 3);   // 1x6, 1x3, 1x1
    EXPECT_EQ(ExrLevelCount(32), 8);
}

TEST(PemFile, FaceLayoutIsABijection) {
    for (int n : {1, 2, 4, 16}) {
        std::set<std::pair<int, int>> seen;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const ExrPixel p = ExrPixelOf(f, i, j, n);
                    ASSERT_GE(p.x, 0);
                    ASSERT_LT(p.x, n);
                    ASSERT_GE(p.y, f * n);
                    ASSERT_LT(p.y, (f + 1) * n);
                    seen.insert({p.x, p.y});
                }
        EXPECT_EQ(seen.size(), static_cast<size_t>(6 * n * n));
    }
}

TEST(PemFile, RoundTripExact) {
    for (auto [size, levels] :
         {std::pair{16, 5}, std::pair{32, 6}, std::pair{8, 1}, std::pair{1, 1}}) {
        const EnvMapF map = RandomMap(size, levels, 42 + static_cast<uint64_t>(size));
        const std::string path = OutputPath("roundtrip_" + std::to_string(size) + ".exr");
        WriteEnvMapExr(map, path);
        EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
        const EnvMapF back = ReadEnvMapExr(path);
        EXPECT_TRUE(back == map) << size;
    }
}

// A 2D map (the lat-long, sphere, paraboloid and tennis layouts) of w x h with `levels` levels.
EnvMapF Random2DMap(int w, int h, int levels, uint64_t seed) {
    EnvMapF map = RandomMap(1, 0, seed);
    map.kind = raster::TextureKind::Tex2D;
    map.size = w;
    map.height = h;
    uint64_t s = seed;
    for (int l = 0; l < levels; ++l) {
        std::vector<float> v(map.LevelTexels(l) * 4);
        for (float& x : v) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            x = static_cast<float>(static_cast<double>(s >> 11) / 9007199254740992.0 - 0.25);
        }
        map.levels.push_back(std::move(v));
    }
    return map;
}

// A 2D map comes back as written, every level bit for bit; it is a plain W x H image (no envmap
// attribute), level 0 row j being the texture's row j.
TEST(PemFile, TwoDimensionalRoundTripExact) {
    for (auto [w, h, levels] :
         {std::tuple{16, 8, 5}, std::tuple{8, 8, 4}, std::tuple{32, 16, 2}, std::tuple{4, 2, 3}}) {
        const EnvMapF map = Random2DMap(w, h, levels, 7 + static_cast<uint64_t>(w + h));
        const std::string path =
            OutputPath("roundtrip2d_" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
        WriteEnvMapExr(map, path);
        const EnvMapF back = ReadEnvMapExr(path);
        EXPECT_EQ(back.kind, raster::TextureKind::Tex2D);
        EXPECT_EQ(back.height, h);
        EXPECT_TRUE(back == map) << w << "x" << h;
        const ExrLevelImage level0 = ReadExrLevel(path, 0);
        ASSERT_EQ(level0.width, w);
        ASSERT_EQ(level0.height, h);
        EXPECT_EQ(level0.rgba, map.levels[0]);
    }
    // Two charts (the paraboloid's and the tennis ball's two textures): both side by side in
    // one image per level, each chart's MIP chain whole, read back as two charts.
    for (auto [w, h, levels] : {std::tuple{8, 8, 4}, std::tuple{16, 4, 5}, std::tuple{2, 2, 2}}) {
        EnvMapF map = Random2DMap(w, h, 0, 11);
        map.charts = 2;
        EnvMapF filled = Random2DMap(2 * w * h, 1, 1, 13);  // values to deal out
        size_t next = 0;
        for (int l = 0; l < levels; ++l) {
            std::vector<float> v(map.LevelTexels(l) * 4);
            for (float& x : v) x = filled.levels[0][next++ % filled.levels[0].size()] + l;
            map.levels.push_back(std::move(v));
        }
        const std::string path = OutputPath("roundtrip2charts_" + std::to_string(w) + ".exr");
        WriteEnvMapExr(map, path);
        const EnvMapF back = ReadEnvMapExr(path);
        EXPECT_EQ(back.charts, 2);
        EXPECT_TRUE(back == map) << w << "x" << h;
        const ExrLevelImage level0 = ReadExrLevel(path, 0);
        ASSERT_EQ(level0.width, 2 * w);
        ASSERT_EQ(level0.height, h);
        // Row 0 of the image: chart 0's row 0, then chart 1's.
        const size_t row = static_cast<size_t>(w) * 4, chart1 = static_cast<size_t>(w * h) * 4;
        for (size_t k = 0; k < row; ++k) {
            EXPECT_EQ(level0.rgba[k], map.levels[0][k]);
            EXPECT_EQ(level0.rgba[row + k], map.levels[0][chart1 + k]);
        }
    }
    // A file that claims two charts it cannot hold (charts taller than wide: their MIP chain is
    // longer than the image's would allow, or an odd count) is refused, not read past its end.
    for (auto [w, h, charts] : {std::tuple{2, 8, 2}, std::tuple{8, 8, 2}, std::tuple{16, 4, 3}}) {
        const std::string path =
            OutputPath("hostile_charts_" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
        Imf::Header header(w, h);
        header.channels().insert("R", Imf::Channel(Imf::FLOAT));
        header.setTileDescription(Imf::TileDescription(32, 32, Imf::MIPMAP_LEVELS));
        header.insert("pemrefCharts", Imf::IntAttribute(charts));
        {
            Imf::TiledOutputFile out(path.c_str(), header);
            std::vector<float> px(static_cast<size_t>(w) * static_cast<size_t>(h), 0.5f);
            for (int l = 0; l < out.numLevels(); ++l) {
                Imf::FrameBuffer fb;
                fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()),
                                          sizeof(float), sizeof(float) * out.levelWidth(l)));
                out.setFrameBuffer(fb);
                out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
            }
        }
        EXPECT_THROW(ReadEnvMapExr(path), std::runtime_error) << w << "x" << h;
    }
    // Wrong level sizes and non-power-of-two shapes are refused before a file is written.
    EnvMapF bad = Random2DMap(16, 8, 2, 3);
    bad.levels[1].pop_back();
    EXPECT_THROW(WriteEnvMapExr(bad, OutputPath("bad2d.exr")), std::invalid_argument);
    EnvMapF odd = Random2DMap(16, 8, 1, 3);
    odd.height = 6;
    EXPECT_THROW(WriteEnvMapExr(odd, OutputPath("odd2d.exr")), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(OutputPath("odd2d.exr")));
}

TEST(PemFile, TailLevelsHoldTheCoarsestMean) {
    EnvMapF map = RandomMap(4, 3, 9);
    const std::string path = OutputPath("tail.exr");
    WriteEnvMapExr(map, path);
    const ExrLevelImage tail = ReadExrLevel(path, ExrLevelCount(4) - 1);
    ASSERT_EQ(tail.width, 1);
    ASSERT_EQ(tail.height, 1);
    double mean[4] = {};
    for (size_t k = 0; k < map.levels[2].size(); ++k)
        mean[k % 4] += static_cast<double>(map.levels[2][k]) / 6.0;
    for (int c = 0; c < 4; ++c)
        EXPECT_EQ(tail.rgba[static_cast<size_t>(c)], static_cast<float>(mean[c]));
}

TEST(PemFile, EightBitCopy) {
    EnvMapF map;
    map.size = 1;
    map.levels.push_back({-0.5f,
                          0.0f,
                          0.1f / 255.0f,
                          1.2f / 255.0f,
                          0.999f,
                          1.0f,
                          2.0f,
                          NAN,
                          0.25f,
                          0.5f,
                          0.75f,
                          1.0f,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0,
                          0});
    const raster::Texture t = ToTextures8(map, {}).front();
    const std::vector<uint8_t> expect{0, 0, 0, 1, 255, 255, 255, 0, 64, 128, 191, 255};
    for (size_t k = 0; k < expect.size(); ++k) EXPECT_EQ(t.levels[0][k], expect[k]) << k;
}

// The 8-bit copy rounds v * 255 half to even, as std::nearbyint: checked on every float in
// [0, 1] near the 255 rounding boundaries (k + 1/2) / 255 (±64 ulps) and on a stride through all.
TEST(PemFile, EightBitCopyRoundsAsNearbyint) {
    std::vector<float> values;
    for (int k = 0; k < 255; ++k) {
        const float b = static_cast<float>((k + 0.5) / 255.0);
        float lo = b, hi = b;
        for (int i = 0; i < 64; ++i) {
            lo = std::nextafter(lo, 0.0f);
            hi = std::nextafter(hi, 1.0f);
            values.insert(values.end(), {lo, hi});
        }
        values.push_back(b);
    }
    for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 7919) {
        float f;
        std::memcpy(&f, &bits, sizeof f);
        values.push_back(f);
    }
    while (values.size() % 24) values.push_back(0.0f);  // whole 1x1 cube maps (6 faces x RGBA)
    EnvMapF map;
    map.size = 1;
    for (size_t k = 0; k < values.size(); k += 24)
        map.levels.emplace_back(values.begin() + static_cast<std::ptrdiff_t>(k),
                                values.begin() + static_cast<std::ptrdiff_t>(k + 24));
    const raster::Texture t = ToTextures8(map, {}).front();
    size_t bad = 0;
    for (size_t k = 0; k < values.size(); ++k) {
        const auto want =
            static_cast<uint8_t>(std::nearbyint(static_cast<double>(values[k]) * 255.0));
        bad += t.levels[k / 24][k % 24] != want;
    }
    EXPECT_EQ(bad, 0u);
}

}  // namespace
}  // namespace pem::infer
