// SPDX-License-Identifier: MIT
// pem_set_test.cpp — the PEM-set loader: maps come back as the hardware's 8-bit copies of what
// was written (texels checked against hand-computed bytes), missing maps are nullptr, and a
// PEM directory opens after it was moved together with its scene.
#include "pipeline/pem_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "base/input_error.h"
#include "infer/pem_file.h"
#include "pipeline/layout.h"
#include "pipeline/pem_pack.h"
#include "tests/pipeline/pem_dir_fixture.h"

namespace pem::pipeline {
namespace {

TEST(PemSet, MapsAreTheEightBitCopiesOfTheFiles) {
    const fs::path dir = FreshDir("pem_set");
    const runtime::MapSet set = LoadMapSet(ReadPemManifest(MakePemDir(dir).dir));
    const raster::Texture* t = set.map(0, 0, "pem_distant");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t, set.map(0, 0, "pem_distant"));  // loaded once
    EXPECT_EQ(t->kind, raster::TextureKind::Cube);
    EXPECT_EQ(t->width, 8);
    ASSERT_EQ(t->NumLevels(), 4);
    // 0.5 → 127.5 → 128 (round half to even of 127.5), 0.25 → 63.75 → 64, 1 → 255.
    for (int l = 0; l < 4; ++l)
        for (size_t k = 0; k < t->levels[static_cast<size_t>(l)].size(); k += 4) {
            const uint8_t* p = &t->levels[static_cast<size_t>(l)][k];
            ASSERT_TRUE(p[0] == 128 && p[1] == 64 && p[2] == 255 && p[3] == 255)
                << "level " << l << " texel " << k / 4 << ": " << int(p[0]) << " " << int(p[1]);
        }
    EXPECT_EQ(set.map(0, 0, "pem_local"), nullptr);
    EXPECT_EQ(set.res, 8);
    ASSERT_EQ(set.samples.size(), 1u);
    EXPECT_EQ(set.samples[0].width, 32);
    fs::remove_all(dir);
}

// A PEM of float maps (manifest "map_format": "rgba32f", infer --map-format): the manifest keeps
// the format, the maps load as RGBA32F textures holding the file's floats as they are (negative
// and above 1 too, where the 8-bit copy clamps them), and packing it (8-bit maps) is refused.
TEST(PemSet, FloatMapsKeepTheirValues) {
    const fs::path dir = FreshDir("pem_float");
    PemManifest m = MakePemDir(dir);
    m.hardware.format = raster::TexelFormat::Rgba32F;
    WritePemManifest(m);
    ASSERT_EQ(ReadPemManifest(m.dir).hardware.format, raster::TexelFormat::Rgba32F);
    infer::WriteEnvMapExr(ConstantMap(8, -0.75f, 2.5f, 0.25f, 1.0f),
                          MapPath(m.dir, 0, 0, "pem_distant"));
    const runtime::MapSet set = LoadMapSet(ReadPemManifest(m.dir));
    const raster::Texture* t = set.map(0, 0, "pem_distant");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->format, raster::TexelFormat::Rgba32F);
    ASSERT_EQ(t->NumLevels(), 4);
    for (int l = 0; l < 4; ++l) {
        const std::vector<float> v = raster::FloatsFromBytes(t->levels[static_cast<size_t>(l)]);
        ASSERT_EQ(v.size(), size_t{4} * 6 * size_t(8 >> l) * size_t(8 >> l));
        for (size_t k = 0; k < v.size(); k += 4)
            ASSERT_TRUE(v[k] == -0.75f && v[k + 1] == 2.5f && v[k + 2] == 0.25f && v[k + 3] == 1.0f)
                << "level " << l << " texel " << k / 4;
    }
    EXPECT_THROW(PackPem(m.dir, (dir / "float.pempack").string(), {}), base::InputError);
    // The inference's tessellation t travels with the maps (the renderers' default t).
    EXPECT_EQ(set.tessT, runtime::kDefaultTessT);
    m.tessT = 2.5;
    WritePemManifest(m);
    EXPECT_EQ(LoadMapSet(ReadPemManifest(m.dir)).tessT, 2.5);
    // Written without the key (8-bit maps), as before it existed.
    m.hardware.format = raster::TexelFormat::Rgba8;
    WritePemManifest(m);
    std::ifstream in(fs::path(m.dir) / kManifestJson);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("map_format"), std::string::npos);
    fs::remove_all(dir);
}

// With max_res (infer --max-res), a map may be larger than res, up to max_res; a size outside
// [res, max_res] or not a power of two is refused with the map's path.
TEST(PemSet, MapSizesWithinResAndMaxRes) {
    const fs::path dir = FreshDir("pem_max_res");
    PemManifest m = MakePemDir(dir);
    m.maxRes = 32;
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).maxRes, 32);
    infer::WriteEnvMapExr(ConstantMap(32, 0.5f, 0.25f, 1.0f, 1.0f),
                          MapPath(m.dir, 0, 0, "pem_distant"));
    infer::WriteEnvMapExr(ConstantMap(64, 0.5f, 0.25f, 1.0f, 1.0f),
                          MapPath(m.dir, 0, 0, "pem_local"));
    infer::WriteEnvMapExr(ConstantMap(4, 0.5f, 0.25f, 1.0f, 1.0f), MapPath(m.dir, 0, 0, "layer_0"));
    const runtime::MapSet set = LoadMapSet(ReadPemManifest(m.dir));
    const raster::Texture* t = set.map(0, 0, "pem_distant");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->width, 32);
    EXPECT_EQ(t->NumLevels(), 6);
    EXPECT_THROW(set.map(0, 0, "pem_local"), base::InputError);  // 64 > max_res
    EXPECT_THROW(set.map(0, 0, "layer_0"), base::InputError);    // 4 < res
    // A manifest whose max_res is below res is refused.
    m.maxRes = 4;
    WritePemManifest(m);
    EXPECT_THROW(ReadPemManifest(m.dir), base::InputError);
    fs::remove_all(dir);
}

// A lat-long PEM (manifest "parameterization": "latlong"): its 2D maps load with the layout's
// wrap (REPEAT along s) and the hardware's filters; a cube map, or a 2D map of another layout's
// shape, in that directory is refused with the map's path; so is packing it.
TEST(PemSet, TwoDimensionalLayouts) {
    const fs::path dir = FreshDir("pem_latlong");
    PemManifest m = MakePemDir(dir);
    m.parameterization = runtime::Parameterization::LatLong;
    WritePemManifest(m);
    ASSERT_EQ(ReadPemManifest(m.dir).parameterization, runtime::Parameterization::LatLong);
    infer::EnvMapF latlong;
    latlong.kind = raster::TextureKind::Tex2D;
    latlong.size = 16, latlong.height = 8;  // LayoutOf(LatLong, 8): 16 x 8
    for (int l = 0; l < 5; ++l) latlong.levels.emplace_back(latlong.LevelTexels(l) * 4, 0.25f);
    infer::WriteEnvMapExr(latlong, MapPath(m.dir, 0, 0, "pem_distant"));
    infer::EnvMapF square = latlong;  // a sphere map's shape: 8 x 8
    square.size = 8;
    square.levels.pop_back();
    for (int l = 0; l < 4; ++l)
        square.levels[static_cast<size_t>(l)].resize(square.LevelTexels(l) * 4);
    infer::WriteEnvMapExr(square, MapPath(m.dir, 0, 0, "layer_0"));
    infer::WriteEnvMapExr(ConstantMap(8, 0.5f, 0.25f, 1.0f, 1.0f),
                          MapPath(m.dir, 0, 0, "pem_local"));
    const runtime::MapSet set = LoadMapSet(ReadPemManifest(m.dir));
    EXPECT_EQ(set.parameterization, runtime::Parameterization::LatLong);
    const raster::Texture* t = set.map(0, 0, "pem_distant");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->kind, raster::TextureKind::Tex2D);
    EXPECT_EQ(t->width, 16);
    EXPECT_EQ(t->height, 8);
    EXPECT_EQ(t->NumLevels(), 5);
    EXPECT_EQ(t->sampler.wrapS, raster::Wrap::Repeat);
    EXPECT_EQ(t->sampler.wrapT, raster::Wrap::ClampToEdge);
    EXPECT_EQ(t->levels[4][0], 64);                              // 0.25 * 255 = 63.75 -> 64
    EXPECT_THROW(set.map(0, 0, "layer_0"), base::InputError);    // 8 x 8 is not lat-long's
    EXPECT_THROW(set.map(0, 0, "pem_local"), base::InputError);  // a cube map
    EXPECT_THROW(PackPem(m.dir, (dir / "p.pempack").string(), {}), base::InputError);  // layer_0
    EXPECT_FALSE(fs::exists(dir / "p.pempack"));
    fs::remove_all(dir);
}

// A two-image layout's map: two textures (charts) of the layout's shape, each with its own MIP
// chain; a map of one chart of that shape, or the charts' shape as one image, is refused.
TEST(PemSet, TwoImageLayoutsAreTwoTextures) {
    const fs::path dir = FreshDir("pem_paraboloid");
    PemManifest m = MakePemDir(dir);
    m.parameterization = runtime::Parameterization::Paraboloid;
    WritePemManifest(m);
    infer::EnvMapF map;  // LayoutOf(Paraboloid, 8): two 8 x 8 textures
    map.kind = raster::TextureKind::Tex2D;
    map.size = 8, map.height = 8, map.charts = 2;
    for (int l = 0; l < 4; ++l) {
        map.levels.emplace_back(map.LevelTexels(l) * 4, 0.25f);
        std::fill(map.levels.back().begin() + static_cast<std::ptrdiff_t>(map.LevelTexels(l) * 2),
                  map.levels.back().end(), 0.5f);  // chart 1
    }
    infer::WriteEnvMapExr(map, MapPath(m.dir, 0, 0, "pem_distant"));
    // Packed (lossless): the same two textures, with the layout's sampler.
    const std::string pack = (dir / "p.pempack").string();
    PackPem(m.dir, pack, {});
    const std::vector<raster::Texture> packed = ReadPemPack(pack).maps.at({0, 0, "pem_distant"});
    const runtime::MapSet fromDir = LoadMapSet(ReadPemManifest(m.dir));
    const raster::Texture* direct = fromDir.map(0, 0, "pem_distant");
    ASSERT_EQ(packed.size(), 2u);
    EXPECT_EQ(packed[0], direct[0]);
    EXPECT_EQ(packed[1], direct[1]);
    infer::EnvMapF one = map;  // one 8 x 8 chart
    one.charts = 1;
    for (int l = 0; l < 4; ++l) one.levels[static_cast<size_t>(l)].resize(one.LevelTexels(l) * 4);
    infer::WriteEnvMapExr(one, MapPath(m.dir, 0, 0, "pem_local"));
    infer::EnvMapF atlas = one;  // the old atlas: one 16 x 8 image
    atlas.size = 16;
    atlas.levels.emplace_back();
    for (int l = 0; l < 5; ++l)
        atlas.levels[static_cast<size_t>(l)].assign(atlas.LevelTexels(l) * 4, 0.25f);
    infer::WriteEnvMapExr(atlas, MapPath(m.dir, 0, 0, "layer_0"));
    const runtime::MapSet set = LoadMapSet(ReadPemManifest(m.dir));
    const raster::Texture* t = set.map(0, 0, "pem_distant");
    ASSERT_NE(t, nullptr);
    for (int c = 0; c < 2; ++c) {
        EXPECT_EQ(t[c].kind, raster::TextureKind::Tex2D);
        EXPECT_EQ(t[c].width, 8);
        EXPECT_EQ(t[c].height, 8);
        EXPECT_EQ(t[c].NumLevels(), 4);
        EXPECT_EQ(t[c].sampler.wrapS, raster::Wrap::ClampToEdge);
        EXPECT_EQ(t[c].levels[3][0], c == 0 ? 64 : 128);  // 0.25, 0.5 * 255 rounded
    }
    EXPECT_THROW(set.map(0, 0, "pem_local"), base::InputError);
    EXPECT_THROW(set.map(0, 0, "layer_0"), base::InputError);
    fs::remove_all(dir);
}

TEST(PemSet, OpensAfterTheDirectoryMovedWithItsScene) {
    const fs::path dir = FreshDir("pem_move");
    MakePemDir(dir / "a");
    fs::rename(dir / "a", dir / "b");
    const auto renderer = OpenPemDirectory((dir / "b" / "pem").string(), 1);
    runtime::RenderSettings s;
    s.method = runtime::Method::Pem;
    const runtime::RenderedFrame f = renderer->Render(renderer->SampleCamera(0), s);
    size_t lens = 0;
    for (uint8_t m : f.lensMask) lens += m;
    EXPECT_GT(lens, 20u);
    // Without its scene the directory names the manifest and both places it looked.
    fs::remove_all(dir / "b" / "scene");
    fs::remove_all(dir / "b" / "env");
    try {
        OpenPemDirectory((dir / "b" / "pem").string(), 1);
        FAIL() << "no exception";
    } catch (const base::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("manifest.json: scene not found"), std::string::npos)
            << e.what();
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pem::pipeline
