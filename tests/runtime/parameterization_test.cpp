// SPDX-License-Identifier: MIT
// parameterization_test.cpp — the five layouts against the notes' own inverse formulas (seed
// 001): every direction lands inside the image of its chart, and the coordinates map back to it.
#include "runtime/parameterization.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "tests/case_generator.h"
#include "tests/runtime/layout_directions.h"

namespace pem::runtime {
namespace {

TEST(Parameterization, NamesRoundTrip) {
    for (Parameterization p : kParameterizations)
        EXPECT_EQ(ParseParameterization(ParameterizationName(p)), p);
    EXPECT_FALSE(ParseParameterization("cubes").has_value());
}

TEST(Parameterization, LayoutsAndTheirTexels) {
    EXPECT_EQ(LayoutOf(Parameterization::Cube, 32).Texels(), 6 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::LatLong, 32).Texels(), 2 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Sphere, 32).Texels(), 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Paraboloid, 32).Texels(), 2 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Tennis, 32).Texels(), 2 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Paraboloid, 32).textures, 2);  // two textures
    EXPECT_EQ(LayoutOf(Parameterization::Paraboloid, 32).width, 32);
    EXPECT_EQ(LayoutOf(Parameterization::LatLong, 32).textures, 1);
    EXPECT_EQ(LayoutOf(Parameterization::LatLong, 32).wrapS, raster::Wrap::Repeat);
    EXPECT_THROW(LayoutOf(Parameterization::Tennis, 24), std::invalid_argument);
    const raster::Texture t = EmptyTexture(LayoutOf(Parameterization::Tennis, 8), {});
    ASSERT_EQ(t.width, 16);  // one band: 16x4 ... 1x1, its own MIP chain
    ASSERT_EQ(t.height, 4);
    ASSERT_EQ(t.NumLevels(), 5);
    EXPECT_EQ(t.levels.back().size(), 4u);
}

// Every direction: inside its chart's image (no clamping needed, the tennis bands with margin
// >= 0) and mapped back to itself by the inverse formulas.
TEST(Parameterization, DirectionsRoundTripThroughTheirChart) {
    test::Rng rng{42};
    const glm::mat3 identity(1.0f);
    for (Parameterization p : kParameterizations) {
        if (p == Parameterization::Cube) continue;
        double worst = 0.0;
        for (int k = 0; k < 20000; ++k) {
            glm::vec3 d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
            if (glm::length(d) < 0.1f || glm::length(d) > 1.0f) continue;
            d = glm::normalize(d);
            if (p == Parameterization::Sphere && d.z < -0.999f) continue;  // the rim's pole
            const int chart = ChartOf(p, d * 3.0f);                        // any length
            const glm::vec2 st = ChartCoord(p, d * 3.0f, chart, identity);
            ASSERT_GE(st.x, 0.0f) << ParameterizationName(p);
            ASSERT_LE(st.x, 1.0f) << ParameterizationName(p);
            ASSERT_GE(st.y, 0.0f) << ParameterizationName(p);
            ASSERT_LE(st.y, 1.0f) << ParameterizationName(p);
            const glm::dvec3 back = LayoutDirection(p, chart, glm::dvec2(st));
            worst = std::max(worst, glm::length(back - glm::dvec3(d)));
        }
        EXPECT_LT(worst, 2e-3) << ParameterizationName(p);  // float coordinates near the rim
    }
}

// The sphere map is GL_SPHERE_MAP: coordinates of the eye-space reflection of the view ray.
TEST(Parameterization, SphereMapUsesEyeSpace) {
    const glm::mat3 eyeFromWorld(glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0)));
    const glm::mat3 turned(glm::lookAt(glm::vec3(5, 0, 0), glm::vec3(0), glm::vec3(0, 1, 0)));
    // Toward the eye (a mirror seen head-on reflects the camera): the centre of the map.
    const glm::vec2 c = ChartCoord(Parameterization::Sphere, {0, 0, 1}, 0, eyeFromWorld);
    EXPECT_FLOAT_EQ(c.x, 0.5f);
    EXPECT_FLOAT_EQ(c.y, 0.5f);
    const glm::vec2 t = ChartCoord(Parameterization::Sphere, {0, 0, 1}, 0, turned);
    EXPECT_GT(std::abs(t.x - 0.5f), 0.3f);  // the same world direction, seen from the side
}

// ToLayout: one chart per triangle, three corners each, lat-long's seam interpolated across; a
// two-image layout's triangles in the pass of their chart's texture.
TEST(Parameterization, ToLayoutGivesEachTriangleOneChart) {
    raster::Pass cube;
    auto vertex = [](glm::vec3 d) {
        raster::Vertex v;
        v.coord[0] = d;
        return v;
    };
    // Triangle 0 straddles the lat-long seam behind the origin (+Z); triangle 1 faces -Z.
    cube.vertices = {vertex({-0.1f, 0, 1}),  vertex({0.1f, 0, 1}),  vertex({0, 0.1f, 1}),
                     vertex({-0.1f, 0, -1}), vertex({0.1f, 0, -1}), vertex({0, 0.1f, -1})};
    const glm::mat3 identity(1.0f);
    cube.texture = {3, 0};
    const std::vector<raster::Pass> lls = ToLayout(cube, 0, Parameterization::LatLong, identity);
    ASSERT_EQ(lls.size(), 1u);
    const raster::Pass& ll = lls[0];
    ASSERT_EQ(ll.vertices.size(), 6u);
    EXPECT_TRUE(ll.indices.empty());
    EXPECT_LT(ll.vertices[0].coord[0].x, 0.05f);  // s near 0 and near 1 in one triangle
    EXPECT_GT(ll.vertices[1].coord[0].x, 0.95f);
    const std::vector<raster::Pass> pb = ToLayout(cube, 0, Parameterization::Paraboloid, identity);
    ASSERT_EQ(pb.size(), 2u);
    ASSERT_EQ(pb[0].vertices.size(), 3u);  // z >= 0: the front image
    ASSERT_EQ(pb[1].vertices.size(), 3u);  // z < 0: the back image
    EXPECT_EQ(pb[0].texture[0], 3);
    EXPECT_EQ(pb[1].texture[0], 4);
    EXPECT_EQ(pb[0].vertices[0].pos, cube.vertices[0].pos);
    EXPECT_EQ(pb[1].vertices[0].pos, cube.vertices[3].pos);
    EXPECT_EQ(ToLayout(cube, 0, Parameterization::Cube, identity), std::vector{cube});
}

}  // namespace
}  // namespace pem::runtime
