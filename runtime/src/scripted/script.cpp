// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/scripted/script.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace gencoord {

void Script::check_coordinates(const std::vector<int>& coordinates) {
  std::vector<int> sorted = coordinates;
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty() && sorted.front() < 0)
    throw std::invalid_argument("gencoord: Script coordinate index " +
                                std::to_string(sorted.front()) + " is negative");
  const auto repeated = std::adjacent_find(sorted.begin(), sorted.end());
  if (repeated != sorted.end())
    throw std::invalid_argument("gencoord: Script coordinate index " + std::to_string(*repeated) +
                                " is scripted twice");
}

Script Script::from_function(std::vector<int> coordinates, Function motion) {
  if (!motion) throw std::invalid_argument("gencoord: Script::from_function needs a motion");
  check_coordinates(coordinates);
  Script script;
  script.coordinates_ = std::move(coordinates);
  script.motion_ = std::move(motion);
  return script;
}

Script Script::from_splines(std::vector<int> coordinates, std::vector<CubicSpline> splines) {
  if (coordinates.size() != splines.size())
    throw std::invalid_argument(
        "gencoord: Script::from_splines needs one spline per "
        "scripted coordinate, got " +
        std::to_string(splines.size()) + " splines for " + std::to_string(coordinates.size()));
  const auto k = static_cast<Eigen::Index>(coordinates.size());
  return from_function(std::move(coordinates), [splines = std::move(splines), k](double t) {
    ScriptSample s{Eigen::VectorXd(k), Eigen::VectorXd(k), Eigen::VectorXd(k)};
    for (Eigen::Index j = 0; j < k; ++j)
      splines[static_cast<std::size_t>(j)].evaluate(t, &s.q[j], &s.v[j], &s.a[j]);
    return s;
  });
}

Script Script::from_keyframes(std::vector<int> coordinates, const std::vector<double>& times,
                              const std::vector<std::vector<double>>& values) {
  if (coordinates.size() != values.size())
    throw std::invalid_argument(
        "gencoord: Script::from_keyframes needs one row of values "
        "per scripted coordinate");
  std::vector<CubicSpline> splines;
  splines.reserve(values.size());
  for (const std::vector<double>& row : values) splines.push_back(CubicSpline::natural(times, row));
  return from_splines(std::move(coordinates), std::move(splines));
}

ScriptSample Script::operator()(double t) const {
  const auto k = static_cast<Eigen::Index>(coordinates_.size());
  if (k == 0) return {Eigen::VectorXd(0), Eigen::VectorXd(0), Eigen::VectorXd(0)};
  ScriptSample s = motion_(t);
  if (s.q.size() != k || s.v.size() != k || s.a.size() != k) {
    std::ostringstream os;
    os << "gencoord: the script returned vectors of sizes (" << s.q.size() << ", " << s.v.size()
       << ", " << s.a.size() << ") at t = " << t << "; expected " << k
       << " (one entry per scripted coordinate)";
    throw std::invalid_argument(os.str());
  }
  if (!s.q.allFinite() || !s.v.allFinite() || !s.a.allFinite()) {
    std::ostringstream os;
    os.precision(17);
    os << "gencoord: the script returned NaN or inf at t = " << t;
    throw std::invalid_argument(os.str());
  }
  return s;
}

}  // namespace gencoord
