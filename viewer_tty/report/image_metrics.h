// SPDX-License-Identifier: MIT
// image_metrics.h — RMSE, PSNR and SSIM between a test image and a reference, either on the float
// values a renderer produced or on what an 8-bit framebuffer would store.
// Conventions: values are clamped to the display range [0, 1] first (NaN counts as 0); RMSE runs
// over all three channels of the selected pixels; PSNR = 20·log10(1 / RMSE) with peak 1, capped at
// 100 dB; SSIM is Wang et al. 2004 (11×11 Gaussian window, σ = 1.5, K1 = 0.01, K2 = 0.03, L = 1),
// per channel, then the mean of the three channels. Single-threaded, fixed summation order, double
// accumulators: the same inputs give the same bits.
// Borders: the SSIM window is cut at the image edge and its weights renormalised, so every pixel
// has an SSIM value (Wang's reference code crops to the "valid" region instead); a mask therefore
// selects window centres anywhere, while the window statistics always use the whole image.
// Not here: colour transforms (sRGB, tone mapping), perceptual metrics other than SSIM.
//
// Usage:
//   MetricImage test{w, h, rgb}, ref{w, h, refRgb};
//   ImageScores f = CompareFloat(test, ref);          // all pixels
//   ImageScores q = Compare8Bit(test, ref, &mask);    // mask[i] != 0 selects pixel i
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "trace/image.h"

namespace pem::report {

// A linear-radiance RGB image: rows top-down, 3 floats per pixel (rgb.size() == 3·width·height).
struct MetricImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
    bool operator==(const MetricImage&) const = default;
};

// The RGB of a frame (the first three channels).
MetricImage ToMetric(const trace::FloatImage& image);

// Scores of one comparison; with an empty selection (pixels == 0) rmse, psnr and ssim are NaN.
struct ImageScores {
    double rmse = 0, psnr = 0, ssim = 0;  // psnr in dB; ssim in [-1, 1]
    size_t pixels = 0;                    // number of pixels the scores cover
    bool operator==(const ImageScores&) const = default;
};
std::ostream& operator<<(std::ostream& os, const ImageScores& scores);

// The SSIM constants (Wang et al. 2004 with L = 1).
inline constexpr int kSsimRadius = 5;  // 11×11 window
inline constexpr double kSsimSigma = 1.5, kSsimC1 = 0.01 * 0.01, kSsimC2 = 0.03 * 0.03;
inline constexpr double kMaxPsnr = 100.0;

// Scores on the clamped float values. `mask` (optional) has width·height entries, non-zero =
// counted. Throws std::invalid_argument if the sizes of test, ref and mask disagree.
ImageScores CompareFloat(const MetricImage& test, const MetricImage& ref,
                         const std::vector<uint8_t>* mask = nullptr);

// Scores after storing both images in an 8-bit framebuffer: q = nearbyint(clamp(v, 0, 1)·255) / 255
// (default rounding mode), then as CompareFloat.
ImageScores Compare8Bit(const MetricImage& test, const MetricImage& ref,
                        const std::vector<uint8_t>* mask = nullptr);

// The display value of one channel, and its 8-bit code (exposed for tests and the report).
double DisplayValue(float v);
uint8_t Quantize8(float v);

}  // namespace pem::report
