// SPDX-License-Identifier: BSD-3-Clause
// The broad phase of surface contact: simplices hashed by the grid cells their bounding boxes
// (grown by a margin) overlap, so that a point finds the simplices near it in one lookup.
// Private to the library (contact_forces.cpp).
//
// The table is a sorted array of (cell key, simplex) rather than a hash map: it is rebuilt at
// every force evaluation, sorting is as fast as inserting, and the candidates of a point come
// out in one deterministic order, so the forces are summed in the same order on every run.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace gencoord::deformable::detail {

template <int Dim>
class SimplexHash {
 public:
  using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<double, Dim, 1>;

  /// Hashes `simplices` (corner indices into the columns of x) grown by `margin` (m). The cell
  /// size is the mean largest extent of a simplex's grown box, so a box overlaps few cells,
  /// but at least 1/32 of the largest, so that no box overlaps more than 33^Dim cells.
  void build(const Points& x, const std::vector<std::array<int, Dim>>& simplices, double margin);

  /// Calls visit(simplex index) once for every simplex whose grown box may contain p (and a
  /// few others whose cells share p's key).
  template <class Visit>
  void for_each_candidate(const Vec& p, Visit&& visit) const {
    const std::uint64_t key = cell_key(cell_of(p));
    auto it = std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(key, -1));
    for (; it != entries_.end() && it->first == key; ++it) visit(it->second);
  }

 private:
  using Cell = Eigen::Matrix<long long, Dim, 1>;
  Cell cell_of(const Vec& p) const;
  static std::uint64_t cell_key(const Cell& cell);

  double inverse_cell_size_ = 1.0;
  std::vector<std::pair<std::uint64_t, int>> entries_;  // sorted, no repeats
};

}  // namespace gencoord::deformable::detail
