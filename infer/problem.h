// SPDX-License-Identifier: MIT
// problem.h — the stacked inference system for one environment map of a frame (a cube map or a 2D
// layout) (docs/method.md §5):
//
//   minimise  sum_rows w (A x - b)^2 + lambda_s |L x|^2 + lambda_p |P x|^2 + lambda_0 |x - xbar|^2
//   as the least-squares system K x ~ h,  K = [W^1/2 A; sqrt(lambda_s) L; sqrt(lambda_p) P;
//   sqrt(lambda_0) I],  h = [W^1/2 (b - offset - known); 0; 0; sqrt(lambda_0) xbar].
//
//   LinearSystem sys = BuildSystem(A, frame, /*texture=*/0, target, weights);
//   SolveResult res = SolveIterative(sys, InitialGuess(sys), options);   // solver.h
//
// Conventions: A is raster's RenderingMatrix of the frame (rows 4 * pixel + c, columns
// 4 * texel + c, x = texel bytes / 255 or HDR radiance). The unknowns are all MIP levels of
// texture `texture` (a cube map or a 2D texture), numbered locally from 0 (TexelLayout,
// regularizer.h); other textures' columns are known and move to the right-hand side with their
// bytes / 255. Image rows are kept when they have confidence > 0 and at least one tap on the
// unknown texture (the mask); imageRowOf maps them back. The prior value xbar is per channel
// (default: the confidence-weighted mean of the target over the mask). Not here: the solvers
// (solver.h), several viewpoints or terms (stack more image blocks).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "infer/regularizer.h"
#include "infer/sparse.h"
#include "raster/frame.h"
#include "raster/render.h"

namespace pem::infer {

// Regularizer weights lambda (regularizer.h states their units).
struct RegularizerWeights {
    double smooth = 1e-3;                // lambda_s: neighbour differences within a level
    double pyramid = 1e-3;               // lambda_p: coarse texel - mean of its 4 children
    double prior = 1e-6;                 // lambda_0: pull toward the constant xbar
    std::optional<Channels> priorValue;  // xbar; default: mean of the target over the mask
};

// The target image per row of A, in the units of the rendered frame ([0, 1] for 8-bit).
struct Target {
    Vector b;           // one value per row of A
    Vector confidence;  // w >= 0 per row; empty = 1 everywhere
};

// How the unknowns are chosen.
struct SystemOptions {
    // < 0: every texel of every level is an unknown. >= 0: only the texels some kept image row
    // taps, grown by this many rings of neighbours within their level (regularizer.h adjacency);
    // regularizer rows that touch a texel outside the set are dropped, and FillUnobserved
    // completes the map afterwards.
    int activeRings = -1;
    // 2D textures of the map: 2 for a two-image layout (textures `texture` and `texture` + 1,
    // equal shapes; regularizer.h numbers them as the map's faces), else 1.
    int charts = 1;
};

struct LinearSystem {
    SparseOperator k;                 // the stacked K
    Vector h;                         // the stacked right-hand side
    int64_t imageRows = 0;            // rows [0, imageRows) of K are W^1/2 A
    double imageWeightSum = 0.0;      // sum of w over the image rows (RMSE denominator)
    std::vector<int64_t> imageRowOf;  // image row -> row of the rendering matrix
    TexelLayout layout;               // unknowns, numbered from 0
    uint32_t globalFirstTexel = 0;    // raster's index of the unknown texture's first texel
    std::vector<uint32_t> active;     // unknown k is local texel active[k]; empty: all texels
    Vector imageSqrtWeight;           // sqrt(w) per image row
    Channels priorValue{};            // xbar per channel
    int64_t Cols() const { return k.Cols(); }
};

LinearSystem BuildSystem(const raster::RenderingMatrix& a, const raster::Frame& frame, int texture,
                         const Target& target, const RegularizerWeights& weights,
                         const SystemOptions& options = {});
// The same, taking over A's storage (the largest part of the system; it is not held twice).
LinearSystem BuildSystem(raster::RenderingMatrix&& a, const raster::Frame& frame, int texture,
                         const Target& target, const RegularizerWeights& weights,
                         const SystemOptions& options = {});

// The solution over every local texel (4 per texel): unknowns copied, the other texels filled
// smoothly — within a level that has unknowns, breadth-first from them, each texel the mean of
// its already filled neighbours; a level without unknowns from the nearest filled level (mean
// of the four children going coarser, the parent going finer); nothing observed at all: the
// prior value. `filled` (optional) receives the number of texels filled.
Vector FillUnobserved(const LinearSystem& system, const Vector& x, int64_t* filled = nullptr);

// xbar in every texel (the default starting point of the solvers).
Vector InitialGuess(const LinearSystem& system);

// The splatted start: each texel the weighted mean of the target over the image rows that tap
// it, sum_r w a_rj b_r / sum_r w a_rj (xbar where no row taps it), clamped into [lo, hi]. For
// a smooth map this is already close to the least-squares solution, so the solver starts near
// the end (the back-projection of the image onto the texels).
Vector SplatGuess(const LinearSystem& system, double lo, double hi, int threads);

// Texel values of every texture of a frame as raster's columns: bytes / 255.
Vector TexelVector(const raster::Frame& frame);

// raster's columns with the unknown texture replaced by x (the local solution).
Vector ExpandSolution(const LinearSystem& system, const raster::Frame& frame, const Vector& x);

// A x + offset for raster's columns (what the linear profile renders).
Vector ApplyRendering(const raster::RenderingMatrix& a, const Vector& xFull, int threads);

// sqrt(sum w (A x - b)^2 / sum w) over the system's image rows (x local).
double MaskedImageRmse(const LinearSystem& system, const Vector& x, int threads);

}  // namespace pem::infer
