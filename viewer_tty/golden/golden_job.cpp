// SPDX-License-Identifier: MIT
// golden_job.cpp — generate, check, update and JUnit (golden_job.h).
#include "viewer_tty/golden/golden_job.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "base/png_io.h"
#include "base/sha256.h"
#include "base/xml_text.h"
#include "raster/profile.h"
#include "viewer_tty/golden/flip.h"
#include "viewer_tty/golden/golden_file.h"
#include "viewer_tty/golden/golden_render.h"
#include "viewer_tty/golden/model_bounds.h"
#include "viewer_tty/golden/suite.h"

namespace pem::golden {
namespace {

namespace fs = std::filesystem;

std::string PixelSha(const base::Image8& image) {
    return base::Sha256Hex(image.rgba.data(), image.rgba.size());
}

double SecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Renders a test: the picture, its hashes and the time it took.
TestResult RenderResult(const GoldenTest& t, const std::string& profile, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    TestResult r;
    r.name = t.name;
    Rendered img = RenderTest(t, profile, threads);
    r.rendered = std::move(img.image);
    r.renderedSha256 = PixelSha(r.rendered);
    r.inputSha256 = img.inputSha256;
    r.seconds = SecondsSince(t0);
    return r;
}

std::string DiffWords(const DiffStats& d) {
    if (d.sizeMismatch) return "the sizes differ";
    if (d.differingPixels == 0) return "";
    return std::to_string(d.differingPixels) + " of " + std::to_string(d.pixels) +
           " pixels differ, largest channel difference " + std::to_string(d.maxDifference);
}

// Compares a rendered test with its golden PNG under the test's rule.
void CompareWithPng(const GoldenTest& t, const base::Image8& golden, int threads, TestResult* r) {
    r->diff = Compare(golden, r->rendered);
    if (r->diff.differingPixels > 0 && !r->diff.sizeMismatch)
        r->flip = FlipMean(golden, r->rendered);
    if (t.boundsLsb) {
        r->rule = "bounds(" + std::to_string(*t.boundsLsb) + " LSB)";
        const BoundsCheck c = CheckBounds(BoundsOf(t, threads), golden, *t.boundsLsb);
        r->passed = c.Accepted();
        r->detail = c.sizeMismatch ? "the sizes differ"
                    : c.Accepted() ? ""
                                   : std::to_string(c.outsidePixels) +
                                         " golden pixels outside the modelled range, worst by " +
                                         std::to_string(c.largestExcess) + " LSB";
        return;
    }
    r->rule = ToString(t.fuzzy);
    r->passed = Accepts(t.fuzzy, r->diff);
    r->detail = DiffWords(r->diff);
}

// One test of a check: rendered, then compared with its golden (if any).
TestResult Evaluate(const GoldenTest& t, const GoldenRecord& record, const std::string& profile,
                    int threads) {
    TestResult r = RenderResult(t, profile, threads);
    const auto t0 = std::chrono::steady_clock::now();
    const GoldenEntry* e = record.Find(t.name);
    if (!e) {
        r.hasGolden = false;
        r.rule = ToString(t.fuzzy);
        r.detail = "no golden yet (pemref golden update blesses it)";
        return r;
    }
    if (e->png.empty()) {
        r.rule = "sha256";
        r.passed = r.renderedSha256 == e->sha256;
        r.detail = r.passed ? "" : "the pixels' SHA-256 differs from golden.json";
    } else {
        CompareWithPng(t, base::ReadPng(record.dir + "/" + e->png), threads, &r);
    }
    if (e->inputSha256 != r.inputSha256)
        r.detail += " (the input changed since the golden was made)";
    r.seconds += SecondsSince(t0);
    return r;
}

// A failure's pictures under diffDir: diff and side by side, or the rendered image alone.
void WriteFailurePictures(const std::string& diffDir, const GoldenRecord& record, TestResult* r) {
    fs::create_directories(diffDir);
    const GoldenEntry* e = record.Find(r->name);
    if (!e || e->png.empty()) {
        r->diffPng = diffDir + "/" + r->name + ".rendered.png";
        base::WritePng(r->diffPng, r->rendered);
        return;
    }
    const base::Image8 golden = base::ReadPng(record.dir + "/" + e->png);
    r->diffPng = diffDir + "/" + r->name + ".diff.png";
    r->sideBySidePng = diffDir + "/" + r->name + ".side.png";
    base::WritePng(r->diffPng, DiffImage(golden, r->rendered));
    base::WritePng(r->sideBySidePng, SideBySide(golden, r->rendered));
}

// The goldens' profile; a different --profile is an error (the goldens would all fail).
std::string ProfileFor(const GoldenRecord& record, const GoldenOptions& options) {
    if (!options.profile.empty() && options.profile != record.profile)
        throw base::InputError(record.dir + "/golden.json",
                               "made with profile " + record.profile + ", not " + options.profile +
                                   " (generate anew to change the profile)");
    raster::ProfileNamed(record.profile);  // a profile this pemref knows
    return record.profile;
}

CheckResult RunCheck(const Suite& suite, const GoldenRecord& record, const GoldenOptions& options,
                     const TestCallback& onTest) {
    CheckResult result{suite.dir, ProfileFor(record, options), {}, {}};
    for (const GoldenTest& t : suite.tests) {
        result.tests.push_back(Evaluate(t, record, result.profile, options.threads));
        if (onTest) onTest(result.tests.back());
    }
    for (const GoldenEntry& e : record.tests)
        if (!suite.Find(e.name)) result.stale.push_back(e.name);
    return result;
}

}  // namespace

int CheckResult::Failures() const {
    int n = 0;
    for (const TestResult& t : tests) n += !t.passed;
    return n;
}

void Generate(const std::string& suiteDir, const std::string& out, const GoldenOptions& options,
              const TestCallback& onTest) {
    const Suite suite = ReadSuite(suiteDir);
    const raster::ProfileInfo& profile =
        raster::ProfileNamed(options.profile.empty() ? "llvmpipe" : options.profile);
    GoldenRecord record{out, profile.name, profile.model, options.version, {}};
    std::vector<TestResult> results;
    for (const GoldenTest& t : suite.tests) {  // every picture first: a failure writes nothing
        results.push_back(RenderResult(t, profile.name, options.threads));
        results.back().passed = true;
        results.back().rule = "generated";
        if (onTest) onTest(results.back());
    }
    fs::create_directories(out);
    for (const TestResult& r : results) {
        const std::string png = options.hashesOnly ? "" : r.name + ".png";
        if (!png.empty()) base::WritePng(out + "/" + png, r.rendered);
        record.tests.push_back(
            {r.name, png, r.renderedSha256, r.inputSha256, r.rendered.width, r.rendered.height});
    }
    WriteGoldenFile(record);
}

CheckResult Check(const std::string& suiteDir, const std::string& dir, const GoldenOptions& options,
                  const TestCallback& onTest) {
    const Suite suite = ReadSuite(suiteDir);
    GoldenRecord record = ReadGoldenFile(dir);
    CheckResult result = RunCheck(suite, record, options, onTest);
    const std::string diffDir = options.diffDir.empty() ? dir + "/diff" : options.diffDir;
    for (TestResult& t : result.tests)
        if (!t.passed) WriteFailurePictures(diffDir, record, &t);
    return result;
}

CheckResult Update(const std::string& suiteDir, const std::string& dir,
                   const GoldenOptions& options, const TestCallback& onTest) {
    const Suite suite = ReadSuite(suiteDir);
    GoldenRecord record = ReadGoldenFile(dir);
    const CheckResult result = RunCheck(suite, record, options, onTest);
    bool hashesOnly = !record.tests.empty();
    for (const GoldenEntry& e : record.tests) hashesOnly = hashesOnly && e.png.empty();
    // Re-bless the failures (their PNGs first, golden.json last), then drop stale entries.
    for (const TestResult& t : result.tests) {
        if (t.passed) continue;
        const std::string png = hashesOnly ? "" : t.name + ".png";
        if (!png.empty()) base::WritePng(dir + "/" + png, t.rendered);
        const GoldenEntry entry{
            t.name, png, t.renderedSha256, t.inputSha256, t.rendered.width, t.rendered.height};
        if (GoldenEntry* e = record.Find(t.name))
            *e = entry;
        else
            record.tests.push_back(entry);
    }
    std::erase_if(record.tests, [&](const GoldenEntry& e) { return !suite.Find(e.name); });
    record.pemref = options.version;
    WriteGoldenFile(record);
    return result;
}

void WriteJUnit(const CheckResult& r, const std::string& path) {
    double seconds = 0.0;
    for (const TestResult& t : r.tests) seconds += t.seconds;
    const std::string counts = "tests=\"" + std::to_string(r.tests.size()) + "\" failures=\"" +
                               std::to_string(r.Failures()) + "\" errors=\"0\"";
    std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites " + counts + ">\n";
    xml += "  <testsuite name=\"pemref golden " + base::XmlEscaped(r.suite) + "\" " + counts +
           " time=\"" + std::to_string(seconds) + "\">\n";
    xml += "    <properties><property name=\"profile\" value=\"" + base::XmlEscaped(r.profile) +
           "\"/></properties>\n";
    for (const TestResult& t : r.tests) {
        xml += "    <testcase classname=\"golden\" name=\"" + base::XmlEscaped(t.name) +
               "\" time=\"" + std::to_string(t.seconds) + "\"";
        if (t.passed) {
            xml += "/>\n";
            continue;
        }
        xml += ">\n      <failure type=\"" + base::XmlEscaped(t.rule) + "\" message=\"" +
               base::XmlEscaped(t.rule + ": " + t.detail) +
               "\">diff: " + base::XmlEscaped(t.diffPng) +
               "\nside by side: " + base::XmlEscaped(t.sideBySidePng) +
               "</failure>\n    </testcase>\n";
    }
    xml += "  </testsuite>\n</testsuites>\n";
    base::WriteTextAtomic(path, xml);
}

}  // namespace pem::golden
