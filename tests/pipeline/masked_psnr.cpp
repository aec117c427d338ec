// SPDX-License-Identifier: MIT
// masked_psnr FRAME.exr REFERENCE.exr MASK.exr — the outside check of the fidelity tests: PSNR
// of the two frames as their 8-bit sRGB PNGs show them, over the pixels whose MASK alpha > 0.5
// (a lens group's b_R.exr, a layer's coverage). Prints "<dB> <pixels>"; exit 2 on bad input.
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "base/display_image.h"
#include "trace/image.h"

int main(int argc, char** argv) {
    using namespace pem;
    if (argc != 4) {
        std::fprintf(stderr, "usage: masked_psnr FRAME.exr REFERENCE.exr MASK.exr\n");
        return 2;
    }
    try {
        const trace::FloatImage a = trace::ReadExr(argv[1]), b = trace::ReadExr(argv[2]),
                                m = trace::ReadExr(argv[3]);
        if (a.width != b.width || a.height != b.height || a.width != m.width ||
            a.height != m.height)
            throw std::runtime_error("sizes differ");
        const base::Image8 da = base::ToDisplayImage(a.data, a.width, a.height, a.channels, 1.0f);
        const base::Image8 db = base::ToDisplayImage(b.data, b.width, b.height, b.channels, 1.0f);
        double se = 0.0;
        long n = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                if (!(m.At(x, y)[3] > 0.5f)) continue;
                const size_t p = 4 * (static_cast<size_t>(y) * static_cast<size_t>(a.width) +
                                      static_cast<size_t>(x));
                for (size_t c = 0; c < 3; ++c) {
                    const double d = (da.rgba[p + c] - db.rgba[p + c]) / 255.0;
                    se += d * d;
                }
                ++n;
            }
        const double psnr = se > 0.0 ? 10.0 * std::log10(3.0 * static_cast<double>(n) / se) : 100.0;
        std::printf("%.2f %ld\n", psnr, n);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "masked_psnr: %s\n", e.what());
        return 2;
    }
    return 0;
}
