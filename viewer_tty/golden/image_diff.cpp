// SPDX-License-Identifier: MIT
// image_diff.cpp — exact and fuzzy comparison, diff pictures (image_diff.h).
#include "viewer_tty/golden/image_diff.h"

#include <algorithm>
#include <cstdlib>

namespace pem::golden {
namespace {

// The largest channel difference of pixel p (images of equal size).
int PixelDifference(const base::Image8& a, const base::Image8& b, size_t p) {
    int d = 0;
    for (size_t c = 0; c < 4; ++c)
        d = std::max(d, std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c])));
    return d;
}

// src magnified k times (nearest) into dst at column x0.
void Paste(const base::Image8& src, int k, int x0, base::Image8* dst) {
    for (int y = 0; y < src.height * k; ++y)
        for (int x = 0; x < src.width * k; ++x)
            std::copy_n(&src.rgba[(size_t(y / k) * size_t(src.width) + size_t(x / k)) * 4], 4,
                        &dst->rgba[(size_t(y) * size_t(dst->width) + size_t(x0 + x)) * 4]);
}

}  // namespace

DiffStats Compare(const base::Image8& a, const base::Image8& b) {
    DiffStats d;
    d.pixels = size_t(a.width) * size_t(a.height);
    if (a.width != b.width || a.height != b.height) {
        d.sizeMismatch = true;
        d.differingPixels = std::max(d.pixels, size_t(b.width) * size_t(b.height));
        d.maxDifference = 255;
        return d;
    }
    for (size_t p = 0; p < d.pixels; ++p) {
        const int diff = PixelDifference(a, b, p);
        d.maxDifference = std::max(d.maxDifference, diff);
        d.differingPixels += diff > 0;
    }
    return d;
}

bool Accepts(const Fuzzy& fuzzy, const DiffStats& d) {
    if (d.sizeMismatch) return false;
    if (fuzzy.Exact()) return d.differingPixels == 0;
    return d.maxDifference <= fuzzy.maxDifference && d.differingPixels <= fuzzy.pixels;
}

std::string ToString(const Fuzzy& fuzzy) {
    return fuzzy.Exact() ? "exact"
                         : "fuzzy(" + std::to_string(fuzzy.maxDifference) + ", " +
                               std::to_string(fuzzy.pixels) + ")";
}

base::Image8 DiffImage(const base::Image8& a, const base::Image8& b) {
    base::Image8 out{a.width, a.height, std::vector<uint8_t>(a.rgba.size(), 255)};
    const bool same = a.width == b.width && a.height == b.height;
    for (size_t p = 0; p < size_t(a.width) * size_t(a.height); ++p) {
        const int diff = same ? PixelDifference(a, b, p) : 255;
        if (diff > 0) {
            out.rgba[4 * p] = uint8_t(std::min(255, 160 + diff));
            out.rgba[4 * p + 1] = out.rgba[4 * p + 2] = 0;
        } else {
            const int grey = (a.rgba[4 * p] * 3 + a.rgba[4 * p + 1] * 6 + a.rgba[4 * p + 2]) / 10;
            out.rgba[4 * p] = out.rgba[4 * p + 1] = out.rgba[4 * p + 2] = uint8_t(64 + grey / 4);
        }
    }
    return out;
}

base::Image8 SideBySide(const base::Image8& a, const base::Image8& b) {
    constexpr int kGap = 4, kMinHeight = 128;
    const base::Image8 diff = DiffImage(a, b);
    const int k = std::max(1, kMinHeight / std::max({1, a.height, b.height}));
    base::Image8 out;
    out.width = k * (a.width + b.width + diff.width) + 2 * kGap;
    out.height = k * std::max(a.height, b.height);
    out.rgba.assign(size_t(out.width) * size_t(out.height) * 4, 255);
    Paste(a, k, 0, &out);
    Paste(b, k, k * a.width + kGap, &out);
    Paste(diff, k, k * (a.width + b.width) + 2 * kGap, &out);
    return out;
}

}  // namespace pem::golden
