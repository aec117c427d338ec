// SPDX-License-Identifier: MIT
// halfblock.h — truecolor half-block terminal output: each character cell shows two vertically
// stacked pixels as '▀' (U+2580) with 24-bit foreground = top pixel, background = bottom pixel.
// Conventions: the image (rows top-down, frame.h) is box-filtered to cols × 2·rows pixels in
// integer arithmetic (exact area weights, rounded half up), so the bytes are deterministic; alpha
// is ignored. A colour escape is emitted only when the colour changes within a row; every row ends
// with "\x1b[0m", rows are joined by "\n" (no trailing newline).
// Not here: palettes or 256-colour fallbacks, sixel, chafa, cursor movement.
#pragma once

#include <string>

#include "base/image8.h"

namespace pem::tty {

// The frame text, or "" when the image or the cell grid is empty.
std::string HalfBlockFrame(const base::Image8& img, int cols, int rows);

struct TermSize {
    int cols = 80;
    int rows = 24;
};

// The terminal size of stdout (else stderr) by ioctl(TIOCGWINSZ); 80 × 24 when neither is a
// terminal.
TermSize TerminalSize();

}  // namespace pem::tty
