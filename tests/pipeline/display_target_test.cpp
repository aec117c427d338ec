// SPDX-License-Identifier: MIT
// display_target_test.cpp — the targets of float maps (pipeline/display_target.h) against
// bisection and against the display's own rule: a pixel above white stays exactly white, the
// rest as traced.
#include "pipeline/display_target.h"

#include <gtest/gtest.h>

#include <random>

namespace pem::pipeline {
namespace {

// Σ w·max(0, v − c): what lowering the values to c removes.
double Removed(const std::vector<std::pair<double, double>>& vw, double c) {
    double r = 0.0;
    for (const auto& [v, w] : vw) r += w * std::max(0.0, v - c);
    return r;
}

TEST(WaterLevel, AgreesWithBisection) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(0.0, 50.0), weight(0.0, 1.0), share(0.0, 1.0);
    for (int trial = 0; trial < 500; ++trial) {
        std::vector<std::pair<double, double>> vw(1 + trial % 9);
        double total = 0.0;
        for (auto& [v, w] : vw) v = value(rng), w = trial % 3 ? weight(rng) : 1.0, total += w * v;
        const double remove = share(rng) * total;
        // Removed(c) falls from total to 0 on [0, max v]: bisection finds the level independently.
        double lo = 0.0, hi = 50.0;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (Removed(vw, mid) > remove ? lo : hi) = mid;
        }
        const double level = WaterLevel(vw, remove);
        EXPECT_NEAR(Removed(vw, level), remove, 1e-9 * (1.0 + total)) << "trial " << trial;
        if (remove > 1e-9 * total) {  // else any level at or above the top value removes nothing
            EXPECT_NEAR(level, 0.5 * (lo + hi), 1e-7) << "trial " << trial;
        }
    }
    EXPECT_EQ(WaterLevel({{3.0, 1.0}, {1.0, 1.0}}, 0.0), 3.0);  // nothing removed: the top value
    EXPECT_EQ(WaterLevel({{3.0, 1.0}, {1.0, 1.0}}, 4.0), 0.0);  // everything removed
    EXPECT_EQ(WaterLevel({{3.0, 1.0}, {1.0, 1.0}}, 1.0), 2.0);
    EXPECT_EQ(WaterLevel({{3.0, 1.0}, {1.0, 1.0}}, 3.0), 0.5);  // both lowered
}

// Two pixels of a K = 3 image: pixel 0 shown 4× white in red (a highlight), pixel 1 below white.
struct TwoPixels {
    trace::FloatImage coverage{6, 3, 4}, frame{2, 1, 4}, fresnel{2, 1, 4};
    std::vector<uint32_t> cells;
    std::vector<double> b;
    TwoPixels() {
        for (uint32_t cell = 0; cell < 18; ++cell) {
            coverage.At(int(cell % 6), int(cell / 6))[3] = 1.0f;
            cells.push_back(cell);
            const bool first = cell % 6 < 3;
            // Pixel 0: one subpixel at 100, eight at 0.5; pixel 1: 1.5 (above 1) and one at 20.
            const double v = first ? (cell == 0 ? 100.0 : 0.5) : (cell == 5 ? 20.0 : 1.5);
            b.insert(b.end(), {v, v, v, 0.75});
        }
        for (int c = 0; c < 3; ++c) {
            frame.At(0, 0)[c] = c == 0 ? 4.0f : 0.9f;
            frame.At(1, 0)[c] = 0.9f;
            fresnel.At(0, 0)[c] = 0.0625f, fresnel.At(1, 0)[c] = 0.5f;
        }
        fresnel.At(0, 0)[3] = fresnel.At(1, 0)[3] = 1.0f;
    }
    double Sum(int pixel, size_t channel) const {
        double s = 0.0;
        for (uint32_t cell = 0; cell < 18; ++cell)
            if (int(cell % 6) / 3 == pixel) s += b[4 * cell + channel];
        return s;
    }
};

TEST(ClipToDisplay, KeepsWhatTheDisplayShows) {
    TwoPixels t;
    const double red0 = t.Sum(0, 0), green0 = t.Sum(0, 1);
    std::vector<double> b = t.b;
    ClipToDisplay({&t.coverage, &t.frame, &t.fresnel}, t.cells, 3, 2.0, &b);
    std::swap(b, t.b);
    // Pixel 0, red: its light divided by P = 4, so 4× less stays exactly white; taken off the
    // highlight only (104 / 4 = 26 → the 100 lowered to 22), the eight others kept.
    EXPECT_NEAR(t.Sum(0, 0), red0 / 4.0, 1e-12);
    EXPECT_NEAR(t.b[0], 100.0 - 0.75 * red0, 1e-12);
    EXPECT_EQ(t.b[4 * 1], 0.5);
    // Green and blue of pixel 0 are below white: kept, the highlight under the F·G cap
    // K² / (F·G · scale) = 9 / (0.0625 · 2) = 72 lowered to it.
    EXPECT_NEAR(t.Sum(0, 1), green0 - 28.0, 1e-12);
    EXPECT_EQ(t.b[1], 72.0);
    // Pixel 1 (below white): 1.5 kept above 1; the 20 above 9 / (0.5 · 2) = 9 lowered to it.
    EXPECT_EQ(t.b[4 * 3], 1.5);
    EXPECT_EQ(t.b[4 * 5], 9.0);
    // Alpha untouched.
    for (size_t i = 3; i < t.b.size(); i += 4) EXPECT_EQ(t.b[i], 0.75);
}

}  // namespace
}  // namespace pem::pipeline
