// SPDX-License-Identifier: MIT
// golden_job.h — the golden-image workflow `pemref golden` runs: generate a golden directory
// from a suite, check a suite against it, update (re-bless) what fails, and the JUnit XML a CI
// system reads.
//
//   GoldenOptions o;  o.profile = "llvmpipe";  o.version = "0.1.0";
//   Generate("suite", "goldens", o);
//   const CheckResult r = Check("suite", "goldens", o, print);   // r.Failures()
//   WriteJUnit(r, "junit.xml");
//
// A golden directory: golden.json (golden_file.h) and one PNG per test — or, generated with
// hashesOnly, golden.json alone (the tests are then compared by the SHA-256 of their pixels;
// pemref's conformance corpus is kept so). Check renders with the goldens' profile. A test
// passes when its image equals the golden (exact), lies within its fuzzy(D, N), or — tests
// with bounds_lsb — when the golden lies within the modelled profiles' range (model_bounds.h).
// A failure writes `<diff>/<name>.diff.png` (differing pixels in red over a dimmed golden) and
// `<name>.side.png` (golden | rendered | diff), diff = DIR/diff unless diffDir is given.
// Errors that stop a run (bad suite, missing golden PNG, unreadable golden.json):
// base::InputError naming the file; nothing is written then.
// Not here: the comparisons (image_diff.h, model_bounds.h, flip.h), rendering (golden_render.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "viewer_tty/golden/image_diff.h"

namespace pem::golden {

struct GoldenOptions {
    std::string profile;  // generate: default llvmpipe; check/update: must match golden.json
    std::string version;  // pemref's, recorded in golden.json
    std::string diffDir;  // check: where failures' pictures go (default DIR/diff)
    int threads = 1;
    bool hashesOnly = false;  // generate: golden.json without PNGs
};

struct TestResult {
    std::string name;
    bool passed = false;
    bool hasGolden = true;  // false: the suite's test has no golden yet
    std::string rule;       // "exact", "fuzzy(2, 40)", "bounds(1 LSB)", "sha256"
    std::string detail;     // what differed, in words ("" when nothing did)
    DiffStats diff;         // rendered against the golden (when it has a PNG)
    double flip = 0.0;      // LDR-ꟻLIP mean, for information (0 when identical)
    std::string diffPng, sideBySidePng;
    double seconds = 0.0;
    base::Image8 rendered;
    std::string renderedSha256, inputSha256;
};

struct CheckResult {
    std::string suite, profile;
    std::vector<TestResult> tests;
    std::vector<std::string> stale;  // in golden.json, no longer in the suite
    int Failures() const;
};

using TestCallback = std::function<void(const TestResult&)>;

// Renders every test of the suite and writes the golden directory `out` (created if needed).
void Generate(const std::string& suite, const std::string& out, const GoldenOptions& options,
              const TestCallback& onTest = {});

// Renders every test with the goldens' profile and compares; failures' pictures are written.
CheckResult Check(const std::string& suite, const std::string& dir, const GoldenOptions& options,
                  const TestCallback& onTest = {});

// Check, then re-bless the failing (and new) tests only and drop stale entries; returns the
// check's result (the names re-blessed are its failures).
CheckResult Update(const std::string& suite, const std::string& dir, const GoldenOptions& options,
                   const TestCallback& onTest = {});

// JUnit XML: one <testsuite> with one <testcase> per test, <failure> for failures.
void WriteJUnit(const CheckResult& result, const std::string& path);

}  // namespace pem::golden
