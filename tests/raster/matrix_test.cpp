// SPDX-License-Identifier: MIT
// matrix_test.cpp — the rendering matrix against the renderer it describes:
//  - Linear profile: render(x) = A x + offset to float rounding for random texels x;
//    rendering a one-hot texel gives column j of A; <A x, y> = <x, A^T y>; the same with
//    anisotropic filtering (footprints of up to thousands of texels).
//  - Llvmpipe profile: the 8-bit frame is within the stated bound of A x + offset:
//    |255 y - 255 (A x + c)| <= P * (0.5 + 1.5 * [8-bit path]) + 1e-3 per channel, P = the
//    fragments blended into the pixel since its last unblended write (RenderingMatrix::fragments),
//    for pixels whose exact value stays below 1 and whose modulation is <= 1.
//    Pixels whose filter weights are NaN (coordinates that overflowed: the extreme_* cases) have
//    NaN entries in their rows and no exact value; both sides are NaN there (llvmpipe stores 0).
//    Float path: the sample is exact up to float rounding, so only the final RNE (<= 0.5) counts.
//    8-bit path: each row lerp and the column lerp round to 8 bits (<= 0.5 each, the column
//    lerp carries the rows' error: <= 1.0), the MIP lerp adds 0.5 more: <= 1.5 on the texel
//    value, times the modulating colour (<= 1 here), then the final RNE: <= 2.0 in all.
//    An RGBA32F colour buffer of float-path samples: A x + offset to float rounding.
//  - Softpipe profile: texels, filters, the tile cache between passes and blending are float,
//    so the 8-bit frame is A x + offset rounded once (float_to_ubyte): within 0.5 + 1e-3
//    (RGBA8 frames only: the model draws nothing else).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "raster/render.h"
#include "tests/case_generator.h"

namespace pem::raster {
namespace {

using test::NamedCase;

// Frames whose passes are linear in the texels (blend none/add), from the conformance corpus.
std::vector<NamedCase> LinearFrames() {
    std::vector<NamedCase> out;
    for (NamedCase& c : test::ConformanceCases()) {
        bool linear = true;
        for (const Pass& p : c.frame.passes)
            linear &= !p.blend.enabled || p.blend == BlendState::Additive();
        if (linear && c.frame.width * c.frame.height <= 96 * 96) out.push_back(std::move(c));
    }
    return out;
}

std::vector<double> Apply(const RenderingMatrix& a, const std::vector<double>& x) {
    std::vector<double> y(static_cast<size_t>(a.rows));
    for (int64_t r = 0; r < a.rows; ++r) {
        double s = a.offset[static_cast<size_t>(r)];
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            s += a.val[static_cast<size_t>(k)] * x[a.col[static_cast<size_t>(k)]];
        y[static_cast<size_t>(r)] = s;
    }
    return y;
}

// x: texel values (bytes / 255, or RGBA32F floats), column 4 * texel + channel.
std::vector<double> TexelVector(const Frame& f) {
    std::vector<double> x;
    for (const Texture& t : f.textures)
        for (int l = 0; l < t.NumLevels(); ++l)
            for (size_t i = 0; i < t.levels[size_t(l)].size() / size_t(t.TexelBytes() / 4); ++i)
                x.push_back(TexelValue(t, l, i));
    return x;
}

// Whether every texture and the colour buffer are RGBA8 (what the softpipe profile draws).
bool RgbaEightOnly(const Frame& f) {
    bool only = f.colorFormat == ColorFormat::Rgba8;
    for (const Texture& t : f.textures) only &= t.format == TexelFormat::Rgba8;
    return only;
}

TEST(RenderingMatrix, LinearProfileEqualsRender) {
    RenderOptions opt;
    opt.profile = Profile::Linear;
    int checked = 0;
    for (const NamedCase& c : LinearFrames()) {
        const PreparedFrame pf(c.frame);
        const RenderingMatrix a = BuildRenderingMatrix(pf, opt);
        ASSERT_EQ(a.cols, static_cast<int64_t>(TexelVector(c.frame).size())) << c.name;
        const std::vector<double> y = Apply(a, TexelVector(c.frame));
        const ImageF img = Render(pf, opt).imageF;
        for (size_t i = 0; i < y.size(); ++i) {
            if (std::isnan(y[i]) && std::isnan(img.rgba[i])) continue;  // NaN weights
            const double tol = 1e-5 * std::max(1.0, std::fabs(y[i])) + 1e-6;
            ASSERT_NEAR(img.rgba[i], y[i], tol) << c.name << " row " << i;
        }
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

// Anisotropic footprints (aniso.h): dozens to thousands of texels per pixel, still exactly
// linear: A x = the linear profile's frame, and a one-hot texel renders its column.
TEST(RenderingMatrix, AnisotropicFootprintsStayLinear) {
    RenderOptions opt;
    opt.profile = Profile::Linear;
    int checked = 0;
    int64_t widest = 0;
    for (const NamedCase& c : LinearFrames()) {
        if (c.name.rfind("aniso_", 0) != 0) continue;
        const PreparedFrame pf(c.frame);
        const RenderingMatrix a = BuildRenderingMatrix(pf, opt);
        for (int64_t r = 0; r < a.rows; ++r)
            widest = std::max(
                widest, a.rowPtr[static_cast<size_t>(r) + 1] - a.rowPtr[static_cast<size_t>(r)]);
        const std::vector<double> y = Apply(a, TexelVector(c.frame));
        const ImageF img = Render(pf, opt).imageF;
        for (size_t i = 0; i < y.size(); ++i) {
            const double tol = 1e-5 * std::max(1.0, std::fabs(y[i])) + 1e-6;
            ASSERT_NEAR(img.rgba[i], y[i], tol) << c.name << " row " << i;
        }
        ++checked;
    }
    EXPECT_GE(checked, 60);
    EXPECT_GT(widest, 1000);  // far beyond the 8 taps of trilinear filtering
    // One-hot texels of an anisotropic mirror sphere (cube, seamless, trilinear, 16).
    for (const NamedCase& c : test::ConformanceCases()) {
        if (c.name != "aniso_sphere_linear_mipmap_linear_mag_linear_seamless") continue;
        Frame f = c.frame;
        f.clear = {0, 0, 0, 0};
        for (auto& level : f.textures[0].levels) std::fill(level.begin(), level.end(), 0);
        const RenderingMatrix a = BuildRenderingMatrix(PreparedFrame(f), opt);
        for (uint32_t col : {a.col[a.col.size() / 5], a.col[a.col.size() / 2]}) {
            Frame g = f;
            uint32_t base = 0;
            for (auto& level : g.textures[0].levels) {
                const uint32_t n = static_cast<uint32_t>(level.size() / 4);
                if (col / 4 < base + n) {
                    level[col - 4 * base] = 255;
                    break;
                }
                base += n;
            }
            const ImageF img = Render(PreparedFrame(g), opt).imageF;
            int lit = 0;
            for (int64_t r = 0; r < a.rows; ++r) {
                double expect = 0;
                for (int64_t k = a.rowPtr[static_cast<size_t>(r)];
                     k < a.rowPtr[static_cast<size_t>(r) + 1]; ++k)
                    if (a.col[static_cast<size_t>(k)] == col)
                        expect = a.val[static_cast<size_t>(k)];
                lit += expect > 0;
                ASSERT_NEAR(img.rgba[static_cast<size_t>(r)], expect, 1e-6)
                    << "column " << col << " row " << r;
            }
            EXPECT_GT(lit, 0);
        }
        ++checked;
    }
    EXPECT_GE(checked, 61);
}

TEST(RenderingMatrix, OneHotTexelRendersColumn) {
    RenderOptions opt;
    opt.profile = Profile::Linear;
    Frame f = test::ConformanceCases()[0].frame;  // a reflective sphere, trilinear, seamless
    f.clear = {0, 0, 0, 0};
    for (auto& level : f.textures[0].levels) std::fill(level.begin(), level.end(), 0);
    const RenderingMatrix a = BuildRenderingMatrix(PreparedFrame(f), opt);
    // Columns touched by the frame: pick a few of them and one untouched texel.
    std::vector<uint32_t> cols = {a.col[a.col.size() / 3], a.col[a.col.size() / 2],
                                  a.col[a.col.size() - 1]};
    cols.push_back(0);  // texel 0, channel 0 (+X face corner of level 0: not visible here)
    for (uint32_t col : cols) {
        const uint32_t texel = col / 4, channel = col % 4;
        Frame g = f;
        // Locate the texel's byte: levels are concatenated in texel order.
        uint32_t base = 0;
        for (auto& level : g.textures[0].levels) {
            const uint32_t n = static_cast<uint32_t>(level.size() / 4);
            if (texel < base + n) {
                for (int c = 0; c < 4; ++c)
                    level[4 * (texel - base) + static_cast<uint32_t>(c)] = 255;
                break;
            }
            base += n;
        }
        const ImageF img = Render(PreparedFrame(g), opt).imageF;
        for (int64_t r = 0; r < a.rows; ++r) {
            if (static_cast<uint32_t>(r % 4) != channel) continue;
            double expect = 0;
            for (int64_t k = a.rowPtr[static_cast<size_t>(r)];
                 k < a.rowPtr[static_cast<size_t>(r) + 1]; ++k)
                if (a.col[static_cast<size_t>(k)] == col) expect = a.val[static_cast<size_t>(k)];
            ASSERT_NEAR(img.rgba[static_cast<size_t>(r)], expect, 1e-6)
                << "column " << col << " row " << r;
        }
    }
}

TEST(RenderingMatrix, AdjointIdentity) {
    RenderOptions opt;
    opt.profile = Profile::Linear;
    const Frame f = test::ConformanceCases()[0].frame;
    const RenderingMatrix a = BuildRenderingMatrix(PreparedFrame(f), opt);
    std::vector<double> x(static_cast<size_t>(a.cols)), y(static_cast<size_t>(a.rows));
    uint64_t s = 12345;
    auto rnd = [&] {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(s >> 11) / 9007199254740992.0 - 0.5;
    };
    for (double& v : x) v = rnd();
    for (double& v : y) v = rnd();
    double axy = 0, xaty = 0;
    std::vector<double> aty(x.size(), 0.0);
    for (int64_t r = 0; r < a.rows; ++r)
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k) {
            axy += a.val[static_cast<size_t>(k)] * x[a.col[static_cast<size_t>(k)]] *
                   y[static_cast<size_t>(r)];
            aty[a.col[static_cast<size_t>(k)]] +=
                a.val[static_cast<size_t>(k)] * y[static_cast<size_t>(r)];
        }
    for (size_t j = 0; j < x.size(); ++j) xaty += x[j] * aty[j];
    EXPECT_NEAR(axy, xaty, 1e-9 * (std::fabs(axy) + 1.0));
    EXPECT_GT(a.val.size(), 1000u);
    for (uint32_t c : a.col) ASSERT_LT(static_cast<int64_t>(c), a.cols);
}

TEST(RenderingMatrix, LlvmpipeFrameWithinStatedBound) {
    int checked = 0;
    for (const NamedCase& c : LinearFrames()) {
        const PreparedFrame pf(c.frame);
        const RenderingMatrix a = BuildRenderingMatrix(pf, {});
        const std::vector<double> y = Apply(a, TexelVector(c.frame));
        // Passes covering each pixel (the number of roundings), and whether an 8-bit path is used.
        bool fixed8 = false;
        for (const Texture& t : c.frame.textures)
            fixed8 |= t.format == TexelFormat::Rgba8 &&
                      (t.kind == TextureKind::Tex2D || !t.sampler.seamless ||
                       (t.sampler.minFilter == Filter::Nearest &&
                        t.sampler.magFilter == Filter::Nearest));
        const double perPass = 0.5 + (fixed8 ? 1.5 : 0.0);
        if (c.frame.colorFormat == ColorFormat::Rgba32F && !fixed8) {
            // A float colour buffer of float-path samples: A x + offset to float rounding.
            for (size_t i = 0; i < y.size(); ++i) {
                if (std::isnan(y[i]) && std::isnan(a.rendered[i])) continue;  // NaN weights
                const double tol = 1e-5 * std::max(1.0, std::fabs(y[i])) + 1e-6;
                ASSERT_NEAR(a.rendered[i], y[i], a.fragments[i / 4] * tol)
                    << c.name << " row " << i;
            }
            ++checked;
            continue;
        }
        for (size_t i = 0; i < y.size(); ++i) {
            if (y[i] > 1.0 - 1e-9 || !(y[i] >= 0.0)) continue;  // saturated, or NaN weights
            const double d = std::fabs(255.0 * a.rendered[i] - 255.0 * y[i]);
            ASSERT_LE(d, a.fragments[i / 4] * perPass + 1e-3) << c.name << " row " << i;
        }
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

TEST(RenderingMatrix, SoftpipeFrameWithinOneRounding) {
    RenderOptions opt;
    opt.profile = Profile::Softpipe;
    int checked = 0;
    for (const NamedCase& c : LinearFrames()) {
        if (!RgbaEightOnly(c.frame)) continue;
        const PreparedFrame pf(c.frame);
        const RenderingMatrix a = BuildRenderingMatrix(pf, opt);
        const std::vector<double> y = Apply(a, TexelVector(c.frame));
        for (size_t i = 0; i < y.size(); ++i) {
            if (y[i] > 1.0 - 1e-9 || !(y[i] >= 0.0)) continue;  // saturated, or NaN weights
            ASSERT_LE(std::fabs(255.0 * a.rendered[i] - 255.0 * y[i]), 0.5 + 1e-3)
                << c.name << " row " << i;
        }
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

uint64_t Bits(double v) {
    return std::bit_cast<uint64_t>(v);
}

// Kept pixels (every third, and the last): their rows are the whole frame's rows of those pixels,
// bit for bit, in every profile (each frame in one of the three), an empty list keeps none, and in
// the linear profile A x is the rendered frame there; a list not increasing inside the frame is
// refused.
// FinestTexels (the test rendering that sizes a map) gives each kept pixel the least texel of its
// rows in the rendering matrix: the frames in every profile, every pixel or a sparse list.
TEST(RenderingMatrix, FinestTexelsAreTheRowsLeastTexel) {
    int checked = 0, withTaps = 0;
    const std::vector<NamedCase> frames = LinearFrames();
    const Profile profiles[] = {Profile::Linear, Profile::Llvmpipe, Profile::Softpipe};
    for (size_t f = 0; f < frames.size(); f += 3) {  // a third of them: each profile, each form
        const NamedCase& c = frames[f];
        RenderOptions opt;
        opt.profile = RgbaEightOnly(c.frame) ? profiles[(f / 3) % 3] : profiles[(f / 3) % 2];
        opt.threads = 1 + static_cast<int>((f / 3) % 4);
        const PreparedFrame pf(c.frame);
        const auto n = static_cast<uint32_t>(c.frame.width * c.frame.height);
        std::vector<uint32_t> pixels;
        for (uint32_t p = 2; p < n; p += 5) pixels.push_back(p);
        {  // every pixel, or (odd frames) a sparse list
            const std::vector<uint32_t>* list = (f / 3) % 2 ? &pixels : nullptr;
            const RenderingMatrix a = BuildRenderingMatrix(pf, opt, list);
            const std::vector<uint32_t> finest = FinestTexels(pf, opt, list);
            ASSERT_EQ(finest.size() * 4, static_cast<size_t>(a.rows)) << c.name;
            for (size_t i = 0; i < finest.size(); ++i) {
                uint32_t least = kNoTexel;  // over the red row's columns 4 * texel
                for (int64_t k = a.rowPtr[4 * i]; k < a.rowPtr[4 * i + 1]; ++k)
                    least = std::min(least, a.col[static_cast<size_t>(k)] / 4);
                ASSERT_EQ(finest[i], least) << c.name << " pixel " << i;
                withTaps += least != kNoTexel;
            }
        }
        ++checked;
    }
    EXPECT_GT(checked, 13);
    EXPECT_GT(withTaps, 1000);
}

TEST(RenderingMatrix, KeptPixelsAreTheWholeFramesRows) {
    int checked = 0;
    const std::vector<NamedCase> frames = LinearFrames();
    const Profile profiles[] = {Profile::Linear, Profile::Llvmpipe, Profile::Softpipe};
    for (size_t f = 0; f < frames.size(); ++f) {
        const NamedCase& c = frames[f];
        const Profile profile = RgbaEightOnly(c.frame) ? profiles[f % 3] : profiles[f % 2];
        RenderOptions opt;
        opt.profile = profile;
        const PreparedFrame pf(c.frame);
        const auto n = static_cast<uint32_t>(c.frame.width * c.frame.height);
        std::vector<uint32_t> pixels;
        for (uint32_t p = 1; p < n; p += 3) pixels.push_back(p);
        if (pixels.empty() || pixels.back() != n - 1) pixels.push_back(n - 1);
        const RenderingMatrix all = BuildRenderingMatrix(pf, opt);
        const RenderingMatrix a = BuildRenderingMatrix(pf, opt, &pixels);
        ASSERT_EQ(a.rows, 4 * static_cast<int64_t>(pixels.size())) << c.name;
        ASSERT_EQ(a.cols, all.cols);
        ASSERT_EQ(a.rowPtr.size(), 4 * pixels.size() + 1) << c.name;
        ASSERT_EQ(a.offset.size(), 4 * pixels.size()) << c.name;
        ASSERT_EQ(a.rendered.size(), 4 * pixels.size()) << c.name;
        ASSERT_EQ(a.fragments.size(), pixels.size()) << c.name;
        ASSERT_EQ(all.fragments.size(), size_t{n}) << c.name;
        ASSERT_EQ(all.rendered.size(), 4 * size_t{n}) << c.name;
        for (size_t i = 0; i < pixels.size(); ++i) {
            const size_t p = pixels[i];
            ASSERT_EQ(a.fragments[i], all.fragments[p]) << c.name;
            for (size_t ch = 0; ch < 4; ++ch) {
                const size_t r = 4 * i + ch, ra = 4 * p + ch;
                ASSERT_EQ(Bits(a.offset[r]), Bits(all.offset[ra])) << c.name;
                ASSERT_EQ(Bits(a.rendered[r]), Bits(all.rendered[ra])) << c.name;
                const int64_t len = a.rowPtr[r + 1] - a.rowPtr[r];
                ASSERT_EQ(len, all.rowPtr[ra + 1] - all.rowPtr[ra]) << c.name << " row " << r;
                for (int64_t k = 0; k < len; ++k) {
                    ASSERT_EQ(a.col[static_cast<size_t>(a.rowPtr[r] + k)],
                              all.col[static_cast<size_t>(all.rowPtr[ra] + k)]);
                    ASSERT_EQ(Bits(a.val[static_cast<size_t>(a.rowPtr[r] + k)]),
                              Bits(all.val[static_cast<size_t>(all.rowPtr[ra] + k)]));
                }
            }
        }
        if (profile == Profile::Linear) {
            const std::vector<double> y = Apply(a, TexelVector(c.frame));
            const ImageF img = Render(pf, opt).imageF;
            for (size_t r = 0; r < y.size(); ++r) {
                const float v = img.rgba[4 * pixels[r / 4] + r % 4];
                if (std::isnan(y[r]) && std::isnan(v)) continue;  // NaN weights
                ASSERT_NEAR(v, y[r], 1e-5 * std::max(1.0, std::fabs(y[r])) + 1e-6) << c.name;
            }
        }
        ++checked;
    }
    EXPECT_GT(checked, 40);
    const NamedCase& c = frames.front();
    const PreparedFrame pf(c.frame);
    const auto n = static_cast<uint32_t>(c.frame.width * c.frame.height);
    // An empty list keeps no rows (a neighbour sample that does not see the group).
    const std::vector<uint32_t> none;
    const RenderingMatrix empty = BuildRenderingMatrix(pf, RenderOptions{}, &none);
    EXPECT_EQ(empty.rows, 0);
    EXPECT_EQ(empty.rowPtr.size(), 1u);
    EXPECT_TRUE(empty.col.empty() && empty.offset.empty() && empty.rendered.empty());
    for (const std::vector<uint32_t>& bad :
         {std::vector<uint32_t>{3, 3}, std::vector<uint32_t>{5, 2}, std::vector<uint32_t>{n}})
        EXPECT_THROW(BuildRenderingMatrix(pf, RenderOptions{}, &bad), std::invalid_argument);
}

}  // namespace
}  // namespace pem::raster
