// SPDX-License-Identifier: MIT
// depth_test.cpp — raster/depth.h against double-precision references, and depth through the
// renderer:
//  - conversion: a unorm depth value is round-half-even of the exact z * (2^n - 1) (computed in
//    double: at most 48 significant bits, so exact) except where llvmpipe's float product first
//    rounds onto or across a half (a "double rounding"), where it is one unit off and the exact
//    product lies within half a float ulp of the half;
//  - the clear value is round-half-even of clear * (2^n - 1) in double, clamped;
//  - fragment depth is the fused plane clamped to [0, 1]; every compare function;
//  - hidden fragments write nothing (colour, depth) and have no entries in the rendering matrix.
#include "raster/depth.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "raster/render.h"
#include "raster/texel_index.h"
#include "tests/case_generator.h"

namespace pem::raster {
namespace {

double Units(DepthFormat f) {
    return f == DepthFormat::Z16 ? 65535.0 : 16777215.0;
}

// Round half to even of a double (the reference; exact, no libm rounding mode involved).
double RoundHalfEven(double x) {
    const double f = std::floor(x), d = x - f;
    if (d != 0.5) return d < 0.5 ? f : f + 1.0;
    return std::fmod(f, 2.0) == 0.0 ? f : f + 1.0;
}

// Checks DepthFromFloat(f, z) against the exact product; returns 1 for a double-rounding case.
int CheckAgainstExact(DepthFormat f, float z) {
    const double exact = static_cast<double>(z) * Units(f);  // exact: 24 x 24 bits
    const double got = DepthFromFloat(f, z);
    if (got == RoundHalfEven(exact)) return 0;
    // Only where the float product (ulp u at the product's magnitude) can land on or jump over
    // the half: |frac(exact) - 0.5| <= u / 2, and then the result is one unit off.
    const float product = z * static_cast<float>(Units(f));
    const double ulp = static_cast<double>(std::nextafter(product, INFINITY) - product);
    EXPECT_LE(std::fabs(exact - std::floor(exact) - 0.5), ulp / 2) << "z " << z;
    EXPECT_EQ(std::fabs(got - RoundHalfEven(exact)), 1.0) << "z " << z;
    return 1;
}

TEST(DepthConversion, UnormIsExactRoundingBarFloatDoubleRounding) {
    for (DepthFormat f : {DepthFormat::Z16, DepthFormat::Z24}) {
        const double n = Units(f);
        int doubleRounded = 0, checked = 0;
        // Codes, the floats next to every code's midpoint, and a sweep of float bit patterns.
        const uint32_t step = f == DepthFormat::Z16 ? 1 : 97;
        for (uint32_t k = 0; k < static_cast<uint32_t>(n); k += step) {
            const float code = static_cast<float>(k / n);
            const float mid = static_cast<float>((k + 0.5) / n);
            for (float z : {code, mid, std::nextafter(mid, 0.0f), std::nextafter(mid, 1.0f)}) {
                doubleRounded += CheckAgainstExact(f, z);
                ++checked;
            }
        }
        int sweepRounded = 0, swept = 0;
        for (uint32_t bits = 0; bits <= FloatBits(1.0f); bits += 4099) {
            sweepRounded += CheckAgainstExact(f, BitsFloat(bits));
            ++swept;
        }
        // Near the midpoints double rounding is common; over all floats it is rare.
        EXPECT_GT(doubleRounded, checked / 100) << "format " << static_cast<int>(f);
        EXPECT_LT(sweepRounded, swept / 100) << "format " << static_cast<int>(f);
        EXPECT_EQ(DepthFromFloat(f, 0.0f), 0u);
        EXPECT_EQ(DepthFromFloat(f, 1.0f), static_cast<uint32_t>(n));
    }
}

TEST(DepthConversion, Z16MagicNumberIsRoundingOfTheFloatProduct) {
    // fl(fl(z * 65535/65536) + 128)'s low 16 bits = RNE(fl(z * 65535)): scaling by 2^16 commutes
    // with rounding, and the sum's ulp is 2^-16.
    for (uint32_t bits = 0; bits <= FloatBits(1.0f); bits += 61) {
        const float z = BitsFloat(bits);
        ASSERT_EQ(DepthFromFloat(DepthFormat::Z16, z),
                  static_cast<uint32_t>(RoundHalfEven(static_cast<double>(z * 65535.0f))))
            << z;
    }
}

TEST(DepthConversion, CodesRoundTrip) {
    for (DepthFormat f : {DepthFormat::Z16, DepthFormat::Z24})
        for (uint32_t k = 0; k <= static_cast<uint32_t>(Units(f)); ++k)
            ASSERT_EQ(DepthFromFloat(f, static_cast<float>(k / Units(f))), k) << k;
    EXPECT_EQ(DepthFromFloat(DepthFormat::Z32F, 0.3f), FloatBits(0.3f));
}

TEST(DepthClear, RoundsInDoubleAndClamps) {
    for (DepthFormat f : {DepthFormat::Z16, DepthFormat::Z24})
        for (float c : {0.0f, 1.0f, 0.3f, 1.0f / 3.0f, 0.5f, 0.999999f, 1e-7f, 0.7f}) {
            const double expect = RoundHalfEven(static_cast<double>(c) * Units(f));
            EXPECT_EQ(DepthClearValue(f, c), static_cast<uint32_t>(expect)) << c;
        }
    EXPECT_EQ(DepthClearValue(DepthFormat::Z24, 2.0f), 16777215u);
    EXPECT_EQ(DepthClearValue(DepthFormat::Z16, -1.0f), 0u);
    EXPECT_EQ(DepthClearValue(DepthFormat::Z32F, 0.3f), FloatBits(0.3f));
    EXPECT_EQ(DepthClearValue(DepthFormat::Z32F, -0.0f), 0x80000000u);  // CLAMP keeps -0
    EXPECT_EQ(DepthClearValue(DepthFormat::Z32F, 5.0f), FloatBits(1.0f));
}

TEST(FragmentDepth, FusedPlaneClampedToUnitRange) {
    const Plane p{0.25f, 0.01f, -0.02f};
    EXPECT_EQ(FragmentDepth(p, 3, 4), std::fma(-0.02f, 4.0f, std::fma(0.01f, 3.0f, 0.25f)));
    EXPECT_EQ(FragmentDepth({0.9f, 0.1f, 0}, 5, 0), 1.0f);
    EXPECT_EQ(FragmentDepth({0.1f, -0.1f, 0}, 5, 0), 0.0f);
    EXPECT_EQ(FragmentDepth({std::numeric_limits<float>::quiet_NaN(), 0, 0}, 0, 0), 1.0f);
    EXPECT_EQ(FloatBits(FragmentDepth({-0.0f, 0, 0}, 0, 0)), 0u);   // -0 -> +0
    EXPECT_EQ(FloatBits(FragmentDepth({1e-40f, 0, 0}, 0, 0)), 0u);  // subnormal flushed
    EXPECT_EQ(FloatBits(FragmentDepth({0, 1e-39f, 0}, 1, 0)), 0u);  // subnormal input
    EXPECT_EQ(FragmentDepth({0.5f, 0, 0}, 7, 9), 0.5f);
}

TEST(DepthPasses, EveryFunctionInEveryFormat) {
    const bool table[8][3] = {// a < b, a == b, a > b
                              {false, false, false}, {true, false, false}, {false, true, false},
                              {true, true, false},   {false, false, true}, {true, false, true},
                              {false, true, true},   {true, true, true}};
    for (int fi = 0; fi < 8; ++fi) {
        const auto func = static_cast<DepthFunc>(fi);
        for (DepthFormat f : {DepthFormat::Z16, DepthFormat::Z24, DepthFormat::Z32F}) {
            const uint32_t lo = DepthFromFloat(f, 0.25f), hi = DepthFromFloat(f, 0.75f);
            EXPECT_EQ(DepthPasses(func, f, lo, hi), table[fi][0]) << fi;
            EXPECT_EQ(DepthPasses(func, f, lo, lo), table[fi][1]) << fi;
            EXPECT_EQ(DepthPasses(func, f, hi, lo), table[fi][2]) << fi;
        }
        // Floats compare as floats: -0 equals +0, a subnormal as 0 (DAZ), NaN passes
        // (unordered predicates) every function but NEVER.
        EXPECT_EQ(DepthPasses(func, DepthFormat::Z32F, 0u, 0x80000000u), table[fi][1]);
        EXPECT_EQ(DepthPasses(func, DepthFormat::Z32F, 0u, FloatBits(1e-40f)), table[fi][1]);
        EXPECT_EQ(DepthPasses(func, DepthFormat::Z32F, 0u, 0x7FC00000u), fi != 0);
    }
}

TEST(DepthRender, ProfilesAgreeOnTheDepthBuffer) {
    // Visibility is llvmpipe's in both profiles: the same depth buffer after every depth case.
    int checked = 0;
    for (const test::NamedCase& c : test::ConformanceCases()) {
        if (!c.frame.depth) continue;
        const PreparedFrame pf(c.frame);
        RenderOptions linear;
        linear.profile = Profile::Linear;
        const RenderResult a = Render(pf, {}), b = Render(pf, linear);
        ASSERT_FALSE(a.depth.empty()) << c.name;
        EXPECT_EQ(a.depth, b.depth) << c.name;
        // Untextured, unblended passes also give the same colours: the same fragments drew.
        bool plain = true;
        for (const Pass& p : c.frame.passes) plain &= p.numUnits == 0 && !p.blend.enabled;
        if (plain) {
            EXPECT_EQ(a.image8, b.image8) << c.name;
        }
        ++checked;
    }
    EXPECT_GE(checked, 60);
}

// A w x h frame: a cube-free set of 2D textures and untextured or textured quads whose window
// depth is constant (clip z = 2 zw - 1 at w = 1).
Pass DepthQuad(float x0, float y0, float x1, float y1, float zw, int texture,
               std::optional<DepthTest> test, const glm::vec4& col = glm::vec4(1.0f)) {
    Pass p;
    p.numUnits = texture < 0 ? 0 : 1;
    p.texture = {std::max(texture, 0), 0};
    p.depthTest = test;
    const glm::vec2 xy[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k : {0, 1, 2, 0, 2, 3}) {
        Vertex v;
        v.pos = {xy[k].x, xy[k].y, 2.0f * zw - 1.0f, 1.0f};
        v.coord[0] = {0.5f * (xy[k].x + 1.0f), 0.5f * (xy[k].y + 1.0f), 0.0f};
        v.color = col;
        p.vertices.push_back(v);
    }
    return p;
}

Texture Random2D(uint64_t seed) {
    Texture t;
    t.kind = TextureKind::Tex2D;
    t.width = t.height = 8;
    t.sampler.mipFilter = MipFilter::None;
    std::vector<uint8_t> bytes(8 * 8 * 4);
    for (uint8_t& b : bytes) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        b = static_cast<uint8_t>(seed >> 56);
    }
    t.levels.push_back(bytes);
    return t;
}

TEST(DepthRender, NearQuadHidesLaterFarQuad) {
    Frame f;
    f.width = f.height = 16;
    f.depth = DepthBuffer{DepthFormat::Z24, 1.0f};
    const DepthTest less{DepthFunc::Less, true};
    f.passes = {DepthQuad(-1, -1, 0, 1, 0.25f, -1, less, {1, 0, 0, 1}),
                DepthQuad(-1, -1, 1, 1, 0.75f, -1, less, {0, 1, 0, 1})};
    const RenderResult r = Render(PreparedFrame(f), {});
    ASSERT_EQ(r.depth.size(), 256u);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const size_t i = static_cast<size_t>(y * 16 + x);
            EXPECT_EQ(r.image8.rgba[4 * i], x < 8 ? 255 : 0) << x << "," << y;
            EXPECT_EQ(r.image8.rgba[4 * i + 1], x < 8 ? 0 : 255) << x << "," << y;
            EXPECT_EQ(r.depth[i], x < 8 ? DepthFromFloat(DepthFormat::Z24, 0.25f)
                                        : DepthFromFloat(DepthFormat::Z24, 0.75f));
        }
    // Without the second pass's test: it covers everything and leaves the depth buffer alone.
    f.passes[1].depthTest.reset();
    const RenderResult u = Render(PreparedFrame(f), {});
    EXPECT_EQ(u.image8.rgba[0], 0);
    EXPECT_EQ(u.depth[15], DepthClearValue(DepthFormat::Z24, 1.0f));
    // Without a depth buffer a depth test passes everything (GL), and there is no buffer.
    f.depth.reset();
    f.passes[1].depthTest = less;
    const RenderResult n = Render(PreparedFrame(f), {});
    EXPECT_EQ(n.image8, u.image8);
    EXPECT_TRUE(n.depth.empty());
}

TEST(DepthRender, FramesDrawnTogetherKeepTheirOwnDepthBuffers) {
    // RenderFrames shares set-up between frames with equal geometry; each keeps its own buffer.
    std::vector<Frame> frames;
    for (const test::NamedCase& c : test::ConformanceCases())
        if (c.name == "depth_multipass_z24" || c.name == "depth_writes_z16")
            frames.push_back(c.frame);
    ASSERT_EQ(frames.size(), 2u);
    Frame other = frames[0];  // same geometry, other depth state and textures
    other.depth = DepthBuffer{DepthFormat::Z16, 0.5f};
    other.passes[2].depthTest = DepthTest{DepthFunc::GEqual, true};
    std::swap(other.textures[0], other.textures[1]);
    frames.push_back(other);
    Frame noDepth = frames[0];
    noDepth.depth.reset();
    frames.push_back(noDepth);
    std::vector<PreparedFrame> prepared;
    for (const Frame& f : frames) prepared.emplace_back(f);
    std::vector<const PreparedFrame*> ptrs;
    for (const PreparedFrame& p : prepared) ptrs.push_back(&p);
    RenderOptions opt;
    opt.threads = 2;
    const std::vector<RenderResult> together = RenderFrames(ptrs, opt);
    for (size_t i = 0; i < frames.size(); ++i) {
        const RenderResult alone = Render(prepared[i], opt);
        EXPECT_EQ(together[i].image8, alone.image8) << i;
        EXPECT_EQ(together[i].depth, alone.depth) << i;
    }
    EXPECT_NE(together[0].image8, together[2].image8);
}

// The bits of a float image (NaN-safe equality).
std::vector<uint32_t> Bits(const ImageF& image) {
    std::vector<uint32_t> bits(image.rgba.size());
    for (size_t i = 0; i < bits.size(); ++i) bits[i] = std::bit_cast<uint32_t>(image.rgba[i]);
    return bits;
}

TEST(DepthRender, LayerPassesDrawnTogetherAsOneAfterTheOther) {
    // A pass writing depth with LESS and replacing, then the same positions tested EQUAL
    // without writes, is drawn in one traversal (render.cpp FusesWithNext), for several frames
    // at once as the renderers draw their terms and samples (whose equal depth buffers are kept
    // once). Reference: each frame alone with an empty pass between the two, so they are drawn
    // one after the other (the order the conformance cases hold to llvmpipe).
    for (const char* name : {"depth_layers_z24", "f32_depth_layers_z32f"}) {
        std::vector<Frame> frames;
        for (const test::NamedCase& c : test::ConformanceCases())
            if (c.name == name) frames.push_back(c.frame);
        ASSERT_EQ(frames.size(), 1u) << name;
        Frame term = frames[0];  // same positions, other coordinates (another term)
        for (Pass& p : term.passes)
            for (Vertex& v : p.vertices)
                v.coord[0] = glm::vec3(-v.coord[0].y, v.coord[0].x, v.coord[0].z);
        frames.push_back(term);
        Frame sample = frames[0];  // same passes, other maps (another sample)
        std::swap(sample.textures[0], sample.textures[1]);
        frames.push_back(sample);
        Frame lequal = frames[0];  // not drawn together: LEQUAL keeps the last of equal depths
        lequal.passes[0].depthTest->func = DepthFunc::LEqual;
        // Order: lequal, term, the case, sample. The last three keep one depth buffer, term's
        // (the first of them: render.cpp SameDepthHistory), but the case and sample have lequal's
        // vertices and are drawn before term in every lane group: the first draw of a shared
        // buffer tests it, whichever frame it belongs to.
        frames = {lequal, term, frames[0], sample};
        std::vector<PreparedFrame> prepared;
        for (const Frame& f : frames) prepared.emplace_back(f);
        std::vector<const PreparedFrame*> ptrs;
        for (const PreparedFrame& p : prepared) ptrs.push_back(&p);
        for (int threads : {1, 3}) {
            RenderOptions opt;
            opt.threads = threads;
            const std::vector<RenderResult> together = RenderFrames(ptrs, opt);
            for (size_t i = 0; i < frames.size(); ++i) {
                Frame apart = frames[i];
                apart.passes.insert(apart.passes.begin() + 1, Pass{});
                const RenderResult alone = Render(PreparedFrame(apart), opt);
                EXPECT_EQ(together[i].image8, alone.image8) << name << " " << i;
                EXPECT_EQ(Bits(together[i].imageF), Bits(alone.imageF)) << name << " " << i;
                EXPECT_EQ(together[i].depth, alone.depth) << name << " " << i;
            }
            EXPECT_NE(together[1].image8, together[2].image8) << name;
        }
    }
}

// The columns (4 * texel + channel) of texture k.
std::pair<uint32_t, uint32_t> Columns(const PreparedFrame& pf, int k) {
    const uint32_t first = pf.indexer().LevelBase(k, 0);
    const uint32_t last = k + 1 < static_cast<int>(pf.frame().textures.size())
                              ? pf.indexer().LevelBase(k + 1, 0)
                              : pf.indexer().TotalTexels();
    return {4 * first, 4 * last};
}

int EntriesIn(const RenderingMatrix& a, std::pair<uint32_t, uint32_t> cols) {
    int n = 0;
    for (uint32_t c : a.col) n += c >= cols.first && c < cols.second;
    return n;
}

TEST(RenderingMatrix, HiddenFragmentsHaveNoTaps) {
    // T0 near on the left, T1 far over everything (visible on the right), T2 fully hidden
    // behind T0, then T1's geometry again with EQUAL, no writes, added (the multipass pattern).
    Frame f;
    f.width = 32;
    f.height = 24;
    f.depth = DepthBuffer{DepthFormat::Z16, 1.0f};
    f.textures = {Random2D(1), Random2D(2), Random2D(3)};
    const DepthTest less{DepthFunc::Less, true};
    Pass again =
        DepthQuad(-1, -1, 1, 1, 0.6f, 1, DepthTest{DepthFunc::Equal, false}, {0.3f, 0.5f, 0.7f, 1});
    again.blend = BlendState::Additive();
    f.passes = {DepthQuad(-1, -1, 0.25f, 1, 0.3f, 0, less), DepthQuad(-1, -1, 1, 1, 0.6f, 1, less),
                DepthQuad(-0.9f, -0.9f, 0.1f, 0.9f, 0.9f, 2, less), again};
    for (Profile profile : {Profile::Linear, Profile::Llvmpipe}) {
        RenderOptions opt;
        opt.profile = profile;
        const PreparedFrame pf(f);
        const RenderingMatrix a = BuildRenderingMatrix(pf, opt);
        EXPECT_GT(EntriesIn(a, Columns(pf, 0)), 0);
        EXPECT_GT(EntriesIn(a, Columns(pf, 1)), 0);
        EXPECT_EQ(EntriesIn(a, Columns(pf, 2)), 0);
        // Rows of T1 only where T1 is visible (x >= 20: clip x > 0.25), with both passes' taps.
        for (int64_t r = 0; r < a.rows; ++r) {
            const int x = static_cast<int>((r / 4) % f.width);
            const auto begin = a.rowPtr[static_cast<size_t>(r)];
            const auto end = a.rowPtr[static_cast<size_t>(r) + 1];
            for (auto k = begin; k < end; ++k) {
                const bool t1 = a.col[static_cast<size_t>(k)] >= Columns(pf, 1).first;
                EXPECT_EQ(t1, x >= 20) << "row " << r;
            }
            EXPECT_EQ(a.fragments[static_cast<size_t>(r / 4)], x >= 20 ? 2 : 1) << "row " << r;
        }
        // A x + offset is the frame (linear: to float rounding; llvmpipe: within 8-bit rounding).
        std::vector<double> xTexels;
        for (const Texture& t : f.textures)
            for (uint8_t b : t.levels[0]) xTexels.push_back(b / 255.0);
        for (int64_t r = 0; r < a.rows; ++r) {
            double y = a.offset[static_cast<size_t>(r)];
            for (auto k = a.rowPtr[static_cast<size_t>(r)];
                 k < a.rowPtr[static_cast<size_t>(r) + 1]; ++k)
                y += a.val[static_cast<size_t>(k)] * xTexels[a.col[static_cast<size_t>(k)]];
            const double tol = profile == Profile::Linear ? 1e-5 : 2 * 2.0 / 255 + 1e-6;
            if (y >= 1.0) continue;  // saturated
            EXPECT_NEAR(a.rendered[static_cast<size_t>(r)], y, tol) << "row " << r;
        }
    }
    // Not vacuous: without its depth test the hidden quad is drawn over T0.
    f.passes[2].depthTest.reset();
    const PreparedFrame pf(f);
    EXPECT_GT(EntriesIn(BuildRenderingMatrix(pf, {}), Columns(pf, 2)), 0);
}

}  // namespace
}  // namespace pem::raster
