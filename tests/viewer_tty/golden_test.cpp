// SPDX-License-Identifier: MIT
// golden_test.cpp — `pemref golden`'s library against references written here: images with a
// known number of altered pixels and a known largest difference (exact and fuzzy comparisons,
// diff pictures), golden directories altered by hand (check fails exactly where they were
// altered, update re-blesses only those), hash-only goldens, the model bounds (an image one
// LSB further out is rejected by exactly that LSB), ꟻLIP's defining properties, bad suites.
// Not here: the command line's exit codes and JUnit parsing (golden_cli.sh), live llvmpipe
// inside the model bounds (conformance_test.cpp).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "base/input_error.h"
#include "base/png_io.h"
#include "base/sha256.h"
#include "raster/profile.h"
#include "viewer_tty/golden/flip.h"
#include "viewer_tty/golden/golden_file.h"
#include "viewer_tty/golden/golden_job.h"
#include "viewer_tty/golden/image_diff.h"
#include "viewer_tty/golden/model_bounds.h"
#include "viewer_tty/golden/suite.h"

namespace pem::golden {
namespace {

namespace fs = std::filesystem;
const std::string kData = PEM_TEST_DATA_DIR;

base::Image8 Pattern(int w, int h) {
    base::Image8 img{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4)};
    for (size_t k = 0; k < img.rgba.size(); ++k) img.rgba[k] = uint8_t((k * 37 + k / 7) % 200 + 20);
    return img;
}

// Adds delta to the red channel of n pixels spread over the image (every 3rd pixel).
base::Image8 Altered(base::Image8 img, int n, int delta) {
    for (int i = 0; i < n; ++i)
        img.rgba[size_t(i) * 3 * 4] = uint8_t(img.rgba[size_t(i) * 3 * 4] + delta);
    return img;
}

size_t RedPixels(const base::Image8& img) {
    size_t n = 0;
    for (size_t p = 0; p < img.rgba.size(); p += 4)
        n += img.rgba[p] >= 160 && img.rgba[p + 1] == 0 && img.rgba[p + 2] == 0;
    return n;
}

fs::path MakeTempDir() {
    std::string pattern = (fs::path(testing::TempDir()) / "pem_golden_XXXXXX").string();
    return mkdtemp(pattern.data());
}

// A suite of three raster cases: quad32 (a local file, exact), cube_exact and cube_fuzzy
// (the same repository case, exact and fuzzy(3, 10)).
fs::path MakeSuite(const fs::path& dir) {
    fs::create_directories(dir);
    fs::copy_file(kData + "/golden_suite/quad32.json", dir / "quad32.json");
    const std::string cube = kData + "/cases/cube64_quad.json";
    std::ofstream(dir / "suite.json")
        << R"({"format": "pemref_golden_suite", "version": 1, "tests": [)"
        << R"({"name": "cube_exact", "case": ")" << cube << R"("},)"
        << R"({"name": "cube_fuzzy", "case": ")" << cube << R"(", "fuzzy": [3, 10]}]})";
    return dir;
}

const TestResult& Named(const CheckResult& r, const std::string& name) {
    for (const TestResult& t : r.tests)
        if (t.name == name) return t;
    throw std::runtime_error("no test " + name);
}

// ----------------------------------------------------------------------------------------------

TEST(ImageDiff, CountsKnownDifferencesAndTheLargest) {
    const base::Image8 a = Pattern(16, 8);
    base::Image8 b = Altered(a, 7, 2);
    b.rgba[4 * 100 + 3] = uint8_t(b.rgba[4 * 100 + 3] - 9);  // pixel 100's alpha by 9
    const DiffStats d = Compare(a, b);
    EXPECT_EQ(d.differingPixels, 8u);
    EXPECT_EQ(d.maxDifference, 9);
    EXPECT_EQ(d.pixels, 128u);
    EXPECT_FALSE(Accepts(Fuzzy{}, d));
    EXPECT_TRUE(Accepts(Fuzzy{9, 8}, d));
    EXPECT_FALSE(Accepts(Fuzzy{8, 8}, d));  // one axis each
    EXPECT_FALSE(Accepts(Fuzzy{9, 7}, d));
    EXPECT_TRUE(Compare(a, a).Identical());
    EXPECT_EQ(ToString(Fuzzy{9, 8}), "fuzzy(9, 8)");
}

TEST(ImageDiff, SizesThatDifferDifferEverywhere) {
    const DiffStats d = Compare(Pattern(4, 4), Pattern(4, 5));
    EXPECT_TRUE(d.sizeMismatch);
    EXPECT_FALSE(Accepts(Fuzzy{255, 1000}, d));
}

TEST(ImageDiff, DiffImageMarksExactlyTheDifferingPixels) {
    const base::Image8 a = Pattern(16, 8);
    const base::Image8 diff = DiffImage(a, Altered(a, 5, 1));
    EXPECT_EQ(RedPixels(diff), 5u);
    EXPECT_EQ(RedPixels(DiffImage(a, a)), 0u);
    const base::Image8 side = SideBySide(a, Altered(a, 5, 1));
    EXPECT_EQ(side.height, 128);  // magnified 16×
    EXPECT_EQ(side.width, 16 * 48 + 8);
    EXPECT_EQ(RedPixels(side), 5u * 16 * 16);
}

TEST(Flip, ZeroForEqualImagesAndGrowsWithTheDifference) {
    const base::Image8 a = Pattern(24, 24);
    EXPECT_EQ(FlipMean(a, a), 0.0);
    const double small = FlipMean(a, Altered(a, 20, 4)), large = FlipMean(a, Altered(a, 20, 40));
    EXPECT_GT(small, 0.0);
    EXPECT_GT(large, small);
    EXPECT_LE(large, 1.0);
}

TEST(Flip, AWhitePixelInABlackFieldIsNearlyTheLargestError) {
    base::Image8 black{32, 32, std::vector<uint8_t>(32 * 32 * 4, 0)};
    for (size_t p = 0; p < black.rgba.size(); p += 4) black.rgba[p + 3] = 255;
    base::Image8 dot = black, white = black;
    for (int c = 0; c < 3; ++c) dot.rgba[4 * (16 * 32 + 16) + size_t(c)] = 255;
    for (size_t p = 0; p < white.rgba.size(); p += 4)
        white.rgba[p] = white.rgba[p + 1] = white.rgba[p + 2] = 255;
    const std::vector<float> map = FlipMap(black, dot);
    EXPECT_GT(map[16 * 32 + 16], 0.8f);  // an edge and a point: ΔEc^(1 − ΔEf) near 1
    EXPECT_LT(map[0], 1e-3f);            // far from it, nothing
    // A flat black against a flat white: colour alone, HyAB(black, white) = 100 against the
    // largest colour difference (green–blue) remapped: 0.95 + (100^0.7 − pccmax)/(cmax −
    // pccmax)·0.05.
    const std::vector<float> flat = FlipMap(black, white);
    EXPECT_GT(flat[16 * 32 + 16], 0.95f);
    EXPECT_LT(flat[16 * 32 + 16], 1.0f);
}

TEST(Suite, BadSuiteFilesNameTheFileAndTheEntry) {
    const fs::path dir = MakeTempDir();
    for (const char* text :
         {R"({"format": "pemref_golden_suite", "version": 1, "tests": [{"case": "x.json"}]})",
          R"({"format": "pemref_golden_suite", "version": 1, "tests": [{"name": "a"}]})",
          R"({"format": "pemref_golden_suite", "version": 1,
              "tests": [{"name": "a", "case": "x.json", "fuzzy": [300, 1]}]})",
          R"({"format": "pemref_golden_suite", "version": 1,
              "tests": [{"name": "a", "case": "x.json", "fuzzy": [2.5, 1]}]})",
          R"({"format": "pemref_golden_suite", "version": 1,
              "tests": [{"name": "a", "case": "x.json", "spp": 1e300}]})",
          R"({"format": "pemref_golden_suite", "version": 1,
              "tests": [{"name": "../a", "case": "x.json"}]})",
          R"({"format": "other", "version": 1})", "{"}) {
        std::ofstream(dir / "suite.json") << text;
        try {
            ReadSuite(dir.string());
            ADD_FAILURE() << "accepted " << text;
        } catch (const base::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("suite.json"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(ReadSuite((dir / "missing").string()), base::InputError);
    fs::remove_all(dir);
}

TEST(GoldenJob, GenerateWritesOnePngPerTestAndItsHash) {
    const fs::path tmp = MakeTempDir(), suite = MakeSuite(tmp / "suite"), out = tmp / "goldens";
    GoldenOptions o;
    o.version = "test";
    Generate(suite.string(), out.string(), o);
    const GoldenRecord r = ReadGoldenFile(out.string());
    EXPECT_EQ(r.profile, "llvmpipe");
    EXPECT_NE(r.model.find("Mesa 22.3.6"), std::string::npos);
    ASSERT_EQ(r.tests.size(), 3u);
    for (const GoldenEntry& e : r.tests) {
        const base::Image8 img = base::ReadPng((out / e.png).string());
        EXPECT_EQ(e.sha256, base::Sha256Hex(img.rgba.data(), img.rgba.size())) << e.name;
    }
    EXPECT_EQ(Check(suite.string(), out.string(), o).Failures(), 0);
    fs::remove_all(tmp);
}

TEST(GoldenJob, CheckFailsWhereTheGoldenWasAlteredAndUpdateReblessesOnlyThose) {
    const fs::path tmp = MakeTempDir(), suite = MakeSuite(tmp / "suite"), out = tmp / "goldens";
    GoldenOptions o;
    Generate(suite.string(), out.string(), o);
    const auto alter = [&](const std::string& name, int n, int delta) {
        const std::string png = (out / (name + ".png")).string();
        base::WritePng(png, Altered(base::ReadPng(png), n, delta));
    };
    alter("cube_exact", 5, 3);
    alter("cube_fuzzy", 11, 3);  // fuzzy(3, 10): one pixel too many
    const CheckResult r = Check(suite.string(), out.string(), o);
    EXPECT_EQ(r.Failures(), 2);
    EXPECT_TRUE(Named(r, "quad32").passed);
    const TestResult& exact = Named(r, "cube_exact");
    EXPECT_FALSE(exact.passed);
    EXPECT_EQ(exact.diff.differingPixels, 5u);
    EXPECT_EQ(exact.diff.maxDifference, 3);
    EXPECT_EQ(RedPixels(base::ReadPng(exact.diffPng)), 5u);
    EXPECT_TRUE(fs::exists(exact.sideBySidePng));
    EXPECT_EQ(Named(r, "cube_fuzzy").diff.differingPixels, 11u);

    alter("cube_fuzzy", 0, 0);
    const std::string quadBefore =
        base::Sha256Hex(base::ReadPng((out / "quad32.png").string()).rgba.data(), 32 * 32 * 4);
    const CheckResult u = Update(suite.string(), out.string(), o);
    EXPECT_EQ(u.Failures(), 2);  // the two it re-blessed
    EXPECT_EQ(
        base::Sha256Hex(base::ReadPng((out / "quad32.png").string()).rgba.data(), 32 * 32 * 4),
        quadBefore);
    EXPECT_EQ(Check(suite.string(), out.string(), o).Failures(), 0);
    fs::remove_all(tmp);
}

TEST(GoldenJob, FuzzyToleranceAcceptsWithinBothAxes) {
    const fs::path tmp = MakeTempDir(), suite = MakeSuite(tmp / "suite"), out = tmp / "goldens";
    GoldenOptions o;
    Generate(suite.string(), out.string(), o);
    const std::string png = (out / "cube_fuzzy.png").string();
    base::WritePng(png, Altered(base::ReadPng(png), 10, 3));
    const CheckResult r = Check(suite.string(), out.string(), o);
    EXPECT_TRUE(Named(r, "cube_fuzzy").passed);
    EXPECT_EQ(Named(r, "cube_fuzzy").diff.differingPixels, 10u);
    EXPECT_GT(Named(r, "cube_fuzzy").flip, 0.0);
    base::WritePng(png, Altered(base::ReadPng(png), 1, 1));  // pixel 0 now 4 away
    EXPECT_FALSE(Named(Check(suite.string(), out.string(), o), "cube_fuzzy").passed);
    fs::remove_all(tmp);
}

TEST(GoldenJob, MissingGoldenPngOrOtherProfileCannotRun) {
    const fs::path tmp = MakeTempDir(), suite = MakeSuite(tmp / "suite"), out = tmp / "goldens";
    GoldenOptions o;
    Generate(suite.string(), out.string(), o);
    o.profile = "d3d-rounding";
    EXPECT_THROW(Check(suite.string(), out.string(), o), base::InputError);
    o.profile.clear();
    fs::remove(out / "quad32.png");
    EXPECT_THROW(Check(suite.string(), out.string(), o), base::InputError);
    // A golden.json naming a profile this pemref does not know.
    fs::remove_all(out);
    Generate(suite.string(), out.string(), o);
    std::ifstream in(out / "golden.json");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find("\"llvmpipe\"");
    ASSERT_NE(at, std::string::npos);
    std::ofstream(out / "golden.json") << text.replace(at, 10, "\"llvmpipx\"");
    EXPECT_THROW(Check(suite.string(), out.string(), o), base::InputError);
    fs::remove_all(tmp);
}

TEST(GoldenJob, HashOnlyGoldensCompareThePixelsHash) {
    const fs::path tmp = MakeTempDir(), suite = MakeSuite(tmp / "suite"), out = tmp / "goldens";
    GoldenOptions o;
    o.hashesOnly = true;
    Generate(suite.string(), out.string(), o);
    EXPECT_FALSE(fs::exists(out / "quad32.png"));
    EXPECT_EQ(Check(suite.string(), out.string(), o).Failures(), 0);
    GoldenRecord r = ReadGoldenFile(out.string());
    r.Find("quad32")->sha256[0] = r.Find("quad32")->sha256[0] == '0' ? '1' : '0';
    WriteGoldenFile(r);
    const CheckResult c = Check(suite.string(), out.string(), o);
    EXPECT_EQ(c.Failures(), 1);
    EXPECT_FALSE(Named(c, "quad32").passed);
    EXPECT_TRUE(fs::exists(Named(c, "quad32").diffPng));  // the rendered image
    Update(suite.string(), out.string(), o);
    EXPECT_FALSE(fs::exists(out / "quad32.png"));  // stays hash-only
    EXPECT_EQ(Check(suite.string(), out.string(), o).Failures(), 0);
    fs::remove_all(tmp);
}

TEST(ModelBounds, SpanTheProfilesAndRejectByTheExcess) {
    GoldenTest t;
    t.name = "cube";
    t.input = kData + "/cases/cube64_quad.json";
    const ModelBounds b = BoundsOf(t, 1);
    ASSERT_EQ(b.profiles.size(), raster::Profiles().size());  // every profile, softpipe too
    EXPECT_GT(b.SpannedPixels(), 0u);                         // the profiles do disagree here
    // An image at the upper bound everywhere is inside; one channel 2 above is 1 LSB outside ±1.
    base::Image8 top{b.width, b.height, b.hi};
    EXPECT_TRUE(CheckBounds(b, top, 0).Accepted());
    size_t k = 0;
    while (b.hi[k] > 250) ++k;
    top.rgba[k] = uint8_t(b.hi[k] + 2);
    const BoundsCheck c = CheckBounds(b, top, 1);
    EXPECT_FALSE(c.Accepted());
    EXPECT_EQ(c.outsidePixels, 1u);
    EXPECT_EQ(c.largestExcess, 1);
    EXPECT_TRUE(CheckBounds(b, top, 2).Accepted());
}

}  // namespace
}  // namespace pem::golden
