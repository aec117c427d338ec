// SPDX-License-Identifier: MIT
// scene_test.cpp — trace/scene.h: the two bundled scenes load with the documented objects,
// materials, lens groups, camera, lights and environment; every malformed input (our crafted
// tests/data/bad_scenes and Debian's assimp-testmodels, which setup.sh installs) gives a one-line
// pem::base::InputError naming the file.
#include "trace/scene.h"

#include <ImfEnvmapAttribute.h>
#include <ImfHeader.h>
#include <ImfRgbaFile.h>
#include <ImfStandardAttributes.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "base/input_error.h"

namespace pem::trace {
namespace {

const std::string kRoot = PEM_SOURCE_DIR;

const Object* FindObject(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return &o;
    return nullptr;
}

void ExpectNear3(const glm::vec3& a, const glm::vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Lens objects by material agree with the scene's pemref_role marks, and normals are unit.
void ExpectConsistentObjects(const Scene& s) {
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const Object& o = s.objects[i];
        EXPECT_EQ(s.IsLens(static_cast<int>(i)), o.lensRole) << o.name;
        EXPECT_EQ(o.normals.size(), o.positions.size()) << o.name;
        for (const glm::vec3& n : o.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << o.name;
        EXPECT_FALSE(o.bounds.Empty());
    }
}

TEST(Scene, HybridGlassTeapotLoads) {
    const auto t0 = std::chrono::steady_clock::now();
    const Scene s = LoadScene(kRoot + "/data/scenes/hybrid_glass_teapot.gltf");
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    RecordProperty("load_ms", std::to_string(ms));
    EXPECT_EQ(s.objects.size(), 20u);  // teapot, cup, 8 columns, floor x2, 4 walls x2
    EXPECT_EQ(s.NumTriangles(), 25188u);
    EXPECT_EQ(s.droppedDegenerate, 0);
    EXPECT_TRUE(s.notes.empty());
    ExpectConsistentObjects(s);
    // Lenses: the glass teapot and the mirror cup, apart.
    const Object* teapot = FindObject(s, "glass_teapot");
    const Object* cup = FindObject(s, "mirror_cup");
    ASSERT_TRUE(teapot && cup);
    EXPECT_EQ(teapot->triangles.size(), 16384u);
    EXPECT_EQ(cup->triangles.size(), 5504u);
    ASSERT_EQ(s.lensGroups.size(), 2u);
    EXPECT_EQ(s.lensGroups[0].objects, std::vector<int>{0});
    EXPECT_EQ(s.lensGroups[1].objects, std::vector<int>{1});
    EXPECT_NEAR(teapot->bounds.lo.y, 0.001f, 1e-5f);  // lifted 1 mm
    EXPECT_NEAR(teapot->bounds.hi.y - teapot->bounds.lo.y, 1.0f, 0.02f);
    // Materials: glass with absorption -ln(c)/1.5, mirror with F0 0.9.
    const Material& glass = s.materials[static_cast<size_t>(teapot->material)];
    EXPECT_EQ(glass.kind, MaterialKind::Glass);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    ExpectNear3(glass.absorption,
                glm::vec3(-std::log(0.82f), -std::log(0.95f), -std::log(0.9f)) / 1.5f, 1e-6f);
    const Material& mirror = s.materials[static_cast<size_t>(cup->material)];
    EXPECT_EQ(mirror.kind, MaterialKind::Mirror);
    ExpectNear3(mirror.baseColor, glm::vec3(0.9f), 1e-6f);
    // Camera: eye (0.25, 1.4, 3.3) looking at (0.25, 0.45, 0), 40 degrees, 640x480.
    ASSERT_TRUE(s.camera.has_value());
    ExpectNear3(s.camera->camera.eye, {0.25f, 1.4f, 3.3f}, 1e-6f);
    ExpectNear3(s.camera->camera.target, {0.25f, 0.45f, 0.0f}, 1e-4f);
    // up: the node's +Y, orthogonal to the view direction (pitched down by ~16 degrees).
    const glm::vec3 forward = glm::normalize(s.camera->camera.target - s.camera->camera.eye);
    EXPECT_NEAR(glm::dot(s.camera->camera.up, forward), 0.0f, 1e-5f);
    ExpectNear3(s.camera->camera.up, {0.0f, 0.96097f, -0.27664f}, 1e-4f);
    EXPECT_NEAR(s.camera->camera.fovYRadians, 40.0f * std::numbers::pi_v<float> / 180.0f, 1e-6f);
    EXPECT_EQ(s.camera->camera.width, 640);
    EXPECT_EQ(s.camera->camera.height, 480);
    // Lights and viewpoints.
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "light_key");
    ExpectNear3(s.lights[0].position, {2.5f, 3.5f, 3.0f}, 1e-6f);
    ExpectNear3(s.lights[0].intensity, glm::vec3(1.0f, 0.96f, 0.9f) * 80.0f, 1e-4f);
    EXPECT_EQ(s.viewpoints.count, 45);
    ExpectNear3(ViewpointCamera(s, 0, 640, 480).eye, s.camera->camera.eye, 1e-5f);
    // Environment: studio.exr, lat-long.
    EXPECT_EQ(s.environment.mapping, Environment::Mapping::LatLong);
    EXPECT_EQ(s.environment.width, 512);
    EXPECT_EQ(s.environment.height, 256);
}

TEST(Scene, PemMirrorTeapotLoads) {
    const Scene s = LoadScene(kRoot + "/data/scenes/pem_mirror_teapot.gltf");
    EXPECT_EQ(s.objects.size(), 17u);
    EXPECT_EQ(s.NumTriangles(), 41576u);
    ExpectConsistentObjects(s);
    ASSERT_EQ(s.lensGroups.size(), 1u);
    ASSERT_EQ(s.lensGroups[0].objects.size(), 1u);
    const Object& teapot = s.objects[static_cast<size_t>(s.lensGroups[0].objects[0])];
    EXPECT_EQ(teapot.name, "mirror_teapot");
    EXPECT_EQ(teapot.triangles.size(), 40000u);
    const Material& m = s.materials[static_cast<size_t>(teapot.material)];
    EXPECT_EQ(m.kind, MaterialKind::Mirror);
    ExpectNear3(m.baseColor, {0.95f, 0.93f, 0.88f}, 1e-6f);
    // The window emits (emissiveFactor x strength 4); nothing else does.
    const Object* window = FindObject(s, "window_light");
    ASSERT_TRUE(window);
    const glm::vec3 e = s.materials[static_cast<size_t>(window->material)].emission;
    EXPECT_GT(std::min(e.x, std::min(e.y, e.z)), 1.0f);
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->camera.width, 480);
    EXPECT_EQ(s.camera->camera.height, 480);
    ExpectNear3(s.camera->camera.target, {0.1f, 0.45f, 0.0f}, 1e-4f);
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.viewpoints.count, 100);
    ExpectNear3(ViewpointCamera(s, 50, 480, 480).eye, s.camera->camera.eye, 1e-5f);
    // Closed room: no environment, black everywhere.
    EXPECT_EQ(s.environment.mapping, Environment::Mapping::None);
    EXPECT_EQ(EnvRadiance(s.environment, {0.0f, 1.0f, 0.0f}), glm::vec3(0.0f));
}

TEST(Scene, ValidTriangleGetsFlatNormalAndNoCamera) {
    const Scene s = LoadScene(kRoot + "/tests/data/trace_scenes/triangle.gltf");
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "tri");
    for (const glm::vec3& n : s.objects[0].normals) EXPECT_EQ(n, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(s.objects[0].bounds.lo, glm::vec3(0.0f));
    EXPECT_EQ(s.objects[0].bounds.hi, glm::vec3(1.0f, 1.0f, 0.0f));
    EXPECT_FALSE(s.camera.has_value());
    EXPECT_TRUE(s.lensGroups.empty());
    EXPECT_EQ(s.materials.back().name, "default");
    EXPECT_EQ(s.objects[0].material, static_cast<int>(s.materials.size()) - 1);
}

// Lens groups: touching, overlapping and nested boxes join; separate ones do not; diffuse
// objects never join.
TEST(Scene, LensGroupsJoinTouchingOverlappingAndNestedBoxes) {
    std::vector<Material> mats(2);
    mats[1].kind = MaterialKind::Glass;
    auto box = [](glm::vec3 lo, glm::vec3 hi, int material) {
        Object o;
        o.material = material;
        o.bounds = {lo, hi};
        return o;
    };
    const std::vector<Object> objs = {
        box({0, 0, 0}, {1, 1, 1}, 1),                    // 0
        box({5, 0, 0}, {6, 1, 1}, 1),                    // 1: alone
        box({1, 0, 0}, {2, 1, 1}, 1),                    // 2: touches 0
        box({0.2f, 0.2f, 0.2f}, {0.4f, 0.4f, 0.4f}, 1),  // 3: nested in 0
        box({6, 0, 0}, {9, 9, 9}, 0),                    // 4: diffuse, touches 1 but is no lens
        box({1.5f, 0.5f, 0.5f}, {3, 3, 3}, 1),           // 5: overlaps 2
    };
    const std::vector<LensGroup> g = FindLensGroups(objs, mats);
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].objects, (std::vector<int>{0, 2, 3, 5}));
    EXPECT_EQ(g[0].bounds.hi, glm::vec3(3.0f));
    EXPECT_EQ(g[1].objects, std::vector<int>{1});
}

// Environment ------------------------------------------------------------------------------

TEST(Environment, LatLongTexelCentresAndSanity) {
    const Environment env =
        LoadEnvironment(kRoot + "/data/env/studio.exr", Environment::Mapping::LatLong, 2.0f);
    ASSERT_EQ(env.width, 512);
    ASSERT_EQ(env.height, 256);
    const double pi = std::numbers::pi;
    // The direction of texel (i, j)'s centre returns that texel exactly (times intensity).
    for (int j : {3, 64, 128, 200}) {
        for (int i : {0, 100, 255, 256, 511}) {
            const double lon = (0.5 - (i + 0.5) / 512.0) * 2.0 * pi,
                         lat = (0.5 - (j + 0.5) / 256.0) * pi;
            const glm::vec3 d(static_cast<float>(std::cos(lat) * std::sin(lon)),
                              static_cast<float>(std::sin(lat)),
                              static_cast<float>(std::cos(lat) * std::cos(lon)));
            const size_t at = 3 * static_cast<size_t>(j * 512 + i);
            const glm::vec3 texel(env.rgb[at], env.rgb[at + 1], env.rgb[at + 2]);
            const glm::vec3 got = EnvRadiance(env, d);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], 2.0f * texel[c], 1e-3f * (1.0f + texel[c])) << i << "," << j;
        }
    }
    // Finite and non-negative everywhere; continuous across the ±π seam.
    for (int k = 0; k < 1000; ++k) {
        const float a = 0.37f * static_cast<float>(k), b = 0.011f * static_cast<float>(k);
        const glm::vec3 r =
            EnvRadiance(env, {std::sin(a) * std::cos(b), std::sin(b), std::cos(a) * std::cos(b)});
        ASSERT_TRUE(std::isfinite(r.x + r.y + r.z));
        ASSERT_GE(std::min(r.x, std::min(r.y, r.z)), 0.0f);
    }
    const glm::vec3 left = EnvRadiance(env, {1e-4f, 0.1f, -1.0f}),
                    right = EnvRadiance(env, {-1e-4f, 0.1f, -1.0f});
    EXPECT_LT(glm::length(left - right), 0.05f * (1.0f + glm::length(left)));
}

// A 4x24 cube map with one constant colour per face: each axis direction reads its face.
TEST(Environment, CubeFacesFollowOpenExrLayout) {
    const int n = 4;
    std::vector<Imf::Rgba> px(static_cast<size_t>(n * 6 * n));
    for (int f = 0; f < 6; ++f)
        for (int k = 0; k < n * n; ++k)
            px[static_cast<size_t>(f * n * n + k)] = Imf::Rgba(float(f + 1), 0.0f, 0.5f, 1.0f);
    const std::string path = testing::TempDir() + "/pemref_cube_test.exr";
    {
        Imf::Header header(n, 6 * n);
        Imf::addEnvmap(header, Imf::ENVMAP_CUBE);
        Imf::RgbaOutputFile out(path.c_str(), header, Imf::WRITE_RGBA);
        out.setFrameBuffer(px.data(), 1, static_cast<size_t>(n));
        out.writePixels(6 * n);
    }
    const Environment env = LoadEnvironment(path, Environment::Mapping::Cube, 1.0f);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) EXPECT_FLOAT_EQ(EnvRadiance(env, axes[f]).x, float(f + 1)) << f;
    EXPECT_THROW(LoadEnvironment(kRoot + "/data/env/studio.exr", Environment::Mapping::Cube, 1.0f),
                 pem::base::InputError);
}

// Bad inputs -------------------------------------------------------------------------------

// Loads `path` as a scene (or an environment for .exr) and returns the base::InputError message, or
// "" when it loaded.
std::string LoadError(const std::string& path) {
    try {
        if (path.size() > 4 && path.substr(path.size() - 4) == ".exr")
            LoadEnvironment(path, Environment::Mapping::LatLong, 1.0f);
        else
            LoadScene(path);
    } catch (const pem::base::InputError& e) {
        return e.what();
    }
    return "";
}

void ExpectOneLineErrorNaming(const std::string& path, const std::string& message,
                              const std::string& cause) {
    ASSERT_FALSE(message.empty()) << path << " loaded without an error";
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(cause), std::string::npos) << message << " lacks \"" << cause << "\"";
}

TEST(SceneErrors, EveryCraftedBadInputGivesOneLineInputError) {
    const std::string dir = kRoot + "/tests/data/bad_scenes";
    std::ifstream tsv(dir + "/expected.tsv");
    std::map<std::string, std::string> expected;
    for (std::string line; std::getline(tsv, line);) {
        if (line.empty() || line[0] == '#') continue;
        const size_t tab = line.find('\t');
        expected[line.substr(0, tab)] = tab == std::string::npos ? "" : line.substr(tab + 1);
    }
    // Every data file in the folder is listed (nothing silently untested).
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name != "expected.tsv" && entry.path().extension() != ".py") {
            EXPECT_TRUE(expected.count(name)) << name;
        }
    }
    ASSERT_GE(expected.size(), 30u);
    for (const auto& [name, cause] : expected) {
        const std::string path = dir + "/" + name;
        ExpectOneLineErrorNaming(path, LoadError(path), cause);
    }
}

TEST(SceneErrors, MissingFileIsAnInputError) {
    const std::string path = kRoot + "/tests/data/bad_scenes/does_not_exist.gltf";
    ExpectOneLineErrorNaming(path, LoadError(path), "cannot open");
}

// Debian's assimp-testmodels (apt-get install assimp-testmodels): the broken glTF2 files must
// give an base::InputError; odd-but-loadable ones must load. Only files present are counted.
TEST(SceneErrors, AssimpTestModelsNeverCrash) {
    const std::string root = "/usr/share/assimp/models/glTF2/";
    ASSERT_TRUE(std::filesystem::is_directory(root))
        << "assimp-testmodels not installed (scripts/setup.sh installs it)";
    const std::vector<std::pair<std::string, std::string>> broken = {
        {"IndexOutOfRange/IndexOutOfRange.gltf", "out of range"},
        {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "out of range"},
        {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite"},
        {"MissingBin/BoxTextured.gltf", "not found"},
        {"RecursiveNodes/RecursiveNodes.gltf", "twice"},
        {"SchemaFailures/sceneWrongType.gltf", "parse error"},
        {"wrongTypes/badArray.gltf", "no triangles"},
        {"wrongTypes/badNumber.gltf", "parse error"},
        {"TestNoRootNode/NoScene.gltf", "no triangles"},
        {"TestNoRootNode/SceneWithoutNodes.gltf", "no triangles"},
        {"draco/2CylinderEngine.gltf", "KHR_draco_mesh_compression"},
        {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "KHR_technique_webgl"},
        {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
         "no triangles"},  // points
        {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf",
         "no triangles"},  // lines
    };
    // Loadable: tinygltf drops wrongly typed optional members (wrongTypes/bad{String,Uint,Object,
    // Extension}), strips/fans, textures, skins/morphs (bind pose).
    const std::vector<std::string> loadable = {
        "wrongTypes/badString.gltf",
        "wrongTypes/badUint.gltf",
        "wrongTypes/badObject.gltf",
        "wrongTypes/badExtension.gltf",
        "BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
        "IncorrectVertexArrays/Cube.gltf",
        "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
        "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf",
        "BoxTextured-glTF/BoxTextured.gltf",
        "simple_skin/simple_skin.gltf",
        "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"};
    int counted = 0;
    for (const auto& [file, cause] : broken) {
        if (!std::filesystem::exists(root + file)) continue;
        ExpectOneLineErrorNaming(root + file, LoadError(root + file), cause);
        ++counted;
    }
    for (const std::string& file : loadable) {
        if (!std::filesystem::exists(root + file)) continue;
        EXPECT_EQ(LoadError(root + file), "") << file;
        ++counted;
    }
    RecordProperty("assimp_files_checked", counted);
    EXPECT_GT(counted, 0);
    // Every other glTF2 file there must load or throw base::InputError, never anything else.
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
        const std::string ext = e.path().extension().string();
        if (ext == ".gltf" || ext == ".glb") {
            EXPECT_NO_THROW(LoadError(e.path().string())) << e.path();
        }
    }
}

// A textured box: the base colour texture is decoded to linear float and sampled by uv.
TEST(Scene, BaseColorTextureIsSampled) {
    const std::string path = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    ASSERT_TRUE(std::filesystem::exists(path))
        << "assimp-testmodels not installed (scripts/setup.sh installs it)";
    const Scene s = LoadScene(path);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_GT(s.textures[0].width, 0);
    const Object& o = s.objects[0];
    ASSERT_EQ(o.uvs.size(), o.positions.size());
    const SurfacePoint sp = SurfaceAt(o, 0, 0.25f, 0.25f);
    const glm::vec3 c = BaseColorAt(s, o, sp);
    EXPECT_TRUE(c.x >= 0.0f && c.x <= 1.0f && c.y >= 0.0f && c.z <= 1.0f);
    const Texture2D& t = s.textures[0];
    EXPECT_EQ(
        SampleTexture(t, {0.5f / static_cast<float>(t.width), 0.5f / static_cast<float>(t.height)}),
        glm::vec3(t.rgb[0], t.rgb[1], t.rgb[2]));
}

}  // namespace
}  // namespace pem::trace
