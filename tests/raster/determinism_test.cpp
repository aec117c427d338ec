// SPDX-License-Identifier: MIT
// determinism_test.cpp — the same bytes (colour and depth buffer) for any thread count and for
// both builds of the fragment stage (baseline and AVX2+FMA, fragment.h), on the conformance
// corpus and the benchmark frame.
#include <gtest/gtest.h>

#include <cstdlib>

#include "raster/fragment.h"
#include "raster/render.h"
#include "tests/case_generator.h"

namespace pem::raster {
namespace {

TEST(Determinism, ThreadCountDoesNotChangeBytes) {
    std::vector<test::NamedCase> cases = test::ConformanceCases();
    cases.push_back({"bench_small", test::BenchmarkFrame(160, 120, 25, 50, 64)});
    for (const auto& c : cases) {
        const PreparedFrame pf(c.frame);
        RenderOptions opt;
        const RenderResult one = Render(pf, opt);
        for (int threads : {2, 3, 8}) {
            opt.threads = threads;
            const RenderResult r = Render(pf, opt);
            ASSERT_EQ(r.image8, one.image8) << c.name << " threads " << threads;
            ASSERT_EQ(r.depth, one.depth) << c.name << " threads " << threads;
        }
    }
}

TEST(Determinism, BaselineAndFmaBuildsAgree) {
    const char* name = nullptr;
    SelectDrawBands(&name);
    if (DrawBandsFma() == nullptr || std::string(name) != "avx2-fma")
        GTEST_SKIP() << "no AVX2+FMA build on this machine/configuration";
    std::vector<test::NamedCase> cases = test::ConformanceCases();
    cases.push_back({"bench_small", test::BenchmarkFrame(160, 120, 25, 50, 64)});
    for (const auto& c : cases) {
        const PreparedFrame pf(c.frame);
        const RenderResult fma = Render(pf, {});
        setenv("PEM_ISA", "base", 1);
        const RenderResult base = Render(pf, {});
        unsetenv("PEM_ISA");
        ASSERT_EQ(fma.image8, base.image8) << c.name;
        ASSERT_EQ(fma.depth, base.depth) << c.name;
    }
}

}  // namespace
}  // namespace pem::raster
