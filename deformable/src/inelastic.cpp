// SPDX-License-Identifier: BSD-3-Clause
// Brittle fracture and plasticity.
#include "gencoord/deformable/inelastic.hpp"

#include <cmath>

namespace gencoord::deformable {

template <int Dim>
int apply_fracture_and_plasticity(MassSpringSystem<Dim>& s) {
  const InelasticParams& p = s.inelastic;
  if (std::isinf(p.fracture_strain) && std::isinf(p.yield_strain)) return 0;  // fast path
  int broken = 0;
  for (int k = 0; k < static_cast<int>(s.springs.size()); ++k) {
    Spring& sp = s.springs[k];
    if (sp.broken) continue;
    typename MassSpringSystem<Dim>::Vec n;
    double length = 0.0;
    spring_direction<Dim>(s.x.col(sp.j) - s.x.col(sp.i), &n, &length);
    const double strain = (length - sp.params.rest_length) / sp.params.rest_length;
    if (strain > p.fracture_strain) {
      sp.broken = true;
      s.fractures.push_back({s.t, s.steps, k, strain});
      ++broken;
    } else if (std::abs(strain) > p.yield_strain) {
      // move the rest length part of the way toward the current length
      sp.params.rest_length += p.plastic_fraction * (length - sp.params.rest_length);
    }
  }
  return broken;
}

template int apply_fracture_and_plasticity<1>(MassSpringSystem<1>&);
template int apply_fracture_and_plasticity<2>(MassSpringSystem<2>&);
template int apply_fracture_and_plasticity<3>(MassSpringSystem<3>&);

}  // namespace gencoord::deformable
