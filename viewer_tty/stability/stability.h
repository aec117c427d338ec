// SPDX-License-Identifier: MIT
// stability.h — the numerical stability suite (issue 6 item 5): stiff systems and extreme inputs
// run through infer/, trace/ and raster/, each with a defined outcome that is checked.
//
//   StabilityOptions opt;
//   opt.dataDir = "tests/data";                                  // for tests/data/bad_scenes
//   std::vector<StabilityCase> cases = RunStabilitySuite(opt);   // ~a few seconds in Release
//   for (const StabilityCase& c : cases) if (!c.passed) ...
//
// Every case has a defined outcome (StabilityCase::expected): either a finite, bounded result
// whose residual and condition estimate are reported, or a clear error (pem::base::InputError whose
// what() is one line naming the file and the cause). A case catches its own exceptions; an
// exception counts as a pass only when that error is the case's defined outcome.
// Families (each also runnable alone):
//  - solver (stiff): grazing reflection, > 64x magnification, near-zero columns, two MIP levels
//    trading off, HDR 1e-4..1e4 with Bounds::Hdr; compared with SolveDirect on the same system;
//  - shells (stiff): rays tangent to / nearly in the plane of every shell kind, fits of nearly
//    coplanar points; a viewpoint exactly on a shell surface (extreme);
//  - ray paths (extreme): IOR 1.0, IOR 4.0, total internal reflection to maxDepth, a viewpoint
//    inside a sphere or exactly on its surface (analytic SurfaceHitFn);
//  - raster (extreme): cube directions exactly on edges and corners; degenerate and sliver
//    triangles through raster::Render and BuildRenderingMatrix;
//  - scenes (extreme): sliver and degenerate triangles in a glTF traced by Embree and brute force;
//    NaN / Inf in scene files (generated, plus tests/data/bad_scenes when dataDir is given).
// Residual and condition: NaN means "not applicable to this case" (the detail says so); every
// case's detail says what its two numbers measure.
// Not here: printing (cmd_stability.h), the infer/trace/raster code under test.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace pem::stability {

struct StabilityOptions {
    std::string dataDir;  // the repository's tests/data ("" = only generated inputs)
    int threads = 1;      // for the solver and the rasterizer (results do not depend on it)
};

struct StabilityCase {
    std::string name;
    std::string category;  // "stiff" or "extreme"
    std::string expected;  // the defined outcome, in words
    std::string outcome;   // what happened, one line
    bool passed = false;
    double residual = std::numeric_limits<double>::quiet_NaN();  // relative residual, masked RMSE,
                                                                 // or geometric error (see detail)
    double condition =
        std::numeric_limits<double>::quiet_NaN();  // condition estimate (see detail for which)
    double seconds = 0.0;
    std::string detail;  // the measurements behind the outcome
};

std::vector<StabilityCase> RunSolverStabilityCases(const StabilityOptions& options = {});
std::vector<StabilityCase> RunShellStabilityCases(const StabilityOptions& options = {});
std::vector<StabilityCase> RunRayPathStabilityCases(const StabilityOptions& options = {});
std::vector<StabilityCase> RunRasterStabilityCases(const StabilityOptions& options = {});
std::vector<StabilityCase> RunSceneStabilityCases(const StabilityOptions& options = {});

// Every family above, in that order.
std::vector<StabilityCase> RunStabilitySuite(const StabilityOptions& options = {});

}  // namespace pem::stability
