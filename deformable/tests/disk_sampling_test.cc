// SPDX-License-Identifier: BSD-3-Clause
// Uniform sampling in a disk: a Kolmogorov-Smirnov test that r^2 / R^2 is uniform on [0, 1],
// for both methods, and rejection sampling's acceptance rate pi / 4.
#include "gencoord/deformable/disk_sampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>
#include "test_helpers.hpp"

namespace gencoord::deformable {
namespace {

using testing::kPi;

// KS statistic sup |F_n(x) - x| of samples in [0, 1] against the uniform distribution.
double KsStatisticAgainstUniform(std::vector<double> u) {
  std::sort(u.begin(), u.end());
  const double n = static_cast<double>(u.size());
  double d = 0.0;
  for (size_t k = 0; k < u.size(); ++k) {
    d = std::max({d, (k + 1) / n - u[k], u[k] - k / n});
  }
  return d;
}

std::vector<double> NormalizedSquaredRadii(const Eigen::Matrix2Xd& points, double radius,
                                           const Eigen::Vector2d& center) {
  std::vector<double> out;
  for (int k = 0; k < points.cols(); ++k) {
    out.push_back((points.col(k) - center).squaredNorm() / (radius * radius));
  }
  return out;
}

constexpr int kSamples = 5000;
// asymptotic KS critical value at significance 0.01: 1.628 / sqrt(n) (Smirnov's table)
const double kCritical = 1.628 / std::sqrt(static_cast<double>(kSamples));

TEST(DiskSamplingTest, RejectionSamplesHaveUniformSquaredRadius) {
  std::mt19937_64 rng(12345);
  const Eigen::Vector2d center(3.0, -1.0);
  const RejectionSamples s = sample_disk_rejection(2.0, kSamples, rng, center);
  const std::vector<double> u = NormalizedSquaredRadii(s.points, 2.0, center);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
  const double d = KsStatisticAgainstUniform(u);
  EXPECT_LT(d, kCritical) << "KS statistic " << d << ", critical value " << kCritical;
}

TEST(DiskSamplingTest, PolarSamplesHaveUniformSquaredRadius) {
  std::mt19937_64 rng(12345);
  const Eigen::Vector2d center(3.0, -1.0);
  const Eigen::Matrix2Xd p = sample_disk_polar(2.0, kSamples, rng, center);
  const std::vector<double> u = NormalizedSquaredRadii(p, 2.0, center);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
  const double d = KsStatisticAgainstUniform(u);
  EXPECT_LT(d, kCritical) << "KS statistic " << d << ", critical value " << kCritical;
  // angles uniform too: theta / (2 pi) against uniform
  std::vector<double> theta;
  for (int k = 0; k < p.cols(); ++k) {
    theta.push_back((std::atan2(p(1, k) - center.y(), p(0, k) - center.x()) + kPi) / (2 * kPi));
  }
  EXPECT_LT(KsStatisticAgainstUniform(theta), kCritical);
}

// The test has teeth: the naive r = R u1 (without the square root) clusters points at the
// centre, and the same KS test rejects it.
TEST(DiskSamplingTest, NaiveRadiusSamplingFailsTheSameTest) {
  std::mt19937_64 rng(12345);
  std::vector<double> u;
  for (int k = 0; k < kSamples; ++k) {
    const double r = uniform01(rng);
    u.push_back(r * r);
  }
  const double d = KsStatisticAgainstUniform(u);
  EXPECT_GT(d, kCritical) << "naive sampling passed: KS " << d;
}

TEST(DiskSamplingTest, RejectionAcceptanceRateIsPiOverFour) {
  std::mt19937_64 rng(777);
  const RejectionSamples s = sample_disk_rejection(1.0, 100000, rng);
  const double rate = static_cast<double>(s.points.cols()) / s.attempts;
  // binomial standard error about 0.0013 at this many attempts
  EXPECT_NEAR(rate, kPi / 4, 0.005) << "acceptance " << rate << ", expected pi / 4 = " << kPi / 4;
}

}  // namespace
}  // namespace gencoord::deformable
