// SPDX-License-Identifier: MIT
#include "tests/case_generator.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <tuple>

#include "runtime/parameterization.h"

namespace pem::test {
namespace {

using raster::BlendEquation;
using raster::BlendFactor;
using raster::BlendState;
using raster::DepthBuffer;
using raster::DepthFormat;
using raster::DepthFunc;
using raster::DepthTest;
using raster::Filter;
using raster::Frame;
using raster::MipFilter;
using raster::Pass;
using raster::SamplerState;
using raster::Texture;
using raster::TextureKind;
using raster::Vertex;
using raster::Wrap;

int Log2(int n) {
    int l = 0;
    while ((1 << (l + 1)) <= n) ++l;
    return l;
}

// A texture with every level random (alphaRandom: alpha random too, else 255).
Texture MakeTexture(TextureKind kind, int w, int h, const SamplerState& s, uint64_t seed,
                    bool alphaRandom = false) {
    Texture t;
    t.kind = kind;
    t.width = w;
    t.height = h;
    t.sampler = s;
    Rng rng{seed};
    const int levels = Log2(std::max(w, h)) + 1;
    for (int l = 0; l < levels; ++l) {
        std::vector<uint8_t> bytes(
            static_cast<size_t>(t.Faces() * t.LevelWidth(l) * t.LevelHeight(l) * 4));
        for (size_t i = 0; i < bytes.size(); i += 4) {
            const uint64_t v = rng.Next();
            bytes[i] = static_cast<uint8_t>(v);
            bytes[i + 1] = static_cast<uint8_t>(v >> 8);
            bytes[i + 2] = static_cast<uint8_t>(v >> 16);
            bytes[i + 3] = alphaRandom ? static_cast<uint8_t>(v >> 24) : 255;
        }
        t.levels.push_back(std::move(bytes));
    }
    return t;
}

// A readable environment for the benchmark and demo: per-face tinted checkerboards with a
// grid, level 0 drawn, each further level the 2x2 box filter of the previous one.
Texture CheckerCube(int size, const SamplerState& s) {
    Texture t;
    t.kind = TextureKind::Cube;
    t.width = t.height = size;
    t.sampler = s;
    static const uint8_t tint[6][3] = {{230, 90, 80}, {80, 200, 120}, {240, 240, 250},
                                       {90, 70, 60},  {90, 130, 240}, {230, 200, 80}};
    std::vector<uint8_t> level(static_cast<size_t>(6 * size * size * 4));
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const bool check = ((i * 8 / size) + (j * 8 / size)) % 2 == 0;
                const bool grid = i % (size / 8) == 0 || j % (size / 8) == 0;
                uint8_t* p = &level[static_cast<size_t>(((f * size + j) * size + i) * 4)];
                for (int c = 0; c < 3; ++c)
                    p[c] = grid ? 20 : static_cast<uint8_t>(check ? tint[f][c] : tint[f][c] / 2);
                p[3] = 255;
            }
    t.levels.push_back(level);
    for (int n = size / 2; n >= 1; n /= 2) {
        const std::vector<uint8_t>& prev = t.levels.back();
        const int m = n * 2;
        std::vector<uint8_t> next(static_cast<size_t>(6 * n * n * 4));
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    for (int c = 0; c < 4; ++c) {
                        auto at = [&](int x, int y) {
                            return prev[static_cast<size_t>(((f * m + y) * m + x) * 4 + c)];
                        };
                        const int sum = at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) +
                                        at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1);
                        next[static_cast<size_t>(((f * n + j) * n + i) * 4 + c)] =
                            static_cast<uint8_t>((sum + 2) >> 2);
                    }
        t.levels.push_back(std::move(next));
    }
    return t;
}

Texture Cube(int size, const SamplerState& s, uint64_t seed, bool alphaRandom = false) {
    return MakeTexture(TextureKind::Cube, size, size, s, seed, alphaRandom);
}

SamplerState Sampler(Filter min, MipFilter mip, Filter mag, bool seamless = true) {
    SamplerState s;
    s.minFilter = min;
    s.mipFilter = mip;
    s.magFilter = mag;
    s.seamless = seamless;
    return s;
}

Vertex V(glm::vec4 pos, glm::vec3 c0, glm::vec4 col = glm::vec4(1.0f),
         glm::vec3 c1 = glm::vec3(0.0f)) {
    Vertex v;
    v.pos = pos;
    v.coord[0] = c0;
    v.coord[1] = c1;
    v.color = col;
    return v;
}

// Two triangles covering the clip rectangle [x0,x1]x[y0,y1] at w = 1 with per-corner coords.
void AddQuad(Pass* p, float x0, float y0, float x1, float y1, const glm::vec3 c[4],
             const glm::vec4& col = glm::vec4(1.0f), const glm::vec3* c1 = nullptr) {
    const glm::vec4 pos[4] = {{x0, y0, 0, 1}, {x1, y0, 0, 1}, {x1, y1, 0, 1}, {x0, y1, 0, 1}};
    const int idx[6] = {0, 1, 2, 0, 2, 3};
    for (int k : idx) p->vertices.push_back(V(pos[k], c[k], col, c1 ? c1[k] : glm::vec3(0)));
}

// A UV sphere seen by a perspective camera, texture coordinate = reflection vector * scale.
void AddSphere(Pass* p, int rings, int segs, float aspect, const glm::vec3& eye,
               const glm::vec3& centre, float radius, float dirScale, Rng* jitter = nullptr) {
    const glm::mat4 proj = glm::perspective(glm::radians(40.0f), aspect, 0.1f, 100.0f);
    const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const glm::mat4 vp = proj * view;
    auto vertex = [&](int i, int j) {
        const float th = 3.14159265f * static_cast<float>(i) / static_cast<float>(rings);
        const float ph = 6.28318531f * static_cast<float>(j) / static_cast<float>(segs);
        const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
        const glm::vec3 pos = centre + radius * n;
        const glm::vec3 in = glm::normalize(pos - eye);
        glm::vec3 r = in - 2.0f * glm::dot(n, in) * n;
        if (jitter) r += glm::vec3(jitter->Uniform(-0.02f, 0.02f), 0.0f, 0.0f);
        return V(vp * glm::vec4(pos, 1.0f), r * dirScale);
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segs; ++j) {
            const Vertex a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                         d = vertex(i, j + 1);
            const uint32_t base = static_cast<uint32_t>(p->vertices.size());
            for (const Vertex& v : {a, b, c, d}) p->vertices.push_back(v);
            for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) p->indices.push_back(base + k);
        }
}

Frame NewFrame(int w, int h, std::array<uint8_t, 4> clear = {0, 0, 0, 255}) {
    Frame f;
    f.width = w;
    f.height = h;
    f.clear = clear;
    return f;
}

const char* FilterName(Filter min, MipFilter mip) {
    static const char* names[2][3] = {
        {"nearest", "nearest_mipmap_nearest", "nearest_mipmap_linear"},
        {"linear", "linear_mipmap_nearest", "linear_mipmap_linear"}};
    return names[min == Filter::Linear][static_cast<int>(mip)];
}

// Reflective spheres with every filter combination, seamless and not. --------------------------
void Spheres(std::vector<NamedCase>* out) {
    const Filter filters[2] = {Filter::Nearest, Filter::Linear};
    const MipFilter mips[3] = {MipFilter::None, MipFilter::Nearest, MipFilter::Linear};
    uint64_t seed = 100;
    for (bool seamless : {true, false})
        for (Filter min : filters)
            for (MipFilter mip : mips)
                for (Filter mag : filters) {
                    Frame f = NewFrame(96, 80);
                    f.textures.push_back(Cube(32, Sampler(min, mip, mag, seamless), ++seed));
                    Pass p;
                    AddSphere(&p, 24, 32, 96.0f / 80.0f, {0.3f, 0.8f, 3.2f}, {0, 0, 0}, 1.0f, 1.0f);
                    f.passes.push_back(p);
                    out->push_back({std::string("sphere_") + FilterName(min, mip) + "_mag_" +
                                        (mag == Filter::Linear ? "linear" : "nearest") +
                                        (seamless ? "_seamless" : "_plain"),
                                    f});
                }
    // Magnified centre, minified rim, min != mag: blocks that mix both filters.
    for (auto [min, mip, mag] : {std::tuple{Filter::Linear, MipFilter::Linear, Filter::Nearest},
                                 std::tuple{Filter::Nearest, MipFilter::Nearest, Filter::Linear},
                                 std::tuple{Filter::Nearest, MipFilter::Linear, Filter::Linear},
                                 std::tuple{Filter::Linear, MipFilter::None, Filter::Nearest}}) {
        for (bool seamless : {true, false}) {
            Frame f = NewFrame(96, 96);
            f.textures.push_back(Cube(128, Sampler(min, mip, mag, seamless), ++seed));
            Pass p;
            AddSphere(&p, 32, 40, 1.0f, {0.1f, 0.3f, 2.2f}, {0, 0, 0}, 1.0f, 1.0f);
            f.passes.push_back(p);
            out->push_back({std::string("mixed_") + FilterName(min, mip) + "_mag_" +
                                (mag == Filter::Linear ? "linear" : "nearest") +
                                (seamless ? "_seamless" : "_plain"),
                            f});
        }
    }
    // A large cube (strong minification at the rim) and a tiny one (magnification).
    for (int size : {256, 2}) {
        Frame f = NewFrame(128, 96);
        f.textures.push_back(
            Cube(size, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), ++seed));
        Pass p;
        AddSphere(&p, 40, 48, 128.0f / 96.0f, {-0.5f, 1.2f, 2.6f}, {0, 0, 0}, 1.0f, 1.0f);
        f.passes.push_back(p);
        out->push_back({"sphere_cube" + std::to_string(size), f});
    }
}

glm::vec4 RandomColour(Rng* rng);

// 24 random triangles whose directions cluster around a cube corner (+-1, +-1, +-1) or an edge
// midpoint, perturbed per vertex; white, or a random colour per vertex.
Pass EdgeCornerTriangles(Rng* rng, bool colours) {
    Pass p;
    for (int t = 0; t < 24; ++t) {
        glm::vec3 base(rng->Int(2) ? 1.0f : -1.0f, rng->Int(2) ? 1.0f : -1.0f,
                       rng->Int(2) ? 1.0f : -1.0f);
        if (rng->Int(2)) base[rng->Int(3)] = 0.0f;
        for (int v = 0; v < 3; ++v) {
            const glm::vec4 pos(rng->Uniform(-1.2f, 1.2f), rng->Uniform(-1.2f, 1.2f),
                                rng->Uniform(-0.5f, 0.5f), rng->Uniform(0.8f, 1.5f));
            const glm::vec3 d =
                base + glm::vec3(rng->Uniform(-0.3f, 0.3f), rng->Uniform(-0.3f, 0.3f),
                                 rng->Uniform(-0.3f, 0.3f));
            p.vertices.push_back(V(pos, d, colours ? RandomColour(rng) : glm::vec4(1.0f)));
        }
    }
    return p;
}

// Random triangles whose directions cluster around cube edges and corners. ----------------------
void EdgesAndCorners(std::vector<NamedCase>* out) {
    Rng rng{7};
    for (int k = 0; k < 12; ++k) {
        const bool seamless = k % 3 != 2;
        const int size = 1 << (k % 4);  // 1, 2, 4, 8
        const MipFilter mip = k % 2 ? MipFilter::Linear : MipFilter::None;
        Frame f = NewFrame(64, 64);
        f.textures.push_back(Cube(size, Sampler(Filter::Linear, mip, Filter::Linear, seamless),
                                  1000 + static_cast<uint64_t>(k)));
        f.passes.push_back(EdgeCornerTriangles(&rng, false));
        out->push_back({"edges_corners_" + std::to_string(k) + (seamless ? "_seamless" : "_plain") +
                            "_n" + std::to_string(size),
                        f});
    }
}

// Blocks where some lanes touch a cube corner and others do not (llvmpipe then filters all
// eight lanes with the weighted sum); a 2x2 cube makes corners frequent. -------------------
void CornerBlocks(std::vector<NamedCase>* out) {
    for (int k = 0; k < 3; ++k) {
        Frame f = NewFrame(256, 256);
        f.textures.push_back(Cube(2, Sampler(Filter::Linear, MipFilter::None, Filter::Linear),
                                  7000 + static_cast<uint64_t>(k)));
        Pass p;
        Rng rng{71 + static_cast<uint64_t>(k)};
        for (int t = 0; t < 64; ++t)
            for (int v = 0; v < 3; ++v) {
                const glm::vec4 pos(rng.Uniform(-1.5f, 1.5f), rng.Uniform(-1.5f, 1.5f), 0, 1);
                const glm::vec3 d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
                const glm::vec4 col(rng.Uniform(0.2f, 1), rng.Uniform(0.2f, 1),
                                    rng.Uniform(0.2f, 1), 1.0f);
                p.vertices.push_back(V(pos, d, col));
            }
        f.passes.push_back(p);
        out->push_back({"corner_blocks_" + std::to_string(k), f});
    }
}

// Minification (directions sweep the whole cube across the screen) and magnification. --------
void MinMag(std::vector<NamedCase>* out) {
    const glm::vec3 sweep[4] = {{-3, -2, 1}, {3, -2, 1}, {2, 3, -1}, {-2, 3, -1}};
    const glm::vec3 zoom[4] = {
        {-0.02f, -0.02f, 1}, {0.03f, -0.02f, 1}, {0.03f, 0.02f, 1}, {-0.02f, 0.03f, 1}};
    for (bool mag : {false, true}) {
        for (MipFilter mip : {MipFilter::Linear, MipFilter::Nearest, MipFilter::None}) {
            Frame f = NewFrame(80, 64);
            f.textures.push_back(
                Cube(mag ? 4 : 128, Sampler(Filter::Linear, mip, Filter::Linear), mag ? 77 : 78));
            Pass p;
            AddQuad(&p, -1, -1, 1, 1, mag ? zoom : sweep);
            f.passes.push_back(p);
            out->push_back(
                {std::string(mag ? "magnify_" : "minify_") + FilterName(Filter::Linear, mip), f});
        }
    }
}

// 2D textures: every min/mag filter and wrap on a perspective quad, and a 1D table. ---------
void Textures2D(std::vector<NamedCase>* out) {
    const Filter filters[2] = {Filter::Nearest, Filter::Linear};
    const MipFilter mips[3] = {MipFilter::None, MipFilter::Nearest, MipFilter::Linear};
    const Wrap wraps[3] = {Wrap::ClampToEdge, Wrap::Repeat, Wrap::MirroredRepeat};
    const char* wrapNames[3] = {"clamp", "repeat", "mirror"};
    uint64_t seed = 500;
    for (int wi = 0; wi < 3; ++wi)
        for (Filter min : filters)
            for (MipFilter mip : mips)
                for (Filter mag : filters) {
                    Frame f = NewFrame(64, 48);
                    SamplerState s = Sampler(min, mip, mag);
                    s.wrapS = wraps[wi];
                    s.wrapT = wraps[(wi + 1) % 3];
                    f.textures.push_back(MakeTexture(TextureKind::Tex2D, 16, 8, s, ++seed));
                    Pass p;
                    // Perspective: the far edge (top) has a larger w.
                    const glm::vec3 c[4] = {
                        {-1.5f, -0.5f, 0}, {2.5f, -0.5f, 0}, {2.5f, 1.7f, 0}, {-1.5f, 1.7f, 0}};
                    const glm::vec4 pos[4] = {
                        {-1, -1, 0, 1}, {1, -1, 0, 1}, {3.5f, 3.5f, 0, 4}, {-3.5f, 3.5f, 0, 4}};
                    for (int k : {0, 1, 2, 0, 2, 3}) p.vertices.push_back(V(pos[k], c[k]));
                    f.passes.push_back(p);
                    out->push_back({std::string("tex2d_") + FilterName(min, mip) + "_mag_" +
                                        (mag == Filter::Linear ? "linear_" : "nearest_") +
                                        wrapNames[wi],
                                    f});
                }
}

// LOD bias and clamps on a minified sphere. ----------------------------------------------------
void LodControls(std::vector<NamedCase>* out) {
    struct Variant {
        const char* name;
        float bias, minLod, maxLod;
        MipFilter mip;
    };
    const Variant vs[] = {{"bias_plus1_3", 1.3f, -1000, 1000, MipFilter::Linear},
                          {"bias_minus2", -2.0f, -1000, 1000, MipFilter::Linear},
                          {"bias_frac_nearest", 0.37f, -1000, 1000, MipFilter::Nearest},
                          {"min_lod_1_5", 0.0f, 1.5f, 1000, MipFilter::Linear},
                          {"max_lod_1", 0.0f, -1000, 1.0f, MipFilter::Linear},
                          {"max_lod_14_nearest", 0.0f, -1000, 14.0f, MipFilter::Nearest},
                          {"min_eq_max_2", 0.0f, 2.0f, 2.0f, MipFilter::Linear},
                          {"min_gt_max", 0.0f, 3.0f, 1.0f, MipFilter::Linear}};
    uint64_t seed = 900;
    for (const Variant& v : vs) {
        Frame f = NewFrame(96, 72);
        SamplerState s = Sampler(Filter::Linear, v.mip, Filter::Linear);
        s.lodBias = v.bias;
        s.minLod = v.minLod;
        s.maxLod = v.maxLod;
        f.textures.push_back(Cube(64, s, ++seed));
        Texture t2 = MakeTexture(TextureKind::Tex2D, 32, 32, s, ++seed);
        t2.sampler.wrapS = t2.sampler.wrapT = Wrap::Repeat;
        f.textures.push_back(t2);
        Pass p;
        AddSphere(&p, 20, 24, 96.0f / 72.0f, {0.2f, 0.5f, 4.5f}, {0, 0, 0}, 1.0f, 1.0f);
        f.passes.push_back(p);
        Pass q;
        q.texture[0] = 1;
        const glm::vec3 c[4] = {{0, 0, 0}, {6, 0, 0}, {6, 1, 0}, {0, 1, 0}};
        AddQuad(&q, -1, -1, 1, -0.6f, c);
        f.passes.push_back(q);
        out->push_back({std::string("lod_") + v.name, f});
    }
}

BlendState RandomBlend(Rng* rng) {
    BlendState b;
    b.enabled = true;
    b.srcRgb = static_cast<BlendFactor>(rng->Int(11));
    b.dstRgb = static_cast<BlendFactor>(rng->Int(11));
    b.srcAlpha = static_cast<BlendFactor>(rng->Int(11));
    b.dstAlpha = static_cast<BlendFactor>(rng->Int(11));
    b.eqRgb = static_cast<BlendEquation>(rng->Int(5));
    b.eqAlpha = static_cast<BlendEquation>(rng->Int(5));
    return b;
}

// Multi-pass blending: named modes and random separate factors. ------------------------------
void Blends(std::vector<NamedCase>* out) {
    Rng rng{31337};
    const BlendState named[4] = {BlendState::None(), BlendState::Over(), BlendState::Additive(),
                                 BlendState::Multiply()};
    const char* names[4] = {"none", "over", "add", "multiply"};
    for (int k = 0; k < 4 + 16; ++k) {
        Frame f = NewFrame(64, 64, {40, 90, 160, 200});
        f.textures.push_back(
            Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 40 + k, true));
        for (int pass = 0; pass < 3; ++pass) {
            Pass p;
            p.blend = k < 4 ? named[k] : RandomBlend(&rng);
            if (pass == 0) p.blend = BlendState::None();
            for (int t = 0; t < 6; ++t)
                for (int v = 0; v < 3; ++v) {
                    const glm::vec4 pos(rng.Uniform(-1.3f, 1.3f), rng.Uniform(-1.3f, 1.3f), 0.0f,
                                        1.0f);
                    const glm::vec3 d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
                    const glm::vec4 col(rng.Uniform(0, 1.2f), rng.Uniform(0, 1.2f),
                                        rng.Uniform(0, 1.2f), rng.Uniform(0, 1));
                    p.vertices.push_back(V(pos, d, col));
                }
            f.passes.push_back(p);
        }
        out->push_back(
            {std::string("blend_") + (k < 4 ? names[k] : "random_" + std::to_string(k)), f});
    }
}

// Conversion and blend probes: one-pixel untextured quads with chosen colours. ---------------
void Probes(std::vector<NamedCase>* out) {
    const int w = 64, h = 64;  // 4096 probe pixels
    auto pixelQuad = [&](Pass* p, int x, int y, const glm::vec4& col) {
        const float x0 = 2.0f * static_cast<float>(x) / w - 1.0f, x1 = x0 + 2.0f / w;
        const float y0 = 2.0f * static_cast<float>(y) / h - 1.0f, y1 = y0 + 2.0f / h;
        const glm::vec3 c[4] = {};
        AddQuad(p, x0, y0, x1, y1, c, col);
    };
    // Values: exact k/255, the float midpoints between codes (ties), near-ties, out of range.
    std::vector<float> values;
    for (int k = 0; k < 256; ++k) values.push_back(static_cast<float>(k) / 255.0f);
    for (int k = 0; k < 255; ++k) {
        const float mid = (static_cast<float>(k) + 0.5f) / 255.0f;
        values.push_back(mid);
        values.push_back(std::nextafter(mid, 0.0f));
        values.push_back(std::nextafter(mid, 1.0f));
    }
    for (float v : {-1.0f, -0.0f, 1.0f, 1.0001f, 2.0f, 1e30f, -1e30f}) values.push_back(v);
    Rng rng{4242};
    for (int variant = 0; variant < 3; ++variant) {
        Frame f = NewFrame(w, h, {128, 64, 200, 100});
        Pass base;  // background for the blend variants
        base.numUnits = 0;
        if (variant > 0) {
            for (int i = 0; i < w * h; ++i) {
                const glm::vec4 col(rng.Uniform(0, 1), rng.Uniform(0, 1), rng.Uniform(0, 1),
                                    rng.Uniform(0, 1));
                pixelQuad(&base, i % w, i / w, col);
            }
            f.passes.push_back(base);
        }
        Pass p;
        p.numUnits = 0;
        p.blend = variant == 0 ? BlendState::None()
                               : (variant == 1 ? BlendState::Over() : BlendState::Additive());
        for (int i = 0; i < w * h; ++i) {
            const float v = values[static_cast<size_t>(i) % values.size()];
            const float a = values[static_cast<size_t>(i * 7 + 3) % values.size()];
            pixelQuad(&p, i % w, i / w, glm::vec4(v, 1.0f - v, a, std::min(std::fabs(a), 1.0f)));
        }
        f.passes.push_back(p);
        const char* names[3] = {"probe_convert", "probe_over", "probe_add"};
        out->push_back({names[variant], f});
    }
}

// Exact ties of the face selection, signed zeros, the zero vector. ---------------------------
void Ties(std::vector<NamedCase>* out) {
    const glm::vec3 dirs[] = {{1, 1, 0},     {-1, 1, 0}, {1, -1, 0},        {0, 1, 1},
                              {0, -1, -1},   {1, 0, 1},  {-1, 0, 1},        {1, 1, 1},
                              {-1, -1, -1},  {1, -1, 1}, {-0.0f, 0, 1},     {0, -0.0f, -1},
                              {-0.0f, 1, 0}, {0, 0, 0},  {0.5f, 0.5f, 0.5f}};
    Frame f = NewFrame(60, 60);
    f.textures.push_back(Cube(4, Sampler(Filter::Linear, MipFilter::None, Filter::Linear), 5));
    f.textures.push_back(Cube(4, Sampler(Filter::Nearest, MipFilter::None, Filter::Nearest), 6));
    f.textures.push_back(Cube(8, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 8));
    const int n = static_cast<int>(std::size(dirs));
    for (int tex = 0; tex < 3; ++tex) {
        Pass p;
        p.texture[0] = tex;
        for (int i = 0; i < n; ++i) {
            const float x0 = -1.0f + 2.0f * static_cast<float>(i) / n, x1 = x0 + 2.0f / n;
            const float y0 = -1.0f + 2.0f * static_cast<float>(tex) / 3, y1 = y0 + 2.0f / 3;
            const glm::vec3 c[4] = {dirs[i], dirs[i], dirs[i], dirs[i]};
            AddQuad(&p, x0, y0, x1, y1, c);
        }
        f.passes.push_back(p);
    }
    out->push_back({"tie_directions", f});
    // Directions that run along an edge and through a corner within the frame.
    Frame g = NewFrame(64, 64);
    g.textures.push_back(Cube(8, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 9));
    Pass p;
    const glm::vec3 c[4] = {{1, 1, -1}, {1, 1, 1}, {-1, 1, 1}, {1, 1, 1}};
    AddQuad(&p, -1, -1, 1, 1, c);
    g.passes.push_back(p);
    out->push_back({"tie_edge_sweep", g});
}

// Direction magnitudes from 1e-30 to 1e30 (the result must not depend on scale). ----------
void Magnitudes(std::vector<NamedCase>* out) {
    for (int e = -30; e <= 30; e += 10) {
        Frame f = NewFrame(64, 64);
        f.textures.push_back(
            Cube(32, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 3));
        Pass p;
        AddSphere(&p, 16, 20, 1.0f, {0.2f, 0.4f, 3.0f}, {0, 0, 0}, 1.0f,
                  std::pow(10.0f, static_cast<float>(e)));
        f.passes.push_back(p);
        out->push_back(
            {"magnitude_1e" + std::string(e < 0 ? "m" : "p") + std::to_string(std::abs(e)), f});
    }
}

// Float-range extremes. ------------------------------------------------------------------------
// Texture coordinates from the smallest denormal to FLT_MAX: denormals (flushed to zero in the
// fragment stage), FLT_MIN, 1e35, 1e38, 3e38 and FLT_MAX, where differences, products, squares
// and 1/ma leave the float range. Each magnitude m is a row of 16-pixel cells:
//  0 sweep      corners across several faces (opposite signs: differences of 2m overflow)
//  1 narrow     a small solid angle around +X (magnified at small m, ulp steps at large m)
//  2 mixed      magnitudes m and 1 within one triangle
//  3 denormal   minor components denormal next to a major m
//  4 ties       |x| = |y| = |z| = m (face ties exact at every magnitude)
//  5 perspective  the sweep at w from 0.25 to 4: the setup's a * (1/w) overflows from m ~ 8.5e37
constexpr float kExtremeMagnitudes[] = {1.4e-45f, 1e-40f, 1.17549435e-38f, 1.0f,           1e35f,
                                        1e38f,    3e38f,  3.2e38f,         3.40282347e+38f};
constexpr int kExtremeCells = 6;

// The corner coordinates of cell `cell` at magnitude m (cube directions; the 2D cases use the
// first two components).
std::array<glm::vec3, 4> ExtremeCorners(int cell, float m) {
    const float d = 1e-39f;  // denormal
    switch (cell) {
        case 1:
            return {glm::vec3(1.0f, 0.3f, -0.2f) * m, glm::vec3(1.0f, 0.32f, -0.2f) * m,
                    glm::vec3(1.0f, 0.32f, -0.18f) * m, glm::vec3(1.0f, 0.3f, -0.18f) * m};
        case 2:
            return {glm::vec3(m, 1.0f, 0.5f), glm::vec3(1.0f, m, -0.5f), glm::vec3(-0.5f, 1.0f, m),
                    glm::vec3(-m, -0.5f * m, 1.0f)};
        case 3:
            return {glm::vec3(m, d, -d), glm::vec3(m, -d, d), glm::vec3(-d, m, d),
                    glm::vec3(d, -d, -m)};
        case 4:
            return {glm::vec3(m, m, m), glm::vec3(m, -m, m), glm::vec3(-m, m, -m),
                    glm::vec3(m, m, -m)};
        default:  // 0 and 5
            return {glm::vec3(-1.0f, -0.66f, 0.33f) * m, glm::vec3(1.0f, -0.66f, 0.33f) * m,
                    glm::vec3(0.66f, 1.0f, -0.33f) * m, glm::vec3(-0.66f, 1.0f, -0.33f) * m};
    }
}

// The rows of cells of every magnitude; `uv`: coordinates for a 2D unit (x, y of each corner).
void AddExtremeRows(Pass* p, bool uv) {
    const int rows = static_cast<int>(std::size(kExtremeMagnitudes));
    for (int r = 0; r < rows; ++r) {
        const float y0 = -1.0f + 2.0f * static_cast<float>(r) / rows, y1 = y0 + 2.0f / rows;
        for (int cell = 0; cell < kExtremeCells; ++cell) {
            const float x0 = -1.0f + 2.0f * static_cast<float>(cell) / kExtremeCells;
            const float x1 = x0 + 2.0f / kExtremeCells;
            std::array<glm::vec3, 4> c = ExtremeCorners(cell, kExtremeMagnitudes[r]);
            if (uv)
                for (glm::vec3& v : c) v.z = 0.0f;
            if (cell != 5) {
                AddQuad(p, x0, y0, x1, y1, c.data());
                continue;
            }
            const float w[4] = {0.25f, 1.0f, 4.0f, 2.0f};
            const glm::vec2 xy[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
            for (int k : {0, 1, 2, 0, 2, 3})
                p->vertices.push_back(
                    V(glm::vec4(xy[k] * w[k], 0.0f, w[k]), c[static_cast<size_t>(k)]));
        }
    }
}

void Extremes(std::vector<NamedCase>* out) {
    const int w = 16 * kExtremeCells, h = 8 * static_cast<int>(std::size(kExtremeMagnitudes));
    // Cube maps on every filter path: the 8-bit path (plain or nearest), the float path
    // (seamless linear, min != mag with a MIP filter), its fast seamless trilinear form, LOD
    // controls and the anisotropic path.
    struct CubeVariant {
        const char* name;
        Filter min;
        MipFilter mip;
        Filter mag;
        bool seamless;
        float bias = 0.0f, maxAniso = 1.0f;
        float fixedLod = -1.0f;  // >= 0: min_lod = max_lod (no derivatives)
    };
    const CubeVariant cubes[] = {
        {"nearest_plain", Filter::Nearest, MipFilter::None, Filter::Nearest, false},
        {"nearest_seamless", Filter::Nearest, MipFilter::None, Filter::Nearest, true},
        {"linear_plain", Filter::Linear, MipFilter::None, Filter::Linear, false},
        {"linear_seamless", Filter::Linear, MipFilter::None, Filter::Linear, true},
        {"linear_mag_nearest_plain", Filter::Linear, MipFilter::None, Filter::Nearest, false},
        {"nmn_plain", Filter::Nearest, MipFilter::Nearest, Filter::Nearest, false},
        {"nml_seamless", Filter::Nearest, MipFilter::Linear, Filter::Nearest, true},
        {"lmn_seamless", Filter::Linear, MipFilter::Nearest, Filter::Linear, true},
        {"lml_plain", Filter::Linear, MipFilter::Linear, Filter::Linear, false},
        {"lml_seamless", Filter::Linear, MipFilter::Linear, Filter::Linear, true},
        {"lml_mag_nearest_seamless", Filter::Linear, MipFilter::Linear, Filter::Nearest, true},
        {"lml_bias_seamless", Filter::Linear, MipFilter::Linear, Filter::Linear, true, 0.6f},
        {"nmn_bias_plain", Filter::Nearest, MipFilter::Nearest, Filter::Nearest, false, -0.3f},
        {"aniso_lml_seamless", Filter::Linear, MipFilter::Linear, Filter::Linear, true, 0, 16},
        {"aniso_nmn_plain", Filter::Nearest, MipFilter::Nearest, Filter::Nearest, false, 0, 4},
        {"lml_lod_fixed_seamless", Filter::Linear, MipFilter::Linear, Filter::Linear, true, 0, 1,
         1.0f},
    };
    uint64_t seed = 15000;
    for (const CubeVariant& v : cubes) {
        Frame f = NewFrame(w, h);
        SamplerState s = Sampler(v.min, v.mip, v.mag, v.seamless);
        s.lodBias = v.bias;
        s.maxAnisotropy = v.maxAniso;
        if (v.fixedLod >= 0.0f) s.minLod = s.maxLod = v.fixedLod;
        f.textures.push_back(Cube(16, s, ++seed));
        Pass p;
        AddExtremeRows(&p, false);
        f.passes.push_back(p);
        out->push_back({std::string("extreme_cube_") + v.name, f});
    }
    // 2D textures: the same rows as (s, t) with each wrap mode.
    struct Variant2D {
        const char* name;
        Filter min;
        MipFilter mip;
        Filter mag;
        Wrap wrapS, wrapT;
        float bias = 0.0f, maxAniso = 1.0f;
    };
    const Variant2D planes[] = {
        {"nearest_repeat", Filter::Nearest, MipFilter::None, Filter::Nearest, Wrap::Repeat,
         Wrap::Repeat},
        {"linear_repeat", Filter::Linear, MipFilter::None, Filter::Linear, Wrap::Repeat,
         Wrap::Repeat},
        {"linear_clamp", Filter::Linear, MipFilter::None, Filter::Linear, Wrap::ClampToEdge,
         Wrap::ClampToEdge},
        {"nearest_mirror", Filter::Nearest, MipFilter::None, Filter::Nearest, Wrap::MirroredRepeat,
         Wrap::MirroredRepeat},
        {"lml_repeat", Filter::Linear, MipFilter::Linear, Filter::Linear, Wrap::Repeat,
         Wrap::Repeat},
        {"nmn_clamp", Filter::Nearest, MipFilter::Nearest, Filter::Nearest, Wrap::ClampToEdge,
         Wrap::ClampToEdge},
        {"lml_mirror", Filter::Linear, MipFilter::Linear, Filter::Linear, Wrap::MirroredRepeat,
         Wrap::MirroredRepeat},
        {"linear_mag_nearest_repeat", Filter::Linear, MipFilter::None, Filter::Nearest,
         Wrap::Repeat, Wrap::Repeat},
        {"nmn_mag_linear_mirror", Filter::Nearest, MipFilter::Nearest, Filter::Linear,
         Wrap::MirroredRepeat, Wrap::MirroredRepeat},
        {"lml_mag_nearest_mirror", Filter::Linear, MipFilter::Linear, Filter::Nearest,
         Wrap::MirroredRepeat, Wrap::MirroredRepeat},
        {"lml_bias_clamp", Filter::Linear, MipFilter::Linear, Filter::Linear, Wrap::ClampToEdge,
         Wrap::ClampToEdge, -0.7f},
        {"aniso_lml_repeat", Filter::Linear, MipFilter::Linear, Filter::Linear, Wrap::Repeat,
         Wrap::Repeat, 0, 16},
        {"linear_repeat_mirror", Filter::Linear, MipFilter::None, Filter::Linear, Wrap::Repeat,
         Wrap::MirroredRepeat},
        {"nmn_mag_linear_repeat_mirror", Filter::Nearest, MipFilter::Nearest, Filter::Linear,
         Wrap::Repeat, Wrap::MirroredRepeat},
    };
    for (const Variant2D& v : planes) {
        Frame f = NewFrame(w, h);
        SamplerState s = Sampler(v.min, v.mip, v.mag);
        s.wrapS = v.wrapS;
        s.wrapT = v.wrapT;
        s.lodBias = v.bias;
        s.maxAnisotropy = v.maxAniso;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 16, 8, s, ++seed));
        Pass p;
        AddExtremeRows(&p, true);
        f.passes.push_back(p);
        out->push_back({std::string("extreme_2d_") + v.name, f});
    }
    // Reflection spheres scaled to the magnitudes past the old 1e30 limit, trilinear seamless.
    const std::pair<const char*, float> spheres[] = {{"denormal_min", 1.4e-45f},
                                                     {"denormal", 1e-40f},
                                                     {"flt_min", 1.17549435e-38f},
                                                     {"1e35", 1e35f},
                                                     {"1e38", 1e38f},
                                                     {"3e38", 3e38f},
                                                     {"flt_max", 3.40282347e+38f}};
    for (const auto& [name, scale] : spheres) {
        Frame f = NewFrame(64, 64);
        f.textures.push_back(
            Cube(32, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 3));
        Pass p;
        AddSphere(&p, 16, 20, 1.0f, {0.2f, 0.4f, 3.0f}, {0, 0, 0}, 1.0f, scale);
        f.passes.push_back(p);
        out->push_back({std::string("extreme_sphere_") + name, f});
    }
    // Clipped triangles carrying huge attributes: the clipper interpolates out + t * (in - out).
    Frame f = NewFrame(64, 48);
    f.textures.push_back(
        Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear, false), ++seed));
    Pass p;
    Rng rng{1500};
    for (int t = 0; t < 24; ++t) {
        const float m = kExtremeMagnitudes[5 + t % 4];
        for (int k = 0; k < 3; ++k) {
            const glm::vec4 pos(rng.Uniform(-2.5f, 2.5f), rng.Uniform(-2.5f, 2.5f),
                                rng.Uniform(-1.5f, 1.5f), 1.0f);
            const glm::vec3 d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
            p.vertices.push_back(V(pos, d * m));
        }
    }
    f.passes.push_back(p);
    out->push_back({"extreme_clipped", f});
}

// Clipping: w near zero, vertices behind the eye, huge triangles, z planes and depth clamp. ---
void Clipping(std::vector<NamedCase>* out) {
    Rng rng{99};
    const char* names[4] = {"clip_w_near_zero", "clip_behind_eye", "clip_huge", "clip_depth"};
    for (int k = 0; k < 4; ++k)
        for (bool clamp : {false, true}) {
            if (k < 3 && clamp) continue;
            Frame f = NewFrame(72, 56);
            f.depthClamp = clamp;
            f.textures.push_back(
                Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 11));
            Pass p;
            for (int t = 0; t < 16; ++t)
                for (int v = 0; v < 3; ++v) {
                    glm::vec4 pos(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1), 1);
                    if (k == 0 && v == 0) pos.w = rng.Uniform(-1e-3f, 1e-3f);
                    if (k == 1 && v < 2) pos.w = rng.Uniform(-2.0f, -0.1f);
                    if (k == 2) pos = glm::vec4(glm::vec3(pos) * 1e6f, 1.0f);
                    if (k == 3) pos.z = rng.Uniform(-3.0f, 3.0f);
                    const glm::vec3 d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
                    p.vertices.push_back(V(pos, d));
                }
            f.passes.push_back(p);
            out->push_back({std::string(names[k]) + (clamp ? "_clamp" : ""), f});
        }
}

// Two texture units: cube times a 1D table (N x 1), 2D times 2D; untextured passes. -------
void TwoUnits(std::vector<NamedCase>* out) {
    Frame f = NewFrame(96, 64);
    f.textures.push_back(Cube(32, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 21));
    SamplerState table = Sampler(Filter::Linear, MipFilter::None, Filter::Linear);
    f.textures.push_back(MakeTexture(TextureKind::Tex2D, 64, 1, table, 22));
    SamplerState tile = Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear);
    tile.wrapS = tile.wrapT = Wrap::Repeat;
    f.textures.push_back(MakeTexture(TextureKind::Tex2D, 16, 16, tile, 23));
    Pass p;
    p.numUnits = 2;
    p.texture = {0, 1};
    Rng rng{5};
    AddSphere(&p, 16, 24, 1.5f, {0.3f, 0.6f, 3.0f}, {0, 0, 0}, 1.0f, 1.0f);
    for (Vertex& v : p.vertices) v.coord[1] = glm::vec3(rng.Uniform(0, 1), 0.5f, 0);
    f.passes.push_back(p);
    Pass q;
    q.numUnits = 2;
    q.texture = {2, 1};
    q.blend = BlendState::Additive();
    const glm::vec3 c0[4] = {{0, 0, 0}, {3, 0, 0}, {3, 2, 0}, {0, 2, 0}};
    const glm::vec3 c1[4] = {{0, 0.5f, 0}, {1, 0.5f, 0}, {1, 0.5f, 0}, {0, 0.5f, 0}};
    AddQuad(&q, -1, -1, 1, -0.3f, c0, glm::vec4(0.7f, 0.9f, 1.0f, 1.0f), c1);
    f.passes.push_back(q);
    Pass u;
    u.numUnits = 0;
    u.blend = BlendState::Over();
    const glm::vec3 z[4] = {};
    AddQuad(&u, 0.2f, 0.2f, 0.9f, 0.9f, z, glm::vec4(0.9f, 0.2f, 0.1f, 0.5f));
    f.passes.push_back(u);
    out->push_back({"two_units", f});
}

// Odd framebuffer sizes (quads and 4x2 lane groups cut by the edge). -------------------------
void OddSizes(std::vector<NamedCase>* out) {
    for (auto [w, h] : {std::pair{61, 37}, std::pair{1, 1}, std::pair{3, 5}, std::pair{127, 2}}) {
        Frame f = NewFrame(w, h);
        f.textures.push_back(
            Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 31));
        Pass p;
        AddSphere(&p, 12, 16, static_cast<float>(w) / static_cast<float>(h), {0.1f, 0.3f, 2.5f},
                  {0, 0, 0}, 1.0f, 1.0f);
        f.passes.push_back(p);
        out->push_back({"odd_" + std::to_string(w) + "x" + std::to_string(h), f});
    }
}

// Depth -------------------------------------------------------------------------------------------

constexpr DepthFormat kDepthFormats[3] = {DepthFormat::Z16, DepthFormat::Z24, DepthFormat::Z32F};

const char* DepthFormatName(DepthFormat f) {
    static const char* names[3] = {"z16", "z24", "z32f"};
    return names[static_cast<int>(f)];
}

const char* DepthFuncName(DepthFunc f) {
    static const char* names[8] = {"never",   "less",     "equal",  "lequal",
                                   "greater", "notequal", "gequal", "always"};
    return names[static_cast<int>(f)];
}

Frame DepthFrame(int w, int h, DepthFormat format, float clear) {
    Frame f = NewFrame(w, h, {20, 30, 40, 255});
    f.depth = DepthBuffer{format, clear};
    return f;
}

Pass DepthPass(DepthFunc func, bool write, const BlendState& blend = BlendState::None()) {
    Pass p;
    p.depthTest = DepthTest{func, write};
    p.blend = blend;
    return p;
}

glm::vec4 RandomColour(Rng* rng) {
    return {rng->Uniform(0.1f, 1), rng->Uniform(0.1f, 1), rng->Uniform(0.1f, 1),
            rng->Uniform(0.3f, 1)};
}

glm::vec3 RandomDirection(Rng* rng) {
    return {rng->Uniform(-1, 1), rng->Uniform(-1, 1), rng->Uniform(-1, 1)};
}

// n random triangles, every vertex with its own clip z in [zLo, zHi] * w (so overlapping
// triangles interpenetrate) and w in [wLo, wHi].
void AddDepthTriangles(Pass* p, Rng* rng, int n, float zLo, float zHi, float wLo = 1.0f,
                       float wHi = 1.0f) {
    for (int t = 0; t < 3 * n; ++t) {
        const float w = rng->Uniform(wLo, wHi);
        const glm::vec4 pos(rng->Uniform(-1.2f, 1.2f) * w, rng->Uniform(-1.2f, 1.2f) * w,
                            rng->Uniform(zLo, zHi) * w, w);
        p->vertices.push_back(V(pos, RandomDirection(rng), RandomColour(rng)));
    }
}

// A quad over the clip rectangle [x0,x1]x[y0,y1] at w = 1 whose window depth runs linearly
// from zLeft (x0) to zRight (x1) and from zBottom to zTop: window z = zw, clip z = 2 zw - 1.
void AddDepthQuad(Pass* p, float x0, float y0, float x1, float y1, float zLeft, float zRight,
                  float zBottom, float zTop, const glm::vec4& col) {
    const float zw[4] = {zLeft + zBottom, zRight + zBottom, zRight + zTop, zLeft + zTop};
    const glm::vec2 xy[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k : {0, 1, 2, 0, 2, 3}) {
        const glm::vec4 pos(xy[k].x, xy[k].y, 2.0f * zw[k] - 1.0f, 1.0f);
        p->vertices.push_back(V(pos, glm::vec3(xy[k], 1.0f), col));
    }
}

// Every compare function on every format: a buffer built by random interpenetrating triangles
// (LESS, writes), then half of them drawn again at the same positions (exact ties) and new ones
// with the function under test, writes on for every other function.
void DepthFunctions(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats)
        for (int fi = 0; fi < 8; ++fi) {
            const auto func = static_cast<DepthFunc>(fi);
            Rng rng{8000 + static_cast<uint64_t>(fi) + 16 * static_cast<uint64_t>(format)};
            Frame f = DepthFrame(64, 48, format, 0.5f);
            f.textures.push_back(
                Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 81));
            f.textures.push_back(
                Cube(8, Sampler(Filter::Linear, MipFilter::None, Filter::Linear), 82));
            Pass base = DepthPass(DepthFunc::Less, true);
            AddDepthTriangles(&base, &rng, 10, -1.0f, 1.0f);
            Pass test =
                DepthPass(func, fi % 2 == 1, fi % 4 < 2 ? BlendState::None() : BlendState::Over());
            test.texture[0] = 1;
            for (size_t v = 0; v < base.vertices.size() / 2; ++v) {
                Vertex again = base.vertices[v];
                again.color = RandomColour(&rng);
                test.vertices.push_back(again);
            }
            test.vertices.resize(test.vertices.size() / 3 * 3);
            AddDepthTriangles(&test, &rng, 6, -1.0f, 1.0f);
            f.passes = {base, test};
            out->push_back(
                {std::string("depth_") + DepthFuncName(func) + "_" + DepthFormatName(format), f});
        }
}

// Clear values 0, 1, 0.3 and 1/3: quads whose depth crosses the clear value, coarsely (a
// visible boundary) and finely (a few buffer units across the frame: the conversion's rounding
// of the fragment and of the clear value decide each pixel).
void DepthClears(std::vector<NamedCase>* out) {
    const float clears[4] = {0.0f, 1.0f, 0.3f, 1.0f / 3.0f};
    const char* names[4] = {"0", "1", "0_3", "third"};
    for (DepthFormat format : kDepthFormats)
        for (int k = 0; k < 4; ++k) {
            const float c = clears[k];
            const float unit = format == DepthFormat::Z16   ? 1.0f / 65535.0f
                               : format == DepthFormat::Z24 ? 1.0f / 16777215.0f
                                                            : 6e-8f;
            Frame f = DepthFrame(64, 32, format, c);
            const DepthFunc first = k == 0 ? DepthFunc::Greater : DepthFunc::Less;
            Pass coarse = DepthPass(first, false);
            coarse.numUnits = 0;
            AddDepthQuad(&coarse, -1, 0, 1, 1, c - 0.05f, c + 0.05f, 0, 0, {1, 0.2f, 0.2f, 1});
            Pass fine = DepthPass(k == 1 ? DepthFunc::LEqual : DepthFunc::GEqual, false);
            fine.numUnits = 0;
            AddDepthQuad(&fine, -1, -1, 1, 0, c - 3 * unit, c + 3 * unit, -unit, unit,
                         {0.2f, 1, 0.4f, 1});
            Pass equal = DepthPass(DepthFunc::Equal, false, BlendState::Additive());
            equal.numUnits = 0;
            AddDepthQuad(&equal, -1, -1, 1, 1, c - 4 * unit, c + 4 * unit, -2 * unit, 2 * unit,
                         {0.1f, 0.1f, 0.9f, 1});
            f.passes = {coarse, fine, equal};
            out->push_back(
                {std::string("depth_clear_") + names[k] + "_" + DepthFormatName(format), f});
        }
    // A subnormal Z32F clear value compares as 0 (DAZ): fragments clamped to exactly 0 fail
    // LESS and pass LEQUAL.
    Frame f = DepthFrame(48, 32, DepthFormat::Z32F, 1e-40f);
    f.depthClamp = true;
    Pass less = DepthPass(DepthFunc::Less, false);
    less.numUnits = 0;
    AddDepthQuad(&less, -1, 0, 1, 1, -0.5f, 0.5f, 0, 0, {1, 0.2f, 0.2f, 1});
    Pass lequal = DepthPass(DepthFunc::LEqual, false);
    lequal.numUnits = 0;
    AddDepthQuad(&lequal, -1, -1, 1, 0, -0.5f, 0.5f, 0, 0, {0.2f, 1, 0.2f, 1});
    f.passes = {less, lequal};
    out->push_back({"depth_clear_subnormal_z32f", f});
}

// The multipass pattern: a sphere writes depth, an occluder in front of part of it too, then
// the same sphere geometry is drawn again with EQUAL (and LEQUAL) without writes, with other
// textures and blending. The sphere is cut by the near plane and the frame edge.
void DepthMultipass(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats)
        for (bool clamp : {false, true}) {
            Frame f = DepthFrame(96, 72, format, 1.0f);
            f.depthClamp = clamp;
            f.textures.push_back(
                Cube(32, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 91));
            f.textures.push_back(
                Cube(16, Sampler(Filter::Nearest, MipFilter::Nearest, Filter::Linear), 92));
            SamplerState tile = Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear);
            tile.wrapS = tile.wrapT = Wrap::Repeat;
            f.textures.push_back(MakeTexture(TextureKind::Tex2D, 16, 16, tile, 93));
            Pass sphere = DepthPass(DepthFunc::Less, true);
            AddSphere(&sphere, 20, 28, 96.0f / 72.0f, {0.1f, 0.05f, 1.05f}, {0.1f, 0, 0}, 1.0f,
                      1.0f);
            Pass occluder = DepthPass(DepthFunc::Less, true);
            occluder.texture[0] = 2;
            const glm::vec3 c[4] = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}};
            const glm::vec4 pos[4] = {{-0.9f, -0.8f, -0.2f, 1},
                                      {0.2f, -0.8f, 0.3f, 1},
                                      {0.2f, 0.1f, 0.3f, 1},
                                      {-0.9f, 0.1f, -0.2f, 1}};
            for (int k : {0, 1, 2, 0, 2, 3}) occluder.vertices.push_back(V(pos[k], c[k]));
            Pass equal = sphere;
            equal.depthTest = DepthTest{DepthFunc::Equal, false};
            equal.texture[0] = 1;
            equal.blend = BlendState::Additive();
            Pass lequal = sphere;
            lequal.depthTest = DepthTest{DepthFunc::LEqual, false};
            lequal.numUnits = 2;
            lequal.texture = {0, 2};
            for (Vertex& v : lequal.vertices) v.coord[1] = glm::vec3(v.coord[0].x, v.coord[0].y, 0);
            lequal.blend = BlendState::Multiply();
            f.passes = {sphere, occluder, equal, lequal};
            out->push_back({std::string("depth_multipass_") + DepthFormatName(format) +
                                (clamp ? "_clamp" : ""),
                            f});
        }
}

// Geometry crossing the near and far planes, with and without GL_DEPTH_CLAMP (clamped fragments
// sit at exactly 0 or 1), tested with LESS, then GEQUAL and GREATER against the clear value.
void DepthClamp(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats)
        for (bool clamp : {false, true}) {
            Rng rng{8500 + static_cast<uint64_t>(format) * 2 + (clamp ? 1 : 0)};
            Frame f = DepthFrame(72, 56, format, 1.0f);
            f.depthClamp = clamp;
            f.textures.push_back(
                Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 95));
            Pass p = DepthPass(DepthFunc::Less, true);
            AddDepthTriangles(&p, &rng, 12, -3.0f, 3.0f, 0.5f, 2.0f);
            Pass q = DepthPass(DepthFunc::GEqual, false, BlendState::Additive());
            AddDepthTriangles(&q, &rng, 8, -3.0f, 3.0f, 0.5f, 2.0f);
            Pass r = DepthPass(DepthFunc::Greater, true, BlendState::Over());
            AddDepthTriangles(&r, &rng, 8, -1.5f, 1.5f);
            f.passes = {p, q, r};
            out->push_back({std::string("depth_near_far_") + DepthFormatName(format) +
                                (clamp ? "_clamp" : "_clip"),
                            f});
        }
}

// Steep depth slopes (triangles almost edge-on: z from 0 to 1 within a few pixels) crossing
// shallow ones, and long slivers.
void DepthSteep(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats) {
        Rng rng{8600 + static_cast<uint64_t>(format)};
        Frame f = DepthFrame(64, 64, format, 1.0f);
        Pass p = DepthPass(DepthFunc::Less, true);
        p.numUnits = 0;
        for (int t = 0; t < 12; ++t) {
            const float x = rng.Uniform(-0.9f, 0.9f), y = rng.Uniform(-0.9f, 0.9f);
            const float dx = rng.Uniform(0.03f, 0.25f), len = rng.Uniform(0.5f, 1.5f);
            const glm::vec4 col = RandomColour(&rng);
            const bool vertical = t % 2 == 0;
            const glm::vec4 a =
                vertical ? glm::vec4(x, y - len, -1, 1) : glm::vec4(x - len, y, -1, 1);
            const glm::vec4 b =
                vertical ? glm::vec4(x + dx, y - len, 1, 1) : glm::vec4(x - len, y + dx, 1, 1);
            const glm::vec4 c = vertical ? glm::vec4(x, y + len, rng.Uniform(-1, 1), 1)
                                         : glm::vec4(x + len, y, rng.Uniform(-1, 1), 1);
            for (const glm::vec4& pos : {a, b, c}) p.vertices.push_back(V(pos, {}, col));
        }
        Pass shallow = DepthPass(DepthFunc::LEqual, true, BlendState::Over());
        shallow.numUnits = 0;
        AddDepthQuad(&shallow, -1, -1, 1, 1, 0.2f, 0.8f, 0.1f, -0.1f, {0.9f, 0.9f, 0.2f, 0.7f});
        f.passes = {p, shallow};
        out->push_back({std::string("depth_steep_") + DepthFormatName(format), f});
    }
}

// Tiny and huge w: perspective-divided depth with w from 1e-3 and up to 1e6.
void DepthExtremeW(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats)
        for (bool huge : {false, true}) {
            Rng rng{8700 + static_cast<uint64_t>(format) * 2 + (huge ? 1 : 0)};
            Frame f = DepthFrame(64, 48, format, 1.0f);
            f.textures.push_back(
                Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 97));
            Pass p = DepthPass(DepthFunc::Less, true);
            AddDepthTriangles(&p, &rng, 12, -1.0f, 1.0f, huge ? 1e4f : 1e-3f, huge ? 1e6f : 1e-2f);
            Pass q = DepthPass(DepthFunc::LEqual, false, BlendState::Additive());
            for (size_t v = 0; v < p.vertices.size(); ++v) {
                Vertex again = p.vertices[(v + 3) % p.vertices.size()];
                again.color = RandomColour(&rng);
                q.vertices.push_back(again);
            }
            f.passes = {p, q};
            out->push_back(
                {std::string("depth_w_") + (huge ? "huge_" : "tiny_") + DepthFormatName(format),
                 f});
        }
}

// Writes on and off and passes without a depth test (which neither test nor write), over
// interpenetrating triangles; a final pass tests GREATER against what is left.
void DepthWrites(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats) {
        Rng rng{8800 + static_cast<uint64_t>(format)};
        Frame f = DepthFrame(64, 64, format, 0.75f);
        f.textures.push_back(
            Cube(16, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 98));
        Pass noWrite = DepthPass(DepthFunc::Less, false);
        AddDepthTriangles(&noWrite, &rng, 8, -1.0f, 1.0f);
        Pass untested;
        AddDepthTriangles(&untested, &rng, 4, -1.0f, 1.0f);
        Pass write = DepthPass(DepthFunc::Less, true);
        AddDepthTriangles(&write, &rng, 10, -1.0f, 1.0f);
        Pass greater = DepthPass(DepthFunc::Greater, false, BlendState::Additive());
        AddDepthTriangles(&greater, &rng, 8, -1.0f, 1.0f);
        f.passes = {noWrite, untested, write, greater};
        out->push_back({std::string("depth_writes_") + DepthFormatName(format), f});
    }
}

// Two intersecting spheres and crossing planes (pixel-exact intersection curves), in an odd
// framebuffer size; every format.
void DepthIntersections(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats) {
        Frame f = DepthFrame(61, 37, format, 1.0f);
        f.textures.push_back(
            Cube(32, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear), 99));
        Pass a = DepthPass(DepthFunc::Less, true);
        AddSphere(&a, 14, 18, 61.0f / 37.0f, {0.0f, 0.3f, 3.0f}, {-0.35f, 0, 0}, 0.8f, 1.0f);
        Pass b = DepthPass(DepthFunc::Less, true);
        AddSphere(&b, 12, 16, 61.0f / 37.0f, {0.0f, 0.3f, 3.0f}, {0.4f, 0.1f, 0.2f}, 0.7f, -1.0f);
        Pass planes = DepthPass(DepthFunc::LEqual, true, BlendState::Over());
        planes.numUnits = 0;
        // Window depths of the spheres: about 0.955..0.97 (near 0.1, far 100, distance 2.2..3.8).
        AddDepthQuad(&planes, -1, -1, 1, 1, 0.955f, 0.966f, 0, 0, {0.9f, 0.3f, 0.3f, 0.6f});
        AddDepthQuad(&planes, -1, -1, 1, 1, 0.966f, 0.955f, -0.002f, 0.002f,
                     {0.3f, 0.9f, 0.3f, 0.6f});
        f.passes = {a, b, planes};
        out->push_back({std::string("depth_intersect_") + DepthFormatName(format), f});
    }
}

void Depth(std::vector<NamedCase>* out) {
    DepthFunctions(out);
    DepthClears(out);
    DepthMultipass(out);
    DepthClamp(out);
    DepthSteep(out);
    DepthExtremeW(out);
    DepthWrites(out);
    DepthIntersections(out);
}

// Anisotropic filtering ------------------------------------------------------------------------

SamplerState Aniso(Filter min, MipFilter mip, Filter mag, float maxAniso, bool seamless = true) {
    SamplerState s = Sampler(min, mip, mag, seamless);
    s.maxAnisotropy = maxAniso;
    return s;
}

const char* MagName(Filter mag) {
    return mag == Filter::Linear ? "linear" : "nearest";
}

// A ground plane y = -1 from just in front of the eye to the horizon (perspective, the eye at
// the origin looking down -z, tilted down by `pitchDeg`): coordinates (x, z) * scale for a 2D
// unit, or the direction (x, -1, z) for a cube unit (its -Y face seen at grazing angles, the
// side faces near the horizon). Footprints grow without bound towards the horizon along z.
void AddGroundPlane(Pass* p, float aspect, float pitchDeg, float scale, bool cubeDirs,
                    bool swapST = false, int tiles = 4) {
    const glm::mat4 proj = glm::perspective(glm::radians(50.0f), aspect, 0.1f, 200.0f);
    const glm::mat4 view = glm::rotate(glm::mat4(1.0f), glm::radians(pitchDeg), glm::vec3(1, 0, 0));
    const glm::mat4 vp = proj * view;
    const float xs[2] = {-60.0f, 60.0f};
    auto vertex = [&](float x, float z) {
        const glm::vec3 pos(x, -1.0f, z);
        const glm::vec2 st = swapST ? glm::vec2(z, x) : glm::vec2(x, z);
        const glm::vec3 c = cubeDirs ? pos : glm::vec3(st * scale, 0.0f);
        return V(vp * glm::vec4(pos, 1.0f), c);
    };
    // Tiles in z (near to far), so the far ones are small in clip space.
    float z0 = -0.3f;
    for (int k = 0; k < tiles; ++k) {
        const float z1 = z0 * 4.0f;
        const Vertex a = vertex(xs[0], z0), b = vertex(xs[1], z0), c = vertex(xs[1], z1),
                     d = vertex(xs[0], z1);
        const uint32_t base = static_cast<uint32_t>(p->vertices.size());
        for (const Vertex& v : {a, b, c, d}) p->vertices.push_back(v);
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) p->indices.push_back(base + i);
        z0 = z1;
    }
}

// A vertical mirror cylinder (radius 1, height 2.4) seen from the side; texture coordinate =
// reflection vector (cube) — stretched strongly across the cylinder near its silhouettes.
void AddMirrorCylinder(Pass* p, int segs, float aspect, const glm::vec3& eye) {
    const glm::mat4 proj = glm::perspective(glm::radians(40.0f), aspect, 0.1f, 100.0f);
    const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const glm::mat4 vp = proj * view;
    auto vertex = [&](int j, float y) {
        const float ph = 6.28318531f * static_cast<float>(j) / static_cast<float>(segs);
        const glm::vec3 n(std::cos(ph), 0.0f, std::sin(ph));
        const glm::vec3 pos(n.x, y, n.z);
        const glm::vec3 in = glm::normalize(pos - eye);
        return V(vp * glm::vec4(pos, 1.0f), in - 2.0f * glm::dot(n, in) * n);
    };
    for (int j = 0; j < segs; ++j) {
        const Vertex a = vertex(j, -1.2f), b = vertex(j + 1, -1.2f), c = vertex(j + 1, 1.2f),
                     d = vertex(j, 1.2f);
        const uint32_t base = static_cast<uint32_t>(p->vertices.size());
        for (const Vertex& v : {a, b, c, d}) p->vertices.push_back(v);
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) p->indices.push_back(base + i);
    }
}

// 2D: every min/mag/mip filter on a ground plane (wraps cycled), max_anisotropy 16. Without a
// MIP filter every footprint stays on level 0, so those planes are textured more coarsely; one
// plane at the finer scale keeps level-0 footprints tens of thousands of texels long (the quads
// at the far edge, whose helper pixels extrapolate towards the horizon).
void AnisoPlanes2D(std::vector<NamedCase>* out) {
    const Filter filters[2] = {Filter::Nearest, Filter::Linear};
    const MipFilter mips[3] = {MipFilter::None, MipFilter::Nearest, MipFilter::Linear};
    const Wrap wraps[3] = {Wrap::Repeat, Wrap::MirroredRepeat, Wrap::ClampToEdge};
    const char* wrapNames[3] = {"repeat", "mirror", "clamp"};
    uint64_t seed = 12000;
    int k = 0;
    for (Filter min : filters)
        for (MipFilter mip : mips)
            for (Filter mag : filters) {
                const int wi = k++ % 3;
                Frame f = NewFrame(64, 48);
                SamplerState s = Aniso(min, mip, mag, 16.0f);
                s.wrapS = wraps[wi];
                s.wrapT = wraps[(wi + 1) % 3];
                f.textures.push_back(MakeTexture(TextureKind::Tex2D, 64, 64, s, ++seed));
                Pass p;
                AddGroundPlane(&p, 64.0f / 48.0f, 8.0f, mip == MipFilter::None ? 0.03f : 0.25f,
                               false);
                f.passes.push_back(p);
                out->push_back({std::string("aniso_plane2d_") + FilterName(min, mip) + "_mag_" +
                                    MagName(mag) + "_" + wrapNames[wi],
                                f});
            }
    Frame f = NewFrame(64, 48);
    SamplerState s = Aniso(Filter::Nearest, MipFilter::None, Filter::Nearest, 16.0f);
    s.wrapS = s.wrapT = Wrap::Repeat;
    f.textures.push_back(MakeTexture(TextureKind::Tex2D, 64, 64, s, ++seed));
    Pass p;
    AddGroundPlane(&p, 64.0f / 48.0f, 8.0f, 0.25f, false);
    f.passes.push_back(p);
    out->push_back({"aniso_plane2d_level0_horizon", f});
}

// 2D: the GL value (off below 2, truncated, clamped to 16), LOD bias and clamps, textures whose
// deep levels are thinner than one texel, magnification, two units.
void AnisoValues2D(std::vector<NamedCase>* out) {
    uint64_t seed = 12100;
    const float values[] = {2.0f, 4.0f, 8.0f, 16.0f, 1.5f, 1.0f, 2.5f, 7.3f, 100.0f};
    const char* names[] = {"2", "4", "8", "16", "1_5", "1", "2_5", "7_3", "100"};
    for (size_t i = 0; i < std::size(values); ++i) {
        Frame f = NewFrame(64, 48);
        SamplerState s = Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, values[i]);
        s.wrapS = s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 64, 64, s, ++seed));
        Pass p;
        AddGroundPlane(&p, 64.0f / 48.0f, 12.0f, 0.5f, false);
        f.passes.push_back(p);
        out->push_back({std::string("aniso_max_") + names[i], f});
    }
    struct Lod {
        const char* name;
        float bias, minLod, maxLod;
        MipFilter mip;
        Filter min, mag;
    };
    const Lod lods[] = {
        {"bias_plus1_3", 1.3f, -1000, 1000, MipFilter::Linear, Filter::Linear, Filter::Linear},
        {"bias_minus2", -2.0f, -1000, 1000, MipFilter::Linear, Filter::Linear, Filter::Linear},
        {"bias_0_37_nearest", 0.37f, -1000, 1000, MipFilter::Nearest, Filter::Nearest,
         Filter::Nearest},
        {"min_lod_1_5", 0.0f, 1.5f, 1000, MipFilter::Linear, Filter::Linear, Filter::Linear},
        {"max_lod_1", 0.0f, -1000, 1.0f, MipFilter::Linear, Filter::Linear, Filter::Linear},
        {"min_eq_max_2", 0.0f, 2.0f, 2.0f, MipFilter::Linear, Filter::Linear, Filter::Linear},
        {"min_gt_max", 0.0f, 3.0f, 1.0f, MipFilter::Nearest, Filter::Linear, Filter::Linear},
        {"bias_minus1_none", -1.0f, -1000, 1000, MipFilter::None, Filter::Linear, Filter::Nearest}};
    for (const Lod& v : lods) {
        Frame f = NewFrame(64, 48);
        SamplerState s = Aniso(v.min, v.mip, v.mag, 8.0f);
        s.lodBias = v.bias;
        s.minLod = v.minLod;
        s.maxLod = v.maxLod;
        s.wrapS = s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 32, 32, s, ++seed));
        Pass p;
        AddGroundPlane(&p, 64.0f / 48.0f, 10.0f, 0.4f, false);
        f.passes.push_back(p);
        out->push_back({std::string("aniso_lod_") + v.name, f});
    }
    // Non-square: the level size llvmpipe scales the coordinates by drops below one texel (in t
    // for the wide ones; in s for the tall one, whose s runs along the view).
    for (auto [w, h] : {std::pair{64, 4}, std::pair{4, 64}, std::pair{128, 1}}) {
        Frame f = NewFrame(64, 48);
        SamplerState s = Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, 16.0f);
        s.wrapS = Wrap::MirroredRepeat;
        s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, w, h, s, ++seed));
        Pass p;
        const bool tall = h > w;
        AddGroundPlane(&p, 64.0f / 48.0f, 6.0f, tall ? 1.0f : 0.3f, false, tall);
        f.passes.push_back(p);
        out->push_back({"aniso_nonsquare_" + std::to_string(w) + "x" + std::to_string(h), f});
    }
    // Magnification (level 0, small ellipses) on a tilted quad, with and without a MIP filter.
    for (MipFilter mip : {MipFilter::Linear, MipFilter::None}) {
        Frame f = NewFrame(64, 64);
        f.textures.push_back(MakeTexture(
            TextureKind::Tex2D, 8, 8, Aniso(Filter::Linear, mip, Filter::Nearest, 4.0f), ++seed));
        Pass p;
        const glm::vec3 c[4] = {{0.1f, 0.2f, 0}, {0.9f, 0.1f, 0}, {0.8f, 0.6f, 0}, {0.2f, 0.5f, 0}};
        const glm::vec4 pos[4] = {
            {-1, -1, 0, 1}, {1, -1, 0, 1}, {2.0f, 2.0f, 0, 2}, {-2.0f, 2.0f, 0, 2}};
        for (int k : {0, 1, 2, 0, 2, 3}) p.vertices.push_back(V(pos[k], c[k]));
        f.passes.push_back(p);
        out->push_back({std::string("aniso_magnify_") + FilterName(Filter::Linear, mip), f});
    }
    // Coordinates near 2^31 texels: boxes whose far edge overflows int32 hold no texel, and
    // llvmpipe filters those pixels bilinearly.
    {
        Frame f = NewFrame(64, 32);
        SamplerState s = Aniso(Filter::Linear, MipFilter::None, Filter::Linear, 16.0f);
        s.wrapS = s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 64, 64, s, ++seed));
        Pass p;
        const float big = 33554430.0f;  // * 64 texels: just below 2^31
        const glm::vec3 c[4] = {
            {big - 40.0f, 0, 0}, {big + 8.0f, 0, 0}, {big + 8.0f, 0.5f, 0}, {big - 40.0f, 0.5f, 0}};
        AddQuad(&p, -1, -1, 1, 1, c);
        f.passes.push_back(p);
        out->push_back({"aniso_coords_beyond_int32", f});
    }
    // A wall receding to the right (w from 1 to 4): LODs differ between the two quads of a
    // lane block, so without a MIP filter the second quad takes the first quad's level.
    const std::tuple<Filter, MipFilter, Filter> walls[] = {
        {Filter::Linear, MipFilter::None, Filter::Nearest},
        {Filter::Nearest, MipFilter::None, Filter::Linear},
        {Filter::Linear, MipFilter::Linear, Filter::Linear},
        {Filter::Nearest, MipFilter::Nearest, Filter::Linear}};
    for (const auto& [min, mip, mag] : walls) {
        Frame f = NewFrame(64, 48);
        SamplerState s = Aniso(min, mip, mag, 16.0f);
        s.wrapS = s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 32, 32, s, ++seed));
        Pass p;
        const glm::vec3 c[4] = {{0, 0, 0}, {6, 0, 0}, {6, 1.5f, 0}, {0, 1.5f, 0}};
        const glm::vec4 pos[4] = {
            {-1, -1, 0, 1}, {3.6f, -3.6f, 0, 4}, {3.6f, 3.6f, 0, 4}, {-1, 1, 0, 1}};
        for (int k : {0, 1, 2, 0, 2, 3}) p.vertices.push_back(V(pos[k], c[k]));
        f.passes.push_back(p);
        out->push_back(
            {std::string("aniso_wall_") + FilterName(min, mip) + "_mag_" + MagName(mag), f});
    }
    // Two units: a 2D plane texture with anisotropy times a plain 1D table.
    {
        Frame f = NewFrame(64, 48);
        SamplerState s = Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, 16.0f);
        s.wrapS = s.wrapT = Wrap::Repeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 32, 32, s, ++seed));
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 16, 1,
                                         Sampler(Filter::Linear, MipFilter::None, Filter::Linear),
                                         ++seed));
        Pass p;
        AddGroundPlane(&p, 64.0f / 48.0f, 8.0f, 0.5f, false);
        p.numUnits = 2;
        p.texture = {0, 1};
        Rng rng{seed};
        for (Vertex& v : p.vertices) v.coord[1] = glm::vec3(rng.Uniform(0, 1), 0.5f, 0);
        f.passes.push_back(p);
        out->push_back({"aniso_two_units", f});
    }
    // Two anisotropic units: a mirror sphere's cube map times a 2D texture addressed by the
    // same reflection vector.
    {
        Frame f = NewFrame(80, 64);
        f.textures.push_back(
            Cube(32, Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, 8.0f), ++seed));
        SamplerState s = Aniso(Filter::Linear, MipFilter::Nearest, Filter::Linear, 4.0f);
        s.wrapS = s.wrapT = Wrap::MirroredRepeat;
        f.textures.push_back(MakeTexture(TextureKind::Tex2D, 32, 16, s, ++seed));
        Pass p;
        AddSphere(&p, 20, 24, 80.0f / 64.0f, {0.3f, 0.6f, 3.0f}, {0, 0, 0}, 1.0f, 1.0f);
        p.numUnits = 2;
        p.texture = {0, 1};
        for (Vertex& v : p.vertices) v.coord[1] = glm::vec3(v.coord[0].x * 2.0f, v.coord[0].y, 0);
        f.passes.push_back(p);
        out->push_back({"aniso_two_units_cube_2d", f});
    }
}

// Cubes: mirror spheres with every filter (seamless and not), a mirror cylinder with each
// max_anisotropy, a cube floor at grazing angles, LOD controls, cube edges and corners.
void AnisoCubes(std::vector<NamedCase>* out) {
    const Filter filters[2] = {Filter::Nearest, Filter::Linear};
    const MipFilter mips[3] = {MipFilter::None, MipFilter::Nearest, MipFilter::Linear};
    uint64_t seed = 12500;
    for (bool seamless : {true, false})
        for (Filter min : filters)
            for (MipFilter mip : mips)
                for (Filter mag : filters) {
                    if (!seamless && mag != min) continue;
                    Frame f = NewFrame(96, 80);
                    f.textures.push_back(Cube(32, Aniso(min, mip, mag, 16.0f, seamless), ++seed));
                    Pass p;
                    AddSphere(&p, 24, 32, 96.0f / 80.0f, {0.3f, 0.8f, 3.2f}, {0, 0, 0}, 1.0f, 1.0f);
                    f.passes.push_back(p);
                    out->push_back({std::string("aniso_sphere_") + FilterName(min, mip) + "_mag_" +
                                        MagName(mag) + (seamless ? "_seamless" : "_plain"),
                                    f});
                }
    const float values[] = {2.0f, 4.0f, 8.0f, 16.0f, 3.7f};
    const char* names[] = {"2", "4", "8", "16", "3_7"};
    for (size_t i = 0; i < std::size(values); ++i)
        for (bool seamless : {true, false}) {
            if (!seamless && i != 3) continue;
            Frame f = NewFrame(96, 64);
            f.textures.push_back(Cube(
                64, Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, values[i], seamless),
                ++seed));
            Pass p;
            AddMirrorCylinder(&p, 48, 96.0f / 64.0f, {0.4f, 0.6f, 3.4f});
            f.passes.push_back(p);
            out->push_back(
                {std::string("aniso_cylinder_") + names[i] + (seamless ? "_seamless" : "_plain"),
                 f});
        }
    for (MipFilter mip : mips)
        for (bool seamless : {true, false}) {
            Frame f = NewFrame(80, 60);
            const Filter mag = mip == MipFilter::None ? Filter::Nearest : Filter::Linear;
            f.textures.push_back(
                Cube(64, Aniso(Filter::Linear, mip, mag, 16.0f, seamless), ++seed));
            Pass p;
            AddGroundPlane(&p, 80.0f / 60.0f, 5.0f, 1.0f, true);
            f.passes.push_back(p);
            out->push_back({std::string("aniso_cube_floor_") + FilterName(Filter::Linear, mip) +
                                (seamless ? "_seamless" : "_plain"),
                            f});
        }
    struct Lod {
        const char* name;
        float bias, minLod, maxLod;
    };
    const Lod lods[] = {{"bias_plus0_6", 0.6f, -1000, 1000},
                        {"bias_minus1_5", -1.5f, -1000, 1000},
                        {"min_lod_2", 0.0f, 2.0f, 1000},
                        {"max_lod_0_5", 0.0f, -1000, 0.5f},
                        {"min_eq_max_1", 0.0f, 1.0f, 1.0f}};
    for (const Lod& v : lods) {
        Frame f = NewFrame(96, 72);
        SamplerState s = Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, 8.0f);
        s.lodBias = v.bias;
        s.minLod = v.minLod;
        s.maxLod = v.maxLod;
        f.textures.push_back(Cube(64, s, ++seed));
        Pass p;
        AddSphere(&p, 20, 24, 96.0f / 72.0f, {0.2f, 0.5f, 4.5f}, {0, 0, 0}, 1.0f, 1.0f);
        f.passes.push_back(p);
        out->push_back({std::string("aniso_cube_lod_") + v.name, f});
    }
    // Random triangles around cube edges and corners on small cubes.
    Rng rng{12900};
    for (int k = 0; k < 4; ++k) {
        const bool seamless = k % 2 == 0;
        const int size = 2 << k;  // 2, 4, 8, 16
        Frame f = NewFrame(64, 64);
        f.textures.push_back(
            Cube(size, Aniso(Filter::Linear, MipFilter::Linear, Filter::Linear, 16.0f, seamless),
                 ++seed));
        f.passes.push_back(EdgeCornerTriangles(&rng, true));
        out->push_back(
            {"aniso_edges_corners_n" + std::to_string(size) + (seamless ? "_seamless" : "_plain"),
             f});
    }
}

void Anisotropy(std::vector<NamedCase>* out) {
    AnisoPlanes2D(out);
    AnisoValues2D(out);
    AnisoCubes(out);
}

// The 2D parameterizations (runtime/parameterization.h) on reflective spheres: lat-long with its
// seam and poles, the sphere map's texgen, and the two-image layouts (two textures, one pass
// each, every triangle in its chart's).
// A coarse sphere shows the lat-long seam's interpolation across the whole map.
void Parameterizations(std::vector<NamedCase>* out) {
    using runtime::Parameterization;
    uint64_t seed = 1800;
    for (Parameterization p : runtime::kParameterizations) {
        if (p == Parameterization::Cube) continue;  // the cube: every other sphere case
        for (auto [min, mip, mag, rings, segs] :
             {std::tuple{Filter::Linear, MipFilter::Linear, Filter::Linear, 24, 32},
              std::tuple{Filter::Nearest, MipFilter::Nearest, Filter::Nearest, 24, 32},
              std::tuple{Filter::Linear, MipFilter::Linear, Filter::Linear, 6, 8}})
            out->push_back({std::string("param_") + std::string(runtime::ParameterizationName(p)) +
                                "_" + FilterName(min, mip) + "_" + std::to_string(rings) + "x" +
                                std::to_string(segs),
                            LayoutSphere(p, 32, Sampler(min, mip, mag), rings, segs, ++seed)});
    }
}

// RGBA32F variants ------------------------------------------------------------------------------

// `t` with RGBA32F texels: every component a random float in [-0.5, 2.5) (24-bit fractions, so
// the filter's products and sums round), same shape and sampler.
Texture FloatTexture(const Texture& t, uint64_t seed) {
    Texture f = t;
    f.format = raster::TexelFormat::Rgba32F;
    Rng rng{seed};
    for (std::vector<uint8_t>& level : f.levels) {
        std::vector<float> values(level.size());
        for (float& v : values) v = rng.Uniform(-0.5f, 2.5f);
        level = raster::FloatBytes(values);
    }
    return f;
}

// Float variants of a spread of the corpus (every case family): every 3rd case with RGBA32F
// textures and colour buffer ("f32_"), every 4th with an RGBA32F colour buffer only ("fb32_":
// 8-bit textures, unclamped float blending), every 5th with RGBA32F textures into RGBA8
// ("tex32_": float filtering, clamped on output; frames with textures).
void FloatFormats(std::vector<NamedCase>* out) {
    const size_t n = out->size();
    for (size_t i = 0; i < n; ++i) {
        const NamedCase c = (*out)[i];
        auto floatTextures = [&](Frame f) {
            for (size_t k = 0; k < f.textures.size(); ++k)
                f.textures[k] = FloatTexture(f.textures[k], 1000 * i + k);
            return f;
        };
        if (i % 3 == 0) {
            Frame f = floatTextures(c.frame);
            f.colorFormat = raster::ColorFormat::Rgba32F;
            out->push_back({"f32_" + c.name, std::move(f)});
        }
        if (i % 4 == 1) {
            Frame f = c.frame;
            f.colorFormat = raster::ColorFormat::Rgba32F;
            out->push_back({"fb32_" + c.name, std::move(f)});
        }
        if (i % 5 == 2 && !c.frame.textures.empty())
            out->push_back({"tex32_" + c.name, floatTextures(c.frame)});
    }
}

// The renderers' layer passes (runtime/README.md): a non-convex mesh drawn with LESS and depth
// writes, replacing the colour, then at the same positions with other coordinates and colours,
// EQUAL without writes, premultiplied over, then once more, additive. The mesh overlaps itself
// (the back of a sphere behind its front, a second sphere through it) and repeats
// every seventh triangle with its own vertices (exact depth ties: the EQUAL passes blend each
// copy, in order). raster/render.cpp draws the first two passes in one traversal
// (FusesWithNext); these cases hold that to llvmpipe. 8-bit and float targets and textures.
void DepthLayers(std::vector<NamedCase>* out) {
    for (DepthFormat format : kDepthFormats)
        for (bool floats : {false, true}) {
            Rng rng{8900 + 2 * static_cast<uint64_t>(format) + (floats ? 1 : 0)};
            Frame f = DepthFrame(80, 64, format, 1.0f);
            const SamplerState trilinear =
                Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear);
            f.textures.push_back(Cube(32, trilinear, 101, true));
            f.textures.push_back(Cube(16, trilinear, 102, true));
            Pass outer = DepthPass(DepthFunc::Less, true);
            const float aspect = 80.0f / 64.0f;
            AddSphere(&outer, 12, 16, aspect, {0.2f, 0.4f, 1.6f}, {0, 0, 0}, 1.0f, 1.0f, &rng);
            AddSphere(&outer, 8, 12, aspect, {0.2f, 0.4f, 1.6f}, {0.5f, 0.2f, 0.3f}, 0.6f, -1.0f);
            const size_t triangles = outer.indices.size() / 3;
            for (size_t t = 0; t < triangles; t += 7)
                for (size_t k = 0; k < 3; ++k) {
                    outer.indices.push_back(static_cast<uint32_t>(outer.vertices.size()));
                    outer.vertices.push_back(outer.vertices[outer.indices[3 * t + k]]);
                }
            Pass inner = outer;
            inner.depthTest = DepthTest{DepthFunc::Equal, false};
            inner.texture[0] = 1;
            inner.blend.enabled = true;
            inner.blend.dstRgb = inner.blend.dstAlpha = BlendFactor::OneMinusSrcAlpha;
            for (Vertex& v : inner.vertices) {
                v.coord[0] = glm::vec3(v.coord[0].z, -v.coord[0].x, v.coord[0].y);
                v.color = RandomColour(&rng);
            }
            Pass added = inner;
            added.blend = BlendState::Additive();
            for (Vertex& v : added.vertices) v.color = 0.25f * RandomColour(&rng);
            f.passes = {outer, inner, added};
            std::string name = std::string("depth_layers_") + DepthFormatName(format);
            if (floats) {
                for (size_t k = 0; k < f.textures.size(); ++k)
                    f.textures[k] = FloatTexture(f.textures[k], 8950 + k);
                f.colorFormat = raster::ColorFormat::Rgba32F;
                name = "f32_" + name;
            }
            out->push_back({name, std::move(f)});
        }
}

}  // namespace

Frame LayoutSphere(runtime::Parameterization p, int size, const SamplerState& sampler, int rings,
                   int segments, uint64_t seed) {
    const glm::vec3 eye(0.3f, 0.8f, 3.2f);
    const glm::mat3 eyeFromWorld(glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0)));
    const runtime::MapLayout layout = runtime::LayoutOf(p, size);
    Frame f = NewFrame(96, 80);
    SamplerState s = sampler;
    s.wrapS = layout.wrapS, s.wrapT = layout.wrapT;
    for (int c = 0; c < layout.textures; ++c)
        f.textures.push_back(
            MakeTexture(layout.kind, layout.width, layout.height, s, seed + uint64_t(c) * 7919));
    Pass cube;
    AddSphere(&cube, rings, segments, 96.0f / 80.0f, eye, {0, 0, 0}, 1.0f, 1.0f);
    for (Pass& pass : runtime::ToLayout(cube, 0, p, eyeFromWorld)) f.passes.push_back(pass);
    return f;
}

std::vector<NamedCase> ConformanceCases() {
    std::vector<NamedCase> out;
    Spheres(&out);
    EdgesAndCorners(&out);
    CornerBlocks(&out);
    MinMag(&out);
    Textures2D(&out);
    LodControls(&out);
    Blends(&out);
    Probes(&out);
    Ties(&out);
    Magnitudes(&out);
    Clipping(&out);
    TwoUnits(&out);
    OddSizes(&out);
    Depth(&out);
    Anisotropy(&out);
    Extremes(&out);
    Parameterizations(&out);
    FloatFormats(&out);
    DepthLayers(&out);  // after FloatFormats: makes its own float variants
    return out;
}

Frame BenchmarkFrame(int width, int height, int rings, int segments, int cubeSize) {
    Frame f = NewFrame(width, height);
    f.textures.push_back(
        CheckerCube(cubeSize, Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear)));
    Pass sky;
    const glm::vec3 c[4] = {
        {-1.2f, -0.8f, -1}, {1.2f, -0.8f, -1}, {1.2f, 0.8f, -1}, {-1.2f, 0.8f, -1}};
    AddQuad(&sky, -1, -1, 1, 1, c);
    f.passes.push_back(sky);
    Pass sphere;
    AddSphere(&sphere, rings, segments, static_cast<float>(width) / static_cast<float>(height),
              {0.0f, 0.4f, 3.0f}, {0, 0, 0}, 1.0f, 1.0f);
    f.passes.push_back(sphere);
    return f;
}

Frame LensFrame(int width, int height, int rings, int segments, int cubeSize) {
    Frame f = DepthFrame(width, height, DepthFormat::Z24, 1.0f);
    f.colorFormat = raster::ColorFormat::Rgba32F;
    const SamplerState trilinear = Sampler(Filter::Linear, MipFilter::Linear, Filter::Linear);
    f.textures.push_back(FloatTexture(Cube(cubeSize, trilinear, 9101, true), 9102));
    f.textures.push_back(FloatTexture(Cube(cubeSize, trilinear, 9103, true), 9104));
    Pass outer = DepthPass(DepthFunc::Less, true);
    AddSphere(&outer, rings, segments, static_cast<float>(width) / static_cast<float>(height),
              {0.0f, 0.8f, 6.0f}, {0, 0, 0}, 1.0f, 1.0f);
    Pass inner = outer;  // the next layer: over, where the outer layer is the visible surface
    inner.depthTest = DepthTest{DepthFunc::Equal, false};
    inner.texture[0] = 1;
    inner.blend.enabled = true;
    inner.blend.dstRgb = inner.blend.dstAlpha = BlendFactor::OneMinusSrcAlpha;
    for (Vertex& v : inner.vertices)
        v.coord[0] = glm::vec3(v.coord[0].z, -v.coord[0].x, v.coord[0].y);
    f.passes = {outer, inner};
    return f;
}

}  // namespace pem::test
