// SPDX-License-Identifier: MIT
// progress.h — a one-line progress indicator for long work: "\r<label> 42% ETA 0:12" (then
// "\x1b[K" to clear what a longer previous line left), written only when the stream is a terminal
// and not quiet, at most every 100 ms; Finish() (or the destructor) ends the line with "\n".
// Conventions: fraction in [0, 1] (clamped); ETA = elapsed · (1 − f) / f, shown as m:ss.
// Not here: bars, multiple lines, thread safety (call from one thread).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>

namespace pem::tty {

// The text of one update; etaSeconds < 0 shows "ETA -:--".
std::string ProgressText(std::string_view label, double fraction, double etaSeconds);

class ProgressLine {
  public:
    explicit ProgressLine(std::string label, bool quiet = false, std::FILE* out = stderr);
    ~ProgressLine();
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    void Update(double fraction);
    void Finish();
    bool Enabled() const { return enabled_; }

  private:
    using Clock = std::chrono::steady_clock;
    void Print(double fraction);

    std::string label_;
    std::FILE* out_;
    bool enabled_;
    bool printed_ = false, finished_ = false;
    double last_ = 0.0;
    Clock::time_point start_, lastPrint_;
};

}  // namespace pem::tty
