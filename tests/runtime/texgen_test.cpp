// SPDX-License-Identifier: MIT
// texgen_test.cpp — the renderer's shortcuts give the same bytes as the plain calls: LayerPass
// in two steps (shared geometry, per-layer fill into a reused pass), ShellCoords, DrawOrder,
// MakePassGeometry and FillLayerPass on threads (DrawOrder also against a plain filter), and
// raster::RenderFrames (passes at the same positions set up once, their attribute planes once
// per distinct vertices, lane groups shaded once for all frames, filter footprints shared by
// textures of one shape) against one Render per frame.
#include "runtime/texgen.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "raster/render.h"
#include "tests/case_generator.h"

namespace pem::runtime {
namespace {

// A bumpy grid in front of the camera with per-vertex exit rays.
struct Fixture {
    LensMesh mesh;
    std::vector<ExitRay> exits;
    raster::Camera camera;

    explicit Fixture(int n = 60) {
        for (int y = 0; y <= n; ++y)
            for (int x = 0; x <= n; ++x) {
                const float u = static_cast<float>(x) / n - 0.5f,
                            v = static_cast<float>(y) / n - 0.5f;
                mesh.positions.emplace_back(u, v, 0.1f * std::sin(9.0f * u) * std::cos(7.0f * v));
                mesh.normals.push_back(glm::normalize(glm::vec3(0.3f * u, 0.2f * v, 1.0f)));
                ExitRay e;
                e.origin = mesh.positions.back();
                e.dir = glm::normalize(glm::vec3(u, v, 1.0f - u * v));
                e.weight = glm::vec3(0.5f + u, 0.5f - v, 0.7f);
                e.valid = (x + 3 * y) % 17 != 0;
                exits.push_back(e);
            }
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const auto id = [n](int i, int j) {
                    return static_cast<uint32_t>(j * (n + 1) + i);
                };
                mesh.triangles.emplace_back(id(x, y), id(x + 1, y), id(x + 1, y + 1));
                mesh.triangles.emplace_back(id(x, y), id(x + 1, y + 1), id(x, y + 1));
            }
        camera.eye = {0.1f, -0.2f, 1.6f};
        camera.target = {0.0f, 0.0f, 0.0f};
        camera.width = 96;
        camera.height = 80;
    }
};

TEST(Texgen, ShellCoordsSameForAnyThreadCount) {
    const Fixture f;
    const trace::Shell shell = trace::SphereShell{{0.0, 0.0, 0.2}, 1.5};
    const std::vector<glm::vec3> one = ShellCoords(f.exits, shell, {0.0f, 0.0f, 0.1f});
    for (int threads : {2, 3})
        EXPECT_EQ(ShellCoords(f.exits, shell, {0.0f, 0.0f, 0.1f}, threads), one) << threads;
}

TEST(Texgen, DrawOrderIsTheFrontFacingTrianglesInMeshOrderForAnyThreadCount) {
    const Fixture f(130);  // 33800 triangles: filtered in parts
    auto tess = f.mesh;    // the left third turned away from the eye
    for (size_t v = 0; v < tess.normals.size(); ++v)
        if (tess.positions[v].x < -0.2f) tess.normals[v] = -tess.normals[v];
    const PassMesh mesh = MeshOf(tess);
    // Reference: the triangles with some vertex normal toward the eye, by increasing index.
    std::vector<uint32_t> reference;
    for (uint32_t i = 0; i < tess.triangles.size(); ++i) {
        const glm::uvec3 t = tess.triangles[i];
        bool front = false;
        for (int k = 0; k < 3; ++k)
            front |= glm::dot(tess.normals[t[k]], f.camera.eye - tess.positions[t[k]]) > 0.0f;
        if (front) reference.push_back(i);
    }
    ASSERT_LT(reference.size(), tess.triangles.size() * 3 / 4);  // culled ones are left out
    ASSERT_GT(reference.size(), 16384u);
    for (int threads : {1, 2, 3}) {
        EXPECT_EQ(DrawOrder(mesh, f.camera, threads), reference) << threads;
        const glm::mat4 vp = PassViewProjection(mesh, f.camera);
        const PassGeometry one = MakePassGeometry(mesh, reference, vp);
        const PassGeometry many = MakePassGeometry(mesh, reference, vp, threads);
        EXPECT_EQ(many.clip, one.clip) << threads;
        EXPECT_EQ(many.indices, one.indices) << threads;
        std::vector<glm::vec3> coords(f.exits.size());
        for (size_t v = 0; v < coords.size(); ++v) coords[v] = f.exits[v].dir;
        PassOptions po;
        po.modulate = true;
        raster::Pass a, b;
        FillLayerPass(one, coords, f.exits, po, {&a, 1});
        FillLayerPass(one, coords, f.exits, po, {&b, 1}, threads);
        EXPECT_EQ(b, a) << threads;
    }
}

TEST(Texgen, FillLayerPassEqualsLayerPass) {
    const Fixture f;
    const PassMesh mesh = MeshOf(f.mesh);
    const std::vector<uint32_t> order = DrawOrder(mesh, f.camera);
    const glm::mat4 vp = PassViewProjection(mesh, f.camera);
    const trace::Shell shell = trace::SphereShell{{0.0, 0.0, 0.0}, 2.0};
    const std::vector<glm::vec3> coords = ShellCoords(f.exits, shell, {0.0f, 0.0f, 0.0f});
    const PassGeometry geometry = MakePassGeometry(mesh, order, vp);
    raster::Pass reused;
    for (bool modulate : {true, false}) {
        PassOptions po;
        po.texture = modulate ? 1 : 0;
        po.modulate = modulate;
        po.blend = modulate ? raster::BlendState::Over() : raster::BlendState::None();
        FillLayerPass(geometry, coords, f.exits, po, {&reused, 1});
        EXPECT_EQ(std::vector{reused}, LayerPass(mesh, order, coords, f.exits, vp, po)) << modulate;
    }
}

// Frames sharing pass geometry but not textures or blending, drawn together or one by one.
TEST(Texgen, RenderFramesEqualsRenderPerFrame) {
    const raster::Frame a = test::BenchmarkFrame(120, 90, 20, 40, 32);
    raster::Frame b = a;
    for (raster::Texture& t : b.textures)
        for (auto& level : t.levels)
            for (size_t i = 0; i < level.size(); ++i)
                level[i] = static_cast<uint8_t>(255 - level[i]);
    if (b.passes.size() > 1) b.passes[1].blend = raster::BlendState::Additive();
    raster::Frame c = a;  // different geometry: drawn on its own
    for (raster::Vertex& v : c.passes[0].vertices) v.pos.x *= 0.9f;
    // Same geometry, textures of another sampler state: no shared filter footprints.
    raster::Frame d = b, e = b;
    for (raster::Texture& t : d.textures) t.sampler.lodBias = 0.7f;
    for (raster::Texture& t : e.textures) t.sampler.mipFilter = raster::MipFilter::Nearest;
    // Same positions, other texture coordinates and colours (another term's pass): coverage
    // shared, attributes not; g and h are one such variant drawn into two frames.
    raster::Frame g = a;
    for (raster::Pass& pass : g.passes)
        for (raster::Vertex& v : pass.vertices) {
            v.coord[0] = glm::vec3(v.coord[0].y, -v.coord[0].z, 1.3f * v.coord[0].x);
            v.color *= 0.6f;
        }
    raster::Frame h = g;
    for (raster::Texture& t : h.textures) t.sampler.lodBias = -0.4f;
    const raster::PreparedFrame pa(a), pb(b), pc(c), pd(d), pe(e), pg(g), ph(h);
    for (int threads : {1, 3}) {
        raster::RenderOptions opt;
        opt.threads = threads;
        const std::vector<const raster::PreparedFrame*> frames{&pa, &pb, &pc, &pg, &pd, &pe, &ph};
        const std::vector<raster::RenderResult> all = raster::RenderFrames(frames, opt);
        ASSERT_EQ(all.size(), frames.size());
        for (size_t f = 0; f < frames.size(); ++f)
            EXPECT_EQ(all[f].image8, raster::Render(*frames[f], opt).image8) << threads << f;
        EXPECT_NE(all[0].image8, all[1].image8);
        EXPECT_NE(all[1].image8, all[4].image8);
        EXPECT_NE(all[1].image8, all[5].image8);
        EXPECT_NE(all[0].image8, all[3].image8);
        EXPECT_NE(all[3].image8, all[6].image8);
    }
}

}  // namespace
}  // namespace pem::runtime
