// SPDX-License-Identifier: MIT
// viewer_demo_main.cpp — `viewer_demo [--keys K] [--frames N] [--cols C] [--rows R]`: the terminal
// viewer (viewer_tty/tty/viewer.h) with a gradient renderer instead of pemref's, for
// tests/viewer_tmux.sh and for trying the keys by hand. The gradient's hue follows the mode, its
// position the azimuth and elevation, its brightness the distance.
// Not here: any real rendering.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "viewer_tty/tty/viewer.h"

namespace {

using namespace pem;

uint8_t Channel(double v) {
    return static_cast<uint8_t>(std::lround(std::fmin(std::fmax(v, 0.0), 1.0) * 255.0));
}

tty::ViewFrame Gradient(const tty::ViewState& s, int width, int height) {
    base::Image8 img{width, height, {}};
    img.rgba.reserve(4 * static_cast<size_t>(width) * static_cast<size_t>(height));
    const double shift = s.azimuthDeg / 360.0, lift = s.elevationDeg / 170.0;
    const double light = 1.0 / std::sqrt(s.distanceScale);
    const int hue = static_cast<int>(s.mode);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double u = std::fmod(static_cast<double>(x) / width + shift, 1.0);
            const double v = static_cast<double>(y) / height + lift;
            const double c[3] = {u, v, 1.0 - u};
            const double blue = c[(hue + 2) % 3] * (hue < 3 ? 1.0 : 0.5);
            img.rgba.push_back(Channel(light * c[hue % 3]));
            img.rgba.push_back(Channel(light * c[(hue + 1) % 3]));
            img.rgba.push_back(Channel(light * blue));
            img.rgba.push_back(255);
        }
    }
    return {img, "demo " + std::to_string(width) + "x" + std::to_string(height)};
}

}  // namespace

int main(int argc, char** argv) {
    tty::ViewerOptions options;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--keys")
            options.keys = value;
        else if (flag == "--frames")
            options.frames = std::atoi(value.c_str());
        else if (flag == "--cols")
            options.cols = std::atoi(value.c_str());
        else if (flag == "--rows")
            options.rows = std::atoi(value.c_str());
        else {
            std::fprintf(stderr, "viewer_demo: unknown option %s\n", flag.c_str());
            return 2;
        }
    }
    return tty::RunViewer(options, tty::ViewState{}, Gradient);
}
