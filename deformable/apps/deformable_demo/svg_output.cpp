// SPDX-License-Identifier: BSD-3-Clause
// SVG rendering with no dependency: one <g> per frame.
#include "svg_output.hpp"

#include <memory>
#include <sstream>
#include <stdexcept>

#include "gencoord/io/output_file.hpp"

namespace gencoord::deformable::demo {

namespace {

constexpr double kPanelWidth = 400.0;  // (px)

struct View {
  double x0, y1, scale;  // world (x0, y1) maps to the panel's top-left corner
  double px(double x) const { return (x - x0) * scale; }
  double py(double y) const { return (y1 - y) * scale; }
};

View MakeView(const Scenario& sc) {
  return {sc.view_min_x, sc.view_max_y, kPanelWidth / (sc.view_max_x - sc.view_min_x)};
}

double PanelHeight(const Scenario& sc) {
  return (sc.view_max_y - sc.view_min_y) * MakeView(sc).scale;
}

// The springs intact at the frame's time, the nodes (pinned ones as squares) and the ground.
void DrawFrame(std::ostream& out, const Scenario& sc, const MassSpringSystem<2>& s,
               const Frame& frame) {
  const View v = MakeView(sc);
  if (s.ground) {
    out << "<line x1='0' x2='" << kPanelWidth << "' y1='" << v.py(s.ground->height) << "' y2='"
        << v.py(s.ground->height) << "' stroke='#6b4f2a' stroke-width='3'/>\n";
  }
  out << "<path stroke='#1f5fa8' stroke-width='0.8' fill='none' d='";
  for (int k = 0; k < static_cast<int>(s.springs.size()); ++k) {
    if (!spring_intact_at(s, k, frame.t)) continue;
    const Spring& sp = s.springs[k];
    out << 'M' << v.px(frame.x(0, sp.i)) << ' ' << v.py(frame.x(1, sp.i)) << 'L'
        << v.px(frame.x(0, sp.j)) << ' ' << v.py(frame.x(1, sp.j));
  }
  out << "'/>\n";
  for (int n = 0; n < frame.x.cols(); ++n) {
    const double x = v.px(frame.x(0, n)), y = v.py(frame.x(1, n));
    if (s.pinned[n]) {
      out << "<rect x='" << x - 2 << "' y='" << y - 2 << "' width='4' height='4' fill='#b22'/>";
    } else if (s.springs.empty()) {
      out << "<circle cx='" << x << "' cy='" << y << "' r='1.5' fill='#1f5fa8'/>";
    }
  }
  out << "\n<text x='8' y='18' font-family='sans-serif' font-size='13'>t = " << frame.t
      << " s</text>\n";
}

// the file with the SVG's opening written (throws OutputError if it cannot be written)
std::unique_ptr<OutputFile> OpenSvg(const std::string& path, double width, double height) {
  auto file = std::make_unique<OutputFile>(path);
  std::ostream& out = file->stream();
  out.precision(5);
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' viewBox='0 0 " << width << ' ' << height << "'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  return file;
}

}  // namespace

void write_svg_panels(const std::string& path, const Scenario& sc,
                      const MassSpringSystem<2>& final_state, const std::vector<Frame>& frames,
                      const std::vector<int>& chosen) {
  const double height = PanelHeight(sc);
  const auto file = OpenSvg(path, kPanelWidth * chosen.size(), height + 24);
  std::ostream& out = file->stream();
  for (size_t p = 0; p < chosen.size(); ++p) {
    out << "<g transform='translate(" << p * kPanelWidth << ",0)'>\n"
        << "<rect width='" << kPanelWidth << "' height='" << height
        << "' fill='none' stroke='#ccc'/>\n";
    DrawFrame(out, sc, final_state, frames.at(chosen[p]));
    out << "</g>\n";
  }
  out << "<text x='8' y='" << height + 17 << "' font-family='sans-serif' font-size='12'>" << sc.name
      << ": " << sc.description << "</text>\n</svg>\n";
  file->close();
}

void write_svg_animation(const std::string& path, const Scenario& sc,
                         const MassSpringSystem<2>& final_state, const std::vector<Frame>& frames) {
  const auto file = OpenSvg(path, kPanelWidth, PanelHeight(sc));
  std::ostream& out = file->stream();
  const double total = frames.back().t > 0 ? frames.back().t : 1.0;
  const size_t count = frames.size();
  for (size_t f = 0; f < count; ++f) {
    // each frame is shown during its share of the loop (discrete keyTimes in [0, 1])
    const double begin = static_cast<double>(f) / count, end = static_cast<double>(f + 1) / count;
    out << "<g display='none'><animate attributeName='display' calcMode='discrete' "
        << "repeatCount='indefinite' dur='" << total << "s' values='none;inline;none' "
        << "keyTimes='0;" << begin << ';' << end << "'/>\n";
    DrawFrame(out, sc, final_state, frames[f]);
    out << "</g>\n";
  }
  out << "</svg>\n";
  file->close();
}

}  // namespace gencoord::deformable::demo
