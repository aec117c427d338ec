// SPDX-License-Identifier: MIT
// report_writer.cpp — the three report documents (markdown tables, an SVG log-log plot, JSON) and
// their atomic publication.
// Conventions: numbers are formatted with snprintf ("%.4g"; PSNR "%.2f dB"; SSIM "%.4f"), so the
// text does not depend on the locale of iostreams. SVG coordinates are in px with 2 decimals.
// Not here: any measurement; the SVG has no scripts, no external fonts, no CSS files.
#include "viewer_tty/report/report_writer.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <nlohmann/json.hpp>
#include <utility>

#include "base/atomic_file.h"
#include "base/xml_text.h"
#include "viewer_tty/report/document_parts.h"

namespace pem::report {

std::string TessSetting(double t) {
    char s[32];
    std::snprintf(s, sizeof s, "t=%g", t);
    return s;
}

namespace {

// ---- Text helpers ------------------------------------------------------------------------------

// Natural order: digit runs compare as numbers ("t=3" < "t=10"), the rest byte-wise.
bool NaturalLess(const std::string& a, const std::string& b) {
    size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (std::isdigit(static_cast<unsigned char>(a[i])) &&
            std::isdigit(static_cast<unsigned char>(b[j]))) {
            size_t ie = i, je = j;
            while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
            while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
            std::string na = a.substr(i, ie - i), nb = b.substr(j, je - j);
            na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
            nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
            if (na.size() != nb.size()) return na.size() < nb.size();
            if (na != nb) return na < nb;
            i = ie, j = je;
        } else {
            if (a[i] != b[j]) return a[i] < b[j];
            ++i, ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

// Distinct values in order of first appearance.
template <typename Get>
std::vector<std::string> FirstAppearance(const std::vector<MethodResult>& results, Get get) {
    std::vector<std::string> out;
    for (const MethodResult& r : results)
        if (std::find(out.begin(), out.end(), get(r)) == out.end()) out.push_back(get(r));
    return out;
}

std::vector<std::string> Methods(const std::vector<MethodResult>& results) {
    return FirstAppearance(results, [](const MethodResult& r) { return r.method; });
}

std::vector<std::string> Positions(const std::vector<MethodResult>& results) {
    return FirstAppearance(results, [](const MethodResult& r) { return r.position; });
}

size_t IndexOf(const std::vector<std::string>& list, const std::string& value) {
    return size_t(std::find(list.begin(), list.end(), value) - list.begin());
}

// ---- Markdown ----------------------------------------------------------------------------------

std::string MarkdownResults(const std::vector<MethodResult>& sorted) {
    std::string md;
    for (const std::string& position : Positions(sorted)) {
        md += "\n## Position: " + (position.empty() ? "(unnamed)" : position) + "\n\n";
        md += HeaderRow({"method", "setting", "seconds", "rays", "RMSE", "PSNR", "SSIM",
                         "RMSE 8-bit", "PSNR 8-bit", "SSIM 8-bit"},
                        "llrrrrrrrr");
        for (const MethodResult& r : sorted) {
            if (r.position != position) continue;
            const ImageScores &f = r.floatScores, &q = r.scores8;
            md += Row({Cell(r.method), Cell(r.setting), Num(r.seconds), std::to_string(r.rays),
                       Num(f.rmse), Num(f.psnr, "%.2f dB"), Num(f.ssim, "%.4f"), Num(q.rmse),
                       Num(q.psnr, "%.2f dB"), Num(q.ssim, "%.4f")});
        }
    }
    return md;
}

std::string MarkdownLeftOut(const std::vector<LeftOutRow>& rows) {
    std::string md = "\n## Left out\n\n";
    if (rows.empty()) return md + "Nothing was left out.\n";
    md += HeaderRow({"group", "decision", "reason", "seconds saved"}, "lllr");
    double total = 0;
    for (const LeftOutRow& r : rows) {
        md += Row({Cell(r.group), Cell(r.decision), Cell(r.reason), Num(r.secondsSaved)});
        if (std::isfinite(r.secondsSaved)) total += r.secondsSaved;
    }
    return md + Row({"**total**", "", "", "**" + Num(total) + "**"});
}

std::string MarkdownStability(const std::vector<StabilityRow>& rows) {
    std::string md = "\n## Stability\n\n";
    if (rows.empty()) return md + "No stability cases were run.\n";
    md += HeaderRow(
        {"case", "category", "expected", "outcome", "result", "residual", "condition", "detail"},
        "lllllrrl");
    size_t passed = 0;
    for (const StabilityRow& r : rows) {
        md += Row({Cell(r.name), Cell(r.category), Cell(r.expected), Cell(r.outcome),
                   r.passed ? "PASS" : "**FAIL**", Num(r.residual), Num(r.condition),
                   Cell(r.detail)});
        passed += r.passed ? 1 : 0;
    }
    return md + "\n" + std::to_string(passed) + " of " + std::to_string(rows.size()) +
           " cases passed.\n";
}

// ---- SVG plot: RMSE (float) against seconds, log-log, one panel per position -------------------

constexpr double kPanelW = 300, kPanelH = 240;                    // plot area of one panel
constexpr double kLeft = 80, kTop = 60, kGap = 70, kBottom = 60;  // margins around panels
constexpr double kLegendW = 190;

bool Plottable(const MethodResult& r) {
    return std::isfinite(r.seconds) && r.seconds > 0 && std::isfinite(r.floatScores.rmse) &&
           r.floatScores.rmse > 0;
}

// A log10 axis over whole decades [lo, hi] (exponents), covering every plotted value.
struct Decades {
    int lo = -3, hi = 0;
    double Fraction(double v) const { return (std::log10(v) - lo) / double(hi - lo); }
    int LabelStep() const { return (hi - lo + 5) / 6; }  // at most about 6 labelled decades
};

Decades DecadesOf(const std::vector<double>& values, Decades fallback) {
    if (values.empty()) return fallback;
    const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
    Decades d{int(std::floor(std::log10(*mn))), int(std::ceil(std::log10(*mx)))};
    if (d.hi <= d.lo) d.hi = d.lo + 1;
    return d;
}

// Frame, decade grid, ticks (minor at 2..9), labels and axis titles of one panel at (x0, y0).
std::string SvgAxes(double x0, double y0, const Decades& xs, const Decades& ys, bool yTitle) {
    std::string s = "<rect x=\"" + P(x0) + "\" y=\"" + P(y0) + "\" width=\"" + P(kPanelW) +
                    "\" height=\"" + P(kPanelH) + "\" fill=\"none\" stroke=\"#333\"/>\n";
    for (int e = xs.lo; e <= xs.hi; ++e) {
        for (int m = 1; m < 10 && (m == 1 || e < xs.hi); ++m) {
            const double x = x0 + kPanelW * xs.Fraction(m * std::pow(10.0, e));
            if (m == 1) s += SvgLine(x, y0, x, y0 + kPanelH, "stroke=\"#ddd\"");
            s += SvgLine(x, y0 + kPanelH, x, y0 + kPanelH + (m == 1 ? 6 : 3), "stroke=\"#333\"");
        }
        if ((e - xs.lo) % xs.LabelStep() != 0) continue;
        s += SvgText(x0 + kPanelW * xs.Fraction(std::pow(10.0, e)), y0 + kPanelH + 20,
                     Format("%g", std::pow(10.0, e)), "text-anchor=\"middle\"");
    }
    for (int e = ys.lo; e <= ys.hi; ++e) {
        for (int m = 1; m < 10 && (m == 1 || e < ys.hi); ++m) {
            const double y = y0 + kPanelH * (1 - ys.Fraction(m * std::pow(10.0, e)));
            if (m == 1) s += SvgLine(x0, y, x0 + kPanelW, y, "stroke=\"#ddd\"");
            s += SvgLine(x0 - (m == 1 ? 6 : 3), y, x0, y, "stroke=\"#333\"");
        }
        if ((e - ys.lo) % ys.LabelStep() != 0) continue;
        s += SvgText(x0 - 9, y0 + kPanelH * (1 - ys.Fraction(std::pow(10.0, e))) + 4,
                     Format("%g", std::pow(10.0, e)), "text-anchor=\"end\"");
    }
    s += SvgText(x0 + kPanelW / 2, y0 + kPanelH + 42, "run time (s, log scale)",
                 "text-anchor=\"middle\"");
    if (yTitle) {
        const double cx = x0 - 62, cy = y0 + kPanelH / 2;
        s +=
            SvgText(cx, cy, "RMSE vs. reference (float, log scale)",
                    "text-anchor=\"middle\" transform=\"rotate(-90 " + P(cx) + " " + P(cy) + ")\"");
    }
    return s;
}

// The markers of one position: a thin line per method through its settings, one circle per
// plottable result, the setting as a label; a note counts the results that could not be plotted.
std::string SvgPanelData(const std::vector<MethodResult>& sorted, const std::string& position,
                         double x0, double y0, const Decades& xs, const Decades& ys) {
    const std::vector<std::string> methods = Methods(sorted);
    std::string lines, markers;
    size_t skipped = 0;
    for (const std::string& method : methods) {
        const char* colour = kColours[IndexOf(methods, method) % std::size(kColours)];
        std::string points;
        for (const MethodResult& r : sorted) {
            if (r.position != position || r.method != method) continue;
            if (!Plottable(r)) {
                ++skipped;
                continue;
            }
            const double x = x0 + kPanelW * xs.Fraction(r.seconds);
            const double y = y0 + kPanelH * (1 - ys.Fraction(r.floatScores.rmse));
            points += P(x) + "," + P(y) + " ";
            markers += "<circle class=\"marker\" cx=\"" + P(x) + "\" cy=\"" + P(y) +
                       "\" r=\"4.5\" fill=\"" + colour + "\" stroke=\"#fff\"><title>" +
                       base::XmlEscaped(method + " " + r.setting + ": " + Num(r.seconds) +
                                        " s, RMSE " + Num(r.floatScores.rmse)) +
                       "</title></circle>\n";
            if (!r.setting.empty())
                markers += SvgText(x + 6, y - 6, r.setting, "font-size=\"10\" fill=\"#333\"");
        }
        if (!points.empty())
            lines += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour +
                     "\" stroke-opacity=\"0.5\"/>\n";
    }
    std::string s = lines + markers;
    if (skipped > 0)
        s += SvgText(x0 + 4, y0 + kPanelH - 6,
                     std::to_string(skipped) + " result(s) not plotted (zero or not finite)",
                     "font-size=\"10\" fill=\"#a00\"");
    return s;
}

std::string SvgLegend(const std::vector<std::string>& methods, double x0, double y0) {
    std::string s = SvgText(x0, y0, "method", "font-weight=\"bold\"");
    for (size_t i = 0; i < methods.size(); ++i) {
        const double y = y0 + 20 + 18 * double(i);
        s += "<circle class=\"legend\" cx=\"" + P(x0 + 5) + "\" cy=\"" + P(y - 4) +
             "\" r=\"4.5\" fill=\"" + kColours[i % std::size(kColours)] + "\"/>\n";
        s += SvgText(x0 + 16, y, methods[i].empty() ? "(unnamed)" : methods[i], "");
    }
    return s;
}

// ---- Error budget ----------------------------------------------------------------------------

std::string MarkdownBudget(const std::vector<GroupBudget>& budget) {
    if (budget.empty()) return "";
    std::string md =
        "\n## Error budget\n\nWhere the method loses against the ray tracer, per lens group: "
        "each stage swaps one part of the method for its exact version (PSNR of the 8-bit sRGB "
        "images on the group's pixels; cost = the dB the stage takes away), against the "
        "reference and against the two-term frame, the method's target (the frame the maps are "
        "fitted to; at the sample: `trace/view_NNN/greedy`).\n\n";
    md += HeaderRow({"group", "position", "stage", "PSNR (dB)", "cost (dB)",
                     "PSNR vs two-term (dB)", "cost vs two-term (dB)"},
                    "lllrrrr");
    const auto dB = [](double v) { return std::isfinite(v) ? Num(v, "%.2f") : "—"; };
    for (const GroupBudget& b : budget)
        for (const BudgetStage& st : b.stages)
            md += Row({Cell(b.group), Cell(b.position), Cell(st.stage), Num(st.psnr, "%.2f"),
                       dB(st.cost), dB(st.psnrVsTarget), dB(st.costVsTarget)});
    return md;
}

// ---- Packed PEMs -------------------------------------------------------------------------------

// The change of a method's PSNR at a position ("" = the mean over positions).
double PackDeltaOf(const PackRow& row, const std::string& method, const std::string& position) {
    double sum = 0;
    int n = 0;
    for (const PackDelta& d : row.deltas)
        if (d.method == method && (position.empty() || d.position == position)) sum += d.delta, ++n;
    return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

std::string MarkdownPacks(const std::vector<PackRow>& packs) {
    if (packs.empty()) return "";
    std::vector<std::string> positions;
    for (const PackDelta& d : packs.front().deltas)
        if (std::find(positions.begin(), positions.end(), d.position) == positions.end())
            positions.push_back(d.position);
    std::string md =
        "\n## Packed PEMs\n\nThe PEM directory packed (`pemref pack`): bytes per viewpoint sample, "
        "the ratio against the directory's float EXR and 8-bit PNG maps, the largest change of an "
        "8-bit texel, and the change of the frames' PSNR (float, lens pixels) when drawn from the "
        "pack instead of the directory (packs.svg).\n\n";
    std::vector<std::string> names = {"setting", "bytes/sample", "vs EXR",
                                      "vs PNG",  "max error",    "pack s"};
    std::string align = "lrrrrr";
    for (const std::string& p : positions) names.push_back("Δ hybrid " + p), align += 'r';
    names.push_back("Δ layered PEM"), names.push_back("Δ single-layer PEM"), align += "rr";
    md += HeaderRow(names, align);
    for (const PackRow& r : packs) {
        const std::string setting = std::string(1, '`').append(Cell(r.setting)).append("`");
        std::vector<std::string> cells = {setting,
                                          Num(r.bytesPerSample, "%.0f"),
                                          Num(r.vsExr, "%.1f:1"),
                                          Num(r.vsPng, "%.1f:1"),
                                          std::to_string(r.maxError),
                                          Num(r.packSeconds, "%.1f")};
        for (const std::string& p : positions)
            cells.push_back(Num(PackDeltaOf(r, "hybrid", p), "%+.2f dB"));
        cells.push_back(Num(PackDeltaOf(r, "layered PEM", ""), "%+.2f dB"));
        cells.push_back(Num(PackDeltaOf(r, "single-layer PEM", ""), "%+.2f dB"));
        md += Row(cells);
    }
    return md;
}

// ---- Files -------------------------------------------------------------------------------------

std::string JoinPath(const std::string& dir, const std::string& name) {
    if (dir.empty()) return name;
    return dir.back() == '/' ? dir + name : dir + "/" + name;
}

}  // namespace

std::vector<MethodResult> SortedResults(const std::vector<MethodResult>& results) {
    const std::vector<std::string> methods = Methods(results);
    std::vector<MethodResult> sorted = results;
    std::stable_sort(
        sorted.begin(), sorted.end(), [&](const MethodResult& a, const MethodResult& b) {
            const size_t ia = IndexOf(methods, a.method), ib = IndexOf(methods, b.method);
            if (ia != ib) return ia < ib;
            return NaturalLess(a.setting, b.setting);
        });
    return sorted;
}

std::string ReportMarkdown(const ReportData& data) {
    // Step 1: the header (what ran where).
    std::string md = "# " + (data.title.empty() ? "pemref report" : data.title) + "\n\n";
    md += HeaderRow({"run", ""}, "ll") + Row({"scene", Cell(data.scene)}) +
          Row({"machine", Cell(data.machine)}) + Row({"threads", std::to_string(data.threads)}) +
          Row({"compiler", Cell(data.compiler)}) + Row({"build flags", Cell(data.buildFlags)});
    // Step 2: the tables, then the notes.
    md += MarkdownResults(SortedResults(data.results));
    md += MarkdownBudget(data.budget);
    md += MarkdownPacks(data.packs);
    md += MarkdownLeftOut(data.leftOut) + MarkdownStability(data.stability);
    if (!data.notes.empty()) {
        md += "\n## Notes\n\n";
        for (const std::string& note : data.notes) md += "- " + Cell(note) + "\n";
    }
    return md;
}

std::string ReportSvg(const ReportData& data) {
    // Step 1: shared log ranges over every plottable result, so the panels compare directly.
    const std::vector<MethodResult> sorted = SortedResults(data.results);
    std::vector<double> seconds, rmse;
    for (const MethodResult& r : sorted) {
        if (!Plottable(r)) continue;
        seconds.push_back(r.seconds);
        rmse.push_back(r.floatScores.rmse);
    }
    const Decades xs = DecadesOf(seconds, {-2, 1}), ys = DecadesOf(rmse, {-3, 0});
    // Step 2: the canvas, one panel per position (at least one), the legend on the right.
    std::vector<std::string> positions = Positions(sorted);
    if (positions.empty()) positions.push_back("");
    const double width = kLeft + double(positions.size()) * (kPanelW + kGap) + kLegendW;
    const double height = kTop + kPanelH + kBottom;
    std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + P(width) + "\" height=\"" +
           P(height) + "\" viewBox=\"0 0 " + P(width) + " " + P(height) +
           "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    svg += SvgText(kLeft, 22,
                   (data.title.empty() ? "pemref report" : data.title) +
                       (data.scene.empty() ? "" : " — scene " + data.scene) +
                       ": error against run time",
                   "font-size=\"15\" font-weight=\"bold\"");
    for (size_t i = 0; i < positions.size(); ++i) {
        const double x0 = kLeft + double(i) * (kPanelW + kGap);
        svg += SvgText(x0 + kPanelW / 2, kTop - 10,
                       positions[i].empty() ? "(no position)" : positions[i],
                       "text-anchor=\"middle\" font-weight=\"bold\"");
        svg += SvgAxes(x0, kTop, xs, ys, i == 0);
        svg += SvgPanelData(sorted, positions[i], x0, kTop, xs, ys);
    }
    const double legendX = kLeft + double(positions.size()) * (kPanelW + kGap) - kGap / 2;
    return svg + SvgLegend(Methods(sorted), legendX, kTop + 10) + "</svg>\n";
}

// A stage's cost as the change it makes: "−1.2" for a loss, "+0.5" for a gain.
std::string SignedLoss(double cost) {
    return cost >= 0.0 ? "−" + Num(cost, "%.1f") : "+" + Num(-cost, "%.1f");
}

std::string BudgetSvg(const ReportData& data) {
    // One row of bars per (group, position): each stage's PSNR as a bar, its cost as a label.
    const double barW = 3.0, rowH = 18.0, left = 330.0, top = 40.0;  // 3 px per dB
    size_t rows = 0;
    for (const GroupBudget& b : data.budget) rows += b.stages.size() + 1;
    const double width = left + 60 * barW + 280, height = top + double(rows) * rowH + 40;
    std::string svg = SvgHeader(width, height);
    svg += SvgText(
        10, 22,
        "Error budget: PSNR after each stage (bar, dB), what it cost, and vs the two-term frame",
        "font-size=\"15\" font-weight=\"bold\"");
    double y = top;
    for (const GroupBudget& b : data.budget) {
        svg += SvgText(10, y + 13, b.group + " — " + b.position, "font-weight=\"bold\"");
        y += rowH;
        for (size_t k = 0; k < b.stages.size(); ++k) {
            const BudgetStage& st = b.stages[k];
            const double w = std::isfinite(st.psnr) ? std::clamp(st.psnr, 0.0, 60.0) * barW : 0.0;
            svg += SvgText(20, y + 13, st.stage, "");
            svg += "<rect x=\"" + P(left) + "\" y=\"" + P(y + 3) + "\" width=\"" + P(w) +
                   "\" height=\"" + P(rowH - 6) + "\" fill=\"" + kColours[k % std::size(kColours)] +
                   "\"/>\n";
            svg += SvgText(left + w + 5, y + 13,
                           Num(st.psnr, "%.1f") + " dB" +
                               (std::isfinite(st.cost) ? " (" + SignedLoss(st.cost) + ")" : "") +
                               (std::isfinite(st.psnrVsTarget)
                                    ? "; vs two-term " + Num(st.psnrVsTarget, "%.1f") + " dB"
                                    : ""),
                           "font-size=\"11\"");
            y += rowH;
        }
    }
    for (int db = 0; db <= 60; db += 10)
        svg += SvgText(left + db * barW, height - 15, std::to_string(db),
                       "text-anchor=\"middle\" "
                       "font-size=\"10\" fill=\"#666\"");
    return svg + "</svg>\n";
}

std::string PacksSvg(const ReportData& data) {
    // Step 1: the axes: ratio to the PNG maps (log2, 1 to the largest), ΔPSNR of the hybrid
    // frame at the first position (dB, from the lowest to +0.5).
    const double left = 80, top = 50, w = 520, h = 300;
    double maxRatio = 32, minDelta = -1.0;
    std::string position;
    for (const PackRow& r : data.packs) {
        if (!r.deltas.empty() && position.empty()) position = r.deltas.front().position;
        maxRatio = std::max(maxRatio, r.vsPng);
        const double d = PackDeltaOf(r, "hybrid", position);
        if (std::isfinite(d)) minDelta = std::min(minDelta, std::floor(d * 2.0) / 2.0);
    }
    const double xMax = std::ceil(std::log2(maxRatio)), yMax = 0.5;
    auto X = [&](double ratio) { return left + std::log2(std::max(ratio, 1.0)) / xMax * w; };
    auto Y = [&](double d) {
        return top + (yMax - std::clamp(d, minDelta, yMax)) / (yMax - minDelta) * h;
    };
    std::string svg = SvgHeader(left + w + 200, top + h + 60);
    svg += SvgText(10, 22,
                   "Packed PEMs: hybrid frame's ΔPSNR (" + position + ") vs ratio to the PNG maps",
                   "font-size=\"14\" font-weight=\"bold\"");
    for (int e = 0; e <= xMax; ++e) {
        svg += SvgLine(X(std::exp2(e)), top, X(std::exp2(e)), top + h, "stroke=\"#ddd\"");
        svg += SvgText(X(std::exp2(e)), top + h + 16, Num(std::exp2(e), "%.0f") + ":1",
                       "text-anchor=\"middle\" font-size=\"10\"");
    }
    for (double d = minDelta; d <= yMax + 1e-9; d += 0.5) {
        svg +=
            SvgLine(left, Y(d), left + w, Y(d), d == 0.0 ? "stroke=\"#888\"" : "stroke=\"#ddd\"");
        svg += SvgText(left - 6, Y(d) + 4, Num(d, "%+.1f"), "text-anchor=\"end\" font-size=\"10\"");
    }
    svg += SvgLine(left, Y(-0.5), left + w, Y(-0.5), "stroke=\"#D55E00\" stroke-dasharray=\"4 3\"");
    svg += SvgLine(X(20), top, X(20), top + h, "stroke=\"#D55E00\" stroke-dasharray=\"4 3\"");
    svg += SvgText(left + w / 2, top + h + 40,
                   "ratio to the PNG maps (log scale); dashed: 20:1, −0.5 dB",
                   "text-anchor=\"middle\"");
    // Step 2: one curve per coding: predictive (lossless, --max-error) and JPEG 2000 (--ratio).
    const char* names[2] = {"predictive", "JPEG 2000"};
    for (int k = 0; k < 2; ++k) {
        std::vector<std::pair<double, double>> pts;
        for (const PackRow& r : data.packs)
            if ((r.setting.find("--ratio") != std::string::npos) == (k == 1))
                pts.push_back({r.vsPng, PackDeltaOf(r, "hybrid", position)});
        std::sort(pts.begin(), pts.end());
        std::string line;
        for (const auto& [ratio, d] : pts) {
            if (!std::isfinite(d)) continue;
            line += P(X(ratio)) + "," + P(Y(d)) + " ";
            svg += "<circle cx=\"" + P(X(ratio)) + "\" cy=\"" + P(Y(d)) + "\" r=\"4\" fill=\"" +
                   kColours[k] + "\"/>\n";
        }
        svg += "<polyline points=\"" + line + "\" fill=\"none\" stroke=\"" + kColours[k] + "\"/>\n";
        svg += "<circle cx=\"" + P(left + w + 20) + "\" cy=\"" + P(top + 10 + 20 * k) +
               "\" r=\"4.5\" fill=\"" + kColours[k] + "\"/>\n";
        svg += SvgText(left + w + 32, top + 14 + 20 * k, names[k], "");
    }
    return svg + "</svg>\n";
}

std::string ReportJson(const ReportData& data) {
    using nlohmann::ordered_json;
    const auto scores = [](const ImageScores& s) {
        return ordered_json{
            {"rmse", s.rmse}, {"psnr", s.psnr}, {"ssim", s.ssim}, {"pixels", s.pixels}};
    };
    // Step 1: the run's context; Step 2: every table, in report order (NaN becomes null).
    ordered_json j = {{"format", "pemref_report/1"}, {"title", data.title},
                      {"scene", data.scene},         {"machine", data.machine},
                      {"threads", data.threads},     {"buildFlags", data.buildFlags},
                      {"compiler", data.compiler}};
    j["results"] = ordered_json::array();
    for (const MethodResult& r : SortedResults(data.results))
        j["results"].push_back({{"method", r.method},
                                {"setting", r.setting},
                                {"position", r.position},
                                {"seconds", r.seconds},
                                {"rays", r.rays},
                                {"float", scores(r.floatScores)},
                                {"8bit", scores(r.scores8)}});
    double saved = 0;
    j["leftOut"] = ordered_json::array();
    for (const LeftOutRow& r : data.leftOut) {
        j["leftOut"].push_back({{"group", r.group},
                                {"decision", r.decision},
                                {"reason", r.reason},
                                {"secondsSaved", r.secondsSaved}});
        if (std::isfinite(r.secondsSaved)) saved += r.secondsSaved;
    }
    j["leftOutSecondsSaved"] = saved;
    j["stability"] = ordered_json::array();
    for (const StabilityRow& r : data.stability)
        j["stability"].push_back({{"name", r.name},
                                  {"category", r.category},
                                  {"expected", r.expected},
                                  {"outcome", r.outcome},
                                  {"passed", r.passed},
                                  {"residual", r.residual},
                                  {"condition", r.condition},
                                  {"detail", r.detail}});
    j["budget"] = ordered_json::array();
    for (const GroupBudget& b : data.budget) {
        ordered_json stages = ordered_json::array();
        for (const BudgetStage& st : b.stages)
            stages.push_back({{"stage", st.stage},
                              {"psnr", st.psnr},
                              {"cost", st.cost},
                              {"psnrVsTwoTerm", st.psnrVsTarget},
                              {"costVsTwoTerm", st.costVsTarget}});
        j["budget"].push_back({{"group", b.group},
                               {"position", b.position},
                               {"pixels", b.pixels},
                               {"stages", stages}});
    }
    j["packs"] = ordered_json::array();
    for (const PackRow& r : data.packs) {
        ordered_json deltas = ordered_json::array();
        for (const PackDelta& d : r.deltas)
            deltas.push_back({{"method", d.method},
                              {"position", d.position},
                              {"psnr", d.psnr},
                              {"delta", d.delta}});
        j["packs"].push_back({{"setting", r.setting},
                              {"bytesPerSample", r.bytesPerSample},
                              {"vsExr", r.vsExr},
                              {"vsPng", r.vsPng},
                              {"maxError", r.maxError},
                              {"packSeconds", r.packSeconds},
                              {"frames", deltas}});
    }
    j["notes"] = data.notes;
    return j.dump(2, ' ', false, ordered_json::error_handler_t::replace) + "\n";
}

void WriteReport(const ReportData& data, const std::string& dir) {
    std::vector<std::pair<std::string, std::string>> files = {
        {JoinPath(dir, "report.md"), ReportMarkdown(data)},
        {JoinPath(dir, "report.svg"), ReportSvg(data)},
        {JoinPath(dir, "report.json"), ReportJson(data)},
        {JoinPath(dir, "budget.svg"), BudgetSvg(data)}};
    if (!data.packs.empty()) files.push_back({JoinPath(dir, "packs.svg"), PacksSvg(data)});
    base::WriteTextsAtomic(files);
}

}  // namespace pem::report
