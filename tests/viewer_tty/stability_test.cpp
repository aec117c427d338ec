// SPDX-License-Identifier: MIT
// stability_test.cpp — the numerical stability suite (viewer_tty/stability/stability.h), one test
// per case family: every case passes, reports finite figures where they apply, and states its
// outcome.
#include "viewer_tty/stability/stability.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace pem::stability {
namespace {

StabilityOptions Options() {
    StabilityOptions o;
    o.dataDir = PEM_TEST_DATA_DIR;
    return o;
}

void Print(const StabilityCase& c) {
    std::printf("[measure] %-48s %s residual %.3g condition %.3g %.3f s | %s\n", c.name.c_str(),
                c.passed ? "PASS" : "FAIL", c.residual, c.condition, c.seconds, c.outcome.c_str());
}

// Common checks; `finiteFigures`: residual and condition must both be finite.
void ExpectPassed(const std::vector<StabilityCase>& cases, size_t count, bool finiteFigures) {
    ASSERT_EQ(cases.size(), count);
    for (const StabilityCase& c : cases) {
        Print(c);
        EXPECT_TRUE(c.passed) << c.name << ": " << c.outcome << "\n  " << c.detail;
        EXPECT_FALSE(c.expected.empty()) << c.name;
        EXPECT_FALSE(c.outcome.empty()) << c.name;
        EXPECT_FALSE(c.detail.empty()) << c.name;
        EXPECT_EQ(c.outcome.find("FAILED"), std::string::npos) << c.name;
        EXPECT_TRUE(c.category == "stiff" || c.category == "extreme") << c.name;
        EXPECT_FALSE(std::isinf(c.residual)) << c.name;
        EXPECT_FALSE(std::isinf(c.condition)) << c.name;
        if (finiteFigures) {
            EXPECT_TRUE(std::isfinite(c.residual)) << c.name;
            EXPECT_TRUE(std::isfinite(c.condition)) << c.name;
        }
        EXPECT_GE(c.seconds, 0.0);
    }
}

TEST(Stability, SolverStiffSystems) {
    const std::vector<StabilityCase> cases = RunSolverStabilityCases(Options());
    ExpectPassed(cases, 5, true);
    for (const StabilityCase& c : cases) {
        EXPECT_EQ(c.category, "stiff");
        EXPECT_GE(c.condition, 1.0) << c.name;  // sigma_max / sigma_min
        EXPECT_LT(c.residual, 0.1) << c.name;
        EXPECT_NE(c.detail.find("SolveDirect"), std::string::npos) << c.name;
    }
}

TEST(Stability, ShellsNearlyCoplanar) {
    std::vector<StabilityCase> cases = RunShellStabilityCases(Options());
    ASSERT_EQ(cases.size(), 3u);
    // Hit points beyond float range (nearly parallel quad rays) give finite lookup vectors.
    const StabilityCase far = cases[1];
    Print(far);
    EXPECT_TRUE(far.passed) << far.outcome;
    cases.erase(cases.begin() + 1);
    ExpectPassed(cases, 2, false);
    EXPECT_TRUE(std::isfinite(cases[0].residual) && std::isfinite(cases[0].condition));
    EXPECT_TRUE(std::isfinite(cases[1].residual));
}

TEST(Stability, RayPathsExtremeIorAndViewpoints) {
    const std::vector<StabilityCase> cases = RunRayPathStabilityCases(Options());
    ExpectPassed(cases, 5, false);
    for (const StabilityCase& c : cases) EXPECT_TRUE(std::isfinite(c.residual)) << c.name;
}

TEST(Stability, RasterCubeEdgesAndDegenerateTriangles) {
    const std::vector<StabilityCase> cases = RunRasterStabilityCases(Options());
    ExpectPassed(cases, 2, false);
    for (const StabilityCase& c : cases) EXPECT_TRUE(std::isfinite(c.residual)) << c.name;
}

TEST(Stability, ScenesSliversAndNonFiniteFiles) {
    const std::vector<StabilityCase> cases = RunSceneStabilityCases(Options());
    ExpectPassed(cases, 2, false);
    EXPECT_TRUE(std::isfinite(cases[0].residual) && std::isfinite(cases[0].condition));
    // The defined outcome of the NaN / Inf files is the clear error.
    EXPECT_NE(cases[1].outcome.find("base::InputError"), std::string::npos);
    EXPECT_NE(cases[1].detail.find("non-finite"), std::string::npos);
}

TEST(Stability, WholeSuiteWithinBudget) {
    StabilityOptions o = Options();
    const std::vector<StabilityCase> cases = RunStabilitySuite(o);
    EXPECT_EQ(cases.size(), 17u);
    double seconds = 0.0;
    for (const StabilityCase& c : cases) seconds += c.seconds;
    std::printf("[measure] whole suite: %zu cases, %.2f s\n", cases.size(), seconds);
#ifdef NDEBUG
    EXPECT_LT(seconds, 20.0);
#endif
}

}  // namespace
}  // namespace pem::stability
