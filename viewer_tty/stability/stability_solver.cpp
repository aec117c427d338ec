// SPDX-License-Identifier: MIT
// stability_solver.cpp — the solver family of the stability suite (stability.h): stiff frames
// rendered by raster/ (linear profile, b = A x*), solved by infer/ with the default
// regularization, floored scaling and bounds, checked for finite bounded texels, and compared
// with the unregularized solve and the SimplicialLDLT oracle.
//
// Figures per case:
//  - residual: the relative image residual |W^1/2 (A x - b')| / |W^1/2 b'| over the masked image
//    rows of the stacked system (b' = the image part of h);
//  - condition: kappa(K D) of channel 0 by Golub-Kahan-Lanczos, a lower bound
//    (stability_condition.h).
// The frames are small copies of tests/infer/infer_frames.cpp (same construction and seeds).
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <tuple>

#include "infer/problem.h"
#include "infer/solver.h"
#include "infer/sparse.h"
#include "raster/render.h"
#include "viewer_tty/stability/stability_condition.h"
#include "viewer_tty/stability/stability_internal.h"

namespace pem::stability {
namespace {

using infer::Vector;
using stability::Checks;
using stability::ConditionEstimate;
using stability::Format;

// Frames (after tests/infer/infer_frames.cpp) --------------------------------------------------

// splitmix64 (tests/case_generator.h's stream), one byte per call.
struct ByteStream {
    uint64_t state;
    uint8_t Next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return static_cast<uint8_t>((z ^ (z >> 31)) >> 24);
    }
};

raster::Texture RandomCube(int size, uint64_t seed) {
    raster::Texture t;
    t.kind = raster::TextureKind::Cube;
    t.width = t.height = size;
    ByteStream rng{seed};
    for (int n = size; n >= 1; n /= 2) {
        std::vector<uint8_t> level(static_cast<size_t>(6 * n * n * 4));
        for (size_t k = 0; k < level.size(); ++k) level[k] = k % 4 == 3 ? 255 : rng.Next();
        t.levels.push_back(std::move(level));
    }
    return t;
}

raster::Frame Blank(int width, int height, int cubeSize, uint64_t seed) {
    raster::Frame f;
    f.width = width;
    f.height = height;
    f.clear = {0, 0, 0, 255};
    f.textures.push_back(RandomCube(cubeSize, seed));
    return f;
}

raster::Vertex At(const glm::vec4& pos, const glm::vec3& dir, const glm::vec4& colour) {
    raster::Vertex v;
    v.pos = pos;
    v.coord[0] = dir;
    v.color = colour;
    return v;
}

void AddQuad(raster::Pass* p, const glm::vec3 dirs[4], const glm::vec4& colour) {
    const glm::vec4 pos[4] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
    for (int k : {0, 1, 2, 0, 2, 3}) p->vertices.push_back(At(pos[k], dirs[k], colour));
}

// A mirror sphere of radius 1 seen from (0.2, 0.5, 3); quads with |n . view| >= rimBand skipped.
raster::Frame Sphere(int size, int cubeSize, float rimBand, uint64_t seed) {
    raster::Frame f = Blank(size, size, cubeSize, seed);
    const glm::vec3 eye(0.2f, 0.5f, 3.0f);
    const glm::mat4 vp = glm::perspective(glm::radians(40.0f), 1.0f, 0.1f, 100.0f) *
                         glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const int rings = 24, segments = 32;
    auto vertex = [&](int i, int j, float* facing) {
        const float th = 3.14159265f * static_cast<float>(i) / static_cast<float>(rings);
        const float ph = 6.28318531f * static_cast<float>(j) / static_cast<float>(segments);
        const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
        const glm::vec3 in = glm::normalize(n - eye);
        if (facing) *facing = std::fabs(glm::dot(n, in));
        return At(vp * glm::vec4(n, 1.0f), in - 2.0f * glm::dot(n, in) * n, glm::vec4(1.0f));
    };
    raster::Pass p;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            float facing = 0.0f;
            const raster::Vertex a = vertex(i, j, nullptr), b = vertex(i + 1, j, nullptr),
                                 c = vertex(i + 1, j + 1, &facing), d = vertex(i, j + 1, nullptr);
            if (facing >= rimBand) continue;
            for (const raster::Vertex& v : {a, b, c, a, c, d}) p.vertices.push_back(v);
        }
    f.passes.push_back(p);
    return f;
}

// A full-screen quad over directions (+-e, +-e, 1): the central part of the +Z face.
raster::Frame FaceQuad(int size, int cubeSize, float e, uint64_t seed) {
    raster::Frame f = Blank(size, size, cubeSize, seed);
    raster::Pass p;
    const glm::vec3 dirs[4] = {{-e, -e, 1}, {e, -e, 1}, {e, e, 1}, {-e, e, 1}};
    AddQuad(&p, dirs, glm::vec4(1.0f));
    f.passes.push_back(p);
    return f;
}

// An additive full-screen pass of colour `weight` sampling around -Z.
void AddFaintPass(raster::Frame* f, float weight) {
    raster::Pass p;
    p.blend = raster::BlendState::Additive();
    const glm::vec3 dirs[4] = {
        {-1.5f, -1.2f, -1}, {1.5f, -1.2f, -1}, {1.5f, 1.2f, -1}, {-1.5f, 1.2f, -1}};
    AddQuad(&p, dirs, glm::vec4(weight, weight, weight, 0.0f));
    f->passes.push_back(p);
}

// One solver case -------------------------------------------------------------------------------

struct SolverSpec {
    std::string name, expected;
    raster::Frame frame;
    bool hdr = false;         // x* log-uniform in 1e-4..1e4, no regularization, Bounds::Hdr
    double rmseLimit = 0.02;  // masked image RMSE bound (LDR cases)
    std::string geometry;     // what makes it stiff, for the detail
};

struct Problem {
    raster::RenderingMatrix a;
    Vector xStar, b;
};

Problem Render(const raster::Frame& frame, bool hdr, int threads) {
    raster::RenderOptions opt;
    opt.profile = raster::Profile::Linear;
    opt.threads = threads;
    Problem p;
    p.a = raster::BuildRenderingMatrix(raster::PreparedFrame(frame), opt);
    p.xStar = infer::TexelVector(frame);
    if (hdr) {  // solver_test.cpp's HDR map: log-uniform per component
        uint64_t st = 77;
        for (double& v : p.xStar) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            v = std::pow(10.0, 8.0 * static_cast<double>(st >> 11) / 9007199254740992.0 - 4.0);
        }
    }
    p.b = infer::ApplyRendering(p.a, p.xStar, threads);
    return p;
}

bool AllFinite(const Vector& x) {
    return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

std::pair<double, double> Range(const Vector& x) {
    if (x.empty())
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    return {*lo, *hi};
}

// |h - K x| / |h| over the image rows.
double ImageRelativeResidual(const infer::LinearSystem& sys, const Vector& x, int threads) {
    Vector kx;
    sys.k.Apply(x, &kx, threads);
    double num = 0.0, den = 0.0;
    for (int64_t r = 0; r < sys.imageRows; ++r) {
        const double h = sys.h[static_cast<size_t>(r)], d = h - kx[static_cast<size_t>(r)];
        num += d * d;
        den += h * h;
    }
    return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
}

// Fraction of image rows whose taps reach two MIP levels of the unknown texture.
double TwoLevelRowFraction(const infer::LinearSystem& sys) {
    const infer::CsrMatrix& k = sys.k.A();
    const infer::TexelLayout& layout = sys.layout;
    int64_t two = 0;
    for (int64_t r = 0; r < sys.imageRows; ++r) {
        int first = -1;
        bool mixed = false;
        for (int64_t e = k.rowPtr[static_cast<size_t>(r)]; e < k.rowPtr[static_cast<size_t>(r + 1)];
             ++e) {
            const uint32_t t = k.col[static_cast<size_t>(e)] / 4;
            int level = 0;
            while (level + 1 < layout.levels && t >= layout.LevelBase(level + 1)) ++level;
            if (first >= 0 && level != first) mixed = true;
            first = level;
        }
        two += mixed;
    }
    return sys.imageRows > 0 ? static_cast<double>(two) / static_cast<double>(sys.imageRows) : 0.0;
}

// The unregularized, unfloored, unbounded solve: what regularization and bounds prevent.
std::string RawSolve(const Problem& p, const raster::Frame& frame, int threads) {
    infer::RegularizerWeights none;
    none.smooth = none.pyramid = none.prior = 0.0;
    const infer::LinearSystem raw = infer::BuildSystem(p.a, frame, 0, {p.b, {}}, none);
    infer::SolveOptions opt;
    opt.bounds = infer::Bounds::None();
    opt.columnFloor = 1e-12;
    opt.maxIterations = 300;
    opt.restartEvery = 0;
    opt.atol = 1e-10;
    opt.logEvery = 0;
    opt.threads = threads;
    const infer::SolveResult r = infer::SolveIterative(raw, infer::InitialGuess(raw), opt);
    const auto [lo, hi] = Range(r.x);
    return Format("unregularized unbounded LSMR: texels [%.4g, %.4g], %s", lo, hi,
                  AllFinite(r.x) ? "finite" : "NOT FINITE");
}

// The SimplicialLDLT oracle on the same (regularized) system, unbounded.
std::string DirectSolve(const infer::LinearSystem& sys, const infer::SolveResult& it, int threads,
                        Checks* checks) {
    if (sys.Cols() > 40000) return "SolveDirect skipped (> 40000 columns)";
    infer::SolveResult d;
    try {
        d = infer::SolveDirect(sys, infer::InitialGuess(sys));
    } catch (const std::runtime_error& e) {  // its documented clear error
        return std::string("SolveDirect: clear error: ") + e.what();
    }
    checks->Expect(AllFinite(d.x), "SolveDirect returned non-finite texels");
    double diff = 0.0, norm = 0.0;
    for (size_t j = 0; j < d.x.size() && j < it.x.size(); ++j) {
        diff += (it.x[j] - d.x[j]) * (it.x[j] - d.x[j]);
        norm += d.x[j] * d.x[j];
    }
    const auto [lo, hi] = Range(d.x);
    return Format(
        "SolveDirect (unbounded, %.3f s): texels [%.4g, %.4g], image rel. residual %.3g, "
        "|x - x_direct| / |x_direct| = %.3g",
        d.seconds, lo, hi, ImageRelativeResidual(sys, d.x, threads),
        norm > 0.0 ? std::sqrt(diff / norm) : std::sqrt(diff));
}

// HDR: the worst relative error over well-observed components (squared norm >= 1/4 of the max).
double WorstObservedError(const infer::LinearSystem& sys, const Vector& x, const Vector& xStar,
                          int threads, int* observed) {
    const Vector norms = sys.k.ColumnSquaredNorms(threads);
    const double maxNorm = *std::max_element(norms.begin(), norms.end());
    double worst = 0.0;
    *observed = 0;
    for (size_t j = 0; j < x.size(); ++j) {
        if (norms[j] < 0.25 * maxNorm) continue;
        const double truth = xStar[4 * sys.globalFirstTexel + j];
        worst = std::max(worst, std::fabs(x[j] - truth) / truth);
        ++*observed;
    }
    return worst;
}

infer::SolveOptions SolverOptionsFor(const SolverSpec& spec, int threads) {
    infer::SolveOptions opt;
    opt.threads = threads;
    opt.maxIterations = 600;
    opt.logEvery = 10;
    if (spec.hdr) {
        opt.bounds = infer::Bounds::Hdr();
        opt.maxIterations = 4000;
        opt.restartEvery = 100;
        opt.atol = 1e-15;
        opt.logEvery = 0;
    }
    return opt;
}

// The solution against the case's expectations: range, masked RMSE, a finite log, and for HDR
// the error of the well-observed texels, otherwise the unregularized solve's figures.
struct SolutionFigures {
    double lo = 0.0, hi = 0.0, rmse = 0.0;
    std::string figures;
};
SolutionFigures CheckSolution(const SolverSpec& spec, const Problem& p,
                              const infer::LinearSystem& sys, const infer::SolveResult& r,
                              int threads, Checks* checks) {
    SolutionFigures f;
    const bool finite = checks->Expect(AllFinite(r.x), "non-finite texels");
    std::tie(f.lo, f.hi) = Range(r.x);
    f.rmse = infer::MaskedImageRmse(sys, r.x, threads);
    checks->Expect(std::isfinite(f.rmse), "non-finite masked RMSE");
    bool logFinite = true;
    double excursion = 0.0;
    for (const infer::IterationRecord& rec : r.log) {
        logFinite = logFinite && std::isfinite(rec.imageRmse) && std::isfinite(rec.residualNorm);
        excursion = std::max({excursion, std::fabs(rec.texelMin), std::fabs(rec.texelMax)});
    }
    checks->Expect(logFinite, "non-finite convergence log");
    if (spec.hdr) {
        const double maxTruth = *std::max_element(p.xStar.begin(), p.xStar.end());
        checks->Expect(!finite || (f.lo >= 0.0 && f.hi <= 10.0 * maxTruth),
                       Format("texels [%.4g, %.4g] outside [0, 10 max x*]", f.lo, f.hi));
        int observed = 0;
        const double worst = WorstObservedError(sys, r.x, p.xStar, threads, &observed);
        checks->Expect(observed > 0 && worst < 1e-4,
                       Format("well-observed relative error %.3g (>= 1e-4)", worst));
        f.figures =
            Format("%d well-observed components, worst relative error %.3g", observed, worst);
    } else {
        checks->Expect(!finite || (f.lo >= 0.0 && f.hi <= 1.0),
                       Format("texels [%.4g, %.4g] outside [0, 1]", f.lo, f.hi));
        checks->Expect(excursion < 10.0, Format("iterate excursion %.3g >= 10", excursion));
        checks->Expect(f.rmse < spec.rmseLimit,
                       Format("masked RMSE %.3g >= %.3g", f.rmse, spec.rmseLimit));
        f.figures = RawSolve(p, spec.frame, threads);
    }
    return f;
}

void RunSolverCase(const SolverSpec& spec, const StabilityOptions& options, StabilityCase* c) {
    const int threads = std::max(1, options.threads);
    const Problem p = Render(spec.frame, spec.hdr, threads);
    infer::RegularizerWeights weights;
    if (spec.hdr) weights.smooth = weights.pyramid = weights.prior = 0.0;
    const infer::LinearSystem sys = infer::BuildSystem(p.a, spec.frame, 0, {p.b, {}}, weights);
    const infer::SolveOptions opt = SolverOptionsFor(spec, threads);
    const infer::SolveResult r = infer::SolveIterative(sys, infer::InitialGuess(sys), opt);
    Checks checks;
    const SolutionFigures sf = CheckSolution(spec, p, sys, r, threads, &checks);
    const double lo = sf.lo, hi = sf.hi, rmse = sf.rmse;
    const std::string& figures = sf.figures;
    c->residual = ImageRelativeResidual(sys, r.x, threads);
    const ConditionEstimate est = stability::EstimateCondition(sys, opt.columnFloor, threads);
    c->condition = est.kappa;
    checks.Expect(std::isfinite(c->residual) && std::isfinite(c->condition),
                  "residual or condition not finite");
    const std::string direct = DirectSolve(sys, r, threads, &checks);
    c->detail = Format(
        "%s; system %lld rows (%lld image) x %lld cols; %.0f%% of image rows tap two MIP levels; "
        "%s after %d iterations (%d restarts, %.3f s); texels [%.4g, %.4g]; masked RMSE %.3g; "
        "residual = |W^1/2(Ax-b)|/|W^1/2 b| over the masked image rows; condition = "
        "Golub-Kahan-Lanczos sigma_max/sigma_min of channel 0 of K D (D the solver's floored "
        "column scaling, %d steps, lower bound on kappa(KD)): sigma %.3g..%.3g over %lld columns "
        "(%lld empty left out), unscaled column-norm spread %.3g; %s; %s",
        spec.geometry.c_str(), static_cast<long long>(sys.k.Rows()),
        static_cast<long long>(sys.imageRows), static_cast<long long>(sys.Cols()),
        100.0 * TwoLevelRowFraction(sys), infer::ToString(r.stop), r.iterations, r.restarts,
        r.seconds, lo, hi, rmse, est.steps, est.sigmaMin, est.sigmaMax,
        static_cast<long long>(est.columns), static_cast<long long>(est.emptyColumns),
        est.columnSpread, figures.c_str(), direct.c_str());
    stability::Conclude(checks,
                        Format("finite texels in [%.3g, %.3g], masked RMSE %.3g, %s", lo, hi, rmse,
                               infer::ToString(r.stop)),
                        c);
}

std::vector<SolverSpec> SolverSpecs() {
    const std::string bounded =
        "finite texels within the bounds [0, 1], iterates within +-10, masked image RMSE < 0.02; "
        "residual and condition reported; SimplicialLDLT oracle compared";
    std::vector<SolverSpec> out;
    out.push_back({"solver: grazing reflection", bounded, Sphere(96, 32, 0.25f, 1), false, 0.02,
                   "mirror sphere rim only (|n.v| < 0.25), cube 32"});
    out.push_back({"solver: >64x magnification", bounded, FaceQuad(96, 16, 0.01f, 5), false, 0.02,
                   "96 px over 0.16 texel of level 0 (600 px per texel), cube 16"});
    raster::Frame faint = Sphere(96, 16, 2.0f, 3);
    AddFaintPass(&faint, 1e-3f);
    out.push_back({"solver: near-zero columns", bounded, faint, false, 0.02,
                   "mirror sphere plus an additive pass of weight 1e-3 around -Z, cube 16"});
    out.push_back({"solver: two MIP levels trade off", bounded, FaceQuad(16, 32, 0.7f, 6), false,
                   0.02, "16 px over 22.4 texels of level 0 (LOD ~0.5, trilinear), cube 32"});
    out.push_back({"solver: HDR 1e-4..1e4 (Bounds::Hdr)",
                   "finite texels in [0, 10 max x*], relative error < 1e-4 on well-observed "
                   "texels; residual and condition reported; SimplicialLDLT oracle compared",
                   FaceQuad(96, 16, 0.5f, 8), true, 0.0,
                   "x* log-uniform in 1e-4..1e4, quad over half the +Z face, no regularization"});
    return out;
}

}  // namespace

std::vector<StabilityCase> RunSolverStabilityCases(const StabilityOptions& options) {
    std::vector<StabilityCase> out;
    for (const SolverSpec& spec : SolverSpecs())
        out.push_back(stability::RunCase(spec.name, "stiff", spec.expected, [&](StabilityCase* c) {
            RunSolverCase(spec, options, c);
        }));
    return out;
}

}  // namespace pem::stability
