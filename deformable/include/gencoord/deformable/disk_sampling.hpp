// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file disk_sampling.hpp
/// Points uniformly distributed in a disk, by two independent methods. Either can seed
/// particles (the columns are positions).

#include <Eigen/Core>
#include <cstdint>
#include <random>

namespace gencoord::deformable {

/// Uniform double in [0, 1) from 53 random bits (same sequence on every platform).
inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// Samples and how many candidate points were drawn to get them.
struct RejectionSamples {
  Eigen::Matrix2Xd points;    ///< 2 x n (m)
  std::int64_t attempts = 0;  ///< candidates drawn in the square; n / attempts -> pi / 4
};

/// n points uniform in the disk of `radius` around `center`: draw uniformly in the bounding
/// square and keep the points inside the disk.
RejectionSamples sample_disk_rejection(double radius, int n, std::mt19937_64& rng,
                                       const Eigen::Vector2d& center = Eigen::Vector2d::Zero());

/// n points uniform in the disk: r = radius sqrt(u1), theta = 2 pi u2 (the square root makes
/// the density uniform in area: P(r < s) = s^2 / radius^2).
Eigen::Matrix2Xd sample_disk_polar(double radius, int n, std::mt19937_64& rng,
                                   const Eigen::Vector2d& center = Eigen::Vector2d::Zero());

}  // namespace gencoord::deformable
