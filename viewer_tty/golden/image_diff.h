// SPDX-License-Identifier: MIT
// image_diff.h — comparing two RGBA8 images as golden-image tools do: exactly, or fuzzily on two
// axes as Mozilla's reftests do (`fuzzy(maxDifference, totalPixels)`: no channel differs by more
// than maxDifference and at most totalPixels pixels differ at all), and the pictures a failure
// is shown with.
//
//   const DiffStats d = Compare(golden, rendered);
//   if (!Accepts(fuzzy, d)) WritePng("diff.png", DiffImage(golden, rendered));
//
// Conventions: a pixel differs when any of its four channels differs; images of different sizes
// differ everywhere (DiffStats::sizeMismatch).
// Not here: the perceptual measure (flip.h), the model bounds (model_bounds.h).
#pragma once

#include <cstddef>
#include <string>

#include "base/image8.h"

namespace pem::golden {

struct DiffStats {
    int maxDifference = 0;       // largest |a − b| over every channel of every pixel
    size_t differingPixels = 0;  // pixels with any channel different
    size_t pixels = 0;
    bool sizeMismatch = false;
    bool Identical() const { return !sizeMismatch && differingPixels == 0; }
};

// Both axes of a reftest's fuzzy(): maxDifference < 0 means exact.
struct Fuzzy {
    int maxDifference = -1;
    size_t pixels = 0;
    bool Exact() const { return maxDifference < 0; }
};

DiffStats Compare(const base::Image8& a, const base::Image8& b);
bool Accepts(const Fuzzy& fuzzy, const DiffStats& d);
std::string ToString(const Fuzzy& fuzzy);  // "exact" or "fuzzy(D, N)"

// Differing pixels in red (brighter for larger differences) over a dimmed grey copy of `a`.
base::Image8 DiffImage(const base::Image8& a, const base::Image8& b);
// a | b | DiffImage(a, b), separated by 4-pixel gaps (the wider height; sizes may differ),
// magnified k× (nearest, k integer) so that small images are at least 128 pixels tall.
base::Image8 SideBySide(const base::Image8& a, const base::Image8& b);

}  // namespace pem::golden
