// SPDX-License-Identifier: MIT
// model_bounds.h — a tolerance derived from the models, for an image from real hardware: the
// test drawn with every modelled profile (raster/profile.h: llvmpipe, linear rounded to 8 bits,
// exact-lod, d3d-rounding, and any profile added later), per pixel and channel the smallest
// and largest value they give, widened by n LSB. An image is accepted when every channel of
// every pixel lies inside — the CTS's "within the precision the specification allows", with
// the allowed variation measured rather than assumed.
//
//   const ModelBounds b = BoundsOf(test, /*threads=*/2);
//   const BoundsCheck c = CheckBounds(b, gpuImage, /*lsb=*/1);   // c.Accepted()
//
// Not here: exact and fuzzy comparisons (image_diff.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/image8.h"
#include "viewer_tty/golden/suite.h"

namespace pem::golden {

struct ModelBounds {
    int width = 0, height = 0;
    std::vector<uint8_t> lo, hi;        // RGBA per pixel, rows top-down
    std::vector<std::string> profiles;  // the profiles that span them

    size_t SpannedPixels() const;  // pixels where the profiles disagree (hi > lo somewhere)
    int WidestSpan() const;        // the largest hi − lo
};

struct BoundsCheck {
    size_t outsidePixels = 0;  // pixels with any channel outside [lo − n, hi + n]
    int largestExcess = 0;     // how far the worst channel lies outside, in LSB
    bool sizeMismatch = false;
    bool Accepted() const { return !sizeMismatch && outsidePixels == 0; }
};

ModelBounds BoundsOf(const GoldenTest& test, int threads);
BoundsCheck CheckBounds(const ModelBounds& bounds, const base::Image8& image, int lsb);

}  // namespace pem::golden
