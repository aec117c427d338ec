// SPDX-License-Identifier: MIT
// model_bounds.cpp — the range the modelled profiles span (model_bounds.h).
#include "viewer_tty/golden/model_bounds.h"

#include <algorithm>

#include "raster/profile.h"
#include "viewer_tty/golden/golden_render.h"

namespace pem::golden {

ModelBounds BoundsOf(const GoldenTest& test, int threads) {
    ModelBounds b;
    for (const raster::ProfileInfo& p : raster::Profiles()) {
        const base::Image8 img = RenderTest(test, p.name, threads).image;
        if (b.profiles.empty()) {
            b.width = img.width, b.height = img.height;
            b.lo = b.hi = img.rgba;
        } else {
            for (size_t k = 0; k < img.rgba.size(); ++k) {
                b.lo[k] = std::min(b.lo[k], img.rgba[k]);
                b.hi[k] = std::max(b.hi[k], img.rgba[k]);
            }
        }
        b.profiles.push_back(p.name);
    }
    return b;
}

size_t ModelBounds::SpannedPixels() const {
    size_t n = 0;
    for (size_t p = 0; p + 3 < lo.size(); p += 4) n += !std::equal(&lo[p], &lo[p] + 4, &hi[p]);
    return n;
}

int ModelBounds::WidestSpan() const {
    int w = 0;
    for (size_t k = 0; k < lo.size(); ++k) w = std::max(w, int(hi[k]) - int(lo[k]));
    return w;
}

BoundsCheck CheckBounds(const ModelBounds& b, const base::Image8& image, int lsb) {
    BoundsCheck c;
    if (image.width != b.width || image.height != b.height) {
        c.sizeMismatch = true;
        return c;
    }
    for (size_t p = 0; p < size_t(b.width) * size_t(b.height); ++p) {
        int excess = 0;
        for (size_t k = 4 * p; k < 4 * p + 4; ++k)
            excess = std::max({excess, int(b.lo[k]) - lsb - int(image.rgba[k]),
                               int(image.rgba[k]) - int(b.hi[k]) - lsb});
        c.outsidePixels += excess > 0;
        c.largestExcess = std::max(c.largestExcess, excess);
    }
    return c;
}

}  // namespace pem::golden
