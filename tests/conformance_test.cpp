// SPDX-License-Identifier: MIT
// conformance_test.cpp — every generated case (case_generator.h) rendered by pemref's llvmpipe
// profile must be byte-identical to Mesa llvmpipe rendering the same case file through EGL, and
// so must the depth buffer of a case that has one (read back with glReadPixels).
// The case goes through its JSON form first (CaseToJson -> ParseCaseJson), so both renderers
// see exactly what a case file carries. On a mismatch the case, both frames and a difference
// mask are written to build/test_output/conformance/.
#include <gtest/gtest.h>

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

void WriteFailure(const std::string& name, const std::string& json, const raster::Image8& ours,
                  const raster::Image8& gl) {
    const std::filesystem::path dir = std::filesystem::path(PEM_TEST_OUTPUT_DIR) / "conformance";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / (name + ".json")) << json;
    base::WritePng((dir / (name + "_pemref.png")).string(), ours);
    base::WritePng((dir / (name + "_llvmpipe.png")).string(), gl);
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
                     const std::vector<uint32_t>& ours, const std::vector<uint32_t>& gl) {
    ASSERT_EQ(ours.size(), gl.size()) << name;
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < ours.size(); ++i)
        if (ours[i] != gl[i] && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << name << ": " << differ << " depth values differ, first at x "
                          << first % size_t(frame.width) << ", row " << first / size_t(frame.width)
                          << " (pemref " << ours[first] << ", llvmpipe " << gl[first] << ")";
}

TEST_P(Conformance, BitIdenticalToLlvmpipe) {
    // The reference must be llvmpipe, also on machines with a GPU.
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    const std::optional<std::string> why = conformance::GlAvailable();
    ASSERT_FALSE(why.has_value()) << "OpenGL (EGL) unavailable: " << *why;
    ASSERT_NE(conformance::GlRendererString().find("llvmpipe"), std::string::npos)
        << "reference renderer is not llvmpipe: " << conformance::GlRendererString();

    const NamedCase& c = Cases()[GetParam()];
    const std::string json = conformance::CaseToJson(c.frame);
    const raster::Frame frame = conformance::ParseCaseJson(json, c.name);
    const raster::PreparedFrame prepared(frame);
    const raster::RenderResult result = raster::Render(prepared, {});
    const raster::Image8& ours = result.image8;
    std::vector<uint32_t> glDepth;
    const raster::Image8 gl = conformance::RenderWithGl(frame, 1, nullptr, &glDepth);
    ASSERT_EQ(ours.rgba.size(), gl.rgba.size());
    ExpectSameDepth(c.name, frame, result.depth, glDepth);
    size_t differ = 0, first = 0;
    int maxDelta = 0;
    for (size_t i = 0; i < ours.rgba.size(); ++i)
        if (ours.rgba[i] != gl.rgba[i]) {
            if (differ++ == 0) first = i;
            maxDelta = std::max(maxDelta, std::abs(ours.rgba[i] - gl.rgba[i]));
        }
    if (differ) WriteFailure(c.name, json, ours, gl);
    EXPECT_EQ(differ, 0u) << c.name << ": " << differ << " bytes differ (max delta " << maxDelta
                          << "), first at pixel " << first / 4 << " (x "
                          << (first / 4) % frame.width << ", row " << (first / 4) / frame.width
                          << ")";
}

INSTANTIATE_TEST_SUITE_P(Cases, Conformance, ::testing::Range<size_t>(0, Cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& p) {
                             return Cases()[p.param].name;
                         });

}  // namespace
}  // namespace pem::test
