// SPDX-License-Identifier: BSD-3-Clause
// CSV frames and spring list.
#include "frame_output.hpp"

#include <memory>

#include "gencoord/io/output_file.hpp"

namespace gencoord::deformable::demo {

namespace {
// the file, opened with the precision of the frames (throws OutputError if it cannot be)
std::unique_ptr<OutputFile> Open(const std::string& path) {
  auto file = std::make_unique<OutputFile>(path);
  file->stream().precision(9);
  return file;
}
}  // namespace

bool spring_intact_at(const MassSpringSystem<2>& s, int k, double t) {
  if (!s.springs[k].broken) return true;
  for (const FractureEvent& e : s.fractures) {
    if (e.spring == k) return t < e.t;
  }
  return true;
}

void write_csv(const std::string& folder, const std::vector<Frame>& frames,
               const MassSpringSystem<2>& final_state) {
  const auto nodes_file = Open(folder + "/frames.csv");
  std::ostream& nodes = nodes_file->stream();
  nodes << "frame,time,node,x,y\n";
  for (size_t f = 0; f < frames.size(); ++f) {
    for (int n = 0; n < frames[f].x.cols(); ++n) {
      nodes << f << ',' << frames[f].t << ',' << n << ',' << frames[f].x(0, n) << ','
            << frames[f].x(1, n) << '\n';
    }
  }
  nodes_file->close();
  const auto springs_file = Open(folder + "/springs.csv");
  std::ostream& springs = springs_file->stream();
  springs << "spring,i,j,broken_at\n";
  std::vector<double> broken_at(final_state.springs.size(), -1.0);
  for (const FractureEvent& e : final_state.fractures) broken_at[e.spring] = e.t;
  for (size_t k = 0; k < final_state.springs.size(); ++k) {
    springs << k << ',' << final_state.springs[k].i << ',' << final_state.springs[k].j << ',';
    if (broken_at[k] >= 0.0) springs << broken_at[k];
    springs << '\n';
  }
  springs_file->close();
}

}  // namespace gencoord::deformable::demo
