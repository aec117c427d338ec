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

// The chart's image in atlas coordinates: [x0, x1] × [y0, y1].
glm::dvec4 ChartBox(Parameterization p, int chart) {
    if (p == Parameterization::Paraboloid) return {chart * 0.5, chart * 0.5 + 0.5, 0.0, 1.0};
    if (p == Parameterization::Tennis) return {0.0, 1.0, chart * 0.5, chart * 0.5 + 0.5};
    return {0.0, 1.0, 0.0, 1.0};
}

TEST(Parameterization, NamesRoundTrip) {
    for (Parameterization p : kParameterizations)
        EXPECT_EQ(ParseParameterization(ParameterizationName(p)), p);
    EXPECT_FALSE(ParseParameterization("cubes").has_value());
}

TEST(Parameterization, LayoutsAndTheirTexels) {
    EXPECT_EQ(LayoutOf(Parameterization::Cube, 32).Texels(), 6 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::LatLong, 32).Texels(), 2 * 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Sphere, 32).Texels(), 32 * 32);
    EXPECT_EQ(LayoutOf(Parameterization::Paraboloid, 32).charts, 2);
    EXPECT_EQ(LayoutOf(Parameterization::LatLong, 32).wrapS, raster::Wrap::Repeat);
    EXPECT_THROW(LayoutOf(Parameterization::Tennis, 24), std::invalid_argument);
    const raster::Texture t = EmptyTexture(LayoutOf(Parameterization::Tennis, 8), {});
    ASSERT_EQ(t.NumLevels(), 5);  // 16x8 ... 1x1
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
            const glm::dvec4 box = ChartBox(p, chart);
            ASSERT_GE(st.x, box.x) << ParameterizationName(p);
            ASSERT_LE(st.x, box.y) << ParameterizationName(p);
            ASSERT_GE(st.y, box.z) << ParameterizationName(p);
            ASSERT_LE(st.y, box.w) << ParameterizationName(p);
            ASSERT_EQ(ChartAt(p, glm::dvec2(st)), chart) << ParameterizationName(p);
            const glm::dvec3 back = LayoutDirection(p, glm::dvec2(st));
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

// ToLayout: one chart per triangle, three corners each, lat-long's seam interpolated across.
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
    const raster::Pass ll = ToLayout(cube, 0, Parameterization::LatLong, identity);
    ASSERT_EQ(ll.vertices.size(), 6u);
    EXPECT_TRUE(ll.indices.empty());
    EXPECT_LT(ll.vertices[0].coord[0].x, 0.05f);  // s near 0 and near 1 in one triangle
    EXPECT_GT(ll.vertices[1].coord[0].x, 0.95f);
    const raster::Pass pb = ToLayout(cube, 0, Parameterization::Paraboloid, identity);
    for (int k = 0; k < 3; ++k) EXPECT_LE(pb.vertices[k].coord[0].x, 0.5f);  // left image
    for (int k = 3; k < 6; ++k) EXPECT_GE(pb.vertices[k].coord[0].x, 0.5f);  // right image
    EXPECT_EQ(ToLayout(cube, 0, Parameterization::Cube, identity), cube);
}

}  // namespace
}  // namespace pem::runtime
