// SPDX-License-Identifier: MIT
// document_parts.cpp — numbers, table rows and SVG elements (document_parts.h).
#include "viewer_tty/report/document_parts.h"

#include <cmath>
#include <cstdio>

#include "base/xml_text.h"

namespace pem::report {

std::string Format(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string Num(double v, const char* format) {
    return std::isfinite(v) ? Format(format, v) : "n/a";
}

std::string Cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|')
            out += "\\|";
        else if (c == '\n' || c == '\r')
            out += ' ';
        else
            out += c;
    }
    return out;
}

std::string Row(const std::vector<std::string>& cells) {
    std::string row = "|";
    for (const std::string& c : cells) row += " " + c + " |";
    return row + "\n";
}

std::string HeaderRow(const std::vector<std::string>& names, const std::string& align) {
    std::string rule = "|";
    for (size_t i = 0; i < names.size(); ++i) rule += align.at(i) == 'r' ? "---:|" : "---|";
    return Row(names) + rule + "\n";
}

std::string P(double v) {
    return Format("%.2f", v);
}

std::string SvgHeader(double width, double height) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg "
           "xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
           P(width) + "\" height=\"" + P(height) +
           "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" "
           "height=\"100%\" fill=\"#fff\"/>\n";
}

std::string SvgText(double x, double y, const std::string& text, const std::string& attrs) {
    return "<text x=\"" + P(x) + "\" y=\"" + P(y) + "\" " + attrs + ">" + base::XmlEscaped(text) +
           "</text>\n";
}

std::string SvgLine(double x1, double y1, double x2, double y2, const std::string& attrs) {
    return "<line x1=\"" + P(x1) + "\" y1=\"" + P(y1) + "\" x2=\"" + P(x2) + "\" y2=\"" + P(y2) +
           "\" " + attrs + "/>\n";
}

}  // namespace pem::report
