// SPDX-License-Identifier: MIT
// active_system_test.cpp — the active-texel system and what surrounds it (issue 4):
//  - the regularizer rows built over the active texels equal the full rows restricted to them;
//  - BuildSystem with activeRings >= 0 solves to the full system's solution on observed texels;
//  - FillUnobserved: no NaN, observed texels unchanged, a constant stays constant, fills stay
//    within the observed range, levels without unknowns come from their pyramid neighbour;
//  - SplatGuess is exact for a constant map;
//  - the fused quad-form LSMR agrees with SolveDirect on an active system, with the same bytes
//    for 1 and 2 threads, and the quad-form products equal the plain CSR products.
#include <gtest/gtest.h>

#include <cstring>

#include "infer/regularizer.h"
#include "tests/infer/infer_frames.h"
#include "tests/infer/infer_test_util.h"

namespace pem::infer {
namespace {

using testing::LinearSetup;

// The texels some image row taps (local texel indices), from an active system.
std::vector<uint8_t> ObservedTexels(const LinearSystem& sys) {
    std::vector<uint8_t> seen(static_cast<size_t>(sys.layout.TexelCount()), 0);
    const CsrMatrix& k = sys.k.A();
    for (int64_t r = 0; r < sys.imageRows; ++r)
        for (int64_t e = k.rowPtr[static_cast<size_t>(r)]; e < k.rowPtr[static_cast<size_t>(r) + 1];
             ++e) {
            const uint32_t col = k.col[static_cast<size_t>(e)];
            const uint32_t t = sys.active.empty() ? col / kChannels : sys.active[col / kChannels];
            seen[t] = 1;
        }
    return seen;
}

// Reference restriction: rows whose texels are all active, columns renumbered.
CsrMatrix Restrict(const CsrMatrix& m, const std::vector<int32_t>& index, int64_t cols) {
    CsrMatrix out;
    out.cols = cols;
    for (int64_t r = 0; r < m.rows; ++r) {
        std::vector<uint32_t> rc;
        std::vector<double> rv;
        bool keep = true;
        for (int64_t k = m.rowPtr[static_cast<size_t>(r)]; k < m.rowPtr[static_cast<size_t>(r) + 1];
             ++k) {
            const uint32_t c = m.col[static_cast<size_t>(k)];
            const int32_t t = index[c / kChannels];
            if (t < 0) {
                keep = false;
                break;
            }
            rc.push_back(static_cast<uint32_t>(t) * kChannels + c % kChannels);
            rv.push_back(m.val[static_cast<size_t>(k)]);
        }
        if (keep) out.AddRow(rc, rv);
    }
    return out;
}

void ExpectSameMatrix(const CsrMatrix& a, const CsrMatrix& b, const char* what) {
    EXPECT_EQ(a.rows, b.rows) << what;
    EXPECT_EQ(a.cols, b.cols) << what;
    EXPECT_EQ(a.rowPtr, b.rowPtr) << what;
    EXPECT_EQ(a.col, b.col) << what;
    EXPECT_EQ(a.val, b.val) << what;
}

TEST(ActiveSystem, RegularizerRowsEqualRestrictedFullRows) {
    for (int size : {1, 2, 8}) {
        const TexelLayout layout{0, size, 1 + (size == 8 ? 3 : size == 2 ? 1 : 0)};
        const auto count = static_cast<size_t>(layout.TexelCount());
        // A pseudo-random active set (about 40 %), plus all of one face of level 0.
        std::vector<int32_t> index(count, -1);
        std::vector<uint32_t> active;
        uint64_t s = 12345;
        for (uint32_t t = 0; t < count; ++t) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            const bool on = (s >> 33) % 10 < 4 || t < static_cast<uint32_t>(size * size);
            if (on) {
                index[t] = static_cast<int32_t>(active.size());
                active.push_back(t);
            }
        }
        const int64_t full = static_cast<int64_t>(count) * kChannels;
        const int64_t cols = static_cast<int64_t>(active.size()) * kChannels;
        ExpectSameMatrix(SmoothnessRows(layout, active, index),
                         Restrict(SmoothnessRows(layout, full), index, cols), "smoothness");
        ExpectSameMatrix(PyramidRows(layout, active, index),
                         Restrict(PyramidRows(layout, full), index, cols), "pyramid");
        ExpectSameMatrix(PriorRows(layout, active, index),
                         Restrict(PriorRows(layout, full), index, cols), "prior");
    }
}

TEST(ActiveSystem, SameSolutionAsFullSystemOnObservedTexels) {
    // A quad over part of +Z: most of the cube is never seen.
    const testing::Setup s = LinearSetup(test::FaceQuad(48, 48, 16, 0.5f, 3));
    const LinearSystem fullSys = BuildSystem(s.a, s.frame, 0, {s.b, {}}, RegularizerWeights{});
    SystemOptions ring2;
    ring2.activeRings = 2;
    const LinearSystem act = BuildSystem(s.a, s.frame, 0, {s.b, {}}, RegularizerWeights{}, ring2);
    ASSERT_FALSE(act.active.empty());
    ASSERT_LT(act.Cols(), fullSys.Cols() / 2);
    EXPECT_TRUE(act.k.HasQuadForm());
    const SolveResult xf = SolveDirect(fullSys, InitialGuess(fullSys));
    const SolveResult xa = SolveDirect(act, InitialGuess(act));
    const std::vector<uint8_t> seen = ObservedTexels(act);
    double worst = 0.0, sum2 = 0.0;
    int64_t observed = 0;
    for (size_t k = 0; k < act.active.size(); ++k) {
        const uint32_t t = act.active[k];
        if (!seen[t]) continue;
        ++observed;
        for (size_t c = 0; c < kChannels; ++c) {
            const double d = std::fabs(xa.x[k * kChannels + c] - xf.x[t * kChannels + c]);
            worst = std::max(worst, d);
            sum2 += d * d;
        }
    }
    const double rms =
        observed > 0 ? std::sqrt(sum2 / static_cast<double>(kChannels * observed)) : 0.0;
    std::printf(
        "active %zu of %lld texels, %lld observed, max |x_active - x_full| = %.3g, rms %.3g\n",
        act.active.size(), static_cast<long long>(fullSys.layout.TexelCount()),
        static_cast<long long>(observed), worst, rms);
    // The full system's regularizer also couples observed texels to far unobserved ones (which
    // it keeps smooth); two rings leave differences of about one 8-bit step at most.
    EXPECT_GT(observed, 0);
    EXPECT_LT(worst, 1e-2);
    EXPECT_LT(rms, 2e-3);
    // The image fit is the same.
    EXPECT_NEAR(MaskedImageRmse(act, xa.x, 1), MaskedImageRmse(fullSys, xf.x, 1), 1e-4);
}

// An active system whose unknowns are level 0 only (a strongly magnified quad).
LinearSystem MagnifiedSystem(int rings) {
    const testing::Setup s = LinearSetup(test::FaceQuad(64, 64, 16, 0.05f, 7));
    SystemOptions o;
    o.activeRings = rings;
    return BuildSystem(s.a, s.frame, 0, {s.b, {}}, RegularizerWeights{}, o);
}

TEST(ActiveSystem, FillUnobservedIsSmoothAndKeepsObservedTexels) {
    const LinearSystem sys = MagnifiedSystem(0);
    const TexelLayout& layout = sys.layout;
    ASSERT_FALSE(sys.active.empty());
    // Random values in [0.2, 0.8] on the active texels.
    Vector x(static_cast<size_t>(sys.Cols()));
    uint64_t s = 99;
    for (double& v : x) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        v = 0.2 + 0.6 * static_cast<double>(s >> 11) / 9007199254740992.0;
    }
    int64_t filled = 0;
    const Vector full = FillUnobserved(sys, x, &filled);
    ASSERT_EQ(static_cast<int64_t>(full.size()), kChannels * layout.TexelCount());
    EXPECT_TRUE(testing::AllFinite(full));
    EXPECT_EQ(filled, layout.TexelCount() - static_cast<int64_t>(sys.active.size()));
    // Observed texels unchanged (the same bytes); the rest within the observed range.
    std::vector<uint8_t> isActive(static_cast<size_t>(layout.TexelCount()), 0);
    for (size_t k = 0; k < sys.active.size(); ++k) {
        isActive[sys.active[k]] = 1;
        for (size_t c = 0; c < kChannels; ++c)
            ASSERT_EQ(full[size_t{sys.active[k]} * kChannels + c], x[k * kChannels + c]);
    }
    const auto [lo, hi] = testing::Range(x);
    for (double v : full) {
        EXPECT_GE(v, lo);
        EXPECT_LE(v, hi);
    }
    // Levels without unknowns: each texel the mean of its four children (going coarser).
    std::vector<uint8_t> levelHas(static_cast<size_t>(layout.levels), 0);
    for (uint32_t t : sys.active)
        for (int l = 0; l < layout.levels; ++l)
            if (t >= layout.LevelBase(l) && t < layout.LevelBase(l + 1))
                levelHas[static_cast<size_t>(l)] = 1;
    ASSERT_TRUE(levelHas[0]);
    int checkedLevels = 0;
    for (int l = 1; l < layout.levels; ++l) {
        if (levelHas[static_cast<size_t>(l)] || !levelHas[static_cast<size_t>(l - 1)]) continue;
        ++checkedLevels;
        const int n = layout.LevelSize(l);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    for (size_t c = 0; c < kChannels; ++c) {
                        double mean = 0.0;
                        for (int d = 0; d < 4; ++d)
                            mean +=
                                full[size_t{layout.Texel(l - 1, f, 2 * i + d % 2, 2 * j + d / 2)} *
                                         kChannels +
                                     c];
                        EXPECT_NEAR(full[size_t{layout.Texel(l, f, i, j)} * kChannels + c],
                                    mean / 4.0, 1e-12);
                    }
    }
    EXPECT_GT(checkedLevels, 0);
    // A constant stays constant (a smooth fill adds no structure).
    const Vector flat = FillUnobserved(sys, Vector(x.size(), 0.375));
    for (double v : flat) ASSERT_NEAR(v, 0.375, 1e-12);
}

TEST(ActiveSystem, SplatGuessIsExactForAConstantMap) {
    test::SphereSpec spec;
    spec.width = spec.height = 48;
    spec.cubeSize = 8;
    raster::Frame frame = test::RandomSphere(spec);
    for (auto& level : frame.textures[0].levels)
        for (size_t k = 0; k < level.size(); ++k)
            level[k] = static_cast<uint8_t>(40 + 50 * (k % 4));
    const testing::Setup s = LinearSetup(frame);
    SystemOptions o;
    o.activeRings = 1;
    const LinearSystem sys = BuildSystem(s.a, s.frame, 0, {s.b, {}}, RegularizerWeights{}, o);
    const Vector x = SplatGuess(sys, 0.0, 1.0, 2);
    for (size_t k = 0; k < x.size(); ++k)
        ASSERT_NEAR(x[k], (40 + 50 * (k % 4)) / 255.0, 1e-7) << k;  // raster's float weights
}

TEST(ActiveSystem, FusedLsmrAgreesWithDirectAndThreads) {
    test::SphereSpec spec;
    spec.width = spec.height = 64;
    spec.cubeSize = 16;
    spec.rimBand = 0.6f;
    const testing::Setup s = LinearSetup(test::RandomSphere(spec));
    SystemOptions o;
    o.activeRings = 1;
    const LinearSystem sys = BuildSystem(s.a, s.frame, 0, {s.b, {}}, RegularizerWeights{}, o);
    ASSERT_TRUE(sys.k.HasQuadForm());
    // Quad-form products are the plain CSR products, byte for byte.
    Vector x(static_cast<size_t>(sys.Cols())), r(static_cast<size_t>(sys.k.Rows()));
    for (size_t k = 0; k < x.size(); ++k) x[k] = std::sin(0.37 * static_cast<double>(k));
    for (size_t k = 0; k < r.size(); ++k) r[k] = std::cos(0.11 * static_cast<double>(k));
    Vector y1, y2, g1, g2;
    sys.k.Apply(x, &y1, 2);
    Multiply(sys.k.A(), x, &y2, 1);
    sys.k.ApplyTranspose(r, &g1, 2);
    Multiply(Transpose(sys.k.A()), r, &g2, 1);
    EXPECT_EQ(std::memcmp(y1.data(), y2.data(), y1.size() * sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(g1.data(), g2.data(), g1.size() * sizeof(double)), 0);
    // So are the column norms from the quad form (no full transpose is kept).
    const Vector n1 = sys.k.ColumnSquaredNorms(2), n2 = ColumnSquaredNorms(Transpose(sys.k.A()), 1);
    ASSERT_EQ(n1.size(), n2.size());
    EXPECT_EQ(std::memcmp(n1.data(), n2.data(), n1.size() * sizeof(double)), 0);
    // Unbounded LSMR to a tight tolerance vs the direct oracle.
    SolveOptions opt;
    opt.bounds = Bounds::None();
    opt.maxIterations = 4000;
    opt.restartEvery = 0;
    opt.atol = 1e-12;
    opt.logEvery = 0;
    opt.threads = 1;
    const SolveResult it1 = SolveIterative(sys, InitialGuess(sys), opt);
    opt.threads = 2;
    const SolveResult it2 = SolveIterative(sys, InitialGuess(sys), opt);
    const SolveResult direct = SolveDirect(sys, InitialGuess(sys));
    ASSERT_EQ(it1.x.size(), it2.x.size());
    EXPECT_EQ(std::memcmp(it1.x.data(), it2.x.data(), it1.x.size() * sizeof(double)), 0);
    double worst = 0.0;
    for (size_t k = 0; k < it1.x.size(); ++k)
        worst = std::max(worst, std::fabs(it1.x[k] - direct.x[k]));
    std::printf("LSMR %d iterations (%s), max |x_lsmr - x_direct| = %.3g\n", it1.iterations,
                ToString(it1.stop), worst);
    EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace pem::infer
