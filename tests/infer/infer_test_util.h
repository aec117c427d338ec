// SPDX-License-Identifier: MIT
// infer_test_util.h — shared steps of the solver tests: a frame with its rendering matrix and a
// known environment map x*, error figures, and the measurement printout.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "infer/env_map.h"
#include "infer/problem.h"
#include "infer/solver.h"
#include "raster/render.h"

namespace pem::infer::testing {

struct Setup {
    raster::Frame frame;
    raster::RenderingMatrix a;
    Vector xStar;  // raster's columns
    Vector b;      // A x* + offset
};

inline Setup LinearSetup(raster::Frame frame) {
    Setup s;
    s.frame = std::move(frame);
    raster::RenderOptions opt;
    opt.profile = raster::Profile::Linear;
    s.a = raster::BuildRenderingMatrix(raster::PreparedFrame(s.frame), opt);
    s.xStar = TexelVector(s.frame);
    s.b = ApplyRendering(s.a, s.xStar, 1);
    return s;
}

struct ImageError {
    double rmse = 0.0, maxAbs = 0.0;
};

// Over the system's image rows (the mask): rendered vs target, in [0, 1] units.
inline ImageError MaskedError(const LinearSystem& sys, const Vector& rendered, const Vector& b) {
    ImageError e;
    double sum = 0.0;
    for (int64_t r : sys.imageRowOf) {
        const double d = rendered[static_cast<size_t>(r)] - b[static_cast<size_t>(r)];
        sum += d * d;
        e.maxAbs = std::max(e.maxAbs, std::fabs(d));
    }
    e.rmse =
        sys.imageRowOf.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(sys.imageRowOf.size()));
    return e;
}

inline std::pair<double, double> Range(const Vector& x) {
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    return {*lo, *hi};
}

inline bool AllFinite(const Vector& x) {
    return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

inline std::string OutputPath(const std::string& name) {
    std::filesystem::create_directories(PEM_TEST_OUTPUT_DIR);
    return std::string(PEM_TEST_OUTPUT_DIR) + "/" + name;
}

inline void PrintSolve(const char* name, const LinearSystem& sys, const SolveResult& r) {
    const auto [lo, hi] = Range(r.x);
    std::printf(
        "[measure] %s: rows %lld (image %lld) cols %lld nnz %lld | %s, %d iterations, %d "
        "restarts, %.3f s | image rmse %.3g | texels [%.4g, %.4g]\n",
        name, static_cast<long long>(sys.k.Rows()), static_cast<long long>(sys.imageRows),
        static_cast<long long>(sys.Cols()), static_cast<long long>(sys.k.NonZeros()),
        ToString(r.stop), r.iterations, r.restarts, r.seconds,
        r.log.empty() ? 0.0 : r.log.back().imageRmse, lo, hi);
}

}  // namespace pem::infer::testing
