// SPDX-License-Identifier: BSD-3-Clause
// The broad phase of surface contact (spatial_hash.hpp).
#include "spatial_hash.hpp"

#include <cmath>

namespace gencoord::deformable::detail {

template <int Dim>
typename SimplexHash<Dim>::Cell SimplexHash<Dim>::cell_of(const Vec& p) const {
  Cell cell;
  for (int d = 0; d < Dim; ++d) {
    // clamped so that the conversion is defined for any finite position
    const double c = std::clamp(std::floor(p(d) * inverse_cell_size_), -1e15, 1e15);
    cell(d) = static_cast<long long>(c);
  }
  return cell;
}

template <int Dim>
std::uint64_t SimplexHash<Dim>::cell_key(const Cell& cell) {
  // large odd multipliers spread neighbouring cells over the key space
  constexpr std::uint64_t kPrimes[3] = {73856093ULL, 19349663ULL, 83492791ULL};
  std::uint64_t key = 0;
  for (int d = 0; d < Dim; ++d) key ^= static_cast<std::uint64_t>(cell(d)) * kPrimes[d];
  return key;
}

template <int Dim>
void SimplexHash<Dim>::build(const Points& x, const std::vector<std::array<int, Dim>>& simplices,
                             double margin) {
  entries_.clear();
  if (simplices.empty()) return;
  std::vector<Vec> lower(simplices.size()), upper(simplices.size());
  double extent_sum = 0.0, extent_max = 0.0;
  for (std::size_t k = 0; k < simplices.size(); ++k) {
    lower[k] = upper[k] = x.col(simplices[k][0]);
    for (int c = 1; c < Dim; ++c) {
      lower[k] = lower[k].cwiseMin(x.col(simplices[k][c]));
      upper[k] = upper[k].cwiseMax(x.col(simplices[k][c]));
    }
    lower[k].array() -= margin;
    upper[k].array() += margin;
    const double extent = (upper[k] - lower[k]).maxCoeff();
    extent_sum += extent;
    extent_max = std::max(extent_max, extent);
  }
  const double size =
      std::max(extent_sum / static_cast<double>(simplices.size()), extent_max / 32.0);
  inverse_cell_size_ = size > 0.0 ? 1.0 / size : 1.0;
  for (std::size_t k = 0; k < simplices.size(); ++k) {
    const Cell from = cell_of(lower[k]), to = cell_of(upper[k]);
    Cell cell = from;
    while (true) {  // every cell of the box [from, to], odometer order
      entries_.emplace_back(cell_key(cell), static_cast<int>(k));
      int d = 0;
      for (; d < Dim; ++d) {
        if (cell(d) < to(d)) {
          ++cell(d);
          break;
        }
        cell(d) = from(d);
      }
      if (d == Dim) break;
    }
  }
  std::sort(entries_.begin(), entries_.end());
  // two cells of one box may share a key: one entry is enough
  entries_.erase(std::unique(entries_.begin(), entries_.end()), entries_.end());
}

template class SimplexHash<2>;
template class SimplexHash<3>;

}  // namespace gencoord::deformable::detail
