// SPDX-License-Identifier: MIT
// conformance_test.cpp — every generated case (case_generator.h) rendered by a pemref profile
// must be byte-identical to the Mesa driver it models rendering the same case file through EGL,
// and so must the depth buffer of a case that has one (read back with glReadPixels).
//  - Conformance.*: the llvmpipe profile against llvmpipe (every case).
//  - Softpipe.*: the softpipe profile against softpipe (GALLIUM_DRIVER=softpipe), every case.
// A process talks to one driver (EGL is initialised once), so CTest runs each test alone.
// The case goes through its JSON form first (CaseToJson -> ParseCaseJson), so both renderers
// see exactly what a case file carries. On a mismatch the case, both frames and a difference
// mask are written to build/test_output/conformance/.
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "base/png_io.h"
#include "raster/render.h"
#include "tests/case_generator.h"
#include "viewer_tty/conformance/case_file.h"
#include "viewer_tty/conformance/gl_reference.h"

namespace pem::test {
namespace {

const std::vector<NamedCase>& Cases() {
    static const std::vector<NamedCase> cases = ConformanceCases();
    return cases;
}

class Conformance : public ::testing::TestWithParam<size_t> {};

// Whether every texture and the colour buffer of `frame` are RGBA8.
bool RgbaEightOnly(const raster::Frame& frame) {
    bool only = frame.colorFormat == raster::ColorFormat::Rgba8;
    for (const raster::Texture& t : frame.textures) only &= t.format == raster::TexelFormat::Rgba8;
    return only;
}

void WriteFailure(const std::string& name, const std::string& json, const raster::Image8& ours,
                  const raster::Image8& gl, const std::string& driver) {
    const std::filesystem::path dir = std::filesystem::path(PEM_TEST_OUTPUT_DIR) / "conformance";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / (name + ".json")) << json;
    base::WritePng((dir / (name + "_pemref.png")).string(), ours);
    base::WritePng((dir / (name + "_" + driver + ".png")).string(), gl);
    raster::Image8 diff = ours;
    for (size_t i = 0; i < diff.rgba.size(); i += 4) {
        const bool same = std::equal(&ours.rgba[i], &ours.rgba[i] + 4, &gl.rgba[i]);
        diff.rgba[i] = diff.rgba[i + 1] = diff.rgba[i + 2] = same ? 0 : 255;
        diff.rgba[i + 3] = 255;
    }
    base::WritePng((dir / (name + "_diff.png")).string(), diff);
}

// The depth buffers (depth.h values, rows top-down) must be equal too.
void ExpectSameDepth(const std::string& name, const raster::Frame& frame,
                     const std::vector<uint32_t>& ours, const std::vector<uint32_t>& gl,
                     const std::string& driver) {
    ASSERT_EQ(ours.size(), gl.size()) << name;
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < ours.size(); ++i)
        if (ours[i] != gl[i] && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << name << ": " << differ << " depth values differ, first at x "
                          << first % size_t(frame.width) << ", row " << first / size_t(frame.width)
                          << " (pemref " << ours[first] << ", " << driver << " " << gl[first]
                          << ")";
}

// The GL driver for this process: Mesa's `driver`, also on machines with a GPU.
void UseDriver(const std::string& driver) {
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    setenv("GALLIUM_DRIVER", driver.c_str(), 1);
    const std::optional<std::string> why = conformance::GlAvailable();
    ASSERT_FALSE(why.has_value()) << "OpenGL (EGL) unavailable: " << *why;
    ASSERT_NE(conformance::GlRendererString().find(driver), std::string::npos)
        << "reference renderer is not " << driver << ": " << conformance::GlRendererString();
}

// An RGBA32F colour buffer must hold the same floats, bit for bit.
void ExpectSameFloats(const std::string& name, const raster::Frame& frame,
                      const raster::ImageF& ours, const raster::ImageF& gl,
                      const std::string& driver) {
    ASSERT_EQ(ours.rgba.size(), gl.rgba.size()) << name;
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < ours.rgba.size(); ++i)
        if (std::bit_cast<uint32_t>(ours.rgba[i]) != std::bit_cast<uint32_t>(gl.rgba[i]) &&
            differ++ == 0)
            first = i;
    EXPECT_EQ(differ, 0u) << name << ": " << differ << " floats differ from " << driver
                          << ", first at x " << (first / 4) % size_t(frame.width) << ", row "
                          << (first / 4) / size_t(frame.width) << " channel " << first % 4
                          << " (pemref " << (differ ? ours.rgba[first] : 0.0f) << ", " << driver
                          << " " << (differ ? gl.rgba[first] : 0.0f) << ")";
}

// `frame` rendered by pemref's `options` and by the current GL driver: same bytes, same depth.
void ExpectSameAsDriver(const std::string& name, const raster::Frame& original,
                        const raster::RenderOptions& options, const std::string& driver) {
    const std::string json = conformance::CaseToJson(original);
    const raster::Frame frame = conformance::ParseCaseJson(json, name);
    const raster::PreparedFrame prepared(frame);
    const raster::RenderResult result = raster::Render(prepared, options);
    const raster::Image8& ours = result.image8;
    std::vector<uint32_t> glDepth;
    raster::ImageF glFloats;
    const raster::Image8 gl = conformance::RenderWithGl(frame, 1, nullptr, &glDepth, &glFloats);
    ExpectSameDepth(name, frame, result.depth, glDepth, driver);
    if (frame.colorFormat == raster::ColorFormat::Rgba32F) {
        ExpectSameFloats(name, frame, result.imageF, glFloats, driver);
        return;
    }
    ASSERT_EQ(ours.rgba.size(), gl.rgba.size());
    size_t differ = 0, first = 0;
    int maxDelta = 0;
    for (size_t i = 0; i < ours.rgba.size(); ++i)
        if (ours.rgba[i] != gl.rgba[i]) {
            if (differ++ == 0) first = i;
            maxDelta = std::max(maxDelta, std::abs(ours.rgba[i] - gl.rgba[i]));
        }
    if (differ) WriteFailure(name, json, ours, gl, driver);
    EXPECT_EQ(differ, 0u) << name << ": " << differ << " bytes differ from " << driver
                          << " (max delta " << maxDelta << "), first at pixel " << first / 4
                          << " (x " << (first / 4) % frame.width << ", row "
                          << (first / 4) / frame.width << ")";
}

TEST_P(Conformance, BitIdenticalToLlvmpipe) {
    UseDriver("llvmpipe");
    const NamedCase& c = Cases()[GetParam()];
    ExpectSameAsDriver(c.name, c.frame, {}, "llvmpipe");
}

INSTANTIATE_TEST_SUITE_P(Cases, Conformance, ::testing::Range<size_t>(0, Cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& p) {
                             return Cases()[p.param].name;
                         });

class Softpipe : public ::testing::TestWithParam<size_t> {};

TEST_P(Softpipe, BitIdenticalToSoftpipe) {
    const NamedCase& c = Cases()[GetParam()];
    if (!RgbaEightOnly(c.frame)) {  // the softpipe model draws RGBA8 only (render.h)
        EXPECT_THROW(
            raster::Render(raster::PreparedFrame(c.frame), {.profile = raster::Profile::Softpipe}),
            std::invalid_argument);
        return;
    }
    UseDriver("softpipe");
    raster::RenderOptions options;
    options.profile = raster::Profile::Softpipe;
    ExpectSameAsDriver(c.name, c.frame, options, "softpipe");
}

INSTANTIATE_TEST_SUITE_P(Cases, Softpipe, ::testing::Range<size_t>(0, Cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& p) {
                             return Cases()[p.param].name;
                         });

}  // namespace
}  // namespace pem::test
