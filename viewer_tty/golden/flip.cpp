// SPDX-License-Identifier: MIT
// flip.cpp — LDR-ꟻLIP (flip.h), step by step as the paper states it.
#include "viewer_tty/golden/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pem::golden {
namespace {

using Vec3 = std::array<double, 3>;
constexpr double kPi = std::numbers::pi;
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kQf = 0.5, kFeatureWidthDeg = 0.082;

// One image as three planes of doubles.
struct Planes {
    int w = 0, h = 0;
    std::array<std::vector<double>, 3> c;
    double& At(int k, int x, int y) { return c[size_t(k)][size_t(y) * size_t(w) + size_t(x)]; }
    double At(int k, int x, int y) const {
        return c[size_t(k)][size_t(std::clamp(y, 0, h - 1)) * size_t(w) +
                            size_t(std::clamp(x, 0, w - 1))];  // edges replicated
    }
};

double SrgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Vec3 RgbToXyz(const Vec3& r) {
    return {0.4124564 * r[0] + 0.3575761 * r[1] + 0.1804375 * r[2],
            0.2126729 * r[0] + 0.7151522 * r[1] + 0.0721750 * r[2],
            0.0193339 * r[0] + 0.1191920 * r[1] + 0.9503041 * r[2]};
}
Vec3 XyzToRgb(const Vec3& x) {
    return {3.2404542 * x[0] - 1.5371385 * x[1] - 0.4985314 * x[2],
            -0.9692660 * x[0] + 1.8760108 * x[1] + 0.0415560 * x[2],
            0.0556434 * x[0] - 0.2040259 * x[1] + 1.0572252 * x[2]};
}
const Vec3 kWhite = RgbToXyz({1.0, 1.0, 1.0});  // D65 of the sRGB primaries

Vec3 XyzToYcxcz(const Vec3& x) {
    const double xr = x[0] / kWhite[0], yr = x[1] / kWhite[1], zr = x[2] / kWhite[2];
    return {116.0 * yr - 16.0, 500.0 * (xr - yr), 200.0 * (yr - zr)};
}
Vec3 YcxczToXyz(const Vec3& v) {
    const double yr = (v[0] + 16.0) / 116.0;
    return {(v[1] / 500.0 + yr) * kWhite[0], yr * kWhite[1], (yr - v[2] / 200.0) * kWhite[2]};
}

// CIELab with the Hunt adjustment (a, b scaled by 0.01 L).
Vec3 HuntLab(const Vec3& xyz) {
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
    const double l = 116.0 * fy - 16.0;
    return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

double HyAB(const Vec3& a, const Vec3& b) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// The image in YCxCz, from 8-bit sRGB.
Planes ToYcxcz(const base::Image8& img) {
    Planes p{img.width, img.height, {}};
    for (auto& c : p.c) c.resize(size_t(img.width) * size_t(img.height));
    for (size_t i = 0; i < p.c[0].size(); ++i) {
        const Vec3 rgb = {SrgbToLinear(img.rgba[4 * i] / 255.0),
                          SrgbToLinear(img.rgba[4 * i + 1] / 255.0),
                          SrgbToLinear(img.rgba[4 * i + 2] / 255.0)};
        const Vec3 v = XyzToYcxcz(RgbToXyz(rgb));
        for (size_t k = 0; k < 3; ++k) p.c[k][i] = v[k];
    }
    return p;
}

// Separable 1D convolution of plane k along x (dir 0) or y (dir 1) with kernel (centre r).
std::vector<double> Convolve1D(const Planes& p, int k, const std::vector<double>& kernel, int dir) {
    const int r = int(kernel.size() / 2);
    std::vector<double> out(size_t(p.w) * size_t(p.h), 0.0);
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) {
            double s = 0.0;
            for (int d = -r; d <= r; ++d)
                s += kernel[size_t(d + r)] * (dir == 0 ? p.At(k, x + d, y) : p.At(k, x, y + d));
            out[size_t(y) * size_t(p.w) + size_t(x)] = s;
        }
    return out;
}

// The CSF of channel k as spatial Gaussians a·sqrt(π/b)·exp(−π² x²/b), x in degrees; each
// Gaussian is separable, the sum normalised to 1 over the window.
Planes FilterCsf(const Planes& p, double ppd) {
    static const double kA[3][2] = {{1.0, 0.0}, {1.0, 0.0}, {34.1, 13.5}};
    static const double kB[3][2] = {{0.0047, 1e-5}, {0.0053, 1e-5}, {0.04, 0.025}};
    const int r = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
    Planes out = p;
    for (int k = 0; k < 3; ++k) {
        std::vector<double> sum(out.c[size_t(k)].size(), 0.0);
        double norm = 0.0;
        for (int term = 0; term < 2; ++term) {
            const double a = kA[k][term], b = kB[k][term];
            if (a == 0.0) continue;
            std::vector<double> g(size_t(2 * r + 1));
            for (int d = -r; d <= r; ++d)
                g[size_t(d + r)] = std::exp(-kPi * kPi * (d / ppd) * (d / ppd) / b);
            double g1 = 0.0;
            for (double v : g) g1 += v;
            const double scale = a * std::sqrt(kPi / b);
            norm += scale * g1 * g1;
            Planes tmp = p;
            tmp.c[size_t(k)] = Convolve1D(p, k, g, 0);
            const std::vector<double> xy = Convolve1D(tmp, k, g, 1);
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += scale * xy[i];
        }
        for (size_t i = 0; i < sum.size(); ++i) out.c[size_t(k)][i] = sum[i] / norm;
    }
    return out;
}

// ΔEc per pixel from the two filtered images.
std::vector<double> ColourDifference(const Planes& ref, const Planes& test) {
    const double cmax =
        std::pow(HyAB(HuntLab(RgbToXyz({0, 1, 0})), HuntLab(RgbToXyz({0, 0, 1}))), kQc);
    const double pccmax = kPc * cmax;
    auto lab = [](const Planes& p, size_t i) {
        Vec3 rgb = XyzToRgb(YcxczToXyz({p.c[0][i], p.c[1][i], p.c[2][i]}));
        for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
        return HuntLab(RgbToXyz(rgb));
    };
    std::vector<double> out(ref.c[0].size());
    for (size_t i = 0; i < out.size(); ++i) {
        const double e = std::pow(HyAB(lab(ref, i), lab(test, i)), kQc);
        out[i] =
            e < pccmax ? (kPt / pccmax) * e : kPt + (e - pccmax) / (cmax - pccmax) * (1.0 - kPt);
    }
    return out;
}

// Edge (first derivative) and point (second derivative) kernels of a Gaussian along x, their
// positive and negative parts normalised to +1 and −1.
std::vector<double> FeatureKernel(double sigma, int r, bool point) {
    std::vector<double> k;
    double pos = 0.0, neg = 0.0;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            const double g = std::exp(-(x * x + y * y) / (2.0 * sigma * sigma));
            const double v = point ? (x * x / (sigma * sigma) - 1.0) * g : -x * g;
            k.push_back(v);
            (v > 0.0 ? pos : neg) += v;
        }
    for (double& v : k) v = v > 0.0 ? v / pos : (v < 0.0 ? v / -neg : 0.0);
    return k;
}

// |response| of the achromatic plane y to kernel k along x and (transposed) along y.
std::vector<double> FeatureMagnitude(const Planes& y, const std::vector<double>& k, int r) {
    std::vector<double> out(size_t(y.w) * size_t(y.h));
    for (int py = 0; py < y.h; ++py)
        for (int px = 0; px < y.w; ++px) {
            double gx = 0.0, gy = 0.0;
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    const double w = k[size_t((dy + r) * (2 * r + 1) + dx + r)];
                    gx += w * y.At(0, px + dx, py + dy);
                    gy += w * y.At(0, px + dy, py + dx);
                }
            out[size_t(py) * size_t(y.w) + size_t(px)] = std::hypot(gx, gy);
        }
    return out;
}

// ΔEf per pixel from the unfiltered images' normalised achromatic channel (Y' + 16) / 116.
std::vector<double> FeatureDifference(Planes ref, Planes test, double ppd) {
    const double sigma = 0.5 * kFeatureWidthDeg * ppd;
    const int r = int(std::ceil(3.0 * sigma));
    for (Planes* p : {&ref, &test})
        for (double& v : p->c[0]) v = (v + 16.0) / 116.0;
    const std::vector<double> ek = FeatureKernel(sigma, r, false),
                              pk = FeatureKernel(sigma, r, true);
    const auto er = FeatureMagnitude(ref, ek, r), et = FeatureMagnitude(test, ek, r);
    const auto pr = FeatureMagnitude(ref, pk, r), pt = FeatureMagnitude(test, pk, r);
    std::vector<double> out(er.size());
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = std::pow(
            std::max(std::abs(er[i] - et[i]), std::abs(pr[i] - pt[i])) / std::numbers::sqrt2, kQf);
    return out;
}

}  // namespace

std::vector<float> FlipMap(const base::Image8& reference, const base::Image8& test, double ppd) {
    if (reference.width != test.width || reference.height != test.height)
        throw std::invalid_argument("FlipMap: images of different sizes");
    const Planes ref = ToYcxcz(reference), tst = ToYcxcz(test);
    const std::vector<double> colour = ColourDifference(FilterCsf(ref, ppd), FilterCsf(tst, ppd));
    const std::vector<double> feature = FeatureDifference(ref, tst, ppd);
    std::vector<float> out(colour.size());
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = float(std::pow(colour[i], 1.0 - std::min(1.0, feature[i])));
    return out;
}

double FlipMean(const base::Image8& reference, const base::Image8& test, double ppd) {
    const std::vector<float> map = FlipMap(reference, test, ppd);
    double sum = 0.0;
    for (float v : map) sum += double(v);
    return map.empty() ? 0.0 : sum / double(map.size());
}

}  // namespace pem::golden
