// SPDX-License-Identifier: MIT
// flip.h — the perceptual difference of two 8-bit sRGB images by LDR-ꟻLIP (Andersson et al.,
// "FLIP: A Difference Evaluator for Alternating Images", HPG 2020), implemented from the paper:
// colour — both images in YCxCz, filtered by the contrast sensitivity functions of the three
// channels for the viewing condition (pixels per degree), back to linear RGB clamped, CIELab
// with the Hunt adjustment, the HyAB distance raised to qc = 0.7 and remapped by pc = 0.4,
// pt = 0.95; features — edges and points of the achromatic channel by first and second
// derivatives of a Gaussian (0.082° wide), their larger difference over √2 raised to qf = 0.5;
// per pixel ΔE = ΔEc^(1 − ΔEf), in [0, 1].
//
//   const double mean = FlipMean(golden, rendered);   // 0: identical to the eye
//
// Printed for information by `pemref golden`; never a pass/fail criterion. Not validated
// against NVIDIA's reference implementation (not available here): the tests check its
// properties (0 for equal images, near 1 (0.87) where a white pixel meets a black field,
// 0.95–1 for black against white everywhere, growing with the difference).
// Not here: the exact and fuzzy comparisons (image_diff.h).
#pragma once

#include <vector>

#include "base/image8.h"

namespace pem::golden {

// 67 pixels per degree: a 0.7 m wide 3840-pixel monitor seen from 0.7 m (the paper's default).
inline constexpr double kFlipPixelsPerDegree = 67.0;

// Per pixel ΔE (rows top-down), images of equal size (alpha ignored).
std::vector<float> FlipMap(const base::Image8& reference, const base::Image8& test,
                           double pixelsPerDegree = kFlipPixelsPerDegree);

// The mean of FlipMap.
double FlipMean(const base::Image8& reference, const base::Image8& test,
                double pixelsPerDegree = kFlipPixelsPerDegree);

}  // namespace pem::golden
