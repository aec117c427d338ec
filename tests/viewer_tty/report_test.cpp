// SPDX-License-Identifier: MIT
// report_test.cpp — image metrics against independent references written here as plain double
// loops (RMSE/PSNR of known perturbations, SSIM by a direct 2D window, constant images, 8-bit
// quantization, masks) and the report writer (three parseable files, one SVG marker per plottable
// result, NaN/zero entries, atomic failure into a missing folder).
// Conventions: tiny images with fixed-seed values. Not here: the `pemref report` command.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

#include "viewer_tty/report/image_metrics.h"
#include "viewer_tty/report/report_writer.h"

namespace pem::report {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

MetricImage RandomImage(int w, int h, uint32_t seed, float lo = 0.1f, float hi = 0.9f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    MetricImage img{w, h, std::vector<float>(size_t(w) * size_t(h) * 3)};
    for (float& v : img.rgb) v = u(rng);
    return img;
}

double Clamp01(float v) {
    return std::isnan(v) ? 0.0 : std::fmin(1.0, std::fmax(0.0, double(v)));
}

// Reference RMSE over the selected pixels, straight from the definition.
double DirectRmse(const MetricImage& a, const MetricImage& b, const std::vector<uint8_t>* mask) {
    double se = 0, n = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        if (mask && (*mask)[i / 3] == 0) continue;
        se += (Clamp01(a.rgb[i]) - Clamp01(b.rgb[i])) * (Clamp01(a.rgb[i]) - Clamp01(b.rgb[i]));
        n += 1;
    }
    return std::sqrt(se / n);
}

// Reference SSIM of channel c at pixel (px, py): the full 2D Gaussian window, cut at the border
// and renormalised, moments and formula evaluated directly (no separable passes).
double DirectSsimAt(const MetricImage& a, const MetricImage& b, int c, int px, int py) {
    double wsum = 0, mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (int y = std::max(0, py - 5); y <= std::min(a.height - 1, py + 5); ++y) {
        for (int x = std::max(0, px - 5); x <= std::min(a.width - 1, px + 5); ++x) {
            const double d2 = double((x - px) * (x - px) + (y - py) * (y - py));
            const double g = std::exp(-d2 / (2 * 1.5 * 1.5));
            const size_t i = (size_t(y) * size_t(a.width) + size_t(x)) * 3 + size_t(c);
            const double va = Clamp01(a.rgb[i]), vb = Clamp01(b.rgb[i]);
            wsum += g, mx += g * va, my += g * vb, xx += g * va * va, yy += g * vb * vb;
            xy += g * va * vb;
        }
    }
    mx /= wsum, my /= wsum, xx /= wsum, yy /= wsum, xy /= wsum;
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    return (2 * mx * my + c1) * (2 * (xy - mx * my) + c2) /
           ((mx * mx + my * my + c1) * (xx - mx * mx + yy - my * my + c2));
}

double DirectSsim(const MetricImage& a, const MetricImage& b, const std::vector<uint8_t>* mask) {
    double sum = 0, n = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            if (mask && (*mask)[size_t(y) * size_t(a.width) + size_t(x)] == 0) continue;
            for (int c = 0; c < 3; ++c) sum += DirectSsimAt(a, b, c, x, y) / 3;
            n += 1;
        }
    }
    return sum / n;
}

TEST(ImageMetric, KnownPerturbationRmsePsnr) {
    const MetricImage ref = RandomImage(17, 9, 1);
    MetricImage test = ref;
    for (size_t i = 0; i < test.rgb.size(); ++i) test.rgb[i] += (i % 2 ? 0.05f : -0.02f);
    const ImageScores s = CompareFloat(test, ref);
    const double rmse = DirectRmse(test, ref, nullptr);
    EXPECT_NEAR(s.rmse, rmse, 1e-12);
    // 459 channel values: 229 odd indices moved by +0.05, 230 even ones by −0.02.
    EXPECT_NEAR(s.rmse, std::sqrt((229 * 0.05 * 0.05 + 230 * 0.02 * 0.02) / 459), 1e-6);
    EXPECT_NEAR(s.psnr, 20 * std::log10(1 / rmse), 1e-9);
    EXPECT_EQ(s.pixels, size_t(17 * 9));
}

TEST(ImageMetric, IdenticalImagesAndClamping) {
    MetricImage ref = RandomImage(12, 12, 2, -0.5f, 1.5f);  // half the values outside [0, 1]
    MetricImage test = ref;
    for (float& v : test.rgb) v = v > 1 ? v + 3 : v < 0 ? v - 3 : v;  // same display values
    for (const ImageScores& s : {CompareFloat(test, ref), Compare8Bit(test, ref)}) {
        EXPECT_EQ(s.rmse, 0.0) << s;
        EXPECT_EQ(s.psnr, kMaxPsnr) << s;
        EXPECT_EQ(s.ssim, 1.0) << s;
    }
    const ImageScores far = CompareFloat(MetricImage{1, 1, {1, 1, 1}}, {1, 1, {0, 0, 0}});
    EXPECT_EQ(far.rmse, 1.0);
    EXPECT_EQ(far.psnr, 0.0);
}

TEST(ImageMetric, SsimConstantOffsetMatchesFormula) {
    const int w = 20, h = 15;
    const double a[3] = {0.25, 0.5, 0.75}, offset = 0.1;
    MetricImage ref{w, h, {}}, test{w, h, {}};
    for (int i = 0; i < w * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            ref.rgb.push_back(float(a[c]));
            test.rgb.push_back(float(a[c] + offset));
        }
    }
    // Constant images: σ = 0, so SSIM = (2 μx μy + C1) / (μx² + μy² + C1) per channel.
    double expected = 0;
    for (int c = 0; c < 3; ++c) {
        const double mx = double(float(a[c] + offset)), my = double(float(a[c]));
        expected += (2 * mx * my + kSsimC1) / (mx * mx + my * my + kSsimC1) / 3;
    }
    EXPECT_NEAR(CompareFloat(test, ref).ssim, expected, 1e-12);
    EXPECT_LT(CompareFloat(test, ref).ssim, 1.0);
}

TEST(ImageMetric, SsimMatchesDirectWindowEverywhere) {
    const MetricImage ref = RandomImage(16, 13, 3);
    MetricImage test = ref;
    std::mt19937 rng(4);
    std::normal_distribution<float> noise(0.0f, 0.08f);
    for (float& v : test.rgb) v += noise(rng);  // some values leave [0, 1]: clamping is exercised
    EXPECT_NEAR(CompareFloat(test, ref).ssim, DirectSsim(test, ref, nullptr), 1e-12);
    // A 4×4 image: every window is cut by the border.
    const MetricImage small = RandomImage(4, 4, 5), small2 = RandomImage(4, 4, 6);
    EXPECT_NEAR(CompareFloat(small, small2).ssim, DirectSsim(small, small2, nullptr), 1e-12);
}

TEST(ImageMetric, EightBitQuantization) {
    EXPECT_EQ(Quantize8(-1.0f), 0);
    EXPECT_EQ(Quantize8(2.0f), 255);
    EXPECT_EQ(Quantize8(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(Quantize8(10.49f / 255), 10);
    EXPECT_EQ(Quantize8(10.51f / 255), 11);
    // A difference below half a code vanishes; one across a rounding boundary becomes a full code.
    const MetricImage ref{2, 1, {10.1f / 255, 0.5f, 0.5f, 10.49f / 255, 0.25f, 0.25f}};
    const MetricImage test{2, 1, {10.3f / 255, 0.5f, 0.5f, 10.51f / 255, 0.25f, 0.25f}};
    const ImageScores f = CompareFloat(test, ref), q = Compare8Bit(test, ref);
    EXPECT_NEAR(f.rmse, DirectRmse(test, ref, nullptr), 1e-12);
    EXPECT_NEAR(q.rmse, std::sqrt((1.0 / 255) * (1.0 / 255) / 6), 1e-12);
    EXPECT_GT(q.rmse, f.rmse);
    // On a random image the 8-bit RMSE equals the direct one on quantized values.
    const MetricImage r1 = RandomImage(9, 7, 7), r2 = RandomImage(9, 7, 8);
    double se = 0;
    for (size_t i = 0; i < r1.rgb.size(); ++i) {
        const double d = std::nearbyint(Clamp01(r1.rgb[i]) * 255) / 255 -
                         std::nearbyint(Clamp01(r2.rgb[i]) * 255) / 255;
        se += d * d;
    }
    EXPECT_NEAR(Compare8Bit(r1, r2).rmse, std::sqrt(se / double(r1.rgb.size())), 1e-12);
}

TEST(ImageMetric, MaskSelectsPixelsAndWindowCentres) {
    const MetricImage ref = RandomImage(14, 11, 9);
    MetricImage test = RandomImage(14, 11, 10);
    std::vector<uint8_t> mask(14 * 11, 0);
    for (size_t i = 0; i < mask.size(); i += 3) mask[i] = 1;
    const ImageScores s = CompareFloat(test, ref, &mask);
    EXPECT_EQ(s.pixels, (mask.size() + 2) / 3);
    EXPECT_NEAR(s.rmse, DirectRmse(test, ref, &mask), 1e-12);
    EXPECT_NEAR(s.ssim, DirectSsim(test, ref, &mask), 1e-12);
    // Changing a masked-out pixel leaves RMSE alone; an all-ones mask equals no mask.
    test.rgb[3] += 0.5f;
    EXPECT_EQ(CompareFloat(test, ref, &mask).rmse, s.rmse);
    const std::vector<uint8_t> all(mask.size(), 255);
    EXPECT_EQ(CompareFloat(test, ref, &all), CompareFloat(test, ref));
    // An empty selection gives NaN scores and no pixels.
    const std::vector<uint8_t> none(mask.size(), 0);
    const ImageScores e = Compare8Bit(test, ref, &none);
    EXPECT_EQ(e.pixels, 0u);
    EXPECT_TRUE(std::isnan(e.rmse) && std::isnan(e.psnr) && std::isnan(e.ssim));
}

TEST(ImageMetric, SizeMismatchThrows) {
    const MetricImage a = RandomImage(4, 4, 1), b = RandomImage(4, 5, 1);
    EXPECT_THROW(CompareFloat(a, b), std::invalid_argument);
    MetricImage shortBuffer = a;
    shortBuffer.rgb.pop_back();
    EXPECT_THROW(CompareFloat(shortBuffer, a), std::invalid_argument);
    const std::vector<uint8_t> mask(15, 1);
    EXPECT_THROW(Compare8Bit(a, a, &mask), std::invalid_argument);
}

TEST(ImageMetric, VgaIsDeterministic) {
    const MetricImage ref = RandomImage(640, 480, 11), test = RandomImage(640, 480, 12);
    const ImageScores first = CompareFloat(test, ref), second = CompareFloat(test, ref);
    EXPECT_EQ(first, second);  // bitwise: operator== on doubles
    EXPECT_GT(first.ssim, -1.0);
    EXPECT_LT(first.ssim, 1.0);
}

// ---- Report writer -----------------------------------------------------------------------------

std::string ReadAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

size_t Count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

fs::path MakeTempDir() {
    std::string pattern = (fs::path(testing::TempDir()) / "pem_report_XXXXXX").string();
    EXPECT_NE(mkdtemp(pattern.data()), nullptr);
    return pattern;
}

MethodResult Result(std::string method, std::string setting, std::string position, double seconds,
                    double rmse) {
    MethodResult r{
        std::move(method), std::move(setting), std::move(position), seconds, 1000, {}, {}};
    r.floatScores = {rmse, 20 * std::log10(1 / rmse), 0.9, 100};
    r.scores8 = {rmse * 1.1, 20 * std::log10(1 / (rmse * 1.1)), 0.89, 100};
    return r;
}

ReportData SampleData() {
    ReportData d;
    d.title = "test report";
    d.scene = "a";
    d.machine = "test machine | 2 cores";
    d.threads = 2;
    d.buildFlags = "-O2 -ffp-contract=off";
    d.compiler = "gcc 12";
    d.results = {Result("layered PEM", "t=10", "on circle", 0.5, 0.01),
                 Result("static EM", "", "on circle", 0.01, 0.2),
                 Result("layered PEM", "t=3", "on circle", 0.2, 0.03),
                 Result("ray tracer", "9 spp", "between samples", 40, 0.005),
                 Result("ray tracer", "1 spp", "between samples", 5, 0.04),
                 Result("hybrid", "t=3", "10° above", 1.5, 0.02)};
    d.leftOut = {{"glass <tracing>", "skipped", "converged", 2.5}, {"mirror", "kept", "", 0.5}};
    d.stability = {{"near-singular", "solve", "finite", "finite", true, 1e-9, 1e8, ""},
                   {"nan input", "input", "error", "crash", false, kNaN, kNaN, "detail"}};
    d.notes = {"first note", "second & <note>"};
    return d;
}

TEST(ReportWriter, WritesFourParseableFiles) {
    const fs::path dir = MakeTempDir();
    ReportData data = SampleData();
    data.budget = {{"[\"lens\"]",
                    "on circle",
                    10,
                    {{"two-term model", 30.0, NAN},
                     {"maps", 20.0, 10.0, 24.5, NAN},
                     {"frame", 19.0, 1.0, 23.0, 1.5}}}};
    WriteReport(data, dir.string());
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4);
    // Markdown: every method and position, the stability verdicts and the left-out total.
    const std::string md = ReadAll(dir / "report.md");
    for (const MethodResult& r : data.results) {
        EXPECT_NE(md.find(r.method), std::string::npos) << r.method;
        EXPECT_NE(md.find("## Position: " + r.position), std::string::npos) << r.position;
    }
    EXPECT_EQ(Count(md, "PASS"), 1u);
    EXPECT_EQ(Count(md, "FAIL"), 1u);
    EXPECT_NE(md.find("**3**"), std::string::npos);  // 2.5 + 0.5 seconds saved
    EXPECT_NE(md.find("test machine \\| 2 cores"), std::string::npos);
    EXPECT_NE(md.find("- second & <note>"), std::string::npos);
    // JSON: parses, keeps the context and every result.
    const nlohmann::json j = nlohmann::json::parse(ReadAll(dir / "report.json"));
    EXPECT_EQ(j.at("threads"), 2);
    EXPECT_EQ(j.at("machine"), data.machine);
    EXPECT_EQ(j.at("buildFlags"), data.buildFlags);
    EXPECT_EQ(j.at("compiler"), data.compiler);
    EXPECT_EQ(j.at("results").size(), data.results.size());
    EXPECT_EQ(j.at("leftOutSecondsSaved"), 3.0);
    EXPECT_TRUE(j.at("stability")[1].at("residual").is_null());
    // SVG: one marker per result, escaped text, no external references.
    const std::string svg = ReadAll(dir / "report.svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_EQ(Count(svg, "class=\"marker\""), data.results.size());
    EXPECT_EQ(svg.find("href"), std::string::npos);
    EXPECT_EQ(svg.find("<script"), std::string::npos);
    // The error budget: a table row per stage against the reference and the two-term frame
    // ("—" and null where not measured), a bar per stage.
    EXPECT_NE(md.find("| two-term model | 30.00 | — | — | — |"), std::string::npos);
    EXPECT_NE(md.find("| maps | 20.00 | 10.00 | 24.50 | — |"), std::string::npos);
    EXPECT_NE(md.find("| frame | 19.00 | 1.00 | 23.00 | 1.50 |"), std::string::npos);
    const nlohmann::json& stages = j.at("budget")[0].at("stages");
    EXPECT_TRUE(stages[0].at("cost").is_null());
    EXPECT_TRUE(stages[0].at("psnrVsTwoTerm").is_null());
    EXPECT_EQ(stages[1].at("psnr"), 20.0);
    EXPECT_EQ(stages[1].at("psnrVsTwoTerm"), 24.5);
    EXPECT_EQ(stages[2].at("costVsTwoTerm"), 1.5);
    const std::string budgetSvg = ReadAll(dir / "budget.svg");
    EXPECT_EQ(Count(budgetSvg, "<rect x="), 3u);
    EXPECT_EQ(Count(budgetSvg, "vs two-term 23.0 dB"), 1u);
    fs::remove_all(dir);
}

// Packed PEMs: a table row per setting with the mean change per method, the JSON rows, and
// packs.svg with a marker per setting on its coding's curve.
TEST(ReportWriter, PackedPemsTableJsonAndCurve) {
    const fs::path dir = MakeTempDir();
    ReportData data = SampleData();
    PackRow lossless{"lossless", 1000, 9.0, 1.2, 2.0, 0, {}};
    PackRow lossy{"--max-error 31 --ratio 16", 200, 45, 6.0, 3.0, 255, {}};
    for (const char* position : {"on circle", "between samples"}) {
        lossless.deltas.push_back({"hybrid", position, 20.0, 0.0});
        lossless.deltas.push_back({"layered PEM", position, 18.0, 0.0});
        lossy.deltas.push_back({"hybrid", position, 19.5, -0.5});
        lossy.deltas.push_back(
            {"layered PEM", position, 17.0, std::string(position) == "on circle" ? -1.0 : -0.5});
    }
    data.packs = {lossless, lossy};
    WriteReport(data, dir.string());
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 5);
    const std::string md = ReadAll(dir / "report.md");
    EXPECT_NE(
        md.find("| `--max-error 31 --ratio 16` | 200 | 45.0:1 | 6.0:1 | 255 | 3.0 | -0.50 dB | "
                "-0.50 dB | -0.75 dB | n/a |"),
        std::string::npos)
        << md;
    const nlohmann::json j = nlohmann::json::parse(ReadAll(dir / "report.json"));
    ASSERT_EQ(j.at("packs").size(), 2u);
    EXPECT_EQ(j.at("packs")[1].at("vsPng"), 6.0);
    EXPECT_EQ(j.at("packs")[1].at("frames").size(), 4u);
    const std::string svg = ReadAll(dir / "packs.svg");
    EXPECT_EQ(Count(svg, "<polyline"), 2u);
    EXPECT_EQ(Count(svg, "<circle"), 4u);  // a marker per setting and two legend entries
    fs::remove_all(dir);
}

TEST(ReportWriter, SortsByMethodAppearanceThenNaturalSetting) {
    const std::vector<MethodResult> sorted = SortedResults(SampleData().results);
    std::vector<std::string> order;
    for (const MethodResult& r : sorted) order.push_back(r.method + "/" + r.setting);
    EXPECT_EQ(order,
              (std::vector<std::string>{"layered PEM/t=3", "layered PEM/t=10", "static EM/",
                                        "ray tracer/1 spp", "ray tracer/9 spp", "hybrid/t=3"}));
    const std::string md = ReportMarkdown(SampleData());
    EXPECT_LT(md.find("| layered PEM | t=3 |"), md.find("| layered PEM | t=10 |"));
}

TEST(ReportWriter, NanAndZeroEntriesAreSkippedNotFatal) {
    ReportData data = SampleData();
    data.results.push_back(Result("static EM", "zero time", "on circle", 0, 0.1));
    data.results.push_back(Result("static EM", "nan error", "on circle", 0.1, kNaN));
    data.results.push_back(Result("static EM", "exact", "on circle", 0.1, 0.0));
    data.results.push_back(Result("hybrid", "negative", "10° above", -1, 0.1));
    const std::string svg = ReportSvg(data);
    EXPECT_EQ(Count(svg, "class=\"marker\""), SampleData().results.size());
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
    EXPECT_NE(ReportMarkdown(data).find("n/a"), std::string::npos);
    // Only unplottable values, and nothing at all, still give a valid document.
    ReportData bad;
    bad.results = {Result("x", "", "", kNaN, kNaN), Result("y", "", "p", 0, 0)};
    EXPECT_EQ(Count(ReportSvg(bad), "class=\"marker\""), 0u);
    EXPECT_EQ(nlohmann::json::parse(ReportJson(bad)).at("results").size(), 2u);
    EXPECT_NE(ReportSvg(ReportData{}).find("</svg>"), std::string::npos);
    const fs::path dir = MakeTempDir();
    EXPECT_NO_THROW(WriteReport(bad, dir.string()));
    fs::remove_all(dir);
}

TEST(ReportWriter, MissingDirectoryThrowsAndLeavesNothing) {
    const fs::path parent = MakeTempDir();
    const fs::path missing = parent / "does_not_exist";
    try {
        WriteReport(SampleData(), missing.string());
        FAIL() << "expected base::InputError";
    } catch (const base::InputError& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_TRUE(fs::is_empty(parent));
    fs::remove_all(parent);
}

}  // namespace
}  // namespace pem::report
