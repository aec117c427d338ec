// SPDX-License-Identifier: MIT
// display_target.h — what float maps are fitted to: the traced radiance as the display shows it.
//
// A traced pixel brighter than white in a channel (P > 1: a light source's highlight, seen with
// radiance of thousands) is shown white, however bright. Fitted as traced, those few subpixels
// outweigh the rest of the fit (maps running to ±7000); clamped at white, the highlight is lost
// (a reflection with F = 0.04 needs 25 times white to show white). ClipToDisplay keeps exactly
// what the display shows:
//  1. every row set (one layer and term) of a pixel with P > 1 gives up the same fraction 1 − 1/P
//     of its light there, taken off its brightest subpixels (WaterLevel): the pixel stays white;
//  2. no subpixel stays brighter than what alone makes its pixel white seen through its term's
//     F·G (K² / (F·G · scale) in map units): brighter is invisible (light hidden behind a front
//     layer, a pixel the rest of which is dark);
//  3. the rest is kept as traced, above 1 where it is (a highlight that does not saturate).
// 8-bit maps clamp their targets into [0, 1] instead (infer_job.cpp: all they can reach).
//
// Not here: reading the images (trace_manifest.h), the rows' weights (infer_job.cpp).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "trace/image.h"

namespace pem::pipeline {

// The level c ≥ 0 at which Σ w·max(0, v − c) = remove, for (v, w) pairs with v, w ≥ 0 and
// 0 ≤ remove ≤ Σ w·v: the brightest values lowered to one level, the others kept.
double WaterLevel(std::vector<std::pair<double, double>> valueWeight, double remove);

// The images of one row set at its viewpoint: `coverage` the K× samples (alpha = the group's
// coverage, the rows' weight), `frame` the traced two-term frame (W × H, what the display shows
// clamped at 1), `fresnel` the row set's F·G (W × H, RGBA premultiplied: alpha = the share of
// samples with the term).
struct DisplayImages {
    const trace::FloatImage* coverage = nullptr;
    const trace::FloatImage* frame = nullptr;
    const trace::FloatImage* fresnel = nullptr;
};

// Targets `b` (4 per entry of `cells`: RGBA, RGB in map units = radiance / scale, nonnegative)
// of the K× subpixels `cells` (row-major indices) clipped to what the display shows (1–3 above;
// alpha untouched).
void ClipToDisplay(const DisplayImages& images, const std::vector<uint32_t>& cells, int k,
                   double scale, std::vector<double>* b);

}  // namespace pem::pipeline
