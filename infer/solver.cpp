// SPDX-License-Identifier: MIT
// solver.cpp — LSMR and CGLS cycles with per-channel recurrences, projected restarts, the
// convergence log, and the SimplicialLDLT oracle (solver.h).
#include "infer/solver.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "base/atomic_file.h"
#include "base/parallel.h"

namespace pem::infer {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Column scaling ------------------------------------------------------------------------------

struct Scaling {
    Vector columnNorm2;  // |k_j|^2
    Vector d;            // 1 / sqrt(max(|k_j|^2, floor))
};

Scaling ColumnScaling(const LinearSystem& sys, double floorRel, int threads) {
    Scaling s;
    s.columnNorm2 = sys.k.ColumnSquaredNorms(threads);
    // Floor: floorRel x the median of the non-zero squared norms.
    Vector positive;
    for (double v : s.columnNorm2)
        if (v > 0.0) positive.push_back(v);
    double floor = 1.0;
    if (!positive.empty()) {
        const size_t mid = positive.size() / 2;
        std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(mid),
                         positive.end());
        floor = floorRel * positive[mid];
    }
    if (!(floor > 0.0)) floor = std::numeric_limits<double>::min();
    s.d.resize(s.columnNorm2.size());
    for (size_t j = 0; j < s.d.size(); ++j)
        s.d[j] = 1.0 / std::sqrt(std::max(s.columnNorm2[j], floor));
    return s;
}

// |K diag(dm)|_F per channel.
Channels FrobeniusNorm(const Scaling& s, const Vector& dm) {
    Channels sum{};
    for (size_t j = 0; j < dm.size(); ++j) sum[j % kChannels] += dm[j] * dm[j] * s.columnNorm2[j];
    return Sqrt(sum);
}

// The scaled operator K diag(dm) and its transpose.
struct ScaledOperator {
    const SparseOperator& k;
    const Vector& dm;
    int threads;
    mutable Vector tmp;
    void Apply(const Vector& y, Vector* out) const {
        Hadamard(dm, y, &tmp);
        k.Apply(tmp, out, threads);
    }
    void ApplyTranspose(const Vector& r, Vector* out) const {
        k.ApplyTranspose(r, &tmp, threads);
        Hadamard(dm, tmp, out);
    }
};

// Called after every cycle iteration with the cycle's y; returns true to stop the cycle.
using Monitor = std::function<bool(int iterationsInCycle, const Vector& y)>;

struct CycleResult {
    Vector y;
    int iterations = 0;
};

Channels Mask(const std::array<bool, kChannels>& active) {
    Channels m{};
    for (int c = 0; c < kChannels; ++c)
        m[static_cast<size_t>(c)] = active[static_cast<size_t>(c)] ? 1.0 : 0.0;
    return m;
}

bool AnyActive(const std::array<bool, kChannels>& active) {
    return std::any_of(active.begin(), active.end(), [](bool a) { return a; });
}

// LSMR ----------------------------------------------------------------------------------------

// The scalar recurrences of LSMR for one channel (no damping: the prior is a block of rows).
struct LsmrChannel {
    double alphabar = 0, zetabar = 0, rho = 1, rhobar = 1, cbar = 1, sbar = 0;
    double betadd = 0, betad = 0, rhodold = 1, tautildeold = 0, thetatilde = 0, zeta = 0;
    double normA2 = 0, normb = 0, normr = 0, normar = 0, lastNormA = 0;

    // Coefficients of the vector updates: hbar = h + hbar_c hbar; y += y_c hbar; h = v + h_c h.
    struct Coeffs {
        double hbar = 0, y = 0, h = 0;
    };

    // beta = |r0|, alpha = |(KD)^T u1|.
    void Start(double beta, double alpha) {
        zetabar = alpha * beta;
        alphabar = alpha;
        betadd = beta;
        normA2 = alpha * alpha;
        normb = beta;
        normr = beta;
        normar = alpha * beta;
    }

    // One step with the new Golub-Kahan scalars alpha_{k+1}, beta_{k+1}; false on breakdown.
    bool Step(double alpha, double beta, Coeffs* out) {
        // Rotation Q_k: eliminate beta from the lower bidiagonal.
        const double rhoold = rho;
        rho = std::hypot(alphabar, beta);
        if (rho == 0.0) return false;
        const double c = alphabar / rho, s = beta / rho;
        const double thetanew = s * alpha;
        alphabar = c * alpha;
        // Rotation Qbar_k: the upper bidiagonal of R_k^T.
        const double rhobarold = rhobar, zetaold = zeta;
        const double thetabar = sbar * rho;
        rhobar = std::hypot(cbar * rho, thetanew);
        if (rhobar == 0.0) return false;
        cbar = cbar * rho / rhobar;
        sbar = thetanew / rhobar;
        zeta = cbar * zetabar;
        zetabar = -sbar * zetabar;
        out->hbar = -(thetabar * rho / (rhoold * rhobarold));
        out->y = zeta / (rho * rhobar);
        out->h = -(thetanew / rho);
        // Estimate |r| (Fong & Saunders §3.3).
        const double betahat = c * betadd;
        betadd = -s * betadd;
        const double thetatildeold = thetatilde;
        const double rhotildeold = std::hypot(rhodold, thetabar);
        const double ctildeold = rhodold / rhotildeold, stildeold = thetabar / rhotildeold;
        thetatilde = stildeold * rhobar;
        rhodold = ctildeold * rhobar;
        betad = -stildeold * betad + ctildeold * betahat;
        tautildeold = (zetaold - thetatildeold * tautildeold) / rhotildeold;
        const double taud = (zeta - thetatilde * tautildeold) / rhodold;
        normr = std::hypot(betad - taud, betadd);
        // Estimate |KD| (Frobenius norm of the bidiagonal) and |(KD)^T r|.
        normA2 += beta * beta;
        normar = std::fabs(zetabar);
        const double normA = std::sqrt(normA2);
        normA2 += alpha * alpha;
        lastNormA = normA;
        return true;
    }

    // The least-squares and consistent-system tests (btol = atol).
    bool Converged(double normy, double atol) const {
        if (normr == 0.0 || normar == 0.0) return true;
        const double test1 = normr / normb;
        const double test2 = normar / (lastNormA * normr);
        const double t1 = test1 / (1.0 + lastNormA * normy / normb);
        const double rtol = atol + atol * lastNormA * normy / normb;
        return test1 <= rtol || test2 <= atol || 1.0 + t1 <= 1.0 || 1.0 + test2 <= 1.0;
    }
};

// Up to maxIts LSMR iterations on min |K diag(dm) y - r0| from y = 0.
CycleResult LsmrCycle(const ScaledOperator& op, Vector r0, int maxIts, double atol, int threads,
                      const Monitor& monitor) {
    const size_t n = op.dm.size();
    CycleResult res;
    res.y.assign(n, 0.0);
    // Golub-Kahan start: beta u = r0, alpha v = (KD)^T u.
    Vector u = std::move(r0), v, h, hbar(n, 0.0), kv, ktu;
    Channels beta = Norm(u, threads);
    Scale(SafeInverse(beta), &u);
    op.ApplyTranspose(u, &v);
    Channels alpha = Norm(v, threads);
    Scale(SafeInverse(alpha), &v);
    h = v;
    std::array<LsmrChannel, kChannels> ch;
    std::array<bool, kChannels> active{};
    for (size_t c = 0; c < kChannels; ++c) {
        ch[c].Start(beta[c], alpha[c]);
        active[c] = alpha[c] * beta[c] > 0.0;
    }
    while (res.iterations < maxIts && AnyActive(active)) {
        // Bidiagonalization: beta u = (KD) v - alpha u, alpha v = (KD)^T u - beta v.
        op.Apply(v, &kv);
        Scale(alpha, &u);
        for (size_t k = 0; k < u.size(); ++k) u[k] = kv[k] - u[k];
        Scale(Mask(active), &u);
        beta = Norm(u, threads);
        Scale(SafeInverse(beta), &u);
        op.ApplyTranspose(u, &ktu);
        Scale(beta, &v);
        for (size_t k = 0; k < v.size(); ++k) v[k] = ktu[k] - v[k];
        Scale(Mask(active), &v);
        alpha = Norm(v, threads);
        Scale(SafeInverse(alpha), &v);
        // Scalar recurrences per channel, then the vector updates.
        Channels cHbar{}, cY{}, cH{};
        for (size_t c = 0; c < kChannels; ++c) {
            LsmrChannel::Coeffs co;
            if (active[c] && ch[c].Step(alpha[c], beta[c], &co)) {
                cHbar[c] = co.hbar;
                cY[c] = co.y;
                cH[c] = co.h;
            } else {
                active[c] = false;
            }
        }
        Xpay(h, cHbar, &hbar);
        Axpy(cY, hbar, &res.y);
        Xpay(v, cH, &h);
        ++res.iterations;
        // Per-channel tests; the monitor may stop the whole cycle.
        const Channels normy = Norm(res.y, threads);
        for (size_t c = 0; c < kChannels; ++c)
            if (active[c] && ch[c].Converged(normy[c], atol)) active[c] = false;
        if (monitor && monitor(res.iterations, res.y)) break;
    }
    return res;
}

// LSMR on the quad form: the same recurrences with the vector work fused into three passes per
// iteration (K product, K^T product, updates), each computing what the separate calls above
// compute, in the same order, so the bytes are the same. u and v are kept unnormalized until
// they are read (u = uRaw / beta per channel), which saves two passes over the row-sized u.
constexpr int64_t kQuadsPerBlock = kReduceBlock / kChannels;

Channels SumBlocks(const std::vector<Channels>& partial) {
    Channels total{};
    for (const Channels& s : partial)
        for (size_t c = 0; c < kChannels; ++c) total[c] += s[c];
    return total;
}

// Over the rows of q in blocks of kQuadsPerBlock: s = Σ_k val_k · in[4 col_k + c] per channel
// (each channel's sum in entry order), then out(r, s) stores row r and returns its squared
// values; returns their sum (blocked order). Scaled: in[..] is read as in[..] · scale[c]
// (sparse.h QuadRowSums).
template <bool Scaled, class Out>
Channels BlockedRowProducts(const CsrMatrix& q, const double* in, const Channels& scale,
                            const Out& out, std::vector<Channels>* partial, int threads) {
    const int64_t blocks = (q.rows + kQuadsPerBlock - 1) / kQuadsPerBlock;
    partial->assign(static_cast<size_t>(blocks), Channels{});
    const int64_t* rowPtr = q.rowPtr.data();
    const uint32_t* col = q.col.data();
    const double* val = q.val.data();
    const int64_t nnz = q.NonZeros();
    Channels* sums = partial->data();
    const Channels sc = scale;
    base::ForRanges(blocks, threads, 2,
                    [&, rowPtr, col, val, in, nnz, sums, sc](int64_t b0, int64_t b1) {
                        for (int64_t b = b0; b < b1; ++b) {
                            Channels acc{};
                            const int64_t end = std::min(q.rows, (b + 1) * kQuadsPerBlock);
                            for (int64_t r = b * kQuadsPerBlock; r < end; ++r) {
                                double s[kChannels];
                                QuadRowSums<Scaled>(rowPtr, col, val, nnz, r, in, sc, s);
                                const Channels sq = out(r, s);
                                for (size_t c = 0; c < kChannels; ++c) acc[c] += sq[c];
                            }
                            sums[b] = acc;
                        }
                    });
    return SumBlocks(*partial);
}

// uRaw <- mask (K vd - alpha (uRaw invBeta)); returns |uRaw|^2 per channel (blocked order).
Channels FusedForward(const CsrMatrix& q, const Vector& vd, const Channels& invBeta,
                      const Channels& alpha, const Channels& mask, Vector* uRaw,
                      std::vector<Channels>* partial, int threads) {
    const double* xp = vd.data();
    double* up = uRaw->data();
    return BlockedRowProducts<false>(
        q, xp, Channels{},
        [&](int64_t r, const double* s) {
            Channels sq{};
            double* ur = up + kChannels * r;
            for (size_t c = 0; c < kChannels; ++c) {
                const double prev = (ur[c] * invBeta[c]) * alpha[c];
                const double next = (s[c] - prev) * mask[c];
                ur[c] = next;
                sq[c] = next * next;
            }
            return sq;
        },
        partial, threads);
}

// vRaw <- mask (dm .* (K^T (uRaw invBeta)) - beta v), in place over v; returns |vRaw|^2.
Channels FusedTranspose(const CsrMatrix& qt, const Vector& uRaw, const Channels& invBeta,
                        const Vector& dm, const Channels& beta, const Channels& mask, Vector* v,
                        std::vector<Channels>* partial, int threads) {
    const double* up = uRaw.data();
    double* vp = v->data();
    return BlockedRowProducts<true>(
        qt, up, invBeta,
        [&](int64_t j, const double* s) {
            Channels sq{};
            const size_t base = static_cast<size_t>(kChannels * j);
            for (size_t c = 0; c < kChannels; ++c) {
                const double ktu = dm[base + c] * s[c];
                const double next = (ktu - vp[base + c] * beta[c]) * mask[c];
                vp[base + c] = next;
                sq[c] = next * next;
            }
            return sq;
        },
        partial, threads);
}

// v = vRaw invAlpha, vd = dm .* v, hbar = h + cHbar hbar, y += cY hbar, h = v + cH h;
// returns |y|^2.
struct FusedVectors {
    Vector v, vd, h, hbar, y;
};
Channels FusedUpdate(const Channels& invAlpha, const Vector& dm, const Channels& cHbar,
                     const Channels& cY, const Channels& cH, FusedVectors* f,
                     std::vector<Channels>* partial, int threads) {
    const int64_t n = static_cast<int64_t>(f->v.size());
    const int64_t blocks = (n + kReduceBlock - 1) / kReduceBlock;
    partial->assign(static_cast<size_t>(blocks), Channels{});
    base::ForRanges(blocks, threads, 4, [&](int64_t b0, int64_t b1) {
        for (int64_t b = b0; b < b1; ++b) {
            Channels acc{};
            const size_t end = static_cast<size_t>(std::min(n, (b + 1) * kReduceBlock));
            double *vp = f->v.data(), *vdp = f->vd.data(), *hp = f->h.data();
            double *hbarp = f->hbar.data(), *yp = f->y.data();
            const double* dmp = dm.data();
            for (size_t k = static_cast<size_t>(b * kReduceBlock); k < end; k += kChannels)
                for (size_t c = 0; c < kChannels; ++c) {
                    const size_t e = k + c;
                    const double v = vp[e] * invAlpha[c];
                    vp[e] = v;
                    vdp[e] = dmp[e] * v;
                    hbarp[e] = hp[e] + cHbar[c] * hbarp[e];
                    yp[e] += cY[c] * hbarp[e];
                    hp[e] = v + cH[c] * hp[e];
                    acc[c] += yp[e] * yp[e];
                }
            (*partial)[static_cast<size_t>(b)] = acc;
        }
    });
    return SumBlocks(*partial);
}

CycleResult LsmrCycleQuads(const SparseOperator& k, const Vector& dm, Vector r0, int maxIts,
                           double atol, int threads, const Monitor& monitor) {
    const size_t n = dm.size();
    CycleResult res;
    std::vector<Channels> partial;
    const Channels none{}, all{1.0, 1.0, 1.0, 1.0};
    // Golub-Kahan start: beta u = r0, alpha v = (KD)^T u.
    Vector u = std::move(r0);
    Channels beta = Norm(u, threads);
    Channels invBeta = SafeInverse(beta);
    FusedVectors f;
    f.v.assign(n, 0.0);
    Channels alpha =
        Sqrt(FusedTranspose(k.QuadsT(), u, invBeta, dm, none, all, &f.v, &partial, threads));
    f.vd.assign(n, 0.0);
    f.h.assign(n, 0.0);
    f.hbar.assign(n, 0.0);
    f.y.assign(n, 0.0);
    // v /= alpha, vd = dm v, h = v (h = v + 0 h, hbar and y stay 0).
    FusedUpdate(SafeInverse(alpha), dm, none, none, none, &f, &partial, threads);
    std::array<LsmrChannel, kChannels> ch;
    std::array<bool, kChannels> active{};
    for (size_t c = 0; c < kChannels; ++c) {
        ch[c].Start(beta[c], alpha[c]);
        active[c] = alpha[c] * beta[c] > 0.0;
    }
    while (res.iterations < maxIts && AnyActive(active)) {
        // Bidiagonalization: beta u = (KD) v - alpha u, alpha v = (KD)^T u - beta v.
        const Channels mask = Mask(active);
        beta = Sqrt(FusedForward(k.Quads(), f.vd, invBeta, alpha, mask, &u, &partial, threads));
        invBeta = SafeInverse(beta);
        alpha =
            Sqrt(FusedTranspose(k.QuadsT(), u, invBeta, dm, beta, mask, &f.v, &partial, threads));
        // Scalar recurrences per channel, then the vector updates.
        Channels cHbar{}, cY{}, cH{};
        for (size_t c = 0; c < kChannels; ++c) {
            LsmrChannel::Coeffs co;
            if (active[c] && ch[c].Step(alpha[c], beta[c], &co)) {
                cHbar[c] = co.hbar;
                cY[c] = co.y;
                cH[c] = co.h;
            } else {
                active[c] = false;
            }
        }
        const Channels normy =
            Sqrt(FusedUpdate(SafeInverse(alpha), dm, cHbar, cY, cH, &f, &partial, threads));
        ++res.iterations;
        // Per-channel tests; the monitor may stop the whole cycle.
        for (size_t c = 0; c < kChannels; ++c)
            if (active[c] && ch[c].Converged(normy[c], atol)) active[c] = false;
        if (monitor && monitor(res.iterations, f.y)) break;
    }
    res.y = std::move(f.y);
    return res;
}

// CGLS ----------------------------------------------------------------------------------------

// Up to maxIts CGLS iterations on min |K diag(dm) y - r0| from y = 0.
CycleResult CglsCycle(const ScaledOperator& op, Vector r0, const Channels& normKD, int maxIts,
                      double atol, int threads, const Monitor& monitor) {
    CycleResult res;
    res.y.assign(op.dm.size(), 0.0);
    const Channels normR0 = Norm(r0, threads);
    Vector r = std::move(r0), s, p, q;
    op.ApplyTranspose(r, &s);
    p = s;
    Channels gamma = SquaredNorm(s, threads);
    std::array<bool, kChannels> active{};
    for (size_t c = 0; c < kChannels; ++c) active[c] = gamma[c] > 0.0;
    while (res.iterations < maxIts && AnyActive(active)) {
        // Step along p: y += a p, r -= a K D p.
        op.Apply(p, &q);
        const Channels delta = SquaredNorm(q, threads);
        Channels a{}, minusA{};
        for (size_t c = 0; c < kChannels; ++c) {
            a[c] = active[c] && delta[c] > 0.0 ? gamma[c] / delta[c] : 0.0;
            minusA[c] = -a[c];
        }
        Axpy(a, p, &res.y);
        Axpy(minusA, q, &r);
        // New gradient and direction: p = s + (gamma_new / gamma) p.
        op.ApplyTranspose(r, &s);
        const Channels gammaNew = SquaredNorm(s, threads);
        const Channels normR = Norm(r, threads);
        Channels b{};
        for (size_t c = 0; c < kChannels; ++c) {
            if (!active[c]) continue;
            b[c] = gamma[c] > 0.0 ? gammaNew[c] / gamma[c] : 0.0;
            if (std::sqrt(gammaNew[c]) <= atol * normKD[c] * normR[c] ||
                normR[c] <= atol * normR0[c] || delta[c] == 0.0)
                active[c] = false;
        }
        gamma = gammaNew;
        Scale(Mask(active), &s);
        Xpay(s, b, &p);
        Scale(Mask(active), &p);
        ++res.iterations;
        if (monitor && monitor(res.iterations, res.y)) break;
    }
    return res;
}

// Evaluation at a point (exact residual and projected gradient) -------------------------------

struct Evaluation {
    Vector r;  // h - K x
    Vector g;  // D K^T r (descent direction of 1/2 |r|^2 in scaled variables)
    Channels rNorm{}, hNorm{}, projectedGradientNorm{};
    double imageRmse = 0.0, texelMin = 0.0, texelMax = 0.0;
};

bool AtLowerBlocked(double x, double g, const Bounds& b) {
    return x <= b.lo && g <= 0.0;
}
bool AtUpperBlocked(double x, double g, const Bounds& b) {
    return x >= b.hi && g >= 0.0;
}

Evaluation Evaluate(const LinearSystem& sys, const Scaling& sc, const Vector& x,
                    const Bounds& bounds, int threads) {
    Evaluation ev;
    sys.k.Apply(x, &ev.r, threads);
    double image = 0.0;
    for (size_t r = 0; r < ev.r.size(); ++r) {
        ev.r[r] = sys.h[r] - ev.r[r];
        if (static_cast<int64_t>(r) < sys.imageRows) image += ev.r[r] * ev.r[r];
    }
    ev.imageRmse = sys.imageWeightSum > 0.0 ? std::sqrt(image / sys.imageWeightSum) : 0.0;
    sys.k.ApplyTranspose(ev.r, &ev.g, threads);
    Vector pg(x.size());
    for (size_t j = 0; j < x.size(); ++j) {
        ev.g[j] *= sc.d[j];
        const bool blocked =
            AtLowerBlocked(x[j], ev.g[j], bounds) || AtUpperBlocked(x[j], ev.g[j], bounds);
        pg[j] = blocked ? 0.0 : ev.g[j];
    }
    ev.rNorm = Norm(ev.r, threads);
    ev.hNorm = Norm(sys.h, threads);
    ev.projectedGradientNorm = Norm(pg, threads);
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    ev.texelMin = x.empty() ? 0.0 : *lo;
    ev.texelMax = x.empty() ? 0.0 : *hi;
    return ev;
}

bool Converged(const Evaluation& ev, const Channels& normKD, double atol) {
    for (size_t c = 0; c < kChannels; ++c) {
        const bool leastSquares = ev.projectedGradientNorm[c] <= atol * normKD[c] * ev.rNorm[c];
        const bool consistent = ev.rNorm[c] <= atol * ev.hNorm[c];
        // The gradient of r = h - K x is not computable below ~eps |KD| |h|.
        const bool roundingFloor =
            ev.projectedGradientNorm[c] <=
            16.0 * std::numeric_limits<double>::epsilon() * normKD[c] * ev.hNorm[c];
        if (!leastSquares && !consistent && !roundingFloor) return false;
    }
    return true;
}

// The norm over all channels from per-channel norms.
double Combined(const Channels& norms) {
    double s = 0.0;
    for (double n : norms) s += n * n;
    return std::sqrt(s);
}

IterationRecord Record(int iteration, double seconds, const Evaluation& ev, double gradientRef) {
    IterationRecord rec;
    rec.iteration = iteration;
    rec.seconds = seconds;
    rec.residualNorm = Combined(ev.rNorm);
    rec.relativeGradient =
        gradientRef > 0.0 ? Combined(ev.projectedGradientNorm) / gradientRef : 0.0;
    rec.imageRmse = ev.imageRmse;
    rec.texelMin = ev.texelMin;
    rec.texelMax = ev.texelMax;
    return rec;
}

void Clamp(const Bounds& b, Vector* x) {
    for (double& v : *x) v = std::min(std::max(v, b.lo), b.hi);
}

// D with the texels frozen on a bound (gradient pushing outward) set to 0.
Vector FreeScaling(const Scaling& sc, const Evaluation& ev, const Vector& x, const Bounds& b) {
    Vector dm = sc.d;
    for (size_t j = 0; j < x.size(); ++j)
        if (AtLowerBlocked(x[j], ev.g[j], b) || AtUpperBlocked(x[j], ev.g[j], b)) dm[j] = 0.0;
    return dm;
}

}  // namespace

const char* ToString(StopReason reason) {
    switch (reason) {
        case StopReason::Converged:
            return "converged";
        case StopReason::ResidualFloor:
            return "residual_floor";
        case StopReason::MaxIterations:
            return "max_iterations";
        case StopReason::Stalled:
            return "stalled";
        case StopReason::Direct:
            return "direct";
    }
    return "?";
}

SolveResult SolveIterative(const LinearSystem& sys, const Vector& x0, const SolveOptions& opt) {
    const Clock::time_point t0 = Clock::now();
    if (static_cast<int64_t>(x0.size()) != sys.Cols())
        throw std::invalid_argument("SolveIterative: x0 size");
    SolveResult res;
    const Scaling sc = ColumnScaling(sys, opt.columnFloor, opt.threads);
    res.x = x0;
    Clamp(opt.bounds, &res.x);
    const int cycleLength = opt.restartEvery > 0 ? opt.restartEvery : opt.maxIterations;

    // Reference for the relative gradient: |(KD)^T h|.
    Vector kth;
    sys.k.ApplyTranspose(sys.h, &kth, opt.threads);
    for (size_t j = 0; j < kth.size(); ++j) kth[j] *= sc.d[j];
    const double gradientRef = std::sqrt(Total(SquaredNorm(kth, opt.threads)));

    while (true) {
        // Evaluate the restart point exactly; stop or start a new cycle from it.
        Evaluation ev = Evaluate(sys, sc, res.x, opt.bounds, opt.threads);
        res.log.push_back(Record(res.iterations, SecondsSince(t0), ev, gradientRef));
        const Channels normKD = FrobeniusNorm(sc, sc.d);
        if (Converged(ev, normKD, opt.atol)) {
            res.stop = StopReason::Converged;
            break;
        }
        if (opt.residualFloor > 0.0 && ev.imageRmse <= opt.residualFloor) {
            res.stop = StopReason::ResidualFloor;
            break;
        }
        if (res.iterations >= opt.maxIterations) {
            res.stop = StopReason::MaxIterations;
            break;
        }

        // One cycle on the free texels, logging the unclamped iterate.
        const Vector dm = FreeScaling(sc, ev, res.x, opt.bounds);
        const ScaledOperator op{sys.k, dm, opt.threads, {}};
        bool floorReached = false;
        const int done = res.iterations;
        const Monitor monitor = [&](int its, const Vector& y) {
            if (opt.logEvery <= 0 || (done + its) % opt.logEvery != 0) return false;
            Vector trial(y.size());
            for (size_t j = 0; j < y.size(); ++j) trial[j] = res.x[j] + dm[j] * y[j];
            const Evaluation e = Evaluate(sys, sc, trial, Bounds::None(), opt.threads);
            res.log.push_back(Record(done + its, SecondsSince(t0), e, gradientRef));
            floorReached = opt.residualFloor > 0.0 && e.imageRmse <= opt.residualFloor;
            return floorReached;
        };
        const int budget = std::min(cycleLength, opt.maxIterations - res.iterations);
        const CycleResult cyc =
            opt.method == Method::Lsmr
                ? (sys.k.HasQuadForm()
                       ? LsmrCycleQuads(sys.k, dm, std::move(ev.r), budget, opt.atol, opt.threads,
                                        monitor)
                       : LsmrCycle(op, std::move(ev.r), budget, opt.atol, opt.threads, monitor))
                : CglsCycle(op, std::move(ev.r), FrobeniusNorm(sc, dm), budget, opt.atol,
                            opt.threads, monitor);
        for (size_t j = 0; j < res.x.size(); ++j) res.x[j] += dm[j] * cyc.y[j];
        Clamp(opt.bounds, &res.x);
        res.iterations += cyc.iterations;
        ++res.restarts;
        if (cyc.iterations == 0) {
            const Evaluation last = Evaluate(sys, sc, res.x, opt.bounds, opt.threads);
            res.log.push_back(Record(res.iterations, SecondsSince(t0), last, gradientRef));
            res.stop = StopReason::Stalled;
            break;
        }
    }
    res.seconds = SecondsSince(t0);
    return res;
}

SolveResult SolveDirect(const LinearSystem& sys, const Vector& x0, double columnFloor) {
    const Clock::time_point t0 = Clock::now();
    const Scaling sc = ColumnScaling(sys, columnFloor, 1);
    const CsrMatrix& k = sys.k.A();
    // K D as an Eigen matrix, and the residual at x0.
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(k.val.size());
    for (int64_t r = 0; r < k.rows; ++r)
        for (int64_t e = k.rowPtr[static_cast<size_t>(r)]; e < k.rowPtr[static_cast<size_t>(r) + 1];
             ++e) {
            const uint32_t c = k.col[static_cast<size_t>(e)];
            trip.emplace_back(static_cast<int>(r), static_cast<int>(c),
                              k.val[static_cast<size_t>(e)] * sc.d[c]);
        }
    Eigen::SparseMatrix<double> kd(static_cast<int>(k.rows), static_cast<int>(k.cols));
    kd.setFromTriplets(trip.begin(), trip.end());
    Vector kx0;
    sys.k.Apply(x0, &kx0, 1);
    Eigen::VectorXd r0(k.rows);
    for (int64_t r = 0; r < k.rows; ++r)
        r0[r] = sys.h[static_cast<size_t>(r)] - kx0[static_cast<size_t>(r)];
    // Normal equations; columns without entries get a unit diagonal (their y stays 0).
    Eigen::SparseMatrix<double> normal = kd.transpose() * kd;
    Eigen::VectorXd rhs = kd.transpose() * r0;
    std::vector<Eigen::Triplet<double>> unit;
    for (size_t j = 0; j < sc.columnNorm2.size(); ++j)
        if (sc.columnNorm2[j] == 0.0)
            unit.emplace_back(static_cast<int>(j), static_cast<int>(j), 1.0);
    if (!unit.empty()) {
        Eigen::SparseMatrix<double> id(normal.rows(), normal.cols());
        id.setFromTriplets(unit.begin(), unit.end());
        normal += id;
    }
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
    if (ldlt.info() != Eigen::Success)
        throw std::runtime_error("SolveDirect: factorization failed");
    const Eigen::VectorXd y = ldlt.solve(rhs);
    if (ldlt.info() != Eigen::Success) throw std::runtime_error("SolveDirect: solve failed");
    SolveResult res;
    res.x = x0;
    for (size_t j = 0; j < res.x.size(); ++j) res.x[j] += sc.d[j] * y[static_cast<Eigen::Index>(j)];
    res.stop = StopReason::Direct;
    res.seconds = SecondsSince(t0);
    return res;
}

void WriteLogCsv(const std::vector<IterationRecord>& log, std::ostream& out) {
    out << "iteration,seconds,residual_norm,relative_gradient,image_rmse,texel_min,texel_max\n";
    char line[256];
    for (const IterationRecord& r : log) {
        std::snprintf(line, sizeof line, "%d,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g\n", r.iteration,
                      r.seconds, r.residualNorm, r.relativeGradient, r.imageRmse, r.texelMin,
                      r.texelMax);
        out << line;
    }
}

void WriteLogCsv(const std::vector<IterationRecord>& log, const std::string& path) {
    std::ostringstream out;
    WriteLogCsv(log, out);
    base::WriteTextAtomic(path, out.str());
}

}  // namespace pem::infer
