// SPDX-License-Identifier: MIT
// solver.h — least-squares solvers for the stacked inference system K x ~ h (problem.h).
//
//   SolveOptions opt;                                  // LSMR, bounds [0, 1], restarts of 50
//   SolveResult res = SolveIterative(system, InitialGuess(system), opt);
//   WriteLogCsv(res.log, "solve.csv");
//   SolveResult oracle = SolveDirect(system, InitialGuess(system));   // small systems only
//
// Iterative (LSMR, Fong & Saunders 2011; CGLS, Hestenes & Stiefel), written against infer's
// SpMV. Every colour channel runs its own recurrence (the system is channel-diagonal), all four
// sharing each product with K and K^T.
//  - Column scaling: y = D^-1 x with D_j = 1 / sqrt(max(|k_j|^2, floor)), floor = columnFloor x
//    the median of the non-zero squared column norms (docs/inference.md: an unfloored Jacobi scale
//    sends texels seen with tiny weights to +-1e5 in the first iterations).
//  - Stopping, per channel, on the scaled system: |(KD)^T r| <= atol |KD| |r| (least squares) or
//    |r| <= atol |h| (consistent), on maxIterations, or when the masked image RMSE reaches
//    residualFloor; or when |(KD)^T r| <= 16 eps |KD| |h|, below which the gradient of
//    r = h - K x is rounding noise. Within a cycle LSMR tests its own estimates of |KD|, |r|,
//    |(KD)^T r|; at every restart the test is repeated exactly, with |KD| the Frobenius norm.
//  - Bounds by projected restarts: from x (clamped into [lo, hi]) compute r = h - K x exactly;
//    freeze the texels that sit on a bound with the gradient pushing outward (their D_j = 0 for
//    this cycle); run at most restartEvery iterations on min |K D y - r|; clamp x + D y; repeat.
//    Converged means the projected gradient passes the test above. Bounds::Unit() is the 8-bit
//    mode, Bounds::Hdr() is [0, inf), Bounds::None() solves unbounded (then restarts only
//    refine: the residual is recomputed exactly every restartEvery iterations).
//  - The log has a record at every restart and every logEvery iterations (the iterate x + D y
//    before clamping, so excursions show). `seconds` is wall time; everything else, including
//    the solution, is the same bytes for any thread count.
// Direct: the normal equations of the scaled system (KD)^T (KD) y = (KD)^T (h - K x0) with Eigen's
// SimplicialLDLT, x = x0 + D y; no bounds. Squares the condition number: use with regularization
// and as the test oracle. Columns without entries keep x0 (as the Krylov solvers do).
// Not here: building the system (problem.h), choosing lambdas.
#pragma once

#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "infer/problem.h"

namespace pem::infer {

enum class Method { Lsmr, Cgls };

struct Bounds {
    double lo = 0.0, hi = 1.0;
    static Bounds Unit() { return {0.0, 1.0}; }
    static Bounds Hdr() { return {0.0, std::numeric_limits<double>::infinity()}; }
    static Bounds None() {
        return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
    bool Active() const {
        return lo > -std::numeric_limits<double>::infinity() ||
               hi < std::numeric_limits<double>::infinity();
    }
};

struct SolveOptions {
    Method method = Method::Lsmr;
    Bounds bounds = Bounds::Unit();
    int maxIterations = 500;     // iterations (one K and one K^T product each), all cycles
    int restartEvery = 50;       // iterations per cycle (<= 0: maxIterations)
    double atol = 1e-6;          // see the stopping rules above
    double residualFloor = 0.0;  // stop at this masked image RMSE (0: off)
    double columnFloor = 1e-2;   // relative floor of the squared column norms
    int threads = 1;
    int logEvery = 5;  // 0: log at restarts only
};

// One line of the convergence log (docs/inference.md §4.2).
struct IterationRecord {
    int iteration = 0;
    double seconds = 0.0;           // since the start of the solve
    double residualNorm = 0.0;      // |h - K x| over the stacked system
    double relativeGradient = 0.0;  // |(KD)^T r|_projected / |(KD)^T h|
    double imageRmse = 0.0;         // masked, confidence-weighted, image rows only
    double texelMin = 0.0, texelMax = 0.0;
};

enum class StopReason { Converged, ResidualFloor, MaxIterations, Stalled, Direct };
const char* ToString(StopReason reason);

struct SolveResult {
    Vector x;  // local texels, columns 4 * texel + c
    int iterations = 0;
    int restarts = 0;
    StopReason stop = StopReason::MaxIterations;
    double seconds = 0.0;
    std::vector<IterationRecord> log;
};

SolveResult SolveIterative(const LinearSystem& system, const Vector& x0,
                           const SolveOptions& options);

// The direct oracle (throws std::runtime_error if the factorization fails).
SolveResult SolveDirect(const LinearSystem& system, const Vector& x0, double columnFloor = 1e-2);

void WriteLogCsv(const std::vector<IterationRecord>& log, std::ostream& out);
void WriteLogCsv(const std::vector<IterationRecord>& log, const std::string& path);

}  // namespace pem::infer
