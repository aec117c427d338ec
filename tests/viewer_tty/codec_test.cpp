// SPDX-License-Identifier: MIT
// codec_test.cpp — byte-level tests of the case-file codecs: base64 (RFC 4648 vectors), hex,
// splitmix64 first values, texel generators.
// Conventions: tiny inline fixtures, fixed seeds. Not here: JSON case parsing (case_file_test.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "viewer_tty/conformance/case_codec.h"

namespace pem::conformance {
namespace {

TEST(Base64, Rfc4648Vectors) {
    const std::pair<std::string, std::string> vectors[] = {{"", ""},
                                                           {"f", "Zg=="},
                                                           {"fo", "Zm8="},
                                                           {"foo", "Zm9v"},
                                                           {"foob", "Zm9vYg=="},
                                                           {"fooba", "Zm9vYmE="},
                                                           {"foobar", "Zm9vYmFy"}};
    for (const auto& [plain, encoded] : vectors) {
        const std::vector<uint8_t> bytes(plain.begin(), plain.end());
        EXPECT_EQ(Base64Encode(bytes), encoded);
        const DecodeResult decoded = Base64Decode(encoded);
        EXPECT_TRUE(decoded.error.empty()) << encoded;
        EXPECT_EQ(decoded.bytes, bytes) << encoded;
    }
}

TEST(Base64, RejectsMalformed) {
    for (const char* bad : {"Zg=", "Zg", "Z===", "Zm9v!A==", "Zg==Zg==", "====", "Zm 9v"})
        EXPECT_FALSE(Base64Decode(bad).error.empty()) << bad;
}

TEST(Hex, DecodeAndReject) {
    const DecodeResult ok = HexDecode("00fFa5");
    EXPECT_TRUE(ok.error.empty());
    EXPECT_EQ(ok.bytes, (std::vector<uint8_t>{0x00, 0xff, 0xa5}));
    EXPECT_FALSE(HexDecode("abc").error.empty());
    EXPECT_FALSE(HexDecode("zz").error.empty());
}

TEST(SplitMix64, FirstValues) {
    SplitMix64 zero(0);
    EXPECT_EQ(zero.Next(), 0xe220a8397b1dcdafull);
    EXPECT_EQ(zero.Next(), 0x6e789e6aa1b965f4ull);
    EXPECT_EQ(zero.Next(), 0x06c45d188009454full);
    SplitMix64 seeded(0x5EED0001);
    EXPECT_EQ(seeded.Next(), 0x03317bb4875fb038ull);
    EXPECT_EQ(seeded.Next(), 0xdc1fe0f7d1dc60ccull);
}

TEST(TexelGen, RandomUsesOneDrawPerTexel) {
    const auto levels =
        GenerateTexels(raster::TextureKind::Cube, 2, 2, 2, {TexelGenKind::Random, 0, -1});
    ASSERT_EQ(levels.size(), 2u);
    ASSERT_EQ(levels[0].size(), 6u * 4 * 4);
    ASSERT_EQ(levels[1].size(), 6u * 1 * 4);
    // First texel = first draw 0xe220a8397b1dcdaf: R=0xaf G=0xcd B=0x1d A=0x7b.
    EXPECT_EQ(levels[0][0], 0xaf);
    EXPECT_EQ(levels[0][1], 0xcd);
    EXPECT_EQ(levels[0][2], 0x1d);
    EXPECT_EQ(levels[0][3], 0x7b);
    // The stream continues into level 1: its first texel is draw number 25.
    SplitMix64 rng(0);
    for (int k = 0; k < 24; ++k) rng.Next();
    EXPECT_EQ(levels[1][0], rng.Next() & 255);
}

TEST(TexelGen, FixedAlpha) {
    const auto levels =
        GenerateTexels(raster::TextureKind::Tex2D, 4, 2, 1, {TexelGenKind::Random, 7, 200});
    for (size_t k = 3; k < levels[0].size(); k += 4) EXPECT_EQ(levels[0][k], 200);
}

TEST(TexelGen, RandomBoxAveragesLevelAbove) {
    const auto levels =
        GenerateTexels(raster::TextureKind::Cube, 2, 2, 2, {TexelGenKind::RandomBox, 3, -1});
    for (int f = 0; f < 6; ++f)
        for (int c = 0; c < 4; ++c) {
            int sum = 2;
            for (int t = 0; t < 4; ++t) sum += levels[0][size_t(f * 16 + t * 4 + c)];
            EXPECT_EQ(levels[1][size_t(f * 4 + c)], sum >> 2);
        }
}

TEST(TexelGen, GradientValues) {
    const auto cube =
        GenerateTexels(raster::TextureKind::Cube, 4, 4, 3, {TexelGenKind::Gradient, 0, -1});
    // Level 0, face 2, row j = 1, columns 0..3: R = 0 85 170 255, G = 85, B = 102, A = 255.
    const size_t row = (2 * 16 + 1 * 4) * 4;
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(cube[0][row + size_t(i) * 4 + 0], 85 * i);
        EXPECT_EQ(cube[0][row + size_t(i) * 4 + 1], 85);
        EXPECT_EQ(cube[0][row + size_t(i) * 4 + 2], 102);
        EXPECT_EQ(cube[0][row + size_t(i) * 4 + 3], 255);
    }
    // Level 2 is 1x1: R = G = 128, A = 255 - 32.
    EXPECT_EQ(cube[2][0], 128);
    EXPECT_EQ(cube[2][1], 128);
    EXPECT_EQ(cube[2][3], 223);
    // 2D: B = 0; 8 wide: round(255*3/7) = 109.
    const auto tex =
        GenerateTexels(raster::TextureKind::Tex2D, 8, 2, 1, {TexelGenKind::Gradient, 0, 9});
    EXPECT_EQ(tex[0][3 * 4 + 0], 109);
    EXPECT_EQ(tex[0][3 * 4 + 2], 0);
    EXPECT_EQ(tex[0][3 * 4 + 3], 9);
}

}  // namespace
}  // namespace pem::conformance
