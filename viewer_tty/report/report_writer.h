// SPDX-License-Identifier: MIT
// report_writer.h — turns the numbers of `pemref report` (timings, ray counts, image scores,
// left-out decisions, stability cases) into report.md, report.svg and report.json in one folder.
// Conventions: methods keep the order of their first appearance in `results`; within a method,
// settings sort in natural order ("t=3" < "t=10", "1 spp" < "9 spp"). NaN / infinite numbers are
// written as "n/a" (markdown), skipped (SVG) or null (JSON). The plot is RMSE (float) against run
// time in seconds, both axes log10, one panel per position. All three files appear atomically:
// each is written to `<file>.tmp.<pid>`, and only when all three are complete are they renamed.
// Not here: computing the numbers (image_metrics.h and the report command), HTML, PNG plots.
//
// Usage:
//   ReportData data;
//   data.scene = "a";  data.results.push_back({"layered PEM", "t=3", "on circle", 0.8, 0, f, q});
//   WriteReport(data, "out/report");   // out/report/report.{md,svg,json}; throws
//   pem::base::InputError
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "base/input_error.h"
#include "viewer_tty/report/image_metrics.h"

namespace pem::report {

// One timed run of one method at one camera position.
struct MethodResult {
    std::string method;    // e.g. "static EM", "single-layer PEM", "layered PEM", "ray tracer"
    std::string setting;   // e.g. "t=3", "9 spp", or ""
    std::string position;  // e.g. "on circle", "between samples", "10° above"
    double seconds = 0;    // wall-clock run time
    uint64_t rays = 0;     // rays traced (0 for pure rasterization)
    ImageScores floatScores, scores8;  // against the reference: float values, 8-bit framebuffer
};

// The setting of a hybrid row drawn with tessellation t ("t=1", "t=2.5").
std::string TessSetting(double t);

// A piece of work the pipeline decided to skip, and what that saved.
struct LeftOutRow {
    std::string group, decision, reason;
    double secondsSaved = 0;
};

// One numerical-stability case (e.g. an ill-conditioned solve) and its outcome.
struct StabilityRow {
    std::string name, category, expected, outcome;
    bool passed = false;
    double residual = std::numeric_limits<double>::quiet_NaN();   // NaN = not measured
    double condition = std::numeric_limits<double>::quiet_NaN();  // NaN = not measured
    std::string detail;
};

// The error budget of one lens group at one position (error_budget.h): stages in order, each
// with the PSNR of the frame that has it and every stage before it, and the dB it cost.
// Each also against the two-term frame, the method's target (the traced greedy image).
struct BudgetStage {
    std::string stage;  // "two-term model", "layered EM", "maps", "hardware frame", ...
    double psnr = 0.0;  // dB against the reference on the group's pixels
    double cost = 0.0;  // PSNR before it − PSNR with it (NaN: first stage, or after 100 dB)
    double psnrVsTarget = std::numeric_limits<double>::quiet_NaN();  // NaN: not measured
    double costVsTarget = std::numeric_limits<double>::quiet_NaN();
};
struct GroupBudget {
    std::string group;     // the group's objects
    std::string position;  // "on circle", "between samples", "10° above"
    size_t pixels = 0;
    std::vector<BudgetStage> stages;
};

// Packed PEMs (pack_study.h): one pack setting, its size and what it does to the frames.
struct PackDelta {
    std::string method, position;
    double psnr = 0.0;   // float PSNR on the lens pixels, drawn from the pack
    double delta = 0.0;  // psnr − the same frame's from the directory (dB)
};
struct PackRow {
    std::string setting;  // the `pemref pack` options
    double bytesPerSample = 0, vsExr = 0, vsPng = 0, packSeconds = 0;
    int maxError = 0;  // largest |decoded − original| of an 8-bit texel
    std::vector<PackDelta> deltas;
};

struct ReportData {
    std::string title, scene;
    std::string machine;
    int threads = 1;
    std::string buildFlags, compiler;
    std::vector<MethodResult> results;
    std::vector<LeftOutRow> leftOut;
    std::vector<StabilityRow> stability;
    std::vector<GroupBudget> budget;
    std::vector<PackRow> packs;
    std::vector<std::string> notes;
};

// Writes dir/report.md, dir/report.svg, dir/report.json, dir/budget.svg and, with pack rows,
// dir/packs.svg (the rate–distortion curve; dir must exist). Throws
// pem::base::InputError("<file>: <cause>") if a file cannot be written; if that happens before the
// renames (the usual case: missing folder, full disk), none of the three is created or replaced.
void WriteReport(const ReportData& data, const std::string& dir);

// The three documents as text (what WriteReport writes).
std::string ReportMarkdown(const ReportData& data);
std::string ReportSvg(const ReportData& data);
std::string ReportJson(const ReportData& data);
std::string BudgetSvg(const ReportData& data);  // one bar per stage's cost, per group
// ΔPSNR of the hybrid frame on the circle against the ratio to the PNG maps, one curve per coding.
std::string PacksSvg(const ReportData& data);

// Results in report order: by method (first appearance), then setting (natural order), stable.
std::vector<MethodResult> SortedResults(const std::vector<MethodResult>& results);

}  // namespace pem::report
