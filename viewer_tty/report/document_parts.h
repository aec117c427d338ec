// SPDX-License-Identifier: MIT
// document_parts.h — the pieces the report's and the study's documents are made of: numbers and
// Markdown table rows for the .md files, lines, text and colours for the .svg files.
//
//   md += HeaderRow({"method", "PSNR"}, "lr") + Row({Cell(name), Num(psnr, "%.2f")});
//   svg += SvgLine(x0, y, x1, y, "stroke=\"#ddd\"") + SvgText(x0, y, "0 dB", "");
//
// Not here: what the documents say (report_writer.h, layout_study_writer.h).
#pragma once

#include <string>
#include <vector>

namespace pem::report {

// printf of one number.
std::string Format(const char* format, double v);
// A number for a table cell; non-finite values are "n/a".
std::string Num(double v, const char* format = "%.4g");
// A table cell: '|' escaped, line breaks flattened.
std::string Cell(const std::string& text);
// One table row of already-formatted cells.
std::string Row(const std::vector<std::string>& cells);
// The header and rule of a table; align has one letter per column, 'l' (text) or 'r' (numbers).
std::string HeaderRow(const std::vector<std::string>& names, const std::string& align);

// Colour-blind-safe colours (Okabe–Ito), one per plotted series.
inline constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                           "#E69F00", "#56B4E9", "#000000", "#999999"};
// A coordinate as SVG writes it (two decimals).
std::string P(double v);
// An SVG document's opening: the XML declaration, <svg> of this size (sans-serif, 12 px) and a
// white background; the caller closes it with "</svg>\n".
std::string SvgHeader(double width, double height);
// A <text> element (text escaped) and a <line> element, each with extra attributes.
std::string SvgText(double x, double y, const std::string& text, const std::string& attrs);
std::string SvgLine(double x1, double y1, double x2, double y2, const std::string& attrs);

}  // namespace pem::report
