// SPDX-License-Identifier: MIT
// stability_raster.cpp — the raster family of the stability suite (stability.h): cube-map
// directions exactly on edges and corners (face selection by the documented tie rule, finite
// face coordinates, seamless taps whose weights sum to 1) and degenerate, sliver and far-off
// triangles through raster::Render and BuildRenderingMatrix (no crash, finite pixels).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "raster/cube_lookup.h"
#include "raster/render.h"
#include "viewer_tty/stability/stability_internal.h"

namespace pem::stability {
namespace {

using stability::Checks;
using stability::Format;

// cube_lookup.h's rule written out: z if |z| >= max(|x|, |y|), else x if |x| > |y|, else y; the
// sign bit of the major component picks the negative face.
int ExpectedFace(const raster::Vec3f& d) {
    const float ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
    const int axis = az >= std::max(ax, ay) ? 2 : (ax > ay ? 0 : 1);
    return 2 * axis + (std::signbit(d[static_cast<size_t>(axis)]) ? 1 : 0);
}

// Every edge direction (two components +-1, one +-0) and every corner (+-1, +-1, +-1).
std::vector<raster::Vec3f> EdgeAndCornerDirections() {
    std::vector<raster::Vec3f> out;
    for (int zero = 0; zero < 3; ++zero)
        for (int signs = 0; signs < 8; ++signs) {
            raster::Vec3f d{};
            for (int k = 0; k < 3; ++k) {
                const float s = (signs >> k) & 1 ? -1.0f : 1.0f;
                d[static_cast<size_t>(k)] = k == zero ? s * 0.0f : s;
            }
            out.push_back(d);  // includes -0.0 in the zero slot
        }
    for (int signs = 0; signs < 8; ++signs)
        out.push_back(
            {signs & 1 ? -1.0f : 1.0f, signs & 2 ? -1.0f : 1.0f, signs & 4 ? -1.0f : 1.0f});
    return out;
}

raster::Texture Cube(int size) {
    raster::Texture t;
    t.width = t.height = size;
    uint32_t state = 7;
    for (int n = size; n >= 1; n /= 2) {
        std::vector<uint8_t> level(static_cast<size_t>(6 * n * n * 4));
        for (size_t k = 0; k < level.size(); ++k) {
            state = state * 1664525u + 1013904223u;
            level[k] = k % 4 == 3 ? 255 : static_cast<uint8_t>(state >> 24);
        }
        t.levels.push_back(std::move(level));
    }
    return t;
}

raster::Vertex V(float x, float y, const glm::vec3& dir, float w = 1.0f) {
    raster::Vertex v;
    v.pos = {x * w, y * w, 0.0f, w};
    v.coord[0] = dir;
    return v;
}

// A full-screen quad whose corners look along dirs[0..3].
raster::Pass Quad(const std::array<glm::vec3, 4>& dirs) {
    raster::Pass p;
    const raster::Vertex c[4] = {V(-1, -1, dirs[0]), V(1, -1, dirs[1]), V(1, 1, dirs[2]),
                                 V(-1, 1, dirs[3])};
    for (int k : {0, 1, 2, 0, 2, 3}) p.vertices.push_back(c[k]);
    return p;
}

struct RenderFigures {
    bool finite = true;
    double weightError = 0.0;   // worst |sum of a row's tap weights - 1| over rows with taps
    double forwardError = 0.0;  // worst |A x + offset - linear render|
    int64_t rowsWithTaps = 0;
};

// Renders in both profiles, builds A, checks finiteness, weights and forward = matrix.
RenderFigures RenderAll(const raster::Frame& f, int threads, bool unitWeights) {
    RenderFigures out;
    const raster::PreparedFrame prepared(f);
    raster::RenderOptions lin;
    lin.profile = raster::Profile::Linear;
    lin.threads = threads;
    raster::RenderOptions pipe;
    pipe.threads = threads;
    (void)raster::Render(prepared, pipe);  // llvmpipe: RGBA8 (finite by type); must not crash
    const raster::RenderResult r = raster::Render(prepared, lin);
    for (float v : r.imageF.rgba) out.finite = out.finite && std::isfinite(v);
    const raster::RenderingMatrix a = raster::BuildRenderingMatrix(prepared, lin);
    std::vector<double> x;
    for (const raster::Texture& t : f.textures)
        for (const auto& level : t.levels)
            for (uint8_t b : level) x.push_back(b / 255.0);
    for (int64_t row = 0; row < a.rows; ++row) {
        double sum = 0.0, ax = a.offset[static_cast<size_t>(row)];
        const int64_t b = a.rowPtr[static_cast<size_t>(row)],
                      e = a.rowPtr[static_cast<size_t>(row + 1)];
        for (int64_t k = b; k < e; ++k) {
            const double w = a.val[static_cast<size_t>(k)];
            out.finite = out.finite && std::isfinite(w);
            sum += w;
            ax += w * x[a.col[static_cast<size_t>(k)]];
        }
        if (e > b && unitWeights) {
            out.weightError = std::max(out.weightError, std::fabs(sum - 1.0));
            ++out.rowsWithTaps;
        }
        const double rendered = static_cast<double>(r.imageF.rgba[static_cast<size_t>(row)]);
        out.forwardError = std::max(out.forwardError, std::fabs(ax - rendered));
    }
    return out;
}

void CubeEdgesAndCorners(const StabilityOptions& options, StabilityCase* c) {
    Checks checks;
    const raster::Vec3f zero{0, 0, 0}, tiny{1e-3f, -2e-3f, 5e-4f};
    int faces[6] = {};
    for (const raster::Vec3f& d : EdgeAndCornerDirections()) {
        const std::string name = Format("(%g, %g, %g)", static_cast<double>(d[0]),
                                        static_cast<double>(d[1]), static_cast<double>(d[2]));
        const int face = raster::CubeFace(d);
        checks.Expect(face == ExpectedFace(d),
                      Format("%s: face %d, rule says %d", name.c_str(), face, ExpectedFace(d)));
        ++faces[std::clamp(face, 0, 5)];
        for (bool deriv : {false, true}) {
            const raster::CubeCoord a = raster::CubeLookup(d, tiny, tiny, deriv);
            const raster::CubeCoord b = raster::CubeLookup(d, tiny, tiny, deriv);
            checks.Expect(std::memcmp(&a, &b, sizeof a) == 0, name + ": not deterministic");
            checks.Expect(a.face == face, name + ": CubeLookup face differs from CubeFace");
            const bool st = std::isfinite(a.s) && std::isfinite(a.t) && a.s >= 0.0f &&
                            a.s <= 1.0f && a.t >= 0.0f && a.t <= 1.0f;
            const bool dd = std::isfinite(a.dsdx) && std::isfinite(a.dtdx) &&
                            std::isfinite(a.dsdy) && std::isfinite(a.dtdy);
            checks.Expect(st && dd, name + ": non-finite or out-of-range face coordinates");
        }
        (void)zero;
    }
    // Frames: a constant direction exactly on a corner / an edge (zero derivatives), and a quad
    // spanning the (1, 1, 1) corner and the (1, 1, 0) edge (seamless corner and edge taps).
    RenderFigures worst;
    const float e = 0.05f;
    const std::vector<std::array<glm::vec3, 4>> quads = {
        {glm::vec3(1, 1, 1), glm::vec3(1, 1, 1), glm::vec3(1, 1, 1), glm::vec3(1, 1, 1)},
        {glm::vec3(1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, -1, 0)},
        {glm::vec3(1 - e, 1 + e, 1), glm::vec3(1 + e, 1 - e, 1 + e), glm::vec3(1, 1 + e, 1 - e),
         glm::vec3(1 - e, 1 - e, 1 + e)},
        {glm::vec3(1, 1 - e, -e), glm::vec3(1, 1 + e, -e), glm::vec3(1, 1 + e, e),
         glm::vec3(1, 1 - e, e)}};
    for (raster::Filter mag : {raster::Filter::Linear, raster::Filter::Nearest})
        for (const auto& dirs : quads) {
            raster::Frame f;
            f.width = f.height = 8;
            f.textures.push_back(Cube(8));
            f.textures[0].sampler.magFilter = mag;
            f.passes.push_back(Quad(dirs));
            const RenderFigures r = RenderAll(f, std::max(1, options.threads), true);
            worst.finite = worst.finite && r.finite;
            worst.weightError = std::max(worst.weightError, r.weightError);
            worst.forwardError = std::max(worst.forwardError, r.forwardError);
            worst.rowsWithTaps += r.rowsWithTaps;
        }
    checks.Expect(worst.finite, "non-finite pixel or tap weight");
    checks.Expect(worst.rowsWithTaps > 0 && worst.weightError < 1e-5,
                  Format("tap weights sum to 1 +- %.3g", worst.weightError));
    checks.Expect(worst.forwardError < 1e-5, Format("A x != render by %.3g", worst.forwardError));
    c->residual = worst.weightError;
    c->detail = Format(
        "24 edge directions (with +-0) and 8 corners: faces +X..-Z chosen %d/%d/%d/%d/%d/%d "
        "times, as the tie rule (z, then x over y strictly, else y; sign bit) predicts; "
        "CubeLookup twice with and without derivatives, bitwise equal; 8 frames 8x8 (constant "
        "corner / edge direction, quads spanning a corner and an edge; linear and nearest mag): "
        "%lld rows with taps; residual = worst |sum of tap weights - 1|; A x vs linear render "
        "%.3g; condition not applicable",
        faces[0], faces[1], faces[2], faces[3], faces[4], faces[5],
        static_cast<long long>(worst.rowsWithTaps), worst.forwardError);
    stability::Conclude(checks, "faces by the tie rule, finite coordinates, weights sum to 1", c);
}

struct TriangleSpec {
    const char* name;
    std::array<raster::Vertex, 3> v;
    bool coversNothing;  // must leave the framebuffer at the clear colour
};

std::vector<TriangleSpec> Triangles() {
    const glm::vec3 d(0.3f, 0.2f, 1.0f);
    return {
        {"zero area (one point)", {V(0.1f, 0.1f, d), V(0.1f, 0.1f, d), V(0.1f, 0.1f, d)}, true},
        {"collinear across the screen", {V(-1, -1, d), V(0, 0, d), V(1, 1, d)}, true},
        {"two equal vertices", {V(-1, -1, d), V(-1, -1, d), V(1, 0.5f, d)}, true},
        {"needle 1e-6 wide", {V(-1, -1, d), V(1, 1, d), V(1, 1.000001f, d)}, false},
        {"sliver 1e-3 px high", {V(-1, 0.0001f, d), V(1, 0.0001f, d), V(1, 0.00035f, d)}, false},
        {"subpixel", {V(0.01f, 0.01f, d), V(0.011f, 0.01f, d), V(0.01f, 0.011f, d)}, false},
        {"huge (1e30 clip units)",
         {V(-1e30f, -1e30f, d), V(1e30f, -1e30f, d), V(0, 1e30f, d)},
         false},
        {"w near 0", {V(-1, -1, d, 1e-30f), V(1, -1, d, 1.0f), V(0, 1, d, 1.0f)}, false},
        {"w negative (behind the eye)",
         {V(-1, -1, d, -1.0f), V(1, -1, d, 1.0f), V(0, 1, d, 1.0f)},
         false},
        {"zero direction",
         {V(-1, -1, glm::vec3(0)), V(1, -1, glm::vec3(0)), V(0, 1, glm::vec3(0))},
         false},
    };
}

void DegenerateTriangles(const StabilityOptions& options, StabilityCase* c) {
    Checks checks;
    int covered = 0;
    std::string zeroDirection;
    double forward = 0.0;
    for (const TriangleSpec& t : Triangles()) {
        raster::Frame f;
        f.width = f.height = 16;
        f.clear = {10, 20, 30, 255};
        f.textures.push_back(Cube(4));
        raster::Pass p;
        for (const raster::Vertex& v : t.v) p.vertices.push_back(v);
        f.passes.push_back(p);
        const RenderFigures r = RenderAll(f, std::max(1, options.threads), false);
        raster::RenderOptions pipe;
        const raster::Image8 img = raster::Render(raster::PreparedFrame(f), pipe).image8;
        int changed = 0;
        for (size_t k = 0; k < img.rgba.size(); k += 4)
            changed += std::memcmp(&img.rgba[k], f.clear.data(), 4) != 0;
        covered += changed;
        if (std::string(t.name) == "zero direction") {
            zeroDirection = r.finite ? "finite" : "NON-FINITE linear pixels";
            checks.Expect(r.finite,
                          "zero cube direction: raster::Render (linear profile) writes NaN "
                          "pixels (s = sc * |0.5 / ma| + 0.5 with ma = 0, cube_lookup.h)");
            continue;
        }
        checks.Expect(r.finite, Format("%s: non-finite pixels or weights", t.name));
        if (t.coversNothing)
            checks.Expect(changed == 0, Format("%s: %d pixels written", t.name, changed));
        forward = std::max(forward, r.forwardError);
    }
    checks.Expect(forward < 1e-5, Format("A x != render by %.3g", forward));
    c->residual = forward;
    c->detail = Format(
        "10 single-triangle frames 16x16 (zero area, collinear, repeated vertex, needle, sliver, "
        "subpixel, 1e30 clip units, w = 1e-30, w < 0, zero direction) in the llvmpipe and linear "
        "profiles and as rendering matrices; %d pixels covered in all; zero direction: %s; "
        "residual = worst |A x + offset - linear render|; condition not applicable",
        covered, zeroDirection.c_str());
    stability::Conclude(checks, "no crash, finite pixels, degenerate triangles draw nothing", c);
}

}  // namespace

std::vector<StabilityCase> RunRasterStabilityCases(const StabilityOptions& options) {
    return {
        stability::RunCase(
            "raster: cube edges and corners", "extreme",
            "the face of cube_lookup.h's tie rule (deterministic), finite s, t in [0, 1], finite "
            "pixels, tap weights summing to 1, A x equal to the linear render",
            [&](StabilityCase* c) { CubeEdgesAndCorners(options, c); }),
        stability::RunCase("raster: degenerate and sliver triangles", "extreme",
                           "no crash; finite pixels and weights; zero-area triangles write no "
                           "pixel; A x equal to the linear render",
                           [&](StabilityCase* c) { DegenerateTriangles(options, c); }),
    };
}

}  // namespace pem::stability
