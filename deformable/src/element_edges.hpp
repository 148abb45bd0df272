// SPDX-License-Identifier: BSD-3-Clause
// What the volume terms and the continuum elements do alike: orient each mesh element
// positively at rest and find the spring along each of its edges when they are added to an
// object, gather their nodes' positions, and act only while none of their springs is broken.
// Private to the library.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/volume_terms.hpp"
#include "message.hpp"

namespace gencoord::deformable::detail {

/// The object's springs by their node pair.
class SpringsByPair {
 public:
  explicit SpringsByPair(const std::vector<Spring>& springs) {
    pairs_.reserve(springs.size());
    for (int k = 0; k < static_cast<int>(springs.size()); ++k)
      pairs_.emplace_back(std::min(springs[k].i, springs[k].j),
                          std::max(springs[k].i, springs[k].j), k);
    std::sort(pairs_.begin(), pairs_.end());
  }
  /// The index of a spring joining nodes a and b, -1 if none does.
  int find(int a, int b) const {
    const int i = std::min(a, b), j = std::max(a, b);
    const auto it = std::lower_bound(pairs_.begin(), pairs_.end(), std::make_tuple(i, j, -1));
    return it != pairs_.end() && std::get<0>(*it) == i && std::get<1>(*it) == j ? std::get<2>(*it)
                                                                                : -1;
  }

 private:
  std::vector<std::tuple<int, int, int>> pairs_;
};

/// Sets element->nodes to `nodes`, swapped into the order whose signed measure at `rest` is
/// positive, and element->springs to the spring of each edge (the order of VolumeTerm::springs);
/// returns the rest measure. `what` ("volume terms") and `index` name the element in errors.
/// \throws ObjectError if the measure is not positive and finite or an edge has no spring.
template <int Dim, class Element>
double place_element(const SpringsByPair& springs, const std::array<int, Dim + 1>& nodes,
                     const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, const char* what,
                     int index, Element* element) {
  element->nodes = nodes;
  Corners<Dim> corners;
  for (int a = 0; a <= Dim; ++a) corners[a] = rest.col(nodes[a]);
  double measure = signed_measure<Dim>(corners);
  if (measure < 0.0) {  // an odd permutation turns it positive; edges and springs stay
    std::swap(element->nodes[Dim - 1], element->nodes[Dim]);
    measure = -measure;
  }
  if (!(measure > 0.0 && std::isfinite(measure)))
    throw ObjectError(message(what, ": element ", index, " has rest measure ", measure,
                              "; need a positive, finite area or volume"),
                      element->nodes[0], -1);
  int edge = 0;
  for (int a = 0; a <= Dim; ++a) {
    for (int b = a + 1; b <= Dim; ++b, ++edge) {
      const int i = element->nodes[a], j = element->nodes[b];
      element->springs[edge] = springs.find(i, j);
      if (element->springs[edge] < 0)
        throw ObjectError(
            message(what, ": element ", index, "'s edge (", std::min(i, j), ", ", std::max(i, j),
                    ") is not a spring of the object; every edge needs one"),
            std::min(i, j), -1);
    }
  }
  return measure;
}

/// Whether none of the element's springs is broken: it still acts.
template <int Dim, class Element>
bool no_spring_broken(const MassSpringSystem<Dim>& s, const Element& element) {
  return std::none_of(element.springs.begin(), element.springs.end(),
                      [&](int k) { return s.springs[k].broken; });
}

/// The columns of x (Dim x n) at the element's nodes, in its node order.
template <int Dim, std::size_t N>
std::array<Eigen::Matrix<double, Dim, 1>, N> gather(
    const std::array<int, N>& nodes, const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x) {
  std::array<Eigen::Matrix<double, Dim, 1>, N> out;
  for (std::size_t a = 0; a < N; ++a) out[a] = x.col(nodes[a]);
  return out;
}

}  // namespace gencoord::deformable::detail
