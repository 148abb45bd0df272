// SPDX-License-Identifier: BSD-3-Clause
// Uniform sampling in a disk, by rejection and by the square-root radius.
#include "gencoord/deformable/disk_sampling.hpp"

#include <cmath>
#include "pi.hpp"

namespace gencoord::deformable {

namespace {
using detail::kPi;
}  // namespace

RejectionSamples sample_disk_rejection(double radius, int n, std::mt19937_64& rng,
                                       const Eigen::Vector2d& center) {
  RejectionSamples out;
  out.points.resize(2, n);
  for (int k = 0; k < n;) {
    const Eigen::Vector2d p(2.0 * uniform01(rng) - 1.0, 2.0 * uniform01(rng) - 1.0);
    ++out.attempts;
    if (p.squaredNorm() < 1.0) out.points.col(k++) = center + radius * p;
  }
  return out;
}

Eigen::Matrix2Xd sample_disk_polar(double radius, int n, std::mt19937_64& rng,
                                   const Eigen::Vector2d& center) {
  Eigen::Matrix2Xd points(2, n);
  for (int k = 0; k < n; ++k) {
    const double r = radius * std::sqrt(uniform01(rng));
    const double theta = 2.0 * kPi * uniform01(rng);
    points.col(k) = center + r * Eigen::Vector2d(std::cos(theta), std::sin(theta));
  }
  return points;
}

}  // namespace gencoord::deformable
