// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/numerics/cubic_spline.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace gencoord {

CubicSpline CubicSpline::natural(std::vector<double> times, std::vector<double> values) {
  return CubicSpline(std::move(times), std::move(values), false, 0.0, 0.0);
}

CubicSpline CubicSpline::clamped(std::vector<double> times, std::vector<double> values,
                                 double start_slope, double end_slope) {
  if (!std::isfinite(start_slope) || !std::isfinite(end_slope))
    throw std::invalid_argument("gencoord: CubicSpline::clamped needs finite end slopes");
  return CubicSpline(std::move(times), std::move(values), true, start_slope, end_slope);
}

CubicSpline::CubicSpline(std::vector<double> times, std::vector<double> values, bool clamped,
                         double start_slope, double end_slope)
    : t_(std::move(times)), y_(std::move(values)) {
  const std::size_t n = t_.size();
  if (n != y_.size())
    throw std::invalid_argument("gencoord: CubicSpline needs as many values as times");
  if (n < 2) throw std::invalid_argument("gencoord: CubicSpline needs at least 2 keyframes");
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(t_[k]) || !std::isfinite(y_[k]))
      throw std::invalid_argument("gencoord: CubicSpline keyframe " + std::to_string(k) +
                                  " is not finite");
    if (k > 0 && !(t_[k] > t_[k - 1]))
      throw std::invalid_argument(
          "gencoord: CubicSpline times must be strictly increasing "
          "(keyframe " +
          std::to_string(k) + ")");
  }
  // tridiagonal system for the second derivatives m: sub, diag, super, rhs (Thomas algorithm)
  std::vector<double> sub(n, 0.0), diag(n, 1.0), super(n, 0.0), rhs(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
    sub[i] = h0;
    diag[i] = 2.0 * (h0 + h1);
    super[i] = h1;
    rhs[i] = 6.0 * ((y_[i + 1] - y_[i]) / h1 - (y_[i] - y_[i - 1]) / h0);
  }
  if (clamped) {
    // y'(t_0) = start_slope, y'(t_{n-1}) = end_slope
    const double h0 = t_[1] - t_[0], hn = t_[n - 1] - t_[n - 2];
    diag[0] = 2.0 * h0;
    super[0] = h0;
    rhs[0] = 6.0 * ((y_[1] - y_[0]) / h0 - start_slope);
    sub[n - 1] = hn;
    diag[n - 1] = 2.0 * hn;
    rhs[n - 1] = 6.0 * (end_slope - (y_[n - 1] - y_[n - 2]) / hn);
  }
  // forward elimination (diagonally dominant: no pivoting needed), back substitution
  for (std::size_t i = 1; i < n; ++i) {
    const double w = sub[i] / diag[i - 1];
    diag[i] -= w * super[i - 1];
    rhs[i] -= w * rhs[i - 1];
  }
  m_.assign(n, 0.0);
  m_[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) m_[i] = (rhs[i] - super[i] * m_[i + 1]) / diag[i];
}

void CubicSpline::evaluate(double t, double* y, double* dy, double* ddy) const {
  const double t0 = t_.front(), tn = t_.back();
  const double slack = 1e-9 * (tn - t0);
  if (!(t >= t0 - slack && t <= tn + slack)) {
    std::ostringstream os;
    os.precision(17);
    os << "gencoord: CubicSpline evaluated at t = " << t << ", outside its keyframes [" << t0
       << ", " << tn << "]; extend the keyframes to cover the whole run";
    throw std::out_of_range(os.str());
  }
  t = std::clamp(t, t0, tn);
  // segment k with t_k <= t <= t_{k+1}
  const std::size_t k =
      std::min<std::size_t>(
          static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()),
          t_.size() - 1) -
      1;
  const double h = t_[k + 1] - t_[k];
  const double a = (t_[k + 1] - t) / h, b = (t - t_[k]) / h;  // a + b = 1
  const double m0 = m_[k], m1 = m_[k + 1];
  if (y)
    *y = a * y_[k] + b * y_[k + 1] + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
  if (dy)
    *dy = (y_[k + 1] - y_[k]) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
  if (ddy) *ddy = a * m0 + b * m1;
}

double CubicSpline::value(double t) const {
  double y;
  evaluate(t, &y, nullptr, nullptr);
  return y;
}

double CubicSpline::derivative(double t) const {
  double dy;
  evaluate(t, nullptr, &dy, nullptr);
  return dy;
}

double CubicSpline::second_derivative(double t) const {
  double ddy;
  evaluate(t, nullptr, nullptr, &ddy);
  return ddy;
}

}  // namespace gencoord
