// SPDX-License-Identifier: MIT
// stability_condition.h — the condition estimate reported by the stability suite's solver cases
// (stability.h): kappa(K D) of channel 0 of the stacked inference system, D the solver's floored
// column scaling (solver.h: D_j = 1 / sqrt(max(|k_j|^2, columnFloor * median |k|^2))).
//
// Method: Golub-Kahan-Lanczos bidiagonalization of K D from a fixed pseudo-random start, with
// full (twice-repeated classical Gram-Schmidt) reorthogonalization of the right vectors, for at
// most kLanczosSteps steps; the singular values of the small bidiagonal B_k (one-sided Jacobi)
// interlace those of K D, so sigma_max(B_k) / sigma_min(B_k) is a LOWER bound on kappa(K D), exact
// once k reaches the column count (on the suite's frames 80 steps give 55-75 % of the 300-step
// figure). Columns without entries are left out (the solvers never move them).
// Not here: the solver cases (stability_solver.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "infer/problem.h"

namespace pem::stability::stability {

constexpr int kLanczosSteps = 80;

struct ConditionEstimate {
    double kappa = std::numeric_limits<double>::quiet_NaN(),
           sigmaMax = std::numeric_limits<double>::quiet_NaN(),
           sigmaMin = std::numeric_limits<double>::quiet_NaN();  // of B_k
    int steps = 0;                                               // k
    int64_t columns = 0, emptyColumns = 0;                       // channel 0, kept / left out
    double columnSpread =
        std::numeric_limits<double>::quiet_NaN();  // sqrt(max / min) of the non-zero unscaled
                                                   // squared column norms
};

ConditionEstimate EstimateCondition(const infer::LinearSystem& system, double columnFloor,
                                    int threads);

}  // namespace pem::stability::stability
