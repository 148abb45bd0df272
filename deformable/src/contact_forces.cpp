// SPDX-License-Identifier: BSD-3-Clause
// Contact with obstacles and between surface simplices (collision.hpp).
#include "contact_forces.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "closest_point.hpp"
#include "spatial_hash.hpp"

namespace gencoord::deformable::detail {

namespace {

// A node touching an obstacle (no corners) or a surface simplex (its corners and the closest
// point's weights), pushed along `normal` by a penalty of `depth` per unit `mass`.
template <int Dim>
struct Contact {
  int node = 0;
  int num_corners = 0;
  std::array<int, Dim> corners{};
  std::array<double, Dim> weights{};
  Eigen::Matrix<double, Dim, 1> normal;
  double depth = 0.0;
  double mass = 0.0;
};

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

// a unit normal of a simplex (its orientation's), for a node lying exactly on it
template <int Dim>
Vec<Dim> simplex_normal(const typename MassSpringSystem<Dim>::Points& x,
                        const std::array<int, Dim>& simplex) {
  Vec<Dim> n;
  if constexpr (Dim == 3) {
    n = (x.col(simplex[1]) - x.col(simplex[0])).cross(x.col(simplex[2]) - x.col(simplex[0]));
  } else {
    const Vec<Dim> along = x.col(simplex[1]) - x.col(simplex[0]);
    n = Vec<Dim>(along(1), -along(0));  // to the right of the segment: out of a CCW boundary
  }
  const double norm = n.norm();
  return norm > 0.0 ? Vec<Dim>(n / norm) : Vec<Dim>::UnitX();
}

template <int Dim>
std::array<double, Dim> closest_weights(const typename MassSpringSystem<Dim>::Points& x, int node,
                                        const std::array<int, Dim>& simplex) {
  if constexpr (Dim == 3) {
    return closest_on_triangle(x.col(node), x.col(simplex[0]), x.col(simplex[1]),
                               x.col(simplex[2]));
  } else {
    return closest_on_segment<Dim>(x.col(node), x.col(simplex[0]), x.col(simplex[1]));
  }
}

// a node inside an obstacle: its depth and outward normal, false when it is outside
template <int Dim>
bool inside_sphere(const SphereObstacle<Dim>& sphere, const Vec<Dim>& p, Vec<Dim>* normal,
                   double* depth) {
  const Vec<Dim> from_center = p - sphere.center;
  const double distance = from_center.norm();
  *depth = sphere.radius - distance;
  if (*depth <= 0.0) return false;
  *normal = distance > 0.0 ? Vec<Dim>(from_center / distance) : Vec<Dim>::UnitX();
  return true;
}

template <int Dim>
bool inside_box(const BoxObstacle<Dim>& box, const Vec<Dim>& p, Vec<Dim>* normal, double* depth) {
  *depth = std::numeric_limits<double>::infinity();
  for (int d = 0; d < Dim; ++d) {
    const double below = p(d) - box.lower(d), above = box.upper(d) - p(d);
    if (below <= 0.0 || above <= 0.0) return false;
    // the nearest face pushes; ties go to the upper face, so a box resting on it stays on top
    if (above <= *depth) {
      *depth = above;
      *normal = Vec<Dim>::Unit(d);
    }
    if (below < *depth) {
      *depth = below;
      *normal = -Vec<Dim>::Unit(d);
    }
  }
  return true;
}

// calls visit(contact) for every contact at positions x, in a fixed order
template <int Dim, class Visit>
void for_each_contact(const MassSpringSystem<Dim>& s,
                      const typename MassSpringSystem<Dim>::Points& x, Visit&& visit) {
  if (!s.collisions) return;
  const Collisions<Dim>& c = *s.collisions;
  Contact<Dim> contact;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.pinned[n]) continue;  // a pinned node ignores forces
    contact.node = n;
    contact.num_corners = 0;
    contact.mass = s.mass(n);
    const Vec<Dim> p = x.col(n);
    for (const auto& sphere : c.spheres) {
      if (inside_sphere(sphere, p, &contact.normal, &contact.depth)) visit(contact);
    }
    for (const auto& box : c.boxes) {
      if (inside_box(box, p, &contact.normal, &contact.depth)) visit(contact);
    }
  }
  // each simplex's thickness; the hash's margin the largest
  auto thickness = [&](std::size_t k) {
    return c.surface_thickness.empty() ? c.params.thickness : c.surface_thickness[k];
  };
  double thickest = c.params.thickness;
  for (const double h : c.surface_thickness) thickest = std::max(thickest, h);
  if (c.surface.empty() || !(thickest > 0.0)) return;
  std::vector<int> nodes;
  for (const auto& simplex : c.surface) nodes.insert(nodes.end(), simplex.begin(), simplex.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  SimplexHash<Dim> hash;
  hash.build(x, c.surface, thickest);
  contact.num_corners = Dim;
  for (const int n : nodes) {
    const Vec<Dim> p = x.col(n);
    hash.for_each_candidate(p, [&](int k) {
      const std::array<int, Dim>& simplex = c.surface[k];
      const double h = thickness(k);
      if (!(h > 0.0) || std::find(simplex.begin(), simplex.end(), n) != simplex.end()) return;
      const std::array<double, Dim> w = closest_weights<Dim>(x, n, simplex);
      Vec<Dim> closest = Vec<Dim>::Zero();
      bool all_pinned = s.pinned[n] != 0, inside_face = true;
      double corner_mass = 0.0;
      for (int a = 0; a < Dim; ++a) {
        closest += w[a] * x.col(simplex[a]);
        corner_mass += w[a] * s.mass(simplex[a]);
        all_pinned = all_pinned && (w[a] == 0.0 || s.pinned[simplex[a]]);
        inside_face = inside_face && w[a] > 0.0;
      }
      if (all_pinned) return;
      const Vec<Dim> gap = p - closest;
      const double distance = gap.norm();
      const Vec<Dim> outward = simplex_normal<Dim>(x, simplex);
      const bool one_sided = c.two_sided.empty() || !c.two_sided[k];
      if (one_sided && gap.dot(outward) < 0.0) {
        // behind a one-sided face: pushed back out while over its face and within h
        if (!inside_face || distance >= h) return;
        contact.normal = -gap / distance;
        contact.depth = h + distance;
      } else {
        if (distance >= h) return;
        contact.normal = distance > 0.0 ? Vec<Dim>(gap / distance) : outward;
        contact.depth = h - distance;
      }
      contact.node = n;
      contact.corners = simplex;
      contact.weights = w;
      // a pinned node may have no mass: the simplex's then sets the penalty
      contact.mass = s.mass(n) > 0.0 ? s.mass(n) : corner_mass;
      visit(contact);
    });
  }
}

// the node's velocity relative to what it touches
template <int Dim>
Vec<Dim> relative_velocity(const Contact<Dim>& contact,
                           const typename MassSpringSystem<Dim>::Points& v) {
  Vec<Dim> relative = v.col(contact.node);
  for (int a = 0; a < contact.num_corners; ++a)
    relative -= contact.weights[a] * v.col(contact.corners[a]);
  return relative;
}

// normal and friction accelerations (per unit mass) of one contact; a_n = 0 when it pulls
template <int Dim>
void contact_acceleration(const ContactParams& p, const Contact<Dim>& contact,
                          const Vec<Dim>& relative, double* a_n, double* drag, Vec<Dim>* a) {
  const double v_n = relative.dot(contact.normal);
  *a_n = p.omega * p.omega * contact.depth - 2.0 * p.damping_ratio * p.omega * v_n;
  *drag = 0.0;
  if (*a_n <= 0.0) {
    *a_n = 0.0;
    a->setZero();
    return;
  }
  const Vec<Dim> v_t = relative - v_n * contact.normal;
  const double speed = v_t.norm();
  if (speed > 0.0) *drag = std::min(p.friction * *a_n / speed, p.omega);
  *a = *a_n * contact.normal - *drag * v_t;
}

// calls visit(contact, drag, a) for every contact that pushes at (x, v): its friction drag
// rate and its acceleration per unit mass (normal and friction)
template <int Dim, class Visit>
void for_each_pushing_contact(const MassSpringSystem<Dim>& s,
                              const typename MassSpringSystem<Dim>::Points& x,
                              const typename MassSpringSystem<Dim>::Points& v, Visit&& visit) {
  if (!s.collisions) return;
  const ContactParams& p = s.collisions->params;
  for_each_contact<Dim>(s, x, [&](const Contact<Dim>& contact) {
    double a_n = 0.0, drag = 0.0;
    Vec<Dim> a;
    contact_acceleration(p, contact, relative_velocity(contact, v), &a_n, &drag, &a);
    if (a_n > 0.0) visit(contact, drag, a);
  });
}

}  // namespace

template <int Dim>
void add_contact_forces(const MassSpringSystem<Dim>& s,
                        const typename MassSpringSystem<Dim>::Points& x,
                        const typename MassSpringSystem<Dim>::Points& v,
                        typename MassSpringSystem<Dim>::Points& f) {
  for_each_pushing_contact<Dim>(s, x, v,
                                [&](const Contact<Dim>& contact, double, const Vec<Dim>& a) {
                                  const Vec<Dim> force = contact.mass * a;
                                  f.col(contact.node) += force;
                                  for (int k = 0; k < contact.num_corners; ++k)
                                    f.col(contact.corners[k]) -= contact.weights[k] * force;
                                });
}

template <int Dim>
double contact_energy(const MassSpringSystem<Dim>& s,
                      const typename MassSpringSystem<Dim>::Points& x) {
  if (!s.collisions) return 0.0;
  const double omega = s.collisions->params.omega;
  double energy = 0.0;
  for_each_contact<Dim>(s, x, [&](const Contact<Dim>& contact) {
    energy += 0.5 * contact.mass * omega * omega * contact.depth * contact.depth;
  });
  return energy;
}

template <int Dim>
std::vector<ContactJacobian<Dim>> contact_jacobians(
    const MassSpringSystem<Dim>& s, const typename MassSpringSystem<Dim>::Points& x,
    const typename MassSpringSystem<Dim>::Points& v) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  std::vector<ContactJacobian<Dim>> out;
  if (!s.collisions) return out;
  const ContactParams& p = s.collisions->params;
  for_each_pushing_contact<Dim>(
      s, x, v, [&](const Contact<Dim>& contact, double drag, const Vec<Dim>&) {
        // the normal's turning is left out; friction counts as the viscous drag it is below
        // its slip speed
        const Mat nn = contact.normal * contact.normal.transpose();
        const Mat k = -contact.mass * p.omega * p.omega * nn;
        const Mat d =
            -contact.mass * (2.0 * p.damping_ratio * p.omega * nn + drag * (Mat::Identity() - nn));
        // |u|_1 |u_i| of the header's bound: 2 for the node and 2 w_a for corner a
        const double node_scale = contact.num_corners > 0 ? 2.0 : 1.0;
        out.push_back({contact.node, node_scale * k, node_scale * d});
        for (int c = 0; c < contact.num_corners; ++c) {
          const double scale = 2.0 * contact.weights[c];
          if (scale > 0.0) out.push_back({contact.corners[c], scale * k, scale * d});
        }
      });
  return out;
}

#define GENCOORD_INSTANTIATE(D)                                          \
  template void add_contact_forces<D>(                                   \
      const MassSpringSystem<D>&, const MassSpringSystem<D>::Points&,    \
      const MassSpringSystem<D>::Points&, MassSpringSystem<D>::Points&); \
  template double contact_energy<D>(const MassSpringSystem<D>&,          \
                                    const MassSpringSystem<D>::Points&); \
  template std::vector<ContactJacobian<D>> contact_jacobians<D>(         \
      const MassSpringSystem<D>&, const MassSpringSystem<D>::Points&,    \
      const MassSpringSystem<D>::Points&);
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable::detail
