// SPDX-License-Identifier: BSD-3-Clause
// Least-squares straight line through (log10 x, log10 y): the exponent of a power law.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gencoord {

/// A fitted power law y = 10^intercept x^slope.
struct LogLogFit {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double intercept = std::numeric_limits<double>::quiet_NaN();
  int points = 0;  // the points used (positive and finite)
};

/// Least-squares fit of log10 y = intercept + slope log10 x over the pairs with x, y > 0 and
/// finite (others are skipped). x and y must have the same size; fewer than two usable points
/// (or all x equal) gives NaN slope and intercept.
inline LogLogFit fit_loglog(const std::vector<double>& x, const std::vector<double>& y) {
  LogLogFit fit;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!(x[i] > 0) || !(y[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    const double lx = std::log10(x[i]), ly = std::log10(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++fit.points;
  }
  const double k = fit.points;
  const double denominator = k * sxx - sx * sx;
  if (fit.points < 2 || !(std::abs(denominator) > 0)) return fit;
  fit.slope = (k * sxy - sx * sy) / denominator;
  fit.intercept = (sy - fit.slope * sx) / k;
  return fit;
}

}  // namespace gencoord
