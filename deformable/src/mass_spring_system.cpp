// SPDX-License-Identifier: BSD-3-Clause
// Forces and energies of a mass-spring system.
#include "gencoord/deformable/mass_spring_system.hpp"

#include <algorithm>
#include <cmath>

#include "contact_forces.hpp"
#include "gencoord/deformable/bending.hpp"

namespace gencoord::deformable {

template <int Dim>
int MassSpringSystem<Dim>::num_unbroken_springs() const {
  return static_cast<int>(
      std::count_if(springs.begin(), springs.end(), [](const Spring& sp) { return !sp.broken; }));
}

template <int Dim>
void accumulate_forces(const MassSpringSystem<Dim>& s,
                       Eigen::Matrix<double, Dim, Eigen::Dynamic>& f) {
  accumulate_forces(s, s.x, s.v, f);
}

template <int Dim>
void accumulate_forces(const MassSpringSystem<Dim>& s,
                       const typename MassSpringSystem<Dim>::Points& x,
                       const typename MassSpringSystem<Dim>::Points& v,
                       Eigen::Matrix<double, Dim, Eigen::Dynamic>& f) {
  // springs and dampers: equal and opposite on the two nodes
  for (const Spring& sp : s.springs) {
    if (sp.broken) continue;
    const SpringForce<Dim> sf =
        spring_force<Dim>(x.col(sp.i), x.col(sp.j), v.col(sp.i), v.col(sp.j), sp.params);
    f.col(sp.i) += sf.f_i;
    f.col(sp.j) -= sf.f_i;
  }
  accumulate_volume_term_forces(s, x, f);
  accumulate_continuum_forces(s, x, v, f);
  accumulate_bending_forces(s, x, f);  // hinges (3D sheets)
  // gravity
  for (int n = 0; n < s.num_nodes(); ++n) f.col(n) += s.mass(n) * s.gravity;
  // ground penalty along the last axis, pushing only
  if (s.ground) {
    const GroundPlane& g = *s.ground;
    constexpr int up = Dim - 1;
    for (int n = 0; n < s.num_nodes(); ++n) {
      const double depth = g.height - x(up, n);
      if (depth <= 0.0) continue;
      const double push =
          s.mass(n) * (g.omega * g.omega * depth - 2.0 * g.damping_ratio * g.omega * v(up, n));
      f(up, n) += std::max(0.0, push);
    }
  }
  if constexpr (Dim > 1) detail::add_contact_forces<Dim>(s, x, v, f);
}

template <int Dim>
double kinetic_energy(const MassSpringSystem<Dim>& s) {
  double e = 0.0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (!s.pinned[n]) e += 0.5 * s.mass(n) * s.v.col(n).squaredNorm();
  }
  return e;
}

template <int Dim>
double potential_energy(const MassSpringSystem<Dim>& s) {
  double e = 0.0;
  for (const Spring& sp : s.springs) {
    if (sp.broken) continue;
    typename MassSpringSystem<Dim>::Vec n;
    double length = 0.0;
    spring_direction<Dim>(s.x.col(sp.j) - s.x.col(sp.i), &n, &length);
    e += spring_energy(length, sp.params);
  }
  e += volume_terms_energy(s);
  e += continuum_energy(s);
  e += bending_energy(s, s.x);  // hinges (3D sheets)
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.pinned[n]) continue;
    e -= s.mass(n) * s.gravity.dot(s.x.col(n));
    if (s.ground) {
      // the undamped part of the penalty force derives from this potential
      const double depth = s.ground->height - s.x(Dim - 1, n);
      if (depth > 0.0) e += 0.5 * s.mass(n) * s.ground->omega * s.ground->omega * depth * depth;
    }
  }
  if constexpr (Dim > 1) e += detail::contact_energy<Dim>(s, s.x);
  return e;
}

template <int Dim>
double min_rest_length(const MassSpringSystem<Dim>& s) {
  double l_min = std::numeric_limits<double>::infinity();
  for (const Spring& sp : s.springs) {
    if (!sp.broken) l_min = std::min(l_min, sp.params.rest_length);
  }
  return l_min;
}

template <int Dim>
void with_ground(MassSpringSystem<Dim>& s, double height, double damping_ratio) {
  GroundPlane g;
  g.height = height;
  g.omega = 0.5 * s.wave_speed / min_rest_length(s);
  g.damping_ratio = damping_ratio;
  s.ground = g;
}

#define GENCOORD_INSTANTIATE(D)                                                       \
  template struct MassSpringSystem<D>;                                                \
  template void accumulate_forces<D>(const MassSpringSystem<D>&,                      \
                                     Eigen::Matrix<double, D, Eigen::Dynamic>&);      \
  template void accumulate_forces<D>(                                                 \
      const MassSpringSystem<D>&, const MassSpringSystem<D>::Points&,                 \
      const MassSpringSystem<D>::Points&, Eigen::Matrix<double, D, Eigen::Dynamic>&); \
  template double kinetic_energy<D>(const MassSpringSystem<D>&);                      \
  template double potential_energy<D>(const MassSpringSystem<D>&);                    \
  template double min_rest_length<D>(const MassSpringSystem<D>&);                     \
  template void with_ground<D>(MassSpringSystem<D>&, double, double);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
