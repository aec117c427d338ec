// SPDX-License-Identifier: MIT
// stability_condition.cpp — the condition estimate of the solver cases (stability_condition.h).
#include "viewer_tty/stability/stability_condition.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "infer/sparse.h"

namespace pem::stability::stability {
namespace {

using infer::Vector;

// Singular values of a small dense square matrix (columns b[j]) by one-sided Jacobi.
std::vector<double> SingularValues(std::vector<Vector> b) {
    const size_t n = b.size();
    for (int sweep = 0; sweep < 60; ++sweep) {
        bool rotated = false;
        for (size_t p = 0; p + 1 < n; ++p)
            for (size_t q = p + 1; q < n; ++q) {
                double alpha = 0.0, beta = 0.0, gamma = 0.0;
                for (size_t i = 0; i < n; ++i) {
                    alpha += b[p][i] * b[p][i];
                    beta += b[q][i] * b[q][i];
                    gamma += b[p][i] * b[q][i];
                }
                if (std::fabs(gamma) <= 1e-15 * std::sqrt(alpha * beta) || gamma == 0.0) continue;
                rotated = true;
                const double zeta = (beta - alpha) / (2.0 * gamma);
                const double t =
                    std::copysign(1.0, zeta) / (std::fabs(zeta) + std::sqrt(1.0 + zeta * zeta));
                const double c = 1.0 / std::sqrt(1.0 + t * t), s = c * t;
                for (size_t i = 0; i < n; ++i) {
                    const double bp = b[p][i], bq = b[q][i];
                    b[p][i] = c * bp - s * bq;
                    b[q][i] = s * bp + c * bq;
                }
            }
        if (!rotated) break;
    }
    std::vector<double> sigma(n);
    for (size_t j = 0; j < n; ++j) {
        double s = 0.0;
        for (double v : b[j]) s += v * v;
        sigma[j] = std::sqrt(s);
    }
    return sigma;
}

double Norm2(const Vector& v) {
    double s = 0.0;
    for (double x : v) s += x * x;
    return std::sqrt(s);
}

// Channel 0 of K D with the empty columns removed.
infer::CsrMatrix ScaledChannel0(const infer::LinearSystem& sys, double columnFloor, int threads,
                                ConditionEstimate* est) {
    const Vector norms = sys.k.ColumnSquaredNorms(threads);
    Vector nonZero;
    for (double v : norms)
        if (v > 0.0) nonZero.push_back(v);
    if (nonZero.empty()) return {};
    std::nth_element(nonZero.begin(), nonZero.begin() + static_cast<long>(nonZero.size() / 2),
                     nonZero.end());
    const double floor = columnFloor * nonZero[nonZero.size() / 2];
    std::vector<int64_t> local(norms.size(), -1);
    Vector scale(norms.size(), 0.0);
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (size_t j = 0; j < norms.size(); j += 4) {
        if (norms[j] <= 0.0) {
            ++est->emptyColumns;
            continue;
        }
        local[j] = est->columns++;
        scale[j] = 1.0 / std::sqrt(std::max(norms[j], floor));
        lo = std::min(lo, norms[j]), hi = std::max(hi, norms[j]);
    }
    est->columnSpread = std::sqrt(hi / lo);
    const infer::CsrMatrix& k = sys.k.A();
    infer::CsrMatrix c;
    c.cols = est->columns;
    std::vector<uint32_t> cols;
    Vector vals;
    for (int64_t r = 0; r < k.rows; r += 4) {
        cols.clear(), vals.clear();
        for (int64_t e = k.rowPtr[static_cast<size_t>(r)]; e < k.rowPtr[static_cast<size_t>(r + 1)];
             ++e) {
            const uint32_t j = k.col[static_cast<size_t>(e)];
            if (local[j] < 0) continue;
            cols.push_back(static_cast<uint32_t>(local[j]));
            vals.push_back(k.val[static_cast<size_t>(e)] * scale[j]);
        }
        c.AddRow(cols, vals);
    }
    return c;
}

// Removes from w its components along the stored vectors (classical Gram-Schmidt, twice).
void Reorthogonalize(const std::vector<Vector>& basis, Vector* w) {
    for (int pass = 0; pass < 2; ++pass)
        for (const Vector& v : basis) {
            double d = 0.0;
            for (size_t i = 0; i < v.size(); ++i) d += v[i] * (*w)[i];
            for (size_t i = 0; i < v.size(); ++i) (*w)[i] -= d * v[i];
        }
}

}  // namespace

ConditionEstimate EstimateCondition(const infer::LinearSystem& sys, double columnFloor,
                                    int threads) {
    ConditionEstimate est;
    const infer::CsrMatrix c = ScaledChannel0(sys, columnFloor, threads, &est);
    if (est.columns == 0) return est;
    const infer::CsrMatrix ct = infer::Transpose(c);
    const int maxSteps = static_cast<int>(std::min<int64_t>(kLanczosSteps, est.columns));
    Vector v(static_cast<size_t>(est.columns)), u, w;
    uint64_t state = 12345;  // a fixed pseudo-random start (LCG)
    for (double& x : v) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        x = static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
    }
    double nv = Norm2(v);
    for (double& x : v) x /= nv;
    std::vector<Vector> basis;
    Vector alphas, betas;
    infer::Multiply(c, v, &u, threads);
    for (int j = 0; j < maxSteps; ++j) {
        const double alpha = Norm2(u);
        if (!(alpha > 1e-300)) break;
        for (double& x : u) x /= alpha;
        alphas.push_back(alpha);
        basis.push_back(v);
        if (j + 1 == maxSteps) break;
        infer::Multiply(ct, u, &w, threads);  // w = C^T u - alpha v
        for (size_t i = 0; i < w.size(); ++i) w[i] -= alpha * v[i];
        Reorthogonalize(basis, &w);
        const double beta = Norm2(w);
        if (!(beta > 1e-14 * alphas.front())) break;  // an invariant subspace: B is complete
        for (size_t i = 0; i < w.size(); ++i) v[i] = w[i] / beta;
        betas.push_back(beta);
        Vector cv;
        infer::Multiply(c, v, &cv, threads);  // u' = C v - beta u
        for (size_t i = 0; i < cv.size(); ++i) cv[i] -= beta * u[i];
        u = std::move(cv);
    }
    // B: alpha on the diagonal, beta above it (C V_k = U_k B_k).
    const size_t n = alphas.size();
    std::vector<Vector> b(n, Vector(n, 0.0));
    for (size_t j = 0; j < n; ++j) {
        b[j][j] = alphas[j];
        if (j > 0) b[j][j - 1] = betas[j - 1];
    }
    const std::vector<double> sigma = SingularValues(std::move(b));
    est.steps = static_cast<int>(n);
    est.sigmaMax = *std::max_element(sigma.begin(), sigma.end());
    est.sigmaMin = *std::min_element(sigma.begin(), sigma.end());
    est.kappa = est.sigmaMax / est.sigmaMin;
    return est;
}

}  // namespace pem::stability::stability
