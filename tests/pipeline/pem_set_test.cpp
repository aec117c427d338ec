// SPDX-License-Identifier: MIT
// pem_set_test.cpp — the PEM-set loader: maps come back as the hardware's 8-bit copies of what
// was written (texels checked against hand-computed bytes), missing maps are nullptr, and a
// PEM directory opens after it was moved together with its scene.
#include "pipeline/pem_set.h"

#include <gtest/gtest.h>

#include <cstring>

#include "base/input_error.h"
#include "infer/pem_file.h"
#include "pipeline/layout.h"
#include "tests/pipeline/pipeline_test_util.h"

namespace pem::pipeline {
namespace {

// A cube map of face size n, every level and texel (r, g, b, a).
infer::CubeMapF ConstantMap(int n, float r, float g, float b, float a) {
    infer::CubeMapF m;
    m.size = n;
    for (int s = n; s >= 1; s /= 2) {
        std::vector<float>& level = m.levels.emplace_back();
        for (int k = 0; k < 6 * s * s; ++k) level.insert(level.end(), {r, g, b, a});
    }
    return m;
}

// dir/scene and dir/env (the mirror sphere and its sky), dir/pem with one sample whose map is
// `pem_distant`.
PemManifest MakePemDir(const fs::path& dir) {
    fs::create_directories(dir / "scene");
    fs::create_directories(dir / "env");
    fs::copy_file(kRoot + "/data/scenes/mirror_sphere.gltf", dir / "scene" / "m.gltf");
    fs::copy_file(kRoot + "/data/scenes/mirror_sphere.bin", dir / "scene" / "mirror_sphere.bin");
    fs::copy_file(kRoot + "/data/env/sky.exr", dir / "env" / "sky.exr");
    TraceManifest t;
    t.dir = (dir / "trace").string();
    t.scene = SceneForStorage(t.dir, (dir / "scene" / "m.gltf").string());
    t.sceneGiven = "m.gltf";
    t.width = 32, t.height = 24, t.spp = 1;
    const trace::Scene scene = trace::LoadScene(kMirrorSphere);
    const raster::Camera c = trace::CameraForSize(*scene.camera, 32, 24);
    t.views = {{c, 0, 0, {}, {}, {}, {}, {}, {}, {}, {}}};
    runtime::LensGroupEm g;
    g.objects = {"mirror_sphere"};
    g.layers = {{"sphere", trace::SphereShell{{0.0, 0.5, 0.0}, 5.0}, 5.0, 10, {}, 1.0, 0.0, {}}};
    g.pem = true;
    g.localShell = trace::EllipsoidShell{{0.0, 0.5, 0.0}, {0.6, 0.6, 0.6}};
    g.distantShell = trace::BoxShell{{-5.0, -0.5, -5.0}, {5.0, 4.0, 5.0}};
    t.groups = {g};
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 8, false, {});
    fs::create_directories(GroupDir(m.dir, 0, 0));
    WritePemManifest(m);
    infer::WriteCubeMapExr(ConstantMap(8, 0.5f, 0.25f, 1.0f, 1.0f),
                           MapPath(m.dir, 0, 0, "pem_distant"));
    return m;
}

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

// With max_res (infer --max-res), a map may be larger than res, up to max_res; a size outside
// [res, max_res] or not a power of two is refused with the map's path.
TEST(PemSet, MapSizesWithinResAndMaxRes) {
    const fs::path dir = FreshDir("pem_max_res");
    PemManifest m = MakePemDir(dir);
    m.maxRes = 32;
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).maxRes, 32);
    infer::WriteCubeMapExr(ConstantMap(32, 0.5f, 0.25f, 1.0f, 1.0f),
                           MapPath(m.dir, 0, 0, "pem_distant"));
    infer::WriteCubeMapExr(ConstantMap(64, 0.5f, 0.25f, 1.0f, 1.0f),
                           MapPath(m.dir, 0, 0, "pem_local"));
    infer::WriteCubeMapExr(ConstantMap(4, 0.5f, 0.25f, 1.0f, 1.0f),
                           MapPath(m.dir, 0, 0, "layer_0"));
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
