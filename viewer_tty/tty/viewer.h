// SPDX-License-Identifier: MIT
// viewer.h — the interactive terminal viewer of `pemref view`: a view state changed by keys, a
// render callback that turns the state into an image, and a loop that prints the image as
// truecolor half blocks (halfblock.h) with a status line. The renderer is plugged in by the caller.
//
//   tty::ViewerOptions options;                        // keys/frames empty: interactive
//   int rc = tty::RunViewer(options, tty::ViewState{}, [&](const tty::ViewState& s, int w, int h) {
//       return tty::ViewFrame{RenderMyView(s, w, h), "nearest 3,4  err 2.1"};
//   });
//
// Keys: ←/→ or h/l azimuth ∓5°; ↑/↓ or k/j elevation ±5° (clamped to ±85°); + or = zoom in
// (distance ×0.9), - or _ zoom out (÷0.9), distance in [0.2, 10]; u/d move off the sample circle
// (height offset ±5°, clamped to ±85°); 1..5 pick a mode, m cycles modes; [ and ] change the
// tessellation threshold t by ∓1 in [1, 64]; r resets the pose and t (not the mode) to the
// initial state; q, Esc or Ctrl-C quit.
// Conventions: a screen of cols × rows cells shows the image in cols × (rows − 1) cells, i.e. the
// renderer is asked for cols × 2·(rows − 1) pixels, and the status line in the last row.
// Not here: rendering, command-line parsing, mouse input, colour fallbacks for old terminals.
#pragma once

#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "base/image8.h"

namespace pem::tty {

// View state ---------------------------------------------------------------------------------

enum class ViewMode { Hybrid, Pem, StaticEm, RayTraced, Difference };  // keys 1..5
inline constexpr int kNumViewModes = 5;
const char* ToString(ViewMode mode);

struct ViewState {
    double azimuthDeg = 0.0;       // around the object, in [0, 360)
    double elevationDeg = 0.0;     // above the sample circle's plane, in [-85, 85]
    double distanceScale = 1.0;    // × the sample circle's radius, in [0.2, 10]
    double heightOffsetDeg = 0.0;  // off the sample circle, in [-85, 85]
    ViewMode mode = ViewMode::Hybrid;
    double t = 5.0;  // tessellation threshold (subpixels), in [1, 64]
    bool quit = false;
    bool operator==(const ViewState&) const = default;
};
std::string ToString(const ViewState& state);
std::ostream& operator<<(std::ostream& os, const ViewState& state);

// Keys ---------------------------------------------------------------------------------------

// Key codes: a byte is its own code (0..255); the arrows are above the byte range.
inline constexpr int kKeyCtrlC = 3, kKeyEscape = 27;
inline constexpr int kKeyUp = 256, kKeyDown = 257, kKeyRight = 258, kKeyLeft = 259;

// Applies one key; returns true if the state changed. `home` is what 'r' returns to.
bool ApplyKey(ViewState* state, int key, const ViewState& home = ViewState{});

// Turns terminal bytes into key codes. Arrows arrive as ESC [ A..D (or ESC O A..D, and with
// modifiers ESC [ 1 ; 5 A); other escape sequences are dropped. A lone ESC stays pending until
// more bytes or Flush() (the caller decides when no more bytes are coming, e.g. after 30 ms).
class KeyDecoder {
  public:
    std::vector<int> Feed(std::string_view bytes);
    std::vector<int> Flush();
    bool Pending() const { return state_ != State::Ground; }

  private:
    enum class State { Ground, Escape, Csi, Ss3 };
    void Step(unsigned char byte, std::vector<int>* keys);
    State state_ = State::Ground;
    int csiLength_ = 0;
};

// Feed(bytes) then Flush(): every key of a complete byte string.
std::vector<int> DecodeKeys(std::string_view bytes);

// The loop ----------------------------------------------------------------------------------

struct ViewFrame {
    base::Image8 image;  // any size; box-filtered to the screen
    std::string info;    // the renderer's part of the status line (samples used, error, ...)
};
using RenderViewFn = std::function<ViewFrame(const ViewState&, int widthPx, int heightPx)>;

struct ViewerOptions {
    std::string keys;  // scripted: apply these keys (DecodeKeys), one frame each; no terminal
    int frames = 0;    // scripted: exactly this many frames (the last state repeats); 0: 1 + keys
    int cols = 0, rows = 0;  // screen size in cells; 0: the terminal's, or 80 × 24 when scripted
    bool quiet = false;      // scripted: print only the separator and status lines, no image
};

// The status line: mode, pose, t, FPS (omitted when fps < 0) and the renderer's info, with control
// characters replaced by spaces, cut to at most maxColumns characters (code points).
std::string StatusLine(const ViewState& state, double fps, std::string_view info, int maxColumns);

// Runs the viewer and returns the exit code. Scripted (keys non-empty or frames > 0): never reads
// stdin; frame N (N = 0 before any key, N = k after the k-th key) is printed as a line
// "--- frame N ---", rows − 1 lines of half blocks and the status line without FPS, so the output
// is deterministic; returns 0 (a quit key ends the frames early). Interactive: raw mode on
// /dev/tty, alternate screen, redraws when the state or the terminal size changes; returns 0 on
// quit. Neither (out or /dev/tty not a terminal): prints an error line to stderr and returns 2.
// Exceptions from `render` propagate after the terminal is restored.
int RunViewer(const ViewerOptions& options, ViewState initial, const RenderViewFn& render,
              std::FILE* out = stdout);

}  // namespace pem::tty
