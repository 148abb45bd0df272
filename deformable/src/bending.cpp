// SPDX-License-Identifier: BSD-3-Clause
// Dihedral-angle bending hinges: angle, gradient, energy, forces, Jacobian, frequency bound
// (bending.hpp).
#include "gencoord/deformable/bending.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gencoord::deformable {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;
}  // namespace

HingeAngle hinge_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  HingeAngle out;
  for (Eigen::Vector3d& g : out.gradient) g.setZero();
  const Eigen::Vector3d e = x1 - x0;
  const Eigen::Vector3d na = e.cross(x2 - x0);
  const Eigen::Vector3d nb = (x0 - x1).cross(x3 - x1);
  const double l2 = e.squaredNorm(), a2 = na.squaredNorm(), b2 = nb.squaredNorm();
  if (!(l2 > 0.0 && a2 > 0.0 && b2 > 0.0)) {
    out.degenerate = true;
    return out;
  }
  const double l = std::sqrt(l2);
  out.angle = std::atan2(na.cross(nb).dot(e) / l, na.dot(nb));
  // the wings move along their triangle's normal, by 1 / height per radian; the edge's nodes
  // take the opposite, shared by where each wing sits along the edge (no force, no torque)
  out.gradient[2] = (-l / a2) * na;
  out.gradient[3] = (-l / b2) * nb;
  const double sa = (x2 - x0).dot(e) / l2, sb = (x3 - x0).dot(e) / l2;
  out.gradient[0] = -(1.0 - sa) * out.gradient[2] - (1.0 - sb) * out.gradient[3];
  out.gradient[1] = -sa * out.gradient[2] - sb * out.gradient[3];
  return out;
}

double angle_change(double angle, double rest_angle) {
  return std::remainder(angle - rest_angle, kTwoPi);
}

template <int Dim>
bool hinge_active(const MassSpringSystem<Dim>& s, const Hinge& h) {
  return h.spring < 0 || !s.springs[h.spring].broken;
}

namespace {
HingeAngle angle_at(const Hinge& h, const Eigen::Matrix3Xd& x) {
  return hinge_angle(x.col(h.nodes[0]), x.col(h.nodes[1]), x.col(h.nodes[2]), x.col(h.nodes[3]));
}
}  // namespace

double hinge_energy(const Hinge& h, const Eigen::Matrix3Xd& x) {
  const HingeAngle a = angle_at(h, x);
  if (a.degenerate) return 0.0;
  const double change = angle_change(a.angle, h.rest_angle);
  return h.stiffness * change * change;
}

std::array<Eigen::Vector3d, 4> hinge_forces(const Hinge& h, const Eigen::Matrix3Xd& x) {
  const HingeAngle a = angle_at(h, x);
  const double scale =
      a.degenerate ? 0.0 : -2.0 * h.stiffness * angle_change(a.angle, h.rest_angle);
  std::array<Eigen::Vector3d, 4> f;
  for (int k = 0; k < 4; ++k) f[k] = scale * a.gradient[k];
  return f;
}

std::array<std::array<Eigen::Matrix3d, 4>, 4> hinge_jacobian(const Hinge& h,
                                                             const Eigen::Matrix3Xd& x) {
  const HingeAngle a = angle_at(h, x);  // a degenerate hinge has a zero gradient
  std::array<std::array<Eigen::Matrix3d, 4>, 4> jac;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c)
      jac[r][c] = (-2.0 * h.stiffness) * a.gradient[r] * a.gradient[c].transpose();
  }
  return jac;
}

template <int Dim>
void accumulate_bending_forces(const MassSpringSystem<Dim>& s,
                               const typename MassSpringSystem<Dim>::Points& x,
                               typename MassSpringSystem<Dim>::Points& f) {
  if constexpr (Dim == 3) {
    for (const Hinge& h : s.hinges) {
      if (!hinge_active(s, h)) continue;
      const std::array<Eigen::Vector3d, 4> hf = hinge_forces(h, x);
      for (int k = 0; k < 4; ++k) f.col(h.nodes[k]) += hf[k];
    }
  }
}

template <int Dim>
double bending_energy(const MassSpringSystem<Dim>& s,
                      const typename MassSpringSystem<Dim>::Points& x) {
  double e = 0.0;
  if constexpr (Dim == 3) {
    for (const Hinge& h : s.hinges) {
      if (hinge_active(s, h)) e += hinge_energy(h, x);
    }
  }
  return e;
}

template <int Dim>
void add_bending_jacobian(const MassSpringSystem<Dim>& s,
                          const typename MassSpringSystem<Dim>::Points& x,
                          const std::vector<int>& dof,
                          std::vector<Eigen::Triplet<double>>* triplets) {
  if constexpr (Dim == 3) {
    for (const Hinge& h : s.hinges) {
      if (!hinge_active(s, h)) continue;
      const auto jac = hinge_jacobian(h, x);
      for (int a = 0; a < 4; ++a) {
        const int ra = dof[h.nodes[a]];
        if (ra < 0) continue;
        for (int b = 0; b < 4; ++b) {
          const int cb = dof[h.nodes[b]];
          if (cb < 0) continue;
          for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) triplets->emplace_back(ra + r, cb + c, jac[a][b](r, c));
          }
        }
      }
    }
  }
}

double bending_frequency_bound(const MassSpringSystem<3>& s) {
  // block Gershgorin on M^-1/2 K_b M^-1/2, K_b = sum_h 2 kb g g^T: row k's blocks have norms
  // 2 kb |g_k| |g_j| / sqrt(m_k m_j); pinned nodes have no row or column
  std::vector<double> rows(s.num_nodes(), 0.0);
  for (const Hinge& h : s.hinges) {
    if (!hinge_active(s, h)) continue;
    const HingeAngle a = angle_at(h, s.x);
    std::array<double, 4> scaled{};
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      const int n = h.nodes[k];
      scaled[k] = s.pinned[n] ? 0.0 : a.gradient[k].norm() / std::sqrt(s.mass(n));
      sum += scaled[k];
    }
    for (int k = 0; k < 4; ++k) rows[h.nodes[k]] += 2.0 * h.stiffness * scaled[k] * sum;
  }
  const double largest = rows.empty() ? 0.0 : *std::max_element(rows.begin(), rows.end());
  return std::sqrt(largest);
}

#define GENCOORD_INSTANTIATE(D)                                                                \
  template bool hinge_active<D>(const MassSpringSystem<D>&, const Hinge&);                     \
  template void accumulate_bending_forces<D>(const MassSpringSystem<D>&,                       \
                                             const MassSpringSystem<D>::Points&,               \
                                             MassSpringSystem<D>::Points&);                    \
  template double bending_energy<D>(const MassSpringSystem<D>&,                                \
                                    const MassSpringSystem<D>::Points&);                       \
  template void add_bending_jacobian<D>(                                                       \
      const MassSpringSystem<D>&, const MassSpringSystem<D>::Points&, const std::vector<int>&, \
      std::vector<Eigen::Triplet<double>>*);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
