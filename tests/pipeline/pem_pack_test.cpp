// SPDX-License-Identifier: MIT
// pem_pack_test.cpp — packed PEMs: the map code gives back the original bytes (lossless) or
// bytes within the stated error (lossy), checked against the original texture; a lossless pack
// renders byte-identically to its directory and unpacks to the same files; damaged or foreign
// files are refused with one error naming them.
#include "pipeline/pem_pack.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <span>

#include "base/atomic_file.h"
#include "base/byte_codec.h"
#include "base/input_error.h"
#include "base/j2k_codec.h"
#include "infer/env_map.h"
#include "pipeline/map_coding.h"
#include "pipeline/pem_set.h"
#include "tests/pipeline/pem_dir_fixture.h"

namespace pem::pipeline {
namespace {

// A cube of face size n with every level: smooth gradients, speckle noise (as inferred maps
// have) and, with `shift`, the same picture moved by a few texels (a neighbouring sample).
raster::Texture Picture(int n, int levels, unsigned seed, int shift = 0) {
    std::mt19937 rng(seed);
    raster::Texture t;
    t.width = t.height = n;
    for (int l = 0; l < levels; ++l) {
        const int m = std::max(1, n >> l);
        std::vector<uint8_t>& level = t.levels.emplace_back();
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < m; ++j)
                for (int i = 0; i < m; ++i)
                    for (int c = 0; c < 4; ++c) {
                        const int smooth =
                            (37 * f + 255 * (i + shift) / m + 90 * j / m + 50 * c) % 256;
                        const int speckle = rng() % 7 == 0 ? static_cast<int>(rng() % 256) : 0;
                        level.push_back(static_cast<uint8_t>(std::min(255, smooth + speckle)));
                    }
    }
    return t;
}

// A cube map through the map code's interface (a map is its textures).
std::span<const raster::Texture> One(const raster::Texture* t) {
    return t ? std::span<const raster::Texture>(t, 1) : std::span<const raster::Texture>();
}
MapShape Cube(int n) {
    return {raster::TextureKind::Cube, 6, n, n};
}
MapCode EncodeCube(const raster::Texture& t, const raster::Texture* previous,
                   const MapCodeOptions& options) {
    return EncodeMap(One(&t), One(previous), options);
}
raster::Texture DecodeCube(const MapCode& code, int n, int levels, const raster::Texture* previous,
                           int maxError) {
    return DecodeMap(code, Cube(n), levels, One(previous), maxError).front();
}

// A 2D chart of w x h with every level (a two-image layout's texture), speckled like Picture.
raster::Texture Chart(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    raster::Texture t;
    t.kind = raster::TextureKind::Tex2D;
    t.width = w, t.height = h;
    for (int l = 0; t.levels.empty() || t.LevelWidth(l - 1) > 1 || t.LevelHeight(l - 1) > 1; ++l) {
        std::vector<uint8_t>& level = t.levels.emplace_back();
        for (int j = 0; j < t.LevelHeight(l); ++j)
            for (int i = 0; i < t.LevelWidth(l); ++i)
                for (int c = 0; c < 4; ++c)
                    level.push_back(static_cast<uint8_t>(
                        (7 * i + 11 * j + 50 * c + (rng() % 5 == 0 ? rng() % 256 : 0)) % 256));
    }
    return t;
}

int LargestDifference(const raster::Texture& a, const raster::Texture& b) {
    int worst = 0;
    for (size_t l = 0; l < a.levels.size(); ++l)
        for (size_t k = 0; k < a.levels[l].size(); ++k)
            worst = std::max(worst, std::abs(int(a.levels[l][k]) - int(b.levels[l][k])));
    return worst;
}

TEST(MapCoding, LosslessGivesBackEveryByte) {
    const raster::Texture a = Picture(16, 5, 1), b = Picture(16, 5, 2, 1);
    for (const raster::Texture* previous : {static_cast<const raster::Texture*>(nullptr), &a}) {
        const MapCode code = EncodeCube(b, previous, {});
        EXPECT_EQ(code.residuals.size(), ResidualBytes(Cube(16), 5));
        const raster::Texture d = DecodeCube(code, 16, 5, previous, 0);
        EXPECT_EQ(d.levels, b.levels);
        EXPECT_EQ(d.width, 16);
        EXPECT_EQ(d.kind, raster::TextureKind::Cube);
    }
}

// Every decoded byte within E of the original, and the stream compresses better as E grows.
TEST(MapCoding, LossyStaysWithinTheError) {
    const raster::Texture a = Picture(32, 6, 3), b = Picture(32, 6, 4, 2);
    size_t last = SIZE_MAX;
    for (int e : {0, 1, 3, 8, kMaxMapError}) {
        const MapCode code = EncodeCube(b, &a, {e, 0.0});
        const raster::Texture d = DecodeCube(code, 32, 6, &a, e);
        EXPECT_LE(LargestDifference(d, b), e) << "max error " << e;
        const size_t bytes = base::Compress(base::ByteCodec::Zstd, code.residuals).size();
        EXPECT_LT(bytes, last) << "max error " << e;
        last = bytes;
    }
}

// The neighbour's copy is used: a map equal to its neighbour codes to almost nothing.
TEST(MapCoding, PredictsFromTheNeighbourSample) {
    const raster::Texture a = Picture(32, 6, 5);
    const MapCode alone = EncodeCube(a, nullptr, {}), fromNeighbour = EncodeCube(a, &a, {});
    const size_t bytesAlone = base::Compress(base::ByteCodec::Zstd, alone.residuals).size();
    const size_t bytesFrom = base::Compress(base::ByteCodec::Zstd, fromNeighbour.residuals).size();
    EXPECT_LT(bytesFrom * 20, bytesAlone);
}

// JPEG 2000 levels: ratio 1 gives back every byte; ratio 4 stays close to the original (PSNR of
// the decoded levels against it) with either wavelet and codes the finest level in about a
// quarter, the next in about an eighth.
TEST(MapCoding, TransformCodedLevels) {
    const raster::Texture a = Picture(32, 6, 9);
    const MapCode lossless = EncodeCube(a, nullptr, {0, 1.0});
    ASSERT_EQ(lossless.transformed.size(), 6u);
    EXPECT_FALSE(lossless.transformed[2].empty());  // 8 wide
    EXPECT_TRUE(lossless.transformed[3].empty());   // 4 wide: predicted
    EXPECT_EQ(DecodeCube(lossless, 32, 6, nullptr, 0).levels, a.levels);
    // A codestream of another size is refused before it is decoded.
    EXPECT_EQ(base::DecodeJ2k(lossless.transformed[0], 32, 192, 4).width, 32);
    EXPECT_THROW(base::DecodeJ2k(lossless.transformed[0], 16, 96, 4), std::runtime_error);
    EXPECT_THROW(base::DecodeJ2k(lossless.transformed[0], 32, 192, 3), std::runtime_error);
    for (base::J2kWavelet w : {base::J2kWavelet::Reversible53, base::J2kWavelet::Irreversible97}) {
        const MapCode lossy = EncodeCube(a, nullptr, {0, 4.0, w});
        const raster::Texture d = DecodeCube(lossy, 32, 6, nullptr, 0);
        EXPECT_NE(d.levels[0], a.levels[0]);
        double se = 0;
        for (size_t k = 0; k < a.levels[0].size(); ++k)
            se += std::pow(double(d.levels[0][k]) - double(a.levels[0][k]), 2);
        const double psnr = 10 * std::log10(255.0 * 255.0 * double(a.levels[0].size()) / se);
        EXPECT_GT(psnr, 20.0);
        EXPECT_LT(lossy.transformed[0].size(), a.levels[0].size() / 3);
        EXPECT_LT(lossy.transformed[1].size(), a.levels[1].size() / 6);  // twice the ratio
        EXPECT_EQ(d.levels[3], a.levels[3]);  // the predicted levels stay lossless at error 0
    }
}

TEST(MapCoding, RefusesACodeOfAnotherSize) {
    const raster::Texture a = Picture(8, 4, 6);
    MapCode code = EncodeCube(a, nullptr, {});
    EXPECT_THROW(DecodeCube(code, 16, 4, nullptr, 0), std::runtime_error);
    EXPECT_THROW(DecodeCube(code, 4, 4, nullptr, 0), std::runtime_error);  // 4 wide: 3 levels
    code.predictors[0] = 2;  // "from the neighbour" without one
    EXPECT_THROW(DecodeCube(code, 8, 4, nullptr, 0), std::runtime_error);
}

// A two-image layout's map (two 2D textures, the tennis ball's 2:1 bands and the paraboloid's
// squares) codes as one: lossless gives back both textures' every level (the coarse ones
// predicted from the decimated finest, 2×1 means where the height has reached 1), from a
// neighbour of the same shape or alone; JPEG 2000 at ratio 1 as well; lossy within the error.
TEST(MapCoding, TwoTextureMaps) {
    for (auto [w, h] : {std::pair{32, 8}, std::pair{16, 16}}) {
        const std::vector<raster::Texture> a{Chart(w, h, 1), Chart(w, h, 2)};
        const std::vector<raster::Texture> b{Chart(w, h, 3), Chart(w, h, 4)};
        const MapShape shape = ShapeOf(b);
        EXPECT_EQ(shape, (MapShape{raster::TextureKind::Tex2D, 2, w, h}));
        const int levels = b[0].NumLevels();
        for (const MapCodeOptions& o : {MapCodeOptions{}, MapCodeOptions{0, 1.0}}) {
            for (std::span<const raster::Texture> previous :
                 {std::span<const raster::Texture>(), std::span<const raster::Texture>(a)}) {
                const MapCode code = EncodeMap(b, previous, o);
                const std::vector<raster::Texture> d = DecodeMap(code, shape, levels, previous, 0);
                ASSERT_EQ(d.size(), 2u);
                for (size_t c = 0; c < 2; ++c) {
                    EXPECT_EQ(d[c].levels, b[c].levels) << w << "x" << h << " chart " << c;
                    EXPECT_EQ(d[c].kind, raster::TextureKind::Tex2D);
                    EXPECT_EQ(d[c].height, h);
                }
            }
        }
        const MapCode lossy = EncodeMap(b, a, {5, 0.0});
        const std::vector<raster::Texture> d = DecodeMap(lossy, shape, levels, a, 5);
        for (size_t c = 0; c < 2; ++c) EXPECT_LE(LargestDifference(d[c], b[c]), 5);
        // The shape is part of the code: a cube's or one chart's is refused.
        EXPECT_THROW(DecodeMap(lossy, {raster::TextureKind::Tex2D, 1, w, h}, levels, {}, 5),
                     std::runtime_error);
    }
}

TEST(ByteCodec, BothCodecsGiveBackTheBytes) {
    std::vector<uint8_t> raw(10000);
    for (size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<uint8_t>((i * i) % 251);
    for (base::ByteCodec c : {base::ByteCodec::Zstd, base::ByteCodec::Xz}) {
        const std::vector<uint8_t> packed = base::Compress(c, raw);
        EXPECT_EQ(base::Decompress(c, packed, raw.size()), raw);
        EXPECT_THROW(base::Decompress(c, packed, raw.size() + 1), std::runtime_error);
        std::vector<uint8_t> cut(packed.begin(), packed.end() - 4);
        EXPECT_THROW(base::Decompress(c, cut, raw.size()), std::runtime_error);
    }
    EXPECT_THROW(base::ByteCodecNamed("gzip"), std::invalid_argument);
}

// A PEM directory whose map is a noisy picture, and a second sample with its neighbour.
PemManifest MakeNoisyPemDir(const fs::path& dir) {
    PemManifest m = MakePemDir(dir);
    raster::Texture t = Picture(8, 4, 7);
    infer::WriteEnvMapExr(infer::FromTextures8({&t, 1}), MapPath(m.dir, 0, 0, "pem_distant"));
    const raster::Texture local = Picture(8, 4, 8, 1);
    infer::WriteEnvMapExr(infer::FromTextures8({&local, 1}), MapPath(m.dir, 0, 0, "pem_local"));
    base::WriteTextAtomic(m.dir + "/infer.json", "{\"note\": \"kept verbatim\"}\n");
    return m;
}

trace::FloatImage RenderPem(const std::string& source) {
    const auto renderer = OpenPemDirectory(source, 1);
    runtime::RenderSettings s;
    s.method = runtime::Method::Pem;
    return renderer->Render(renderer->SampleCamera(0), s).image;
}

TEST(PemPack, LosslessRendersAndUnpacksAsTheDirectory) {
    const fs::path dir = FreshDir("pem_pack");
    const PemManifest m = MakeNoisyPemDir(dir);
    const std::string pack = (dir / "p.pempack").string();
    for (base::ByteCodec codec : {base::ByteCodec::Zstd, base::ByteCodec::Xz}) {
        const PackStats s = PackPem(m.dir, pack, {codec, {}, {}});
        EXPECT_EQ(s.maps, 2);
        EXPECT_EQ(s.maxError, 0);
        EXPECT_TRUE(IsPemPack(pack));
        EXPECT_EQ(RenderPem(pack), RenderPem(m.dir));
    }
    // JPEG 2000 lossless (ratio 1) renders the same frame too.
    EXPECT_EQ(PackPem(m.dir, pack, {base::ByteCodec::Zstd, {0, 1.0}, {}}).maxError, 0);
    EXPECT_EQ(RenderPem(pack), RenderPem(m.dir));
    // Unpacked: the same maps (as 8-bit copies), the same other files, a manifest that finds the
    // scene from the new place.
    UnpackPem(pack, (dir / "out").string(), 1);
    const auto before = ReadTree(m.dir), after = ReadTree(dir / "out");
    EXPECT_EQ(after.at("infer.json"), before.at("infer.json"));
    EXPECT_EQ(after.size(), 6u);  // manifest, infer.json, two maps' EXR and PNG
    EXPECT_EQ(RenderPem((dir / "out").string()), RenderPem(m.dir));
    EXPECT_THROW(UnpackPem(pack, (dir / "out").string(), 1), base::InputError);  // exists
    fs::remove_all(dir);
}

TEST(PemPack, LossyKeepsTheBound) {
    const fs::path dir = FreshDir("pem_pack_lossy");
    const PemManifest m = MakeNoisyPemDir(dir);
    const std::string pack = (dir / "p.pempack").string();
    const PackStats s = PackPem(m.dir, pack, {base::ByteCodec::Zstd, {4, 0.0}, {}});
    EXPECT_LE(s.maxError, 4);
    EXPECT_GT(s.maxError, 0);
    const PemPack p = ReadPemPack(pack);
    EXPECT_EQ(p.maxError, 4);
    const raster::Texture original = Picture(8, 4, 7);
    EXPECT_LE(LargestDifference(p.maps.at({0, 0, "pem_distant"}).front(), original), 4);
    fs::remove_all(dir);
}

TEST(PemPack, RefusesDamagedAndForeignFiles) {
    const fs::path dir = FreshDir("pem_pack_bad");
    const PemManifest m = MakeNoisyPemDir(dir);
    const std::string pack = (dir / "p.pempack").string();
    PackPem(m.dir, pack, {});
    std::string bytes = ReadTree(dir).at("p.pempack");
    auto write = [&](const std::string& name, const std::string& content) {
        const std::string path = (dir / name).string();
        std::ofstream(path, std::ios::binary) << content;
        return path;
    };
    const std::string foreign = write("foreign", "not a pack at all");
    EXPECT_FALSE(IsPemPack(foreign));
    EXPECT_EQ(ErrorOf([&] { ReadPemPack(foreign); }).rfind(foreign + ": not a packed PEM", 0), 0u);
    const std::string cut = write("cut", bytes.substr(0, bytes.size() - 10));
    EXPECT_NE(ErrorOf([&] { ReadPemPack(cut); }).find("truncated"), std::string::npos);
    std::string flipped = bytes;
    flipped[flipped.size() - 3] ^= 0x40;
    const std::string damaged = write("damaged", flipped);
    EXPECT_NE(ErrorOf([&] { ReadPemPack(damaged); }).find("checksum"), std::string::npos);
    const std::string header = write("header", bytes.substr(0, 40));
    EXPECT_EQ(ErrorOf([&] { ReadPemPack(header); }).rfind(header + ": ", 0), 0u);
    EXPECT_EQ(ErrorOf([&] { OpenPemDirectory(damaged, 1); }).rfind(damaged + ": ", 0), 0u);
    // A header (outside the payload's checksum) naming a map outside the directory.
    const size_t headerLength =
        static_cast<unsigned char>(bytes[8]) + 256 * static_cast<unsigned char>(bytes[9]);
    std::string text = bytes.substr(16, headerLength);
    const size_t at = text.find("\"name\":\"pem_distant\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 20, "\"name\":\"../../evil\"");
    std::string hostile = bytes.substr(0, 8);
    for (int b = 0; b < 8; ++b) hostile += static_cast<char>((text.size() >> (8 * b)) & 0xff);
    const std::string evil = write("evil", hostile + text + bytes.substr(16 + headerLength));
    EXPECT_NE(ErrorOf([&] { ReadPemPack(evil); }).find("letters, digits and _ only"),
              std::string::npos);
    EXPECT_THROW(UnpackPem(evil, (dir / "out").string(), 1), base::InputError);
    EXPECT_FALSE(fs::exists(dir / "out"));
    // A failed unpack leaves nothing behind.
    EXPECT_THROW(UnpackPem(damaged, (dir / "out").string(), 1), base::InputError);
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pem::pipeline
