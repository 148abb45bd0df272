// SPDX-License-Identifier: BSD-3-Clause
// A prescribed motion of some generalized coordinates: q_s(t), v_s(t), a_s(t), given as a
// function or as keyframes interpolated by cubic splines. Model-independent: it names the
// scripted coordinates by index; ScriptedModel (scripted/model.hpp) checks them against a
// model.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "gencoord/numerics/cubic_spline.hpp"

namespace gencoord {

/// The scripted coordinates' values at one time, each of dim k (the number scripted), in the
/// order of Script::coordinates().
struct ScriptSample {
  Eigen::VectorXd q;  // q_s(t)
  Eigen::VectorXd v;  // v_s(t) = dq_s/dt
  Eigen::VectorXd a;  // a_s(t) = d2q_s/dt2
};

/// A prescribed motion of k coordinates. The caller guarantees that v and a are the time
/// derivatives of q; from_splines() does so by construction.
class Script {
 public:
  using Function = std::function<ScriptSample(double t)>;

  /// No coordinate scripted (k = 0): a ScriptedModel with it is the free model.
  Script() = default;

  /// Coordinates `coordinates` follow `motion(t)` (its vectors of dim k = coordinates.size()).
  /// \throws std::invalid_argument if motion is empty or a coordinate index is negative or
  ///         repeated (indices beyond the model are caught by ScriptedModel).
  static Script from_function(std::vector<int> coordinates, Function motion);

  /// Coordinate coordinates[j] follows splines[j]: q = y(t), v = y'(t), a = y''(t).
  /// \throws std::invalid_argument if the sizes differ or an index is negative or repeated.
  static Script from_splines(std::vector<int> coordinates, std::vector<CubicSpline> splines);

  /// Keyframes: coordinate coordinates[j] passes through values[j][i] at times[i], by a
  /// natural cubic spline (from_splines() takes clamped ones).
  /// \throws std::invalid_argument as from_splines() and CubicSpline::natural().
  static Script from_keyframes(std::vector<int> coordinates, const std::vector<double>& times,
                               const std::vector<std::vector<double>>& values);

  /// The scripted coordinates' indices (k of them).
  const std::vector<int>& coordinates() const { return coordinates_; }
  int size() const { return static_cast<int>(coordinates_.size()); }

  /// q_s, v_s and a_s at time t (each dim size()).
  /// \throws std::invalid_argument if the motion returns vectors of the wrong size or
  ///         non-finite entries; whatever the motion throws (std::out_of_range from a spline
  ///         evaluated outside its keyframes).
  ScriptSample operator()(double t) const;

 private:
  static void check_coordinates(const std::vector<int>& coordinates);

  std::vector<int> coordinates_;
  Function motion_;
};

}  // namespace gencoord
