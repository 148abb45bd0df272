// SPDX-License-Identifier: BSD-3-Clause
// CubicSpline: exact on cubics (clamped), natural end conditions, derivative consistency,
// fourth-order convergence, and its errors.
#include "gencoord/numerics/cubic_spline.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace gencoord {
namespace {

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[static_cast<std::size_t>(i)] = a + (b - a) * i / (n - 1);
  return x;
}

TEST(CubicSpline, ClampedReproducesACubicExactly) {
  // y = 1 - 2t + 0.5 t^2 + 0.3 t^3, uneven keyframes
  auto y = [](double t) { return 1.0 - 2.0 * t + 0.5 * t * t + 0.3 * t * t * t; };
  auto dy = [](double t) { return -2.0 + t + 0.9 * t * t; };
  auto ddy = [](double t) { return 1.0 + 1.8 * t; };
  const std::vector<double> times{-1.0, -0.3, 0.1, 0.8, 2.0};
  std::vector<double> values;
  for (double t : times) values.push_back(y(t));
  const CubicSpline s = CubicSpline::clamped(times, values, dy(-1.0), dy(2.0));
  for (double t = -1.0; t <= 2.0; t += 0.0371) {
    EXPECT_NEAR(s.value(t), y(t), 1e-12) << "t = " << t;
    EXPECT_NEAR(s.derivative(t), dy(t), 1e-12) << "t = " << t;
    EXPECT_NEAR(s.second_derivative(t), ddy(t), 1e-11) << "t = " << t;
  }
}

TEST(CubicSpline, NaturalHasZeroCurvatureAtTheEndsAndInterpolates) {
  const std::vector<double> times{0.0, 0.5, 1.5, 2.0, 3.0};
  const std::vector<double> values{0.0, 1.0, -1.0, 0.5, 2.0};
  const CubicSpline s = CubicSpline::natural(times, values);
  EXPECT_NEAR(s.second_derivative(0.0), 0.0, 1e-13);
  EXPECT_NEAR(s.second_derivative(3.0), 0.0, 1e-13);
  for (std::size_t k = 0; k < times.size(); ++k)
    EXPECT_NEAR(s.value(times[k]), values[k], 1e-14) << "keyframe " << k;
}

TEST(CubicSpline, DerivativesAreTheDerivativesOfTheValue) {
  const std::vector<double> times = linspace(0.0, 2.0, 9);
  std::vector<double> values;
  for (double t : times) values.push_back(std::sin(3.0 * t));
  const CubicSpline s = CubicSpline::natural(times, values);
  const double h = 1e-6;
  for (double t = 0.01; t < 1.99; t += 0.0737) {
    EXPECT_NEAR(s.derivative(t), (s.value(t + h) - s.value(t - h)) / (2 * h), 1e-8) << t;
    EXPECT_NEAR(s.second_derivative(t), (s.derivative(t + h) - s.derivative(t - h)) / (2 * h), 1e-6)
        << t;
  }
}

TEST(CubicSpline, ClampedErrorIsFourthOrderInTheSpacing) {
  // max |s - sin| over [0, 2] for 8, 16, 32 intervals: each halving divides it by ~16
  std::vector<double> errors;
  for (int n : {8, 16, 32}) {
    const std::vector<double> times = linspace(0.0, 2.0, n + 1);
    std::vector<double> values;
    for (double t : times) values.push_back(std::sin(3.0 * t));
    const CubicSpline s = CubicSpline::clamped(times, values, 3.0, 3.0 * std::cos(6.0));
    double worst = 0.0;
    for (double t = 0.0; t <= 2.0; t += 0.001)
      worst = std::max(worst, std::abs(s.value(t) - std::sin(3.0 * t)));
    errors.push_back(worst);
  }
  const double rate1 = std::log2(errors[0] / errors[1]), rate2 = std::log2(errors[1] / errors[2]);
  std::printf("spline error at 8/16/32 intervals: %.3e %.3e %.3e, rates %.2f %.2f\n", errors[0],
              errors[1], errors[2], rate1, rate2);
  EXPECT_GT(rate1, 3.7);
  EXPECT_GT(rate2, 3.7);
}

TEST(CubicSpline, RejectsBadInputAndTimesOutsideTheKeyframes) {
  EXPECT_THROW(CubicSpline::natural({0.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline::natural({0.0, 1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline::natural({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline::natural({0.0, NAN}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline::clamped({0.0, 1.0}, {1.0, 2.0}, INFINITY, 0.0), std::invalid_argument);
  const CubicSpline s = CubicSpline::natural({0.0, 1.0}, {1.0, 3.0});
  EXPECT_NEAR(s.value(0.5), 2.0, 1e-15);  // two keyframes: a straight line
  EXPECT_NO_THROW(s.value(1.0 + 1e-12));  // round-off past the end is clamped
  EXPECT_THROW(s.value(1.01), std::out_of_range);
  EXPECT_THROW(s.value(-0.01), std::out_of_range);
}

}  // namespace
}  // namespace gencoord
