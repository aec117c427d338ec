// SPDX-License-Identifier: MIT
// determinism_test.cpp — the same bytes for any thread count and for both builds of the fragment
// stage (baseline and AVX2+FMA, fragment.h), on the conformance corpus and the benchmark frame.
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
        const Image8 one = Render(pf, opt).image8;
        for (int threads : {2, 3, 8}) {
            opt.threads = threads;
            ASSERT_EQ(Render(pf, opt).image8, one) << c.name << " threads " << threads;
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
        const Image8 fma = Render(pf, {}).image8;
        setenv("PEM_ISA", "base", 1);
        const Image8 base = Render(pf, {}).image8;
        unsetenv("PEM_ISA");
        ASSERT_EQ(fma, base) << c.name;
    }
}

}  // namespace
}  // namespace pem::raster
