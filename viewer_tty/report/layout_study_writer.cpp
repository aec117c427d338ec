// SPDX-License-Identifier: MIT
// layout_study_writer.cpp — study.md, study.svg, study.json (layout_study_writer.h).
#include "viewer_tty/report/layout_study_writer.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "viewer_tty/report/document_parts.h"

namespace pem::report {
namespace {

std::string LayoutName(runtime::Parameterization p) {
    return std::string(runtime::ParameterizationName(p));
}

std::vector<const LayoutPoint*> PointsOf(const LayoutStudy& s, const std::string& scene) {
    std::vector<const LayoutPoint*> out;
    for (const LayoutPoint& p : s.points)
        if (p.scene == scene) out.push_back(&p);
    return out;
}

double FrameSeconds(const LayoutPoint& p, const std::string& position, const std::string& method) {
    for (const LayoutScore& s : p.scores)
        if (s.position == position && s.method == method) return s.seconds;
    return std::nan("");
}

// ---- study.md ---------------------------------------------------------------------------------

std::string SceneTable(const LayoutStudy& s, const std::string& scene) {
    std::vector<std::string> names = {"layout", "size", "texels", "fit rmse", "infer s/sample"};
    std::string align = "lrrrr";
    for (const char* method : kStudyMethods)
        for (const std::string& pos : s.positions) {
            names.push_back(std::string(method) + " " + pos + " (dB)");
            align += 'r';
        }
    names.push_back("hybrid frame (ms)");
    align += 'r';
    std::string md = HeaderRow(names, align);
    for (const LayoutPoint* p : PointsOf(s, scene)) {
        std::vector<std::string> row = {LayoutName(p->layout), std::to_string(p->size),
                                        std::to_string(p->texels), Num(p->rmse8, "%.4f"),
                                        Num(p->inferSeconds, "%.2f")};
        for (const char* method : kStudyMethods)
            for (const std::string& pos : s.positions)
                row.push_back(Num(p->Psnr(pos, method), "%.2f"));
        row.push_back(Num(1e3 * FrameSeconds(*p, s.positions.front(), "hybrid"), "%.0f"));
        md += Row(row);
    }
    return md;
}

// The hybrid PSNR of a point averaged over the positions (NaN if one is missing).
double MeanHybrid(const LayoutStudy& s, const LayoutPoint& p) {
    double sum = 0.0;
    for (const std::string& pos : s.positions) sum += p.Psnr(pos, "hybrid");
    return sum / static_cast<double>(s.positions.size());
}

// The texels at which a layout's curve (its sizes in increasing order) first reaches `db`,
// linear in log2(texels) between two sizes; NaN when no size reaches it.
double TexelsToReach(const LayoutStudy& s, const std::string& scene, runtime::Parameterization l,
                     double db) {
    const LayoutPoint* prev = nullptr;
    for (const LayoutPoint* p : PointsOf(s, scene)) {
        if (p->layout != l) continue;
        const double v = MeanHybrid(s, *p);
        if (v >= db) {
            if (!prev) return static_cast<double>(p->texels);
            const double v0 = MeanHybrid(s, *prev);
            const double x0 = std::log2(static_cast<double>(prev->texels));
            const double x1 = std::log2(static_cast<double>(p->texels));
            return std::exp2(x0 + (x1 - x0) * (db - v0) / (v - v0));
        }
        prev = p;
    }
    return std::nan("");
}

// Per cube size: the texels each other layout needs for the cube's mean hybrid PSNR, as a
// multiple of the cube's (the resolution the PEM paper says the parameterization decides).
std::string MatchTable(const LayoutStudy& s, const std::string& scene) {
    std::vector<std::string> names = {"cube size", "cube texels", "mean hybrid (dB)"};
    std::string align = "rrr";
    for (runtime::Parameterization l : s.options.layouts)
        if (l != runtime::Parameterization::Cube) names.push_back(LayoutName(l)), align += 'r';
    std::string md = HeaderRow(names, align);
    for (const LayoutPoint* c : PointsOf(s, scene)) {
        if (c->layout != runtime::Parameterization::Cube) continue;
        const double db = MeanHybrid(s, *c);
        std::vector<std::string> row = {std::to_string(c->size), std::to_string(c->texels),
                                        Num(db, "%.2f")};
        for (runtime::Parameterization l : s.options.layouts) {
            if (l == runtime::Parameterization::Cube) continue;
            const double t = TexelsToReach(s, scene, l, db);
            row.push_back(std::isfinite(t) ? Num(t / static_cast<double>(c->texels), "%.2f") + "×"
                                           : "not reached");
        }
        md += Row(row);
    }
    return md;
}

std::string Pictures(const LayoutStudy& s, const std::string& scene) {
    std::string md;
    const int largest = *std::max_element(s.options.sizes.begin(), s.options.sizes.end());
    for (const LayoutPoint* p : PointsOf(s, scene))
        if (p->size == largest && !p->picture.empty())
            md += "- " + LayoutName(p->layout) + " (size " + std::to_string(p->size) + "): ![" +
                  LayoutName(p->layout) + "](" + p->picture + ")\n";
    return md;
}

// ---- study.svg --------------------------------------------------------------------------------

constexpr double kPanelW = 280, kPanelH = 200, kLeft = 70, kTop = 60, kGapX = 60, kGapY = 80;
constexpr double kLegendW = 150;

struct Axes {
    double x0, y0;    // the panel's top-left corner
    int xLo, xHi;     // log2 texels
    double yLo, yHi;  // dB
    double X(double texels) const { return x0 + (std::log2(texels) - xLo) / (xHi - xLo) * kPanelW; }
    double Y(double db) const {
        return y0 + (yHi - std::clamp(db, yLo, yHi)) / (yHi - yLo) * kPanelH;
    }
};

// The x axis over every point of the study, the y axis over the scene's.
Axes AxesOf(const LayoutStudy& s, const std::string& scene, double x0, double y0) {
    Axes a{x0, y0, 30, 0, 1e9, -1e9};
    for (const LayoutPoint& p : s.points) {
        const int e = static_cast<int>(std::floor(std::log2(static_cast<double>(p.texels))));
        a.xLo = std::min(a.xLo, e);
        a.xHi = std::max(a.xHi, e + 1);
        for (const LayoutScore& q : p.scores)
            if (p.scene == scene && q.method == "hybrid" && std::isfinite(q.psnr)) {
                a.yLo = std::min(a.yLo, std::floor(q.psnr));
                a.yHi = std::max(a.yHi, std::ceil(q.psnr));
            }
    }
    if (a.xHi <= a.xLo) a.xLo = 0, a.xHi = 1;
    if (a.yHi <= a.yLo) a.yLo = 0, a.yHi = 1;
    return a;
}

std::string Panel(const LayoutStudy& s, const std::string& scene, const std::string& pos,
                  const Axes& a) {
    std::string svg = SvgText(a.x0, a.y0 - 8, scene + ", " + pos, "font-weight=\"bold\"");
    for (int e = a.xLo; e <= a.xHi; ++e) {
        svg +=
            SvgLine(a.X(std::exp2(e)), a.y0, a.X(std::exp2(e)), a.y0 + kPanelH, "stroke=\"#ddd\"");
        if ((e - a.xLo) % 2 == 0)
            svg += SvgText(a.X(std::exp2(e)), a.y0 + kPanelH + 14, "2^" + std::to_string(e),
                           "text-anchor=\"middle\" font-size=\"10\"");
    }
    const double step = a.yHi - a.yLo > 10 ? 2.0 : 1.0;
    for (double d = a.yLo; d <= a.yHi + 1e-9; d += step) {
        svg += SvgLine(a.x0, a.Y(d), a.x0 + kPanelW, a.Y(d), "stroke=\"#ddd\"");
        svg +=
            SvgText(a.x0 - 6, a.Y(d) + 4, Num(d, "%.0f"), "text-anchor=\"end\" font-size=\"10\"");
    }
    for (size_t k = 0; k < s.options.layouts.size(); ++k) {
        std::string line;
        const char* colour = kColours[k % std::size(kColours)];
        for (const LayoutPoint* p : PointsOf(s, scene)) {
            const double db = p->Psnr(pos, "hybrid");
            if (p->layout != s.options.layouts[k] || !std::isfinite(db)) continue;
            const double x = a.X(static_cast<double>(p->texels)), y = a.Y(db);
            line += P(x) + "," + P(y) + " ";
            svg += "<circle cx=\"" + P(x) + "\" cy=\"" + P(y) + "\" r=\"3\" fill=\"" + colour +
                   "\"/>\n";
        }
        svg += "<polyline points=\"" + line + "\" fill=\"none\" stroke=\"" + colour + "\"/>\n";
    }
    return svg;
}

}  // namespace

std::string LayoutStudyMarkdown(const LayoutStudy& s) {
    const LayoutStudyOptions& o = s.options;
    std::string md = "# pemref study: environment-map parameterizations\n\n";
    std::string sizes;
    for (int size : o.sizes) sizes += (sizes.empty() ? "" : ", ") + std::to_string(size);
    md += "Each layout of the notes (seed 001) inferred at sizes " + sizes;
    md += " from one trace per scene (" + o.views + ", " + std::to_string(o.width) + "×" +
          std::to_string(o.height) + ", " + std::to_string(o.spp) + "×" + std::to_string(o.spp) +
          " samples), the same regularizer and hardware (llvmpipe, trilinear). Scores: 8-bit PSNR "
          "over the lens pixels against the ray tracer (full tree, " +
          std::to_string(o.referenceSpp) + "×" + std::to_string(o.referenceSpp) +
          " samples per pixel), on the first sample, halfway to the next and 10° above. Texels: "
          "level 0, every face (a cube of size n has 6n², lat-long, paraboloid and tennis 2n², "
          "the sphere map n²). Fit rmse: the mean of the maps' solve residuals ([0, 1]).\n\n";
    for (const std::string& scene : s.scenes) {
        md += "## " + scene + "\n\n" + SceneTable(s, scene) + "\n";
        if (std::find(s.options.layouts.begin(), s.options.layouts.end(),
                      runtime::Parameterization::Cube) != s.options.layouts.end())
            md +=
                "Texels each layout needs for the cube's hybrid PSNR (mean of the three "
                "positions), as a multiple of the cube's (interpolated in log texels between "
                "sizes; not reached: not at the sizes studied):\n\n" +
                MatchTable(s, scene) + "\n";
        md +=
            "Maps of the first sample, outer layer (the 8-bit copies, levels stacked, rows as "
            "the texture stores them: t = 0 at the top):\n\n" +
            Pictures(s, scene) + "\n";
    }
    md += "![hybrid PSNR against texels](study.svg)\n";
    return md;
}

std::string LayoutStudySvg(const LayoutStudy& s) {
    const size_t cols = std::max<size_t>(1, s.positions.size()), rows = s.scenes.size();
    const double width = kLeft + cols * (kPanelW + kGapX) + kLegendW;
    const double height = kTop + rows * (kPanelH + kGapY);
    std::string svg = SvgHeader(width, height);
    svg += SvgText(10, 22, "Hybrid frame PSNR (dB, lens pixels) against level-0 texels per map",
                   "font-size=\"14\" font-weight=\"bold\"");
    for (size_t r = 0; r < rows; ++r)
        for (size_t c = 0; c < s.positions.size(); ++c) {
            const Axes a =
                AxesOf(s, s.scenes[r], kLeft + c * (kPanelW + kGapX), kTop + r * (kPanelH + kGapY));
            svg += Panel(s, s.scenes[r], s.positions[c], a);
            if (r + 1 == rows)
                svg += SvgText(a.x0 + kPanelW / 2, a.y0 + kPanelH + 32,
                               "texels per map (level 0, log scale)", "text-anchor=\"middle\"");
        }
    const double lx = kLeft + cols * (kPanelW + kGapX);
    for (size_t k = 0; k < s.options.layouts.size(); ++k) {
        svg += "<circle cx=\"" + P(lx) + "\" cy=\"" + P(kTop + 10 + 20 * k) +
               "\" r=\"4.5\" fill=\"" + kColours[k % std::size(kColours)] + "\"/>\n";
        svg += SvgText(lx + 12, kTop + 14 + 20 * k, LayoutName(s.options.layouts[k]), "");
    }
    return svg + "</svg>\n";
}

std::string LayoutStudyJson(const LayoutStudy& s) {
    using nlohmann::ordered_json;
    const auto finite = [](double v) {
        return std::isfinite(v) ? ordered_json(v) : ordered_json();
    };
    const LayoutStudyOptions& o = s.options;
    ordered_json j = {{"format", "pemref_study/1"},
                      {"views", o.views},
                      {"size", {o.width, o.height}},
                      {"spp", o.spp},
                      {"reference_spp", o.referenceSpp},
                      {"threads", o.threads},
                      {"sizes", o.sizes},
                      {"scenes", s.scenes},
                      {"positions", s.positions}};
    j["points"] = ordered_json::array();
    for (const LayoutPoint& p : s.points) {
        ordered_json scores = ordered_json::array();
        for (const LayoutScore& q : p.scores)
            scores.push_back({{"position", q.position},
                              {"method", q.method},
                              {"psnr", finite(q.psnr)},
                              {"seconds", q.seconds}});
        j["points"].push_back({{"scene", p.scene},
                               {"layout", LayoutName(p.layout)},
                               {"size", p.size},
                               {"texels", p.texels},
                               {"maps", p.maps},
                               {"fit_rmse", finite(p.rmse8)},
                               {"infer_seconds_per_sample", p.inferSeconds},
                               {"pem_dir", p.pemDir},
                               {"picture", p.picture},
                               {"scores", scores}});
    }
    return j.dump(2) + "\n";
}

void WriteLayoutStudy(const LayoutStudy& s, const std::string& dir) {
    base::WriteTextsAtomic({{dir + "/study.md", LayoutStudyMarkdown(s)},
                            {dir + "/study.svg", LayoutStudySvg(s)},
                            {dir + "/study.json", LayoutStudyJson(s)}});
}

}  // namespace pem::report
