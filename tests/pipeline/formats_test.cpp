// SPDX-License-Identifier: MIT
// formats_test.cpp — every on-disk format of pipeline/ read back by its one reader gives what its
// one writer was given (cameras bit for bit), old and malformed files are refused with one line
// naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>

#include "base/input_error.h"
#include "pipeline/infer_report.h"
#include "pipeline/json_values.h"
#include "pipeline/layout.h"
#include "pipeline/pem_manifest.h"
#include "pipeline/pem_set.h"
#include "pipeline/trace_manifest.h"
#include "tests/pipeline/pipeline_test_util.h"

namespace pem::pipeline {
namespace {

raster::Camera OddCamera() {
    raster::Camera c;
    c.eye = {0.1f, 1.0f / 3.0f, -7.25e-3f};
    c.target = {std::nextafter(1.0f, 2.0f), -0.0f, 3e-8f};
    c.up = {0.01f, 0.99995f, 0.0f};
    c.fovYRadians = 0.6981317f;
    c.width = 641, c.height = 479;
    return c;
}

runtime::LensGroupEm SomeGroup(int index) {
    runtime::LensGroupEm g;
    g.index = index;
    g.objects = {"teapot", "lid"};
    g.glass = index == 0;
    g.emOrigin = {0.25f, 0.45f, 1.0f / 7.0f};
    g.records = 1234;
    g.lbgIterations = 7;
    g.lbgConverged = true;
    runtime::EmLayer inner{"sphere", trace::SphereShell{{0.1, 0.2, 0.3}, 1.5}, 1.25, 99, {"a"}, 0.5,
                           0.75,     {{"sphere", 0.75}, {"cylinder", 1.5}}};
    trace::QuadShell q;
    q.centre = {0.0, -0.5, 0.0};
    q.normal = {0.0, 1.0, 0.0};
    q.u = {1.0, 0.0, 0.0};
    q.v = {0.0, 0.0, -1.0};
    q.halfExtent = {3.0, 4.0};
    runtime::EmLayer floor{"quad", q, 2.5, 0, {}, 0.0, 0.0, {}};
    runtime::EmLayer room{
        "cylinder",
        trace::CylinderShell{{0.5, -1.0}, 3.0, 0.0, std::numeric_limits<double>::infinity()},
        9.0,
        3,
        {},
        0.1,
        std::numeric_limits<double>::quiet_NaN(),
        {}};
    g.layers = {inner, floor, room};
    if (!g.glass) {
        g.pem = true;
        g.localShell = trace::EllipsoidShell{{0.0, 0.5, 0.0}, {0.3, 0.4, 0.5}};
        g.localParallaxDeg = 29.75;
        g.distantShell = trace::BoxShell{{-5.0, -0.5, -5.0}, {5.0, 4.0, 5.0}};
        g.distantMeanDistance = 3.75;
    }
    return g;
}

void ExpectSameGroup(const runtime::LensGroupEm& a, const runtime::LensGroupEm& b) {
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.objects, b.objects);
    EXPECT_EQ(a.glass, b.glass);
    EXPECT_EQ(a.emOrigin, b.emOrigin);
    EXPECT_EQ(a.records, b.records);
    ASSERT_EQ(a.layers.size(), b.layers.size());
    for (size_t l = 0; l < a.layers.size(); ++l) {
        EXPECT_TRUE(a.layers[l].shell == b.layers[l].shell) << l;
        EXPECT_EQ(a.layers[l].kind, b.layers[l].kind);
        EXPECT_EQ(a.layers[l].radius, b.layers[l].radius);
        EXPECT_EQ(a.layers[l].records, b.layers[l].records);
        EXPECT_EQ(std::isnan(a.layers[l].parallaxDeg), std::isnan(b.layers[l].parallaxDeg));
        if (!std::isnan(a.layers[l].parallaxDeg)) {
            EXPECT_EQ(a.layers[l].parallaxDeg, b.layers[l].parallaxDeg);
        }
        EXPECT_EQ(a.layers[l].candidates.size(), b.layers[l].candidates.size());
    }
    EXPECT_EQ(a.pem, b.pem);
    EXPECT_TRUE(a.localShell == b.localShell);
    EXPECT_EQ(a.localParallaxDeg, b.localParallaxDeg);
    EXPECT_TRUE(a.distantShell == b.distantShell);
}

void WriteFile(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

std::string ReadFile(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(JsonValues, CameraRoundTripsBitForBit) {
    const raster::Camera c = OddCamera();
    const raster::Camera back = CameraFromJson(json::parse(CameraJson(c).dump()));
    EXPECT_EQ(std::memcmp(&back, &c, sizeof c), 0);
}

TEST(JsonValues, CameraOutOfRangeRefused) {
    json j = CameraJson(OddCamera());
    j["fov_y_radians"] = 0.0;
    EXPECT_ANY_THROW(CameraFromJson(j));
    j = CameraJson(OddCamera());
    j["eye"] = json::array({1.0, "x", 2.0});
    EXPECT_ANY_THROW(CameraFromJson(j));
    j = CameraJson(OddCamera());
    j["target"] = j["eye"];
    EXPECT_ANY_THROW(CameraFromJson(j));
}

TEST(JsonValues, LensGroupRoundTrips) {
    for (int index : {0, 1}) {
        const runtime::LensGroupEm g = SomeGroup(index);
        ExpectSameGroup(LensGroupFromJson(json::parse(LensGroupJson(g).dump()), index), g);
    }
}

TEST(TraceManifest, RoundTripsAndResolvesTheSceneAfterAMove) {
    const fs::path dir = FreshDir("trace_manifest");
    TraceManifest m;
    m.dir = (dir / "a" / "trace").string();
    fs::create_directories(m.dir);
    fs::copy_file(kMirrorSphere, dir / "a" / "scene.gltf");
    m.scene = SceneForStorage(m.dir, (dir / "a" / "scene.gltf").string());
    m.sceneGiven = "somewhere/scene.gltf";
    m.width = 64, m.height = 48, m.spp = 3;
    m.views.push_back({OddCamera(), 1.0, 2.0, {1, 2, 3}, {}, {}, {}, {0.5, 20.0, 10}, {}, {}, {}});
    m.views[0].lens.psnr = std::numeric_limits<double>::infinity();
    m.groups = {SomeGroup(0), SomeGroup(1)};
    WriteTraceManifest(m);
    EXPECT_EQ(m.scene, "../scene.gltf");
    // Moved: the directory and its scene together.
    fs::rename(dir / "a", dir / "b");
    const TraceManifest r = ReadTraceManifest((dir / "b" / "trace").string());
    EXPECT_EQ(ResolveScene(r.dir, r.scene, r.sceneGiven),
              (dir / "b" / "scene.gltf").lexically_normal().string());
    ASSERT_EQ(r.views.size(), 1u);
    EXPECT_EQ(std::memcmp(&r.views[0].camera, &m.views[0].camera, sizeof(raster::Camera)), 0);
    EXPECT_EQ(r.views[0].reference.secondary, 2u);
    EXPECT_TRUE(std::isinf(r.views[0].lens.psnr));
    ASSERT_EQ(r.groups.size(), 2u);
    ExpectSameGroup(r.groups[1], m.groups[1]);
    fs::remove_all(dir);
}

TEST(TraceManifest, OldAndMalformedFilesRefusedNamingTheFile) {
    const fs::path dir = FreshDir("trace_bad");
    const std::string path = (dir / kTraceJson).string();
    WriteFile(path, R"({"scene": "x.gltf", "size": "64x48", "views": [{"eye": [0,0,1]}]})");
    EXPECT_NE(ErrorOf([&] { ReadTraceManifest(dir.string()); }).find(path + ": "),
              std::string::npos);
    EXPECT_NE(ErrorOf([&] { ReadTraceManifest(dir.string()); }).find("trace again"),
              std::string::npos);
    WriteFile(path, "{\"format\": \"pemref_trace\", \"version\": 2, \"scene\": ");
    EXPECT_EQ(ErrorOf([&] { ReadTraceManifest(dir.string()); }).rfind(path + ": ", 0), 0u);
    fs::remove(path);
    EXPECT_NE(ErrorOf([&] { ReadTraceManifest(dir.string()); }).find("cannot open"),
              std::string::npos);
    fs::remove_all(dir);
}

// A trace of the mirror sphere at 64x48 (spp × spp), one sample, one mirror-only group.
TraceManifest SmallTrace(const fs::path& dir, int spp) {
    TraceManifest t;
    t.dir = (dir / "trace").string();
    t.scene = SceneForStorage(t.dir, kMirrorSphere);
    t.sceneGiven = kMirrorSphere;
    t.width = 64, t.height = 48, t.spp = spp;
    t.views = {{OddCamera(), 0, 0, {}, {}, {}, {}, {}, {}, {}, {}}};
    t.groups = {SomeGroup(1)};  // a mirror-only group, the scene's first
    t.groups[0].index = 0;
    return t;
}

TEST(PemManifest, RoundTripsFromATrace) {
    const fs::path dir = FreshDir("pem_manifest");
    const TraceManifest t = SmallTrace(dir, 2);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {});
    fs::create_directories(m.dir);
    WritePemManifest(m);
    const PemManifest r = ReadPemManifest(m.dir);
    EXPECT_EQ(r.inferred, std::vector<int>{0});
    EXPECT_EQ(r.res, 32);
    EXPECT_EQ(r.spp, 2);
    ASSERT_EQ(r.views.size(), 1u);
    EXPECT_EQ(std::memcmp(&r.views[0], &t.views[0].camera, sizeof(raster::Camera)), 0);
    EXPECT_EQ(ResolveScene(r.dir, r.scene, r.sceneGiven),
              fs::path(kMirrorSphere).lexically_normal().string());
    ExpectSameGroup(r.groups[0], t.groups[0]);
    EXPECT_TRUE(r.alsoTessT.empty());
    // The further t the maps also fit (infer --also-t) travel with them; out of range: refused.
    m.alsoTessT = {5.0, 2.5};
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).alsoTessT, (std::vector<double>{5.0, 2.5}));
    m.alsoTessT = {0.0};
    WritePemManifest(m);
    const std::string path = (fs::path(m.dir) / kManifestJson).string();
    EXPECT_EQ(ErrorOf([&] { ReadPemManifest(m.dir); }).rfind(path + ": ", 0), 0u);
    // The first manifest format is refused with what to do.
    WriteFile(fs::path(m.dir) / kManifestJson, R"({"format": "pemref_pem/1"})");
    EXPECT_NE(ErrorOf([&] { ReadPemManifest(m.dir); }).find("infer again"), std::string::npos);
    fs::remove_all(dir);
}

TEST(PemManifest, HardwareRoundTripsAndImpossibleAnisotropyIsRefused) {
    const fs::path dir = FreshDir("pem_manifest_hw");
    const TraceManifest t = SmallTrace(dir, 1);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {},
                                   runtime::MapHardware{"exact-lod", 8.0f});
    fs::create_directories(m.dir);
    WritePemManifest(m);
    const PemManifest r = ReadPemManifest(m.dir);
    EXPECT_EQ(r.hardware.profile, "exact-lod");
    EXPECT_EQ(r.hardware.maxAnisotropy, 8.0f);
    EXPECT_EQ(r.hardware.Sampler().maxAnisotropy, 8.0f);
    // Out of GL's range, or not a number: one line naming the file.
    const std::string path = (fs::path(m.dir) / kManifestJson).string();
    const std::string text = ReadFile(path);
    const size_t at = text.find("\"max_anisotropy\": 8.0");
    ASSERT_NE(at, std::string::npos);
    for (const char* bad : {"0.5", "17.0", "-1", "\"x\""}) {
        std::string t2 = text;
        t2.replace(at, std::string("\"max_anisotropy\": 8.0").size(),
                   std::string("\"max_anisotropy\": ") + bad);
        WriteFile(path, t2);
        EXPECT_EQ(ErrorOf([&] { ReadPemManifest(m.dir); }).rfind(path + ": ", 0), 0u) << bad;
    }
    // Absent (directories written before the key existed): isotropic.
    std::string old = text;
    old.replace(at, std::string("\"max_anisotropy\": 8.0,").size(), "");
    WriteFile(path, old);
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.maxAnisotropy, 1.0f);
    fs::remove_all(dir);
}

// Integers that are not (2.5, 1e300, 2^40 for an int, a string) and profiles this pemref does not
// know: one line naming the file and the key, never a wrapped value or an escaping exception.
TEST(PemManifest, NonIntegersAndUnknownProfilesAreRefusedNamingTheKey) {
    const fs::path dir = FreshDir("pem_manifest_ints");
    const TraceManifest t = SmallTrace(dir, 1);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {});
    fs::create_directories(m.dir);
    WritePemManifest(m);
    const std::string path = (fs::path(m.dir) / kManifestJson).string();
    const json good = json::parse(ReadFile(path));
    const auto refused = [&](const char* key, const json& value, size_t index = 0) {
        json bad = good;
        json& slot = bad.at(key).is_array() ? bad.at(key).at(index) : bad.at(key);
        slot = value;
        WriteFile(path, bad.dump(2));
        const std::string error = ErrorOf([&] { ReadPemManifest(m.dir); });
        EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << key << " = " << value.dump();
        EXPECT_NE(error.find(key), std::string::npos) << error;
    };
    for (const json& v :
         {json(1e300), json(32.5), json(-1e300), json(int64_t{1} << 40), json("32")})
        refused("res", v);
    refused("max_res", json(1e300));
    refused("size", json(int64_t{1} << 33), 0);
    refused("spp", json(-2.5e10));
    refused("inferred_views", json(1e300), 0);
    refused("profile", json("llvmpipx"));
    WriteFile(path, good.dump(2));
    EXPECT_EQ(ReadPemManifest(m.dir).res, 32);
    fs::remove_all(dir);
}

// Each of `bads` in place of the value of `entry` (a key and value as the manifest in `dir`
// writes them) makes ReadPemManifest fail naming the file; then the manifest is left without the
// key, as directories written before it.
void RefuseValuesThenDrop(const std::string& dir, const std::string& entry,
                          std::initializer_list<const char*> bads) {
    const std::string path = (fs::path(dir) / kManifestJson).string();
    const std::string text = ReadFile(path);
    const size_t at = text.find(entry);
    ASSERT_NE(at, std::string::npos) << entry;
    const std::string name = entry.substr(0, entry.find(':') + 2);  // "\"key\": "
    for (const char* bad : bads) {
        std::string t2 = text;
        t2.replace(at, entry.size(), name + bad);
        WriteFile(path, t2);
        EXPECT_EQ(ErrorOf([&] { ReadPemManifest(dir); }).rfind(path + ": ", 0), 0u) << bad;
    }
    std::string old = text;
    old.replace(at, entry.size() + 1, "");  // with its comma
    WriteFile(path, old);
}

TEST(PemManifest, LodBiasRoundTripsWithinItsRange) {
    const fs::path dir = FreshDir("pem_manifest_lod_bias");
    const TraceManifest t = SmallTrace(dir, 1);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {},
                                   runtime::MapHardware{"llvmpipe", 1.0f, 2.0f, -2.5f});
    fs::create_directories(m.dir);
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.lodBias, -2.5f);
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.Sampler().lodBias, -2.5f);
    RefuseValuesThenDrop(m.dir, "\"lod_bias\": -2.5", {"-4.5", "4.01", "1e9", "\"x\"", "null"});
    // Absent (directories written before the key existed): no bias.
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.lodBias, 0.0f);
    fs::remove_all(dir);
}

// The topology threshold the maps were fitted with (infer --t-topology): written when there is
// one, read back, checked; absent (directories written before it) means t alone.
TEST(PemManifest, TopologyThresholdRoundTripsAndAbsentMeansTAlone) {
    const fs::path dir = FreshDir("pem_manifest_topology");
    const TraceManifest t = SmallTrace(dir, 1);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {});
    EXPECT_EQ(m.topologyT, runtime::kDefaultTopologyT);
    m.topologyT = 1.5;
    fs::create_directories(m.dir);
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).topologyT, 1.5);
    EXPECT_EQ(LoadMapSet(ReadPemManifest(m.dir)).topologyT, 1.5);
    RefuseValuesThenDrop(m.dir, "\"t_topology\": 1.5", {"-1", "0.1", "1e5", "\"x\"", "null"});
    const std::string path = (fs::path(m.dir) / kManifestJson).string();
    EXPECT_EQ(ReadPemManifest(m.dir).topologyT, 0.0);
    // 0 (t alone) is written as absent.
    m.topologyT = 0.0;
    WritePemManifest(m);
    EXPECT_EQ(ReadFile(path).find("\"t_topology\""), std::string::npos);
    EXPECT_EQ(ReadPemManifest(m.dir).topologyT, 0.0);
    fs::remove_all(dir);
}

TEST(PemManifest, RadianceScaleRoundTripsAndOnlyPowersOfTwoAreTaken) {
    const fs::path dir = FreshDir("pem_manifest_scale");
    const TraceManifest t = SmallTrace(dir, 1);
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 32, false, {},
                                   runtime::MapHardware{"llvmpipe", 1.0f, 4.0f});
    fs::create_directories(m.dir);
    WritePemManifest(m);
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.radianceScale, 4.0f);
    const std::string path = (fs::path(m.dir) / kManifestJson).string();
    const std::string text = ReadFile(path);
    const std::string key = "\"radiance_scale\": 4.0";
    const size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos);
    for (const char* bad : {"3.0", "0.5", "0", "128.0", "-2", "\"x\""}) {
        std::string t2 = text;
        t2.replace(at, key.size(), std::string("\"radiance_scale\": ") + bad);
        WriteFile(path, t2);
        EXPECT_EQ(ErrorOf([&] { ReadPemManifest(m.dir); }).rfind(path + ": ", 0), 0u) << bad;
    }
    // Absent (directories written before the key existed): the maps hold radiance itself.
    std::string old = text;
    old.replace(at, key.size() + 1, "");
    WriteFile(path, old);
    EXPECT_EQ(ReadPemManifest(m.dir).hardware.radianceScale, 1.0f);
    for (float s : {1.0f, 2.0f, 64.0f}) EXPECT_TRUE(runtime::IsRadianceScale(s)) << s;
    for (float s : {0.0f, 3.0f, 0.5f, 128.0f, -2.0f})
        EXPECT_FALSE(runtime::IsRadianceScale(s)) << s;
    fs::remove_all(dir);
}

TEST(InferReport, SampleAndInferJsonRoundTrip) {
    const fs::path dir = FreshDir("infer_report");
    MapReport map;
    map.view = 2, map.group = 1, map.layer = 0, map.term = "R", map.name = "pem_local";
    map.rows = 10, map.cols = 20, map.nnz = 30, map.rmse8 = 0.125, map.directRmse8 = 0.25;
    fs::create_directories(ViewDir(dir.string(), 2));
    WriteSampleJson(dir.string(),
                    {{2, 1.5, 0.5, 99, 7}, {map}, {{2, 1, "PEM local layer", "convex"}}});
    const SampleRecord s = ReadSampleJson(dir.string(), 2);
    EXPECT_EQ(s.sample.vertexRays, 99u);
    ASSERT_EQ(s.maps.size(), 1u);
    EXPECT_EQ(s.maps[0].name, "pem_local");
    EXPECT_EQ(s.maps[0].rmse8, 0.125);
    EXPECT_EQ(s.maps[0].directRmse8, 0.25);
    ASSERT_EQ(s.leftOut.size(), 1u);
    EXPECT_EQ(s.leftOut[0].why, "convex");
    InferRecord rec;
    rec.dir = dir.string();
    rec.res = 64, rec.neighbours = 1, rec.maps = s.maps, rec.samples = {s.sample};
    WriteInferJson(rec);
    const InferRecord r = ReadInferJson(dir.string());
    EXPECT_EQ(r.res, 64);
    EXPECT_EQ(r.neighbours, 1);
    EXPECT_EQ(r.maps.size(), 1u);
    EXPECT_EQ(r.lambda.smooth, rec.lambda.smooth);
    fs::remove_all(dir);
}

TEST(Layout, OneSpellingOfEveryPath) {
    EXPECT_EQ(MapFile(3, 1, "layer_0"), "view_003/group_1/layer_0.exr");
    EXPECT_EQ(GroupImagePath("t", 12, 0, LayerImageName(1, 1)), "t/view_012/group_0/layer_1_T.exr");
    EXPECT_EQ(SampleJsonPath("p", 0), "p/view_000/sample.json");
    EXPECT_EQ(PreviewPath("a/b_R.exr"), "a/b_R.png");
    EXPECT_EQ(BakeJsonPath("out/b"), "out/b/bake.json");
}

}  // namespace
}  // namespace pem::pipeline
