// SPDX-License-Identifier: MIT
// static_em_test.cpp — the direct images of a lens group's layers (runtime/static_em.h
// TraceDirectImages) against the static map's tracer and the scene's geometry.
#include "runtime/static_em.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raster/cube_lookup.h"
#include "trace/embree_scene.h"
#include "trace/layers.h"
#include "trace/scene.h"

namespace pem::runtime {
namespace {

// Scene (a)'s mirror cup, standing on the floor: layer 0 the floor, layer 1 everything else.
struct Cup {
    trace::Scene scene =
        trace::LoadScene(std::string(PEM_SOURCE_DIR) + "/data/scenes/hybrid_glass_teapot.gltf");
    trace::EmbreeDevice device{trace::EmbreeOptions{2, "auto"}};
    trace::EmbreeScene embree{device, scene};
    trace::Tracer tracer{scene, embree, trace::TraceOptions{}};
    LensGroupEm group;

    Cup() {
        for (size_t g = 0; g < scene.lensGroups.size(); ++g)
            for (int o : scene.lensGroups[g].objects)
                if (scene.objects[static_cast<size_t>(o)].name == "mirror_cup")
                    group.index = static_cast<int>(g);
        group.emOrigin = trace::GroupEmOrigin(scene, group.index);
        EmLayer floor, rest;
        floor.radius = 1.0, floor.records = 1;
        rest.radius = 20.0, rest.records = 1;
        for (const trace::Object& o : scene.objects)  // the floor: two primitives, floor#0 and #1
            if (o.name.rfind("floor", 0) == 0)
                floor.objects.push_back(o.name);
            else if (o.name != "mirror_cup")
                rest.objects.push_back(o.name);
        group.layers = {floor, rest};
    }
};

// The world direction of texel (face, i, j) of a face-size-n cube's level 0.
glm::vec3 Direction(int face, int i, int j, int n) {
    const raster::Vec3f d =
        raster::FaceDirection(face, 2.0f * (i + 0.5f) / n - 1.0f, 2.0f * (j + 0.5f) / n - 1.0f);
    return glm::normalize(glm::vec3(d[0], d[1], d[2]));
}

TEST(DirectImages, LayersAgreeWithTheStaticMapAndTheFloor) {
    Cup cup;
    const int n = 8;
    const DirectImages d = TraceDirectImages(cup.tracer, cup.group, n, 2);
    ASSERT_EQ(d.levels.size(), 3u);  // two layers and the whole environment
    // The whole environment: the static map's floats (its 8-bit texels, rounded the same way).
    const raster::Texture st =
        TraceStaticMap(cup.tracer, cup.group.index, cup.group.emOrigin, n, 2);
    for (size_t k = 0; k < st.levels[0].size(); ++k)
        EXPECT_EQ(st.levels[0][k], static_cast<uint8_t>(std::nearbyint(
                                       std::clamp(d.levels[2][0][k], 0.0f, 1.0f) * 255.0f)))
            << "byte " << k;
    int down = 0, up = 0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const size_t at = ((static_cast<size_t>(f) * n + j) * n + i) * 4;
                const float* floor = &d.levels[0][0][at];
                const float* rest = &d.levels[1][0][at];
                const float* all = &d.levels[2][0][at];
                EXPECT_TRUE(floor[3] == 0.0f || floor[3] == 1.0f);
                EXPECT_EQ(rest[3], 1.0f);  // the outermost layer: a hit or the environment
                const float y = Direction(f, i, j, n).y;
                if (y < -0.2f) {  // down from the cup's centre: the floor, the nearest hit
                    ++down;
                    EXPECT_EQ(floor[3], 1.0f) << f << " " << i << " " << j;
                    for (int c = 0; c < 3; ++c) EXPECT_EQ(floor[c], all[c]);
                } else if (y > 0.2f) {  // up: never the floor
                    ++up;
                    EXPECT_EQ(floor[3], 0.0f);
                    for (int c = 0; c < 3; ++c) EXPECT_EQ(floor[c], 0.0f);
                }
            }
    EXPECT_GT(down, 50);
    EXPECT_GT(up, 50);
    // Level 1: the means of 2×2 texels of level 0.
    const float mean = 0.25f * (d.levels[1][0][0] + d.levels[1][0][4] + d.levels[1][0][4 * n] +
                                d.levels[1][0][4 * n + 4]);
    EXPECT_FLOAT_EQ(d.levels[1][1][0], mean);
}

}  // namespace
}  // namespace pem::runtime
