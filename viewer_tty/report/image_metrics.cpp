// SPDX-License-Identifier: MIT
// image_metrics.cpp — CompareFloat / Compare8Bit: one channel at a time, planes of doubles, a
// separable Gaussian window (horizontal pass, then vertical pass, each cut at the border and
// renormalised) over the five SSIM moments x, y, x², y², xy.
// Conventions: every sum runs in index order (row-major, taps from −r to +r); no threads.
// Not here: the report (report_writer.h).
#include "viewer_tty/report/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

namespace pem::report {

MetricImage ToMetric(const trace::FloatImage& img) {
    MetricImage m{img.width, img.height, {}};
    m.rgb.reserve(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
    for (size_t p = 0; p < static_cast<size_t>(img.width) * static_cast<size_t>(img.height); ++p)
        for (size_t c = 0; c < 3; ++c)
            m.rgb.push_back(img.data[p * static_cast<size_t>(img.channels) + c]);
    return m;
}

namespace {

using Plane = std::vector<double>;
using Taps = std::array<double, 2 * kSsimRadius + 1>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void CheckSizes(const MetricImage& test, const MetricImage& ref, const std::vector<uint8_t>* mask) {
    const auto pixels = [](const MetricImage& m) { return size_t(m.width) * size_t(m.height); };
    if (test.width < 0 || test.height < 0 || test.width != ref.width || test.height != ref.height)
        throw std::invalid_argument("image metrics: test is " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height) + ", reference is " +
                                    std::to_string(ref.width) + "x" + std::to_string(ref.height));
    if (test.rgb.size() != 3 * pixels(test) || ref.rgb.size() != 3 * pixels(ref))
        throw std::invalid_argument("image metrics: rgb buffer size is not 3 * width * height");
    if (mask && mask->size() != pixels(test))
        throw std::invalid_argument("image metrics: mask size is not width * height");
}

// Channel c of an image as display values, or as stored 8-bit codes / 255.
Plane Channel(const MetricImage& img, int c, bool quantize) {
    Plane p(size_t(img.width) * size_t(img.height));
    for (size_t i = 0; i < p.size(); ++i) {
        const float v = img.rgb[3 * i + size_t(c)];
        p[i] = quantize ? double(Quantize8(v)) / 255.0 : DisplayValue(v);
    }
    return p;
}

// The 1D Gaussian, g[k + r] = exp(−k² / 2σ²) (unnormalised: every window divides by its own sum).
Taps GaussianTaps() {
    Taps g{};
    for (int k = -kSsimRadius; k <= kSsimRadius; ++k)
        g[size_t(k + kSsimRadius)] = std::exp(-double(k * k) / (2.0 * kSsimSigma * kSsimSigma));
    return g;
}

// One pass of the window along x (stride 1, count w) or y (stride w, count h): each output is the
// weighted mean of the taps that fall inside the image.
Plane BlurPass(const Plane& in, int w, int h, bool alongX) {
    static const Taps g = GaussianTaps();
    Plane out(in.size());
    const int n = alongX ? w : h;
    const ptrdiff_t stride = alongX ? 1 : w;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int at = alongX ? x : y;
            const int lo = std::max(-kSsimRadius, -at), hi = std::min(kSsimRadius, n - 1 - at);
            const ptrdiff_t centre = ptrdiff_t(y) * w + x;
            double sum = 0, weight = 0;
            for (int k = lo; k <= hi; ++k) {
                sum += g[size_t(k + kSsimRadius)] * in[size_t(centre + k * stride)];
                weight += g[size_t(k + kSsimRadius)];
            }
            out[size_t(centre)] = sum / weight;
        }
    }
    return out;
}

Plane Blur(const Plane& in, int w, int h) {
    return BlurPass(BlurPass(in, w, h, true), w, h, false);
}

Plane Product(const Plane& a, const Plane& b) {
    Plane p(a.size());
    for (size_t i = 0; i < p.size(); ++i) p[i] = a[i] * b[i];
    return p;
}

bool Selected(const std::vector<uint8_t>* mask, size_t i) {
    return !mask || (*mask)[i] != 0;
}

// Sum of the SSIM map of one channel over the selected window centres.
double SsimSum(const Plane& x, const Plane& y, int w, int h, const std::vector<uint8_t>* mask) {
    // Step 1: local means, variances and covariance through the Gaussian window.
    const Plane mx = Blur(x, w, h), my = Blur(y, w, h);
    const Plane exx = Blur(Product(x, x), w, h), eyy = Blur(Product(y, y), w, h);
    const Plane exy = Blur(Product(x, y), w, h);
    // Step 2: the SSIM formula per centre, summed in index order.
    double sum = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        if (!Selected(mask, i)) continue;
        const double sxx = exx[i] - mx[i] * mx[i], syy = eyy[i] - my[i] * my[i];
        const double sxy = exy[i] - mx[i] * my[i];
        const double num = (2 * mx[i] * my[i] + kSsimC1) * (2 * sxy + kSsimC2);
        const double den = (mx[i] * mx[i] + my[i] * my[i] + kSsimC1) * (sxx + syy + kSsimC2);
        sum += num / den;
    }
    return sum;
}

ImageScores Compare(const MetricImage& test, const MetricImage& ref,
                    const std::vector<uint8_t>* mask, bool quantize) {
    // Step 1: validate and count the selected pixels.
    CheckSizes(test, ref, mask);
    const int w = test.width, h = test.height;
    ImageScores s;
    s.pixels =
        mask ? size_t(std::count_if(mask->begin(), mask->end(), [](uint8_t m) { return m != 0; }))
             : size_t(w) * size_t(h);
    if (s.pixels == 0) return {kNaN, kNaN, kNaN, 0};
    // Step 2: per channel, squared error and SSIM sums.
    double squaredError = 0, ssimSum = 0;
    for (int c = 0; c < 3; ++c) {
        const Plane x = Channel(test, c, quantize), y = Channel(ref, c, quantize);
        for (size_t i = 0; i < x.size(); ++i)
            if (Selected(mask, i)) squaredError += (x[i] - y[i]) * (x[i] - y[i]);
        ssimSum += SsimSum(x, y, w, h, mask) / double(s.pixels);
    }
    // Step 3: the scores.
    s.rmse = std::sqrt(squaredError / (3.0 * double(s.pixels)));
    s.psnr = s.rmse > 0 ? std::min(kMaxPsnr, 20.0 * std::log10(1.0 / s.rmse)) : kMaxPsnr;
    s.ssim = ssimSum / 3.0;
    return s;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const ImageScores& scores) {
    return os << "{rmse " << scores.rmse << ", psnr " << scores.psnr << " dB, ssim " << scores.ssim
              << ", pixels " << scores.pixels << "}";
}

double DisplayValue(float v) {
    return std::isnan(v) ? 0.0 : std::clamp(double(v), 0.0, 1.0);
}

uint8_t Quantize8(float v) {
    return uint8_t(std::nearbyint(DisplayValue(v) * 255.0));
}

ImageScores CompareFloat(const MetricImage& test, const MetricImage& ref,
                         const std::vector<uint8_t>* mask) {
    return Compare(test, ref, mask, false);
}

ImageScores Compare8Bit(const MetricImage& test, const MetricImage& ref,
                        const std::vector<uint8_t>* mask) {
    return Compare(test, ref, mask, true);
}

}  // namespace pem::report
