// SPDX-License-Identifier: MIT
// progress.cpp — ProgressLine: TTY check at construction, rate-limited "\r" rewrites.
#include "viewer_tty/tty/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace pem::tty {

namespace {

constexpr std::chrono::milliseconds kInterval{100};

std::string FormatClock(double seconds) {
    if (!(seconds >= 0.0) || seconds > 359999.0) return "-:--";
    const long s = std::lround(seconds);
    const long sec = s % 60;
    return std::to_string(s / 60) + ":" + (sec < 10 ? "0" : "") + std::to_string(sec);
}

}  // namespace

std::string ProgressText(std::string_view label, double fraction, double etaSeconds) {
    const int percent = static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0));
    // Appended piecewise: GCC 12 flags `"\r" + std::string(...)` with a false -Wrestrict.
    std::string text = "\r";
    text.append(label);
    text.append(" ").append(std::to_string(percent)).append("% ETA ");
    text.append(FormatClock(etaSeconds)).append("\x1b[K");
    return text;
}

ProgressLine::ProgressLine(std::string label, bool quiet, std::FILE* out)
    : label_(std::move(label)),
      out_(out),
      enabled_(!quiet && out != nullptr && isatty(fileno(out)) == 1),
      start_(Clock::now()) {}

ProgressLine::~ProgressLine() {
    Finish();
}

void ProgressLine::Update(double fraction) {
    if (!enabled_ || finished_) return;
    last_ = std::clamp(fraction, 0.0, 1.0);
    if (printed_ && Clock::now() - lastPrint_ < kInterval) return;
    Print(last_);
}

void ProgressLine::Finish() {
    if (finished_) return;
    finished_ = true;
    if (!printed_) return;
    Print(last_);
    std::fputc('\n', out_);
    std::fflush(out_);
}

void ProgressLine::Print(double fraction) {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
    std::fputs(ProgressText(label_, fraction, eta).c_str(), out_);
    std::fflush(out_);
    printed_ = true;
    lastPrint_ = now;
}

}  // namespace pem::tty
