// SPDX-License-Identifier: MIT
// parameterization.cpp — texture layouts and texgen of the five parameterizations
// (parameterization.h).
#include "runtime/parameterization.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pem::runtime {
namespace {

constexpr double kPi = std::numbers::pi;

struct Named {
    Parameterization p;
    std::string_view name;
};
constexpr std::array<Named, 5> kNames = {{{Parameterization::Cube, "cube"},
                                          {Parameterization::LatLong, "latlong"},
                                          {Parameterization::Sphere, "sphere"},
                                          {Parameterization::Paraboloid, "paraboloid"},
                                          {Parameterization::Tennis, "tennis"}}};

double Clamp01(double v) {
    return std::clamp(v, 0.0, 1.0);
}

// A tennis band's angles (θ, φ) for band 0 or 1, in double.
glm::dvec2 TennisAngles(const glm::dvec3& d, int band) {
    if (band == 0) return {std::asin(std::clamp(d.y, -1.0, 1.0)), std::atan2(d.x, -d.z)};
    return {std::asin(std::clamp(d.x, -1.0, 1.0)), std::atan2(d.y, d.z)};
}

// How far (in radians) a direction lies inside a tennis band: min(π/4 - |θ|, 3π/4 - |φ|).
double TennisMargin(const glm::dvec3& d, int band) {
    const glm::dvec2 a = TennisAngles(d, band);
    return std::min(kPi / 4.0 - std::abs(a.x), 3.0 * kPi / 4.0 - std::abs(a.y));
}

// Step: the unit direction in double (zero stays zero).
glm::dvec3 UnitDouble(const glm::vec3& dir) {
    const glm::dvec3 d(dir);
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    return len > 0.0 ? d / len : glm::dvec3(0.0);
}

glm::dvec2 LatLongCoord(const glm::dvec3& d) {
    if (d == glm::dvec3(0.0)) return {0.5, 0.5};
    return {0.5 + std::atan2(d.x, -d.z) / (2.0 * kPi), std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi};
}

// GL_SPHERE_MAP (GL 4.6 compatibility §12.1.3) on the eye-space direction.
glm::dvec2 SphereCoord(const glm::dvec3& r) {
    const double m = 2.0 * std::sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
    if (!(m > 0.0)) return {0.5, 0.5};
    return {r.x / m + 0.5, r.y / m + 0.5};
}

glm::dvec2 ParaboloidCoord(const glm::dvec3& d, int chart) {
    const double den = chart == 0 ? 1.0 + d.z : 1.0 - d.z;
    if (!(den > 0.0)) return {chart == 0 ? 0.5 : 1.0, 0.5};
    const double s = Clamp01(0.5 * d.x / den + 0.5), t = Clamp01(0.5 * d.y / den + 0.5);
    return {s, t};
}

glm::dvec2 TennisCoord(const glm::dvec3& d, int band) {
    if (d == glm::dvec3(0.0)) return {0.5, 0.5};
    const glm::dvec2 a = TennisAngles(d, band);
    return {Clamp01(a.y / (1.5 * kPi) + 0.5), Clamp01(a.x / (0.5 * kPi) + 0.5)};
}

}  // namespace

std::string_view ParameterizationName(Parameterization p) {
    for (const Named& n : kNames)
        if (n.p == p) return n.name;
    return "cube";
}

std::optional<Parameterization> ParseParameterization(std::string_view name) {
    for (const Named& n : kNames)
        if (n.name == name) return n.p;
    return std::nullopt;
}

int64_t MapLayout::Texels() const {
    return static_cast<int64_t>(width) * height * (kind == raster::TextureKind::Cube ? 6 : 1) *
           textures;
}

MapLayout LayoutOf(Parameterization p, int size) {
    if (size < 2 || (size & (size - 1)) != 0)
        throw std::invalid_argument("map size " + std::to_string(size) +
                                    ": expected a power of two >= 2");
    MapLayout l;
    l.parameterization = p;
    l.kind = p == Parameterization::Cube ? raster::TextureKind::Cube : raster::TextureKind::Tex2D;
    const bool twoImages = MapTextures(p) == 2;
    l.width = p == Parameterization::LatLong || p == Parameterization::Tennis ? 2 * size : size;
    l.height = p == Parameterization::Tennis ? size / 2 : size;
    if (p == Parameterization::LatLong) l.wrapS = raster::Wrap::Repeat;
    l.charts = p == Parameterization::Cube ? 6 : twoImages ? 2 : 1;
    l.textures = MapTextures(p);
    return l;
}

int MapTextures(Parameterization p) {
    return p == Parameterization::Paraboloid || p == Parameterization::Tennis ? 2 : 1;
}

raster::SamplerState LayoutSampler(const MapLayout& layout, const raster::SamplerState& sampler) {
    raster::SamplerState s = sampler;
    s.wrapS = layout.wrapS, s.wrapT = layout.wrapT;
    return s;
}

raster::Texture EmptyTexture(const MapLayout& layout, const raster::SamplerState& sampler) {
    raster::Texture t;
    t.kind = layout.kind;
    t.width = layout.width, t.height = layout.height;
    t.sampler = LayoutSampler(layout, sampler);
    for (int l = 0; l == 0 || t.LevelWidth(l - 1) > 1 || t.LevelHeight(l - 1) > 1; ++l)
        t.levels.emplace_back(
            static_cast<size_t>(t.Faces()) * t.LevelWidth(l) * t.LevelHeight(l) * 4, 0);
    return t;
}

glm::dvec3 LayoutDirection(Parameterization p, int chart, const glm::dvec2& st) {
    switch (p) {
        case Parameterization::LatLong: {
            const double phi = (st.x - 0.5) * 2.0 * kPi, theta = st.y * kPi;  // from +Y
            return {std::sin(theta) * std::sin(phi), std::cos(theta),
                    -std::sin(theta) * std::cos(phi)};
        }
        case Parameterization::Sphere: {
            // The gazing ball's normal n = (u, v, nz) reflects the view ray (0, 0, -1) into r.
            const double u = 2.0 * st.x - 1.0, v = 2.0 * st.y - 1.0;
            const glm::dvec3 n(u, v, std::sqrt(std::max(0.0, 1.0 - u * u - v * v)));
            const glm::dvec3 in(0.0, 0.0, -1.0);
            return glm::normalize(in - 2.0 * glm::dot(n, in) * n);
        }
        case Parameterization::Paraboloid: {
            // (u, v) = (x, y) / (1 ± z) solved for a unit direction: |z| = (1 - q) / (1 + q).
            const double u = 2.0 * st.x - 1.0, v = 2.0 * st.y - 1.0;
            const double q = u * u + v * v, a = (1.0 - q) / (1.0 + q);
            return {u * (1.0 + a), v * (1.0 + a), chart == 0 ? a : -a};
        }
        case Parameterization::Tennis: {
            const double phi = (st.x - 0.5) * 1.5 * kPi;
            const double theta = (st.y - 0.5) * 0.5 * kPi;
            // Band 0: y = sin θ, (x, -z) at angle φ; band 1: x = sin θ, (y, z) at angle φ.
            const double c = std::cos(theta);
            if (chart == 0) return {c * std::sin(phi), std::sin(theta), -c * std::cos(phi)};
            return {std::sin(theta), c * std::sin(phi), c * std::cos(phi)};
        }
        case Parameterization::Cube:
            break;
    }
    throw std::invalid_argument("LayoutDirection: the cube has faces, not 2D coordinates");
}

glm::mat3 EyeFromWorld(const raster::Camera& camera) {
    return glm::mat3(raster::ViewMatrix(camera));
}

int ChartOf(Parameterization p, const glm::vec3& dir) {
    const glm::dvec3 d = UnitDouble(dir);
    if (p == Parameterization::Paraboloid) return d.z >= 0.0 ? 0 : 1;
    if (p == Parameterization::Tennis && d != glm::dvec3(0.0))
        return TennisMargin(d, 1) > TennisMargin(d, 0) ? 1 : 0;
    return 0;
}

glm::vec2 ChartCoord(Parameterization p, const glm::vec3& dir, int chart,
                     const glm::mat3& eyeFromWorld) {
    glm::dvec2 st(0.5);
    switch (p) {
        case Parameterization::Cube:
            throw std::invalid_argument("a cube map has no 2D chart");
        case Parameterization::LatLong:
            st = LatLongCoord(UnitDouble(dir));
            break;
        case Parameterization::Sphere:
            st = SphereCoord(UnitDouble(eyeFromWorld * dir));
            break;
        case Parameterization::Paraboloid:
            st = ParaboloidCoord(UnitDouble(dir), chart);
            break;
        case Parameterization::Tennis:
            st = TennisCoord(UnitDouble(dir), chart);
            break;
    }
    return glm::vec2(st);
}

std::vector<raster::Pass> ToLayout(const raster::Pass& cubePass, int unit, Parameterization p,
                                   const glm::mat3& eyeFromWorld) {
    if (p == Parameterization::Cube) return {cubePass};
    // Step: one pass per texture with the pass's state, without its geometry (not copied only
    // to be cleared).
    const int textures = MapTextures(p);
    std::vector<raster::Pass> out(static_cast<size_t>(textures));
    for (int c = 0; c < textures; ++c) {
        raster::Pass& pass = out[static_cast<size_t>(c)];
        pass.numUnits = cubePass.numUnits;
        pass.texture = cubePass.texture;
        pass.texture[static_cast<size_t>(unit)] += c;
        pass.blend = cubePass.blend;
        pass.depthTest = cubePass.depthTest;
    }
    const size_t corners = static_cast<size_t>(cubePass.NumTriangles()) * 3;
    if (textures == 1) out[0].vertices.reserve(corners);
    auto corner = [&](size_t k) {
        return cubePass.vertices[cubePass.indices.empty() ? k : cubePass.indices[k]];
    };
    for (size_t k = 0; k < corners; k += 3) {
        // Step: the triangle's chart, from the sum of its corner directions.
        const glm::vec3 sum = corner(k).coord[static_cast<size_t>(unit)] +
                              corner(k + 1).coord[static_cast<size_t>(unit)] +
                              corner(k + 2).coord[static_cast<size_t>(unit)];
        const int chart = ChartOf(p, sum);
        // Step: its corners with that chart's coordinates, in that chart's pass.
        for (size_t c = 0; c < 3; ++c) {
            raster::Vertex v = corner(k + c);
            glm::vec3& coord = v.coord[static_cast<size_t>(unit)];
            coord = glm::vec3(ChartCoord(p, coord, chart, eyeFromWorld), 0.0f);
            out[static_cast<size_t>(chart)].vertices.push_back(v);
        }
    }
    return out;
}

}  // namespace pem::runtime
