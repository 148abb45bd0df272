// SPDX-License-Identifier: BSD-3-Clause
// A log-log line plot as a standalone SVG file, hand-written (no dependencies): decade ticks
// with labels on both axes, one polyline with markers per series, a legend.
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "gencoord/io/output_file.hpp"

namespace gencoord::drivers {

/// One series of a log-log plot: (x, y) points (non-positive or non-finite ones are skipped).
struct LogLogSeries {
  std::string label;
  std::string color;  // any SVG color, e.g. "#1f77b4"
  std::vector<double> x, y;
};

namespace detail {
inline std::string escape_xml(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}
inline std::string decade_label(int e) {
  if (e == 0) return "1";
  if (e == 1) return "10";
  return "1e" + std::to_string(e);
}
}  // namespace detail

/// Writes a log-log plot of `series` to `path` (overwritten), with `note` (may be empty) as a
/// line of text in the plot's lower left corner.
/// \return false (and writes nothing) if no series has a usable point.
/// \throws gencoord::OutputError if the file cannot be written.
inline bool write_loglog_svg(const std::string& path, const std::string& title,
                             const std::string& x_label, const std::string& y_label,
                             const std::vector<LogLogSeries>& series,
                             const std::string& note = "") {
  // data range in decades
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!(s.x[i] > 0) || !(s.y[i] > 0) || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        continue;
      xlo = std::min(xlo, std::log10(s.x[i]));
      xhi = std::max(xhi, std::log10(s.x[i]));
      ylo = std::min(ylo, std::log10(s.y[i]));
      yhi = std::max(yhi, std::log10(s.y[i]));
    }
  if (!std::isfinite(xlo) || !std::isfinite(ylo)) return false;
  const int x0 = static_cast<int>(std::floor(xlo)),
            x1 = std::max(x0 + 1, static_cast<int>(std::ceil(xhi)));
  const int y0 = static_cast<int>(std::floor(ylo)),
            y1 = std::max(y0 + 1, static_cast<int>(std::ceil(yhi)));
  // page layout
  const double W = 720, H = 480, left = 90, right = 30, top = 50, bottom = 70;
  const double pw = W - left - right, ph = H - top - bottom;
  auto px = [&](double lx) { return left + (lx - x0) / (x1 - x0) * pw; };
  auto py = [&](double ly) { return top + (1.0 - (ly - y0) / (y1 - y0)) * ph; };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" viewBox=\"0 0 " << W << ' ' << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << W / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">"
      << detail::escape_xml(title) << "</text>\n";
  // grid, ticks and labels: decades labelled, 2..9 minor ticks
  const int ystride = std::max(1, (y1 - y0 + 9) / 10);
  for (int e = x0; e <= x1; ++e) {
    svg << "<line x1=\"" << px(e) << "\" y1=\"" << top << "\" x2=\"" << px(e) << "\" y2=\""
        << top + ph << "\" stroke=\"#ddd\"/>\n"
        << "<text x=\"" << px(e) << "\" y=\"" << top + ph + 18 << "\" text-anchor=\"middle\">"
        << detail::decade_label(e) << "</text>\n";
    for (int m = 2; m <= 9 && e < x1; ++m) {
      const double lx = e + std::log10(m);
      svg << "<line x1=\"" << px(lx) << "\" y1=\"" << top + ph << "\" x2=\"" << px(lx) << "\" y2=\""
          << top + ph - 4 << "\" stroke=\"#888\"/>\n";
    }
  }
  for (int e = y0; e <= y1; ++e) {
    svg << "<line x1=\"" << left << "\" y1=\"" << py(e) << "\" x2=\"" << left + pw << "\" y2=\""
        << py(e) << "\" stroke=\"#ddd\"/>\n";
    if ((e - y0) % ystride == 0)
      svg << "<text x=\"" << left - 8 << "\" y=\"" << py(e) + 4 << "\" text-anchor=\"end\">"
          << detail::decade_label(e) << "</text>\n";
    for (int m = 2; m <= 9 && e < y1 && ystride == 1; ++m) {
      const double ly = e + std::log10(m);
      svg << "<line x1=\"" << left << "\" y1=\"" << py(ly) << "\" x2=\"" << left + 4 << "\" y2=\""
          << py(ly) << "\" stroke=\"#888\"/>\n";
    }
  }
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 20 << "\" text-anchor=\"middle\">"
      << detail::escape_xml(x_label) << "</text>\n"
      << "<text transform=\"translate(22," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << detail::escape_xml(y_label) << "</text>\n";
  // series and legend
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    std::ostringstream points, marks;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!(s.x[i] > 0) || !(s.y[i] > 0) || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        continue;
      const double X = px(std::log10(s.x[i])), Y = py(std::log10(s.y[i]));
      points << X << ',' << Y << ' ';
      marks << "<circle cx=\"" << X << "\" cy=\"" << Y << "\" r=\"3.5\" fill=\"" << s.color
            << "\"/>\n";
    }
    svg << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.8\" points=\""
        << points.str() << "\"/>\n"
        << marks.str();
    const double ly = top + 14 + 18 * static_cast<double>(k);
    svg << "<line x1=\"" << left + pw - 210 << "\" y1=\"" << ly << "\" x2=\"" << left + pw - 185
        << "\" y2=\"" << ly << "\" stroke=\"" << s.color << "\" stroke-width=\"2\"/>\n"
        << "<text x=\"" << left + pw - 178 << "\" y=\"" << ly + 4 << "\">"
        << detail::escape_xml(s.label) << "</text>\n";
  }
  if (!note.empty())
    svg << "<text x=\"" << left + 10 << "\" y=\"" << top + ph - 12 << "\">"
        << detail::escape_xml(note) << "</text>\n";
  svg << "</svg>\n";
  OutputFile file(path);
  file.stream() << svg.str();
  file.close();
  return true;
}

}  // namespace gencoord::drivers
