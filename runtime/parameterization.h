// SPDX-License-Identifier: MIT
// parameterization.h — the five environment-map parameterizations of the notes (seed 001): cube,
// lat-long, sphere map, dual paraboloid and tennis ball, as the texture layouts the hardware
// samples and the per-vertex texture coordinates (texgen) that address them.
//
//   const MapLayout layout = LayoutOf(Parameterization::LatLong, 64);  // one 128 x 64 2D texture
//   raster::Pass pass = ...;                     // unit 0 holds cube coordinates (directions)
//   raster::Pass flat = ToLayout(pass, 0, Parameterization::LatLong, eyeFromWorld);
//
// Layouts (size = the layout's size parameter, a power of two; level-0 texels in brackets):
//  - cube:       a cube map of size² faces, the hardware's own face selection      [6 size²]
//  - latlong:    2size × size, s = 1/2 + atan2(x, -z) / 2π (Repeat), t = acos(y) / π [2 size²]
//  - sphere:     size × size, GL_SPHERE_MAP's formula on the eye-space direction r:
//                m = 2 sqrt(rx² + ry² + (rz + 1)²), (s, t) = (rx / m, ry / m) + 1/2   [size²]
//  - paraboloid: 2size × size, two size² images side by side: z >= 0 (x, y) / (1 + z) on the
//                left, z < 0 (x, y) / (1 - z) on the right, each [-1, 1]² to its half  [2 size²]
//  - tennis:     2size × size, two 2size × size/2 bands stacked: band 0 (θ, φ) = (asin y,
//                atan2(x, -z)), band 1 (asin x, atan2(y, z)), each |θ| <= π/4, |φ| <= 3π/4
//                (the two interlocking halves of a tennis ball's seam)                [2 size²]
// Charts: a layout with two images (paraboloid, tennis) draws each triangle from one of them —
// the one holding the sum of its corner directions farthest from its border — with that
// image's coordinates at all three corners, clamped to the image (the era's two-texture draw:
// each triangle bound to one map). Lat-long and the sphere map interpolate per-vertex
// coordinates as GL does: a triangle across the lat-long seam (s from 1 to 0) or around a pole
// interpolates across the whole map, the defects the notes warn about. The two images share one
// 2D texture (pemref's maps are one texture each), so bilinear filtering and the coarse MIP
// levels mix them along their common edge — the atlas's cost, which inference accounts for.
// Directions need not be unit (shell coordinates); a zero direction maps to chart 0's centre.
// atan2, asin and acos are evaluated in double and rounded to float: a last-bit difference of
// the double (glibc's variants per ISA) changes the float only within 2^-29 of a rounding tie.
// Not here: the passes' cube coordinates (texgen.h), inference of the maps (infer/).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>

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
    int64_t Texels() const;  // level 0, every face
};

// size: a power of two >= 2 (the tennis bands are size / 2 tall).
MapLayout LayoutOf(Parameterization p, int size);

// `sampler`'s filters with the layout's wrap modes.
raster::SamplerState LayoutSampler(const MapLayout& layout, const raster::SamplerState& sampler);

// An empty texture of the layout (every level zero) with `sampler`'s filters and the layout's
// wrap modes.
raster::Texture EmptyTexture(const MapLayout& layout, const raster::SamplerState& sampler);

// The rotation from world to `camera`'s eye space: the sphere map's eyeFromWorld for a pass
// drawn from that camera.
glm::mat3 EyeFromWorld(const raster::Camera& camera);

// Step: the chart of a direction (0 for cube, latlong and sphere).
int ChartOf(Parameterization p, const glm::vec3& dir);

// Step: the texture coordinates (s, t) of a direction on one chart, atlas position included.
// eyeFromWorld turns world directions into eye space (the sphere map's only).
glm::vec2 ChartCoord(Parameterization p, const glm::vec3& dir, int chart,
                     const glm::mat3& eyeFromWorld);

// The inverse of ChartCoord for a 2D layout: the chart an atlas position (s, t) lies in, and the
// unit direction it shows (the sphere map's in eye space; outside the sphere map's and the
// paraboloid's discs the formulas continue past the rim: directions the charts never use).
// Double precision, for building maps (static_em.h) and checks; throws std::invalid_argument
// for the cube.
int ChartAt(Parameterization p, const glm::dvec2& st);
glm::dvec3 LayoutDirection(Parameterization p, const glm::dvec2& st);

// A pass whose unit `unit` holds cube coordinates, drawn with the layout instead: the cube
// returns the pass unchanged; a 2D layout gives each triangle its own three corners (triangle
// order kept, indices dropped) with (s, t, 0) on unit `unit`.
raster::Pass ToLayout(const raster::Pass& cubePass, int unit, Parameterization p,
                      const glm::mat3& eyeFromWorld);

}  // namespace pem::runtime
