// SPDX-License-Identifier: BSD-3-Clause
// Cubic spline interpolation of keyframes, with consistent first and second derivatives:
// the scripted coordinates' q(t), v(t) = q'(t), a(t) = q''(t) come from one piecewise cubic.
#pragma once

#include <vector>

namespace gencoord {

/// An interpolating cubic spline y(t) through keyframes (t_k, y_k), k = 0..n-1, n >= 2, with
/// t_k strictly increasing. C2: y, y' and y'' are continuous; y'' is piecewise linear.
/// Natural end conditions set y'' = 0 at both ends; clamped ones set y' there. The value is
/// fourth-order accurate in the keyframe spacing, y' third, y'' second (for smooth data and
/// exact clamped slopes; natural ends lose accuracy near the ends unless y'' vanishes there).
class CubicSpline {
 public:
  /// Natural spline: y''(t_0) = y''(t_{n-1}) = 0.
  /// \param[in] times   Keyframe times (n >= 2, strictly increasing, finite).
  /// \param[in] values  Keyframe values (n, finite).
  /// \throws std::invalid_argument if the sizes differ, n < 2, the times are not strictly
  ///         increasing, or an entry is not finite.
  static CubicSpline natural(std::vector<double> times, std::vector<double> values);

  /// Clamped spline: y'(t_0) = start_slope, y'(t_{n-1}) = end_slope.
  /// \throws std::invalid_argument as natural(), or if a slope is not finite.
  static CubicSpline clamped(std::vector<double> times, std::vector<double> values,
                             double start_slope, double end_slope);

  /// y(t), y'(t) and y''(t); any output pointer may be null.
  /// \throws std::out_of_range if t lies outside [t_0, t_{n-1}] by more than
  ///         1e-9 (t_{n-1} - t_0) (a little outside is clamped to the end, so that a time
  ///         computed as t_0 + k h may round past the last keyframe).
  void evaluate(double t, double* y, double* dy, double* ddy) const;

  double value(double t) const;              ///< y(t); throws as evaluate()
  double derivative(double t) const;         ///< y'(t); throws as evaluate()
  double second_derivative(double t) const;  ///< y''(t); throws as evaluate()

  double start_time() const { return t_.front(); }
  double end_time() const { return t_.back(); }
  int size() const { return static_cast<int>(t_.size()); }  ///< number of keyframes

 private:
  CubicSpline(std::vector<double> times, std::vector<double> values, bool clamped,
              double start_slope, double end_slope);

  std::vector<double> t_, y_;
  std::vector<double> m_;  // y'' at the keyframes
};

}  // namespace gencoord
