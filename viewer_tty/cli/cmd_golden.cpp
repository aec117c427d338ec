// SPDX-License-Identifier: MIT
// cmd_golden.cpp — argument parsing and output of `pemref golden` (cmd_golden.h).
#include "viewer_tty/cli/cmd_golden.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "base/input_error.h"
#include "base/png_io.h"
#include "viewer_tty/cli/args.h"
#include "viewer_tty/golden/flip.h"
#include "viewer_tty/golden/golden_job.h"
#include "viewer_tty/golden/model_bounds.h"
#include "viewer_tty/golden/suite.h"

namespace pem::cli {
namespace {

namespace fs = std::filesystem;

struct GoldenArgs {
    std::string suite, dir, out, junit, diffDir, profile;
    std::string imageA, imageB, fuzzy, diff, bounds;
    int threads = 1, lsb = -1;
    bool hashesOnly = false;
};

GoldenArgs& Args() {
    static GoldenArgs args;
    return args;
}

golden::GoldenOptions Options() {
    const GoldenArgs& a = Args();
    golden::GoldenOptions o;
    o.profile = a.profile;
    o.version = PemrefVersion();
    o.diffDir = a.diffDir;
    o.threads = a.threads;
    o.hashesOnly = a.hashesOnly;
    return o;
}

void PrintTest(const golden::TestResult& t) {
    std::printf("%-4s %-32s %-16s %s", t.passed ? "PASS" : "FAIL", t.name.c_str(), t.rule.c_str(),
                t.detail.c_str());
    if (t.flip > 0.0) std::printf("  (ꟻLIP mean %.4f)", t.flip);
    std::printf("\n");
    std::fflush(stdout);
}

void PrintGenerated(const golden::TestResult& t) {
    std::printf("%-32s %4dx%-4d %.16s  %.2f s\n", t.name.c_str(), t.rendered.width,
                t.rendered.height, t.renderedSha256.c_str(), t.seconds);
    std::fflush(stdout);
}

void PrintFailures(const golden::CheckResult& r) {
    for (const golden::TestResult& t : r.tests) {
        if (t.passed) continue;
        std::printf("%s: %s", t.name.c_str(), t.diffPng.c_str());
        if (!t.sideBySidePng.empty()) std::printf("  %s", t.sideBySidePng.c_str());
        std::printf("\n");
    }
    for (const std::string& s : r.stale)
        std::printf("stale golden (not in the suite): %s\n", s.c_str());
}

int RunCheck() {
    const GoldenArgs& a = Args();
    const golden::CheckResult r = golden::Check(a.suite, a.dir, Options(), PrintTest);
    PrintFailures(r);
    if (!a.junit.empty()) golden::WriteJUnit(r, a.junit);
    std::printf("%zu tests, %d failed (profile %s)\n", r.tests.size(), r.Failures(),
                r.profile.c_str());
    return r.Failures() == 0 ? 0 : 1;
}

int RunUpdate() {
    const GoldenArgs& a = Args();
    const golden::CheckResult r = golden::Update(a.suite, a.dir, Options(), PrintTest);
    int blessed = 0;
    for (const golden::TestResult& t : r.tests)
        if (!t.passed) std::printf("re-blessed: %s\n", t.name.c_str()), ++blessed;
    for (const std::string& s : r.stale) std::printf("removed (not in the suite): %s\n", s.c_str());
    std::printf("%zu tests, %d re-blessed, %zu removed\n", r.tests.size(), blessed, r.stale.size());
    return 0;
}

// "D,N" → fuzzy(D, N).
golden::Fuzzy ParseFuzzy(const std::string& text) {
    int d = -1;
    long long n = -1;
    char end = 0;
    if (std::sscanf(text.c_str(), "%d,%lld%c", &d, &n, &end) != 2 || d < 0 || d > 255 || n < 0)
        throw base::InputError("--fuzzy", "expects D,N (D in 0..255, N >= 0), not " + text);
    return {d, size_t(n)};
}

// The suite test SUITE/TEST names, or a raster case file named directly.
golden::GoldenTest BoundsTest(const std::string& spec) {
    const fs::path p(spec);
    if (p.extension() == ".json" && fs::is_regular_file(p)) {
        golden::GoldenTest t;
        t.name = p.stem().string();
        t.input = p.lexically_normal().string();
        return t;
    }
    const golden::Suite suite = golden::ReadSuite(p.parent_path().string());
    const golden::GoldenTest* t = suite.Find(p.filename().string());
    if (!t) throw base::InputError(spec, "no such test in " + suite.dir);
    return *t;
}

int RunBoundsCompare() {
    const GoldenArgs& a = Args();
    const golden::GoldenTest test = BoundsTest(a.bounds);
    const int lsb = a.lsb >= 0 ? a.lsb : test.boundsLsb.value_or(1);
    const base::Image8 image = base::ReadPng(a.imageA);
    const golden::ModelBounds b = golden::BoundsOf(test, a.threads);
    const golden::BoundsCheck c = golden::CheckBounds(b, image, lsb);
    std::string profiles;
    for (const std::string& p : b.profiles) profiles += (profiles.empty() ? "" : ", ") + p;
    std::printf("the profiles %s disagree on %zu of %d pixels, by up to %d\n", profiles.c_str(),
                b.SpannedPixels(), b.width * b.height, b.WidestSpan());
    if (c.sizeMismatch)
        std::printf("REJECTED: %s is %dx%d, the test %dx%d\n", a.imageA.c_str(), image.width,
                    image.height, b.width, b.height);
    else
        std::printf("%s: %zu pixels outside their range widened by %d LSB (worst by %d LSB)\n",
                    c.Accepted() ? "ACCEPTED" : "REJECTED", c.outsidePixels, lsb, c.largestExcess);
    return c.Accepted() ? 0 : 1;
}

int RunCompare() {
    const GoldenArgs& a = Args();
    if (!a.bounds.empty()) return RunBoundsCompare();
    if (a.imageB.empty()) throw base::InputError("compare", "needs two images (or --bounds)");
    const golden::Fuzzy fuzzy = a.fuzzy.empty() ? golden::Fuzzy{} : ParseFuzzy(a.fuzzy);
    const base::Image8 A = base::ReadPng(a.imageA), B = base::ReadPng(a.imageB);
    const golden::DiffStats d = golden::Compare(A, B);
    const bool accepted = golden::Accepts(fuzzy, d);
    if (d.sizeMismatch)
        std::printf("DIFFERENT: %dx%d against %dx%d\n", A.width, A.height, B.width, B.height);
    else
        std::printf(
            "%s (%s): %zu of %zu pixels differ, largest channel difference %d, "
            "ꟻLIP mean %.4f\n",
            accepted ? "ACCEPTED" : "DIFFERENT", golden::ToString(fuzzy).c_str(), d.differingPixels,
            d.pixels, d.maxDifference, d.differingPixels ? golden::FlipMean(A, B) : 0.0);
    if (!a.diff.empty()) base::WritePng(a.diff, golden::DiffImage(A, B));
    return accepted ? 0 : 1;
}

}  // namespace

void AddGoldenCommand(CLI::App& app) {
    GoldenArgs& a = Args();
    CLI::App* sub = app.add_subcommand("golden", "golden images: generate, check, update, compare");
    sub->require_subcommand(1);
    CLI::App* gen = sub->add_subcommand("generate", "render a suite into a golden directory");
    gen->add_option("suite", a.suite, "suite folder (case files, suite.json)")->required();
    gen->add_option("--out", a.out, "golden directory to write")->required();
    AddProfileOption(gen, &a.profile);
    gen->add_flag("--hashes-only", a.hashesOnly, "golden.json alone, no PNGs");
    CLI::App* check =
        sub->add_subcommand("check", "re-render a suite and compare with its goldens");
    check->add_option("suite", a.suite, "suite folder")->required();
    check->add_option("dir", a.dir, "golden directory")->required();
    check->add_option("--junit", a.junit, "write JUnit XML to this file");
    check->add_option("--diff-dir", a.diffDir, "failures' pictures (default DIR/diff)");
    AddProfileOption(check, &a.profile);
    CLI::App* update = sub->add_subcommand("update", "re-bless the failing tests only");
    update->add_option("suite", a.suite, "suite folder")->required();
    update->add_option("dir", a.dir, "golden directory")->required();
    AddProfileOption(update, &a.profile);
    for (CLI::App* s : {gen, check, update})
        s->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    CLI::App* cmp =
        sub->add_subcommand("compare", "compare two PNGs (or one with the model bounds)");
    cmp->add_option("a", a.imageA, "first image (the golden), or the image under --bounds")
        ->required();
    cmp->add_option("b", a.imageB, "second image");
    cmp->add_option("--fuzzy", a.fuzzy, "D,N: at most N pixels differ, none by more than D");
    cmp->add_option("--diff", a.diff, "write the diff image here");
    cmp->add_option("--bounds", a.bounds, "SUITE/TEST (or a case file): the modelled range");
    cmp->add_option("--lsb", a.lsb, "widen the bounds by N (default: bounds_lsb, else 1)")
        ->check(CLI::Range(0, 255));
    cmp->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
}

int RunGoldenCommand(const CLI::App& app) {
    const CLI::App* sub = app.get_subcommand("golden");
    const GoldenArgs& a = Args();
    try {
        if (sub->got_subcommand("generate")) {
            golden::Generate(a.suite, a.out, Options(), PrintGenerated);
            std::printf("goldens written to %s\n", a.out.c_str());
            return 0;
        }
        if (sub->got_subcommand("check")) return RunCheck();
        if (sub->got_subcommand("update")) return RunUpdate();
        return RunCompare();
    } catch (const std::exception& e) {  // could not run
        std::fprintf(stderr, "pemref: %s\n", e.what());
        return 2;
    }
}

}  // namespace pem::cli
