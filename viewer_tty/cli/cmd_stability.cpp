// SPDX-License-Identifier: MIT
// cmd_stability.cpp — argument parsing, the table and the JSON report of `pemref stability`
// (cmd_stability.h). The suite itself is viewer_tty/stability/stability.h.
#include "viewer_tty/cli/cmd_stability.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "base/atomic_file.h"
#include "viewer_tty/stability/stability.h"

namespace pem::cli {

namespace {

using nlohmann::json;

struct StabilityArgs {
    std::string json, data;
    int threads = 1;
    bool verbose = false;
};

StabilityArgs& Args() {
    static StabilityArgs args;
    return args;
}

// NaN ("not applicable") as JSON null.
json Number(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

json CaseJson(const stability::StabilityCase& c) {
    return {{"name", c.name},
            {"category", c.category},
            {"expected", c.expected},
            {"outcome", c.outcome},
            {"passed", c.passed},
            {"residual", Number(c.residual)},
            {"condition", Number(c.condition)},
            {"seconds", c.seconds},
            {"detail", c.detail}};
}

// A figure for the table: "-" when not applicable (NaN).
std::string Figure(double v) {
    if (std::isnan(v)) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

void PrintRow(const stability::StabilityCase& c, bool verbose) {
    std::printf("%-52s %-7s %-4s %10s %10s %7.3f  %s\n", c.name.c_str(), c.category.c_str(),
                c.passed ? "PASS" : "FAIL", Figure(c.residual).c_str(), Figure(c.condition).c_str(),
                c.seconds, c.outcome.c_str());
    if (verbose)
        std::printf("    expected: %s\n    detail:   %s\n", c.expected.c_str(), c.detail.c_str());
}

}  // namespace

void AddStabilityCommand(CLI::App& app) {
    StabilityArgs& a = Args();
    CLI::App* sub = app.add_subcommand(
        "stability", "numerical stability suite: stiff systems and extreme inputs, one row each");
    sub->add_option("--json", a.json, "write every case as JSON to this file");
    sub->add_option("--data", a.data, "the repository's tests/data (for bad_scenes)");
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_flag("--verbose", a.verbose, "print each case's expected outcome and detail");
}

int RunStabilityCommand() {
    const StabilityArgs& a = Args();
    stability::StabilityOptions options;
    options.dataDir = a.data;
    options.threads = a.threads;
    const std::vector<stability::StabilityCase> cases = stability::RunStabilitySuite(options);
    std::printf("%-52s %-7s %-4s %10s %10s %7s  %s\n", "case", "kind", "", "residual", "condition",
                "seconds", "outcome");
    int failed = 0;
    double seconds = 0.0;
    json all = json::array();
    for (const stability::StabilityCase& c : cases) {
        PrintRow(c, a.verbose);
        failed += !c.passed;
        seconds += c.seconds;
        all.push_back(CaseJson(c));
    }
    std::printf("%zu cases, %d failed, %.2f s%s\n", cases.size(), failed, seconds,
                a.data.empty() ? " (no --data: tests/data/bad_scenes not read)" : "");
    if (!a.json.empty())
        base::WriteTextAtomic(
            a.json, json{{"cases", all}, {"failed", failed}, {"seconds", seconds}}.dump(2) + "\n");
    return failed == 0 ? 0 : 1;
}

}  // namespace pem::cli
