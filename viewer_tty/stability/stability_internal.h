// SPDX-License-Identifier: MIT
// stability_internal.h — shared steps of the stability suite's case files (stability.h): running
// one case with its clock and exception guard, collecting failed checks, formatting numbers.
// Not a public interface: only stability*.cpp include it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "viewer_tty/stability/stability.h"

namespace pem::stability::stability {

// The failed checks of one case, in order.
class Checks {
  public:
    // Records `what` as failed unless ok; returns ok.
    bool Expect(bool ok, const std::string& what) {
        if (!ok) failed_.push_back(what);
        return ok;
    }
    bool Ok() const { return failed_.empty(); }
    std::string Failures() const;  // "a; b; c"

  private:
    std::vector<std::string> failed_;
};

// Sets c.passed and c.outcome from the checks: passed iff no check failed; the outcome is
// `summary` on success, "FAILED: <failures>" otherwise (summary appended).
void Conclude(const Checks& checks, const std::string& summary, StabilityCase* c);

using CaseBody = std::function<void(StabilityCase*)>;

// Runs one case: times it, turns any exception the body lets escape into a failed case (with the
// exception text as its outcome), and fails a case that reports an infinite residual or
// condition (NaN stays "not applicable").
StabilityCase RunCase(const std::string& name, const std::string& category,
                      const std::string& expected, const CaseBody& body);

// printf-style formatting into a std::string.
std::string Format(const char* format, ...) __attribute__((format(printf, 1, 2)));

// Checks for a one-line error message `<path>: <cause>` that contains `cause` (when non-empty).
bool IsOneLineError(const std::string& message, const std::string& path, const std::string& cause);

}  // namespace pem::stability::stability
