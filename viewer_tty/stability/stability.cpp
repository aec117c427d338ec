// SPDX-License-Identifier: MIT
// stability.cpp — the suite's runner: one case with its clock and exception guard, and the
// families in order (stability.h). The cases themselves are in stability_{solver,geometry,
// raster,scene}.cpp.
#include "viewer_tty/stability/stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <exception>

#include "viewer_tty/stability/stability_internal.h"

namespace pem::stability {
namespace stability {

std::string Checks::Failures() const {
    std::string out;
    for (const std::string& f : failed_) out += (out.empty() ? "" : "; ") + f;
    return out;
}

void Conclude(const Checks& checks, const std::string& summary, StabilityCase* c) {
    c->passed = checks.Ok();
    c->outcome = c->passed ? summary : "FAILED: " + checks.Failures() + " (" + summary + ")";
}

std::string Format(const char* format, ...) {
    va_list args, copy;
    va_start(args, format);
    va_copy(copy, args);
    const int n = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    std::string out(static_cast<size_t>(std::max(n, 0)) + 1, '\0');
    std::vsnprintf(out.data(), out.size(), format, args);
    va_end(args);
    out.pop_back();
    return out;
}

bool IsOneLineError(const std::string& message, const std::string& path, const std::string& cause) {
    return message.rfind(path + ": ", 0) == 0 && message.size() > path.size() + 2 &&
           message.find('\n') == std::string::npos && message.find(cause) != std::string::npos;
}

StabilityCase RunCase(const std::string& name, const std::string& category,
                      const std::string& expected, const CaseBody& body) {
    StabilityCase c;
    c.name = name;
    c.category = category;
    c.expected = expected;
    const auto start = std::chrono::steady_clock::now();
    try {
        body(&c);
    } catch (const std::exception& e) {
        c.passed = false;
        c.outcome = std::string("FAILED: unexpected exception: ") + e.what();
    } catch (...) {
        c.passed = false;
        c.outcome = "FAILED: unexpected non-standard exception";
    }
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // NaN means "not applicable"; an infinite figure is a failure to stay bounded.
    if (std::isinf(c.residual) || std::isinf(c.condition)) {
        c.passed = false;
        c.outcome = "FAILED: infinite residual or condition reported; " + c.outcome;
    }
    return c;
}

}  // namespace stability

std::vector<StabilityCase> RunStabilitySuite(const StabilityOptions& options) {
    std::vector<StabilityCase> all;
    for (auto family : {RunSolverStabilityCases, RunShellStabilityCases, RunRayPathStabilityCases,
                        RunRasterStabilityCases, RunSceneStabilityCases}) {
        std::vector<StabilityCase> cases = family(options);
        all.insert(all.end(), cases.begin(), cases.end());
    }
    return all;
}

}  // namespace pem::stability
