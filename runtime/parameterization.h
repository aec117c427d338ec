// SPDX-License-Identifier: MIT
// parameterization.h — the five environment-map parameterizations of the notes (seed 001): cube,
// lat-long, sphere map, dual paraboloid and tennis ball, as the texture layouts the hardware
// samples and the per-vertex texture coordinates (texgen) that address them.
//
//   const MapLayout layout = LayoutOf(Parameterization::LatLong, 64);  // one 128 x 64 2D texture
//   raster::Pass pass = ...;                     // unit 0 holds cube coordinates (directions)
//   std::vector<raster::Pass> flat = ToLayout(pass, 0, Parameterization::LatLong, eyeFromWorld);
//
// Layouts (size = the layout's size parameter, a power of two; level-0 texels in brackets):
//  - cube:       a cube map of size² faces, the hardware's own face selection      [6 size²]
//  - latlong:    2size × size, s = 1/2 + atan2(x, -z) / 2π (Repeat), t = acos(y) / π [2 size²]
//  - sphere:     size × size, GL_SPHERE_MAP's formula on the eye-space direction r:
//                m = 2 sqrt(rx² + ry² + (rz + 1)²), (s, t) = (rx / m, ry / m) + 1/2   [size²]
//  - paraboloid: two size × size textures: chart 0 z >= 0, (s, t) = (x, y) / (1 + z) / 2 + 1/2;
//                chart 1 z < 0, (x, y) / (1 - z) / 2 + 1/2                          [2 size²]
//  - tennis:     two 2size × size/2 textures (bands): band 0 (θ, φ) = (asin y, atan2(x, -z)),
//                band 1 (asin x, atan2(y, z)), each |θ| <= π/4, |φ| <= 3π/4 at (s, t) =
//                (φ / 1.5π + 1/2, θ / 0.5π + 1/2) (a tennis ball's two interlocking halves)
//                                                                                  [2 size²]
// Two-image layouts (paraboloid, tennis) are the era's two textures, each with its own MIP
// chain and clamped edges: a map is MapLayout::textures consecutive textures (Frame::textures
// k and k + 1), and a pass drawing it is one pass per texture (ToLayout), each triangle in the
// pass of the chart holding the sum of its corner directions farthest from its border, with
// that chart's coordinates at all three corners, clamped to the chart. Lat-long and the sphere
// map interpolate per-vertex coordinates as GL does: a triangle across the lat-long seam (s
// from 1 to 0) or around a pole interpolates across the whole map, the defects the notes warn
// about.
// Directions need not be unit (shell coordinates); a zero direction maps to chart 0's centre.
// atan2, asin and acos are evaluated in double and rounded to float: a last-bit difference of
// the double (glibc's variants per ISA) changes the float only within 2^-29 of a rounding tie.
// Not here: the passes' cube coordinates (texgen.h), inference of the maps (infer/).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "raster/camera.h"
#include "raster/frame.h"

namespace pem::runtime {

enum class Parameterization { Cube, LatLong, Sphere, Paraboloid, Tennis };

inline constexpr std::array<Parameterization, 5> kParameterizations = {
    Parameterization::Cube, Parameterization::LatLong, Parameterization::Sphere,
    Parameterization::Paraboloid, Parameterization::Tennis};

// "cube", "latlong", "sphere", "paraboloid", "tennis".
std::string_view ParameterizationName(Parameterization p);
std::optional<Parameterization> ParseParameterization(std::string_view name);

// The texture one map occupies.
struct MapLayout {
    Parameterization parameterization = Parameterization::Cube;
    raster::TextureKind kind = raster::TextureKind::Cube;
    int width = 1, height = 1;  // level 0 (a cube's face size)
    raster::Wrap wrapS = raster::Wrap::ClampToEdge, wrapT = raster::Wrap::ClampToEdge;
    int charts = 1;          // images drawn from: 6 faces, 1 or 2
    int textures = 1;        // textures of one map: 2 for the two-image layouts, else 1
    int64_t Texels() const;  // level 0, every face of every texture
};

// size: a power of two >= 2 (the tennis bands are size / 2 tall).
MapLayout LayoutOf(Parameterization p, int size);

// The textures of one map of the layout at any size (LayoutOf(p, size).textures): 1 or 2.
int MapTextures(Parameterization p);

// `sampler`'s filters with the layout's wrap modes.
raster::SamplerState LayoutSampler(const MapLayout& layout, const raster::SamplerState& sampler);

// An empty texture of the layout (every level zero) with `sampler`'s filters and the layout's
// wrap modes: one of the map's `textures` (they have the same shape).
raster::Texture EmptyTexture(const MapLayout& layout, const raster::SamplerState& sampler);

// The rotation from world to `camera`'s eye space: the sphere map's eyeFromWorld for a pass
// drawn from that camera.
glm::mat3 EyeFromWorld(const raster::Camera& camera);

// Step: the chart of a direction (0 for cube, latlong and sphere).
int ChartOf(Parameterization p, const glm::vec3& dir);

// Step: the texture coordinates (s, t) of a direction on one chart (in that chart's texture).
// eyeFromWorld turns world directions into eye space (the sphere map's only).
glm::vec2 ChartCoord(Parameterization p, const glm::vec3& dir, int chart,
                     const glm::mat3& eyeFromWorld);

// The inverse of ChartCoord for a 2D layout: the unit direction position (s, t) of a chart's
// texture shows (the sphere map's in eye space; outside the sphere map's and the paraboloid's
// discs the formulas continue past the rim: directions the charts never use). Double
// precision, for building maps (static_em.h) and checks; throws std::invalid_argument for the
// cube.
glm::dvec3 LayoutDirection(Parameterization p, int chart, const glm::dvec2& st);

// A pass whose unit `unit` holds cube coordinates, drawn with the layout instead: the cube
// returns the pass unchanged; a 2D layout gives one pass per texture of the map (pass c binds
// texture cubePass.texture[unit] + c on `unit`) holding the triangles of chart c, each with its
// own three corners (triangle order kept, indices dropped) with (s, t, 0) on unit `unit`.
std::vector<raster::Pass> ToLayout(const raster::Pass& cubePass, int unit, Parameterization p,
                                   const glm::mat3& eyeFromWorld);

}  // namespace pem::runtime
