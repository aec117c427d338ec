// SPDX-License-Identifier: MIT
// halfblock.cpp — integer box filter, then one '▀' per cell with run-length colour escapes.
// The filter works on a common grid: along an axis with `in` source and `out` target pixels,
// source pixel i covers [i·out, (i+1)·out) and target pixel o covers [o·in, (o+1)·in); the weight
// is the overlap length, so every target pixel's weights sum to `in` on that axis.
#include "viewer_tty/tty/halfblock.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

namespace pem::tty {

namespace {

struct Rgb {
    uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

struct Tap {
    int index = 0;
    uint64_t weight = 0;
};

// For each target pixel along one axis, the source pixels it overlaps and their weights.
std::vector<std::vector<Tap>> BoxTaps(int in, int out) {
    std::vector<std::vector<Tap>> taps(static_cast<size_t>(out));
    for (int o = 0; o < out; ++o) {
        const int64_t lo = int64_t{o} * in, hi = lo + in;
        for (int i = static_cast<int>(lo / out); i < in && int64_t{i} * out < hi; ++i) {
            const int64_t overlap =
                std::min(hi, int64_t{i + 1} * out) - std::max(lo, int64_t{i} * out);
            if (overlap > 0)
                taps[static_cast<size_t>(o)].push_back({i, static_cast<uint64_t>(overlap)});
        }
    }
    return taps;
}

// The image box-filtered to width × height RGB pixels, rows top-down.
std::vector<Rgb> Resample(const base::Image8& img, int width, int height) {
    const auto xTaps = BoxTaps(img.width, width);
    const auto yTaps = BoxTaps(img.height, height);
    const uint64_t total = static_cast<uint64_t>(img.width) * static_cast<uint64_t>(img.height);
    std::vector<Rgb> out;
    out.reserve(static_cast<size_t>(width) * static_cast<size_t>(height));
    for (const auto& ys : yTaps) {
        for (const auto& xs : xTaps) {
            uint64_t sum[3] = {0, 0, 0};
            for (const Tap& ty : ys) {
                for (const Tap& tx : xs) {
                    const size_t at =
                        4 * (static_cast<size_t>(ty.index) * static_cast<size_t>(img.width) +
                             static_cast<size_t>(tx.index));
                    for (size_t c = 0; c < 3; ++c)
                        sum[c] += ty.weight * tx.weight * img.rgba[at + c];
                }
            }
            const auto avg = [&](size_t c) {
                return static_cast<uint8_t>((sum[c] + total / 2) / total);
            };
            out.push_back({avg(0), avg(1), avg(2)});
        }
    }
    return out;
}

// Decimal digits of 0 <= v <= 999 at p; returns the end.
char* PutDecimal(char* p, int v) {
    if (v >= 100) *p++ = static_cast<char>('0' + v / 100);
    if (v >= 10) *p++ = static_cast<char>('0' + v / 10 % 10);
    *p++ = static_cast<char>('0' + v % 10);
    return p;
}

// ESC [ layer ; 2 ; r ; g ; b m, formatted in place (no temporaries: a frame has thousands).
void AppendColour(std::string* out, int layer, const Rgb& c) {
    char buf[32];
    char* p = buf;
    *p++ = '\x1b';
    *p++ = '[';
    p = PutDecimal(p, layer);
    *p++ = ';';
    *p++ = '2';
    for (const uint8_t v : {c.r, c.g, c.b}) {
        *p++ = ';';
        p = PutDecimal(p, v);
    }
    *p++ = 'm';
    out->append(buf, p);
}

}  // namespace

std::string HalfBlockFrame(const base::Image8& img, int cols, int rows) {
    if (cols <= 0 || rows <= 0 || img.width <= 0 || img.height <= 0) return "";
    // Step 1: two pixels per cell vertically.
    const std::vector<Rgb> px = Resample(img, cols, 2 * rows);
    const auto at = [&](int x, int y) {
        return px[static_cast<size_t>(y) * static_cast<size_t>(cols) + static_cast<size_t>(x)];
    };
    // Step 2: one '▀' per cell; an escape only where the colour changes along the row.
    std::string out;
    out.reserve(static_cast<size_t>(cols) * static_cast<size_t>(rows) * 24);
    for (int row = 0; row < rows; ++row) {
        if (row > 0) out += '\n';
        std::optional<Rgb> fg, bg;
        for (int col = 0; col < cols; ++col) {
            const Rgb top = at(col, 2 * row), bottom = at(col, 2 * row + 1);
            if (fg != top) AppendColour(&out, 38, top);
            if (bg != bottom) AppendColour(&out, 48, bottom);
            fg = top;
            bg = bottom;
            out += "\xe2\x96\x80";  // U+2580 UPPER HALF BLOCK
        }
        out += "\x1b[0m";
    }
    return out;
}

TermSize TerminalSize() {
    for (int fd : {STDOUT_FILENO, STDERR_FILENO}) {
        winsize ws{};
        if (ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
            return {ws.ws_col, ws.ws_row};
        }
    }
    return {};
}

}  // namespace pem::tty
