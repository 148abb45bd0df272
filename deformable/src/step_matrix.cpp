// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler's step matrix, kept between steps (step_matrix.hpp).
#include "step_matrix.hpp"

#include <algorithm>
#include <cstddef>

#include "contact_forces.hpp"
#include "gencoord/deformable/bending.hpp"
#include "gencoord/deformable/volume_terms.hpp"

namespace gencoord::deformable::detail {

template <int Dim>
bool StepMatrix<Dim>::matches(const MassSpringSystem<Dim>& s) const {
  if (s.pinned != pinned_ || spring_nodes_.size() != 3 * s.springs.size()) return false;
  for (std::size_t k = 0; k < s.springs.size(); ++k) {
    const Spring& sp = s.springs[k];
    if (spring_nodes_[3 * k] != sp.i || spring_nodes_[3 * k + 1] != sp.j ||
        spring_nodes_[3 * k + 2] != static_cast<int>(sp.broken))
      return false;
  }
  if (hinge_nodes_.size() != 4 * s.hinges.size()) return false;
  for (std::size_t k = 0; k < s.hinges.size(); ++k) {
    if (!std::equal(s.hinges[k].nodes.begin(), s.hinges[k].nodes.end(), &hinge_nodes_[4 * k]))
      return false;
  }
  return true;
}

template <int Dim>
int StepMatrix<Dim>::slot(int a, int b, int c) const {
  if (dof_[a] < 0 || dof_[b] < 0) return -1;
  const int column = dof_[b] + c;
  const int* begin = a_.innerIndexPtr() + a_.outerIndexPtr()[column];
  const int* end = a_.innerIndexPtr() + a_.outerIndexPtr()[column + 1];
  // the block's Dim rows are consecutive in the sorted column
  return static_cast<int>(std::lower_bound(begin, end, dof_[a]) - a_.innerIndexPtr());
}

template <int Dim>
void StepMatrix<Dim>::build(const MassSpringSystem<Dim>& s) {
  const int count = s.num_nodes();
  pinned_ = s.pinned;
  dof_.assign(count, -1);
  int unknowns = 0;
  for (int n = 0; n < count; ++n) {
    if (!s.pinned[n]) {
      dof_[n] = unknowns;
      unknowns += Dim;
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(unknowns) * Dim + s.springs.size() * 2 * Dim * Dim);
  auto add_block = [&](int a, int b) {
    if (dof_[a] < 0 || dof_[b] < 0) return;
    for (int c = 0; c < Dim; ++c) {
      for (int r = 0; r < Dim; ++r) entries.emplace_back(dof_[a] + r, dof_[b] + c, 0.0);
    }
  };
  for (int n = 0; n < count; ++n) add_block(n, n);
  spring_nodes_.clear();
  spring_nodes_.reserve(3 * s.springs.size());
  for (const Spring& sp : s.springs) {
    spring_nodes_.insert(spring_nodes_.end(), {sp.i, sp.j, static_cast<int>(sp.broken)});
    if (sp.broken) continue;
    add_block(sp.i, sp.j);
    add_block(sp.j, sp.i);
  }
  // a hinge couples its four nodes, also its two wings, which no spring joins
  hinge_nodes_.clear();
  for (const Hinge& h : s.hinges) {
    hinge_nodes_.insert(hinge_nodes_.end(), h.nodes.begin(), h.nodes.end());
    if (!hinge_active(s, h)) continue;
    for (int a : h.nodes) {
      for (int b : h.nodes) add_block(a, b);
    }
  }
  a_.resize(unknowns, unknowns);
  a_.setFromTriplets(entries.begin(), entries.end());  // duplicates (parallel springs) summed
  a_.makeCompressed();

  spring_slots_.assign(s.springs.size() * 4 * Dim, -1);
  for (std::size_t k = 0; k < s.springs.size(); ++k) {
    const Spring& sp = s.springs[k];
    if (sp.broken) continue;
    const int blocks[4][2] = {{sp.i, sp.i}, {sp.j, sp.j}, {sp.i, sp.j}, {sp.j, sp.i}};
    for (int blk = 0; blk < 4; ++blk) {
      for (int c = 0; c < Dim; ++c)
        spring_slots_[(k * 4 + blk) * Dim + c] = slot(blocks[blk][0], blocks[blk][1], c);
    }
  }
  hinge_slots_.assign(s.hinges.size() * 16 * Dim, -1);
  for (std::size_t k = 0; k < s.hinges.size(); ++k) {
    const Hinge& h = s.hinges[k];
    if (!hinge_active(s, h)) continue;
    for (int blk = 0; blk < 16; ++blk) {
      for (int c = 0; c < Dim; ++c)
        hinge_slots_[(k * 16 + blk) * Dim + c] = slot(h.nodes[blk / 4], h.nodes[blk % 4], c);
    }
  }
  diagonal_slots_.resize(unknowns);
  for (int n = 0; n < count; ++n) {
    if (dof_[n] < 0) continue;
    for (int c = 0; c < Dim; ++c) diagonal_slots_[dof_[n] + c] = slot(n, n, c) + c;
  }
}

template <int Dim>
void StepMatrix<Dim>::assemble(const MassSpringSystem<Dim>& s, const Points& q, const Points& v,
                               double dt, Eigen::VectorXd* masses, Eigen::VectorXd* k_v) {
  fill(s, q, v, {1.0, dt, dt * dt, true}, masses, k_v);
}

template <int Dim>
void StepMatrix<Dim>::assemble_stiffness(const MassSpringSystem<Dim>& s, const Points& q,
                                         Eigen::VectorXd* masses) {
  Eigen::VectorXd k_v;
  fill(s, q, Points::Zero(Dim, s.num_nodes()), {0.0, 0.0, 1.0, false}, masses, &k_v);
}

template <int Dim>
void StepMatrix<Dim>::fill(const MassSpringSystem<Dim>& s, const Points& q, const Points& v,
                           const Scales& scales, Eigen::VectorXd* masses, Eigen::VectorXd* k_v) {
  // A = scales.mass M - scales.damping D - scales.stiffness K (dt and dt^2 for a step)
  const double h_d = scales.damping, h_k = scales.stiffness;
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Block = Eigen::Matrix<double, Dim, Dim>;
  double* values = a_.valuePtr();
  std::fill(values, values + a_.nonZeros(), 0.0);
  masses->resize(unknowns());
  k_v->setZero(unknowns());
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (dof_[n] < 0) continue;
    for (int c = 0; c < Dim; ++c) {
      (*masses)[dof_[n] + c] = s.mass(n);
      values[diagonal_slots_[dof_[n] + c]] = scales.mass * s.mass(n);
    }
  }
  // adds sign * block at the block's slots (one per column; its Dim rows follow)
  auto add = [&](const int* slots, double sign, const Block& block) {
    if (slots[0] < 0) return;
    for (int c = 0; c < Dim; ++c) {
      for (int r = 0; r < Dim; ++r) values[slots[c] + r] += sign * block(r, c);
    }
  };
  for (std::size_t k = 0; k < s.springs.size(); ++k) {
    const Spring& sp = s.springs[k];
    if (sp.broken) continue;
    const SpringForce<Dim> sf =
        spring_force<Dim>(q.col(sp.i), q.col(sp.j), v.col(sp.i), v.col(sp.j), sp.params);
    const SpringJacobian<Dim> jac = spring_jacobian<Dim>(sf, sp.params, /*definite=*/true);
    // K has -J at ii and jj and +J at ij and ji (springs.hpp), D the same with the damping J
    const Block c = h_d * jac.f_i_D_dv + h_k * jac.f_i_D_d;
    const int* slots = &spring_slots_[k * 4 * Dim];
    add(slots, 1.0, c);
    add(slots + Dim, 1.0, c);
    add(slots + 2 * Dim, -1.0, c);
    add(slots + 3 * Dim, -1.0, c);
    const int di = dof_[sp.i], dj = dof_[sp.j];
    const Vec vi = di >= 0 ? Vec(v.col(sp.i)) : Vec::Zero();
    const Vec vj = dj >= 0 ? Vec(v.col(sp.j)) : Vec::Zero();
    const Vec kv = jac.f_i_D_d * (vj - vi);
    if (di >= 0) k_v->template segment<Dim>(di) += kv;
    if (dj >= 0) k_v->template segment<Dim>(dj) -= kv;
  }
  // area and volume terms, definite: every node pair of an element is a spring, so each of
  // their blocks is one of the pattern's while the element acts
  for_each_volume_term_block(s, q, /*definite=*/true, [&](int a, int b, const Block& k_ab) {
    if (dof_[a] < 0 || dof_[b] < 0) return;
    for (int c = 0; c < Dim; ++c) {
      const int at = slot(a, b, c);
      for (int r = 0; r < Dim; ++r) values[at + r] -= h_k * k_ab(r, c);
    }
    k_v->template segment<Dim>(dof_[a]) += k_ab * v.col(b);
  });
  // continuum elements: as the volume terms, with their damping blocks
  for_each_continuum_block(s, q, [&](int a, int b, const Block& k_ab, const Block& d_ab) {
    if (dof_[a] < 0 || dof_[b] < 0) return;
    const Block c = h_d * d_ab + h_k * k_ab;
    for (int col = 0; col < Dim; ++col) {
      const int at = slot(a, b, col);
      for (int r = 0; r < Dim; ++r) values[at + r] -= c(r, col);
    }
    k_v->template segment<Dim>(dof_[a]) += k_ab * v.col(b);
  });
  // hinges: K_ab = -2 kb g_a g_b^T (bending.hpp), so A gets h_k 2 kb g_a g_b^T
  if constexpr (Dim == 3) {
    for (std::size_t k = 0; k < s.hinges.size(); ++k) {
      const Hinge& h = s.hinges[k];
      if (!hinge_active(s, h)) continue;
      const HingeAngle angle =
          hinge_angle(q.col(h.nodes[0]), q.col(h.nodes[1]), q.col(h.nodes[2]), q.col(h.nodes[3]));
      const double weight = 2.0 * h.stiffness;
      double g_v = 0.0;  // g . v over the free nodes
      for (int a = 0; a < 4; ++a) {
        if (dof_[h.nodes[a]] >= 0) g_v += angle.gradient[a].dot(v.col(h.nodes[a]));
      }
      for (int a = 0; a < 4; ++a) {
        const int da = dof_[h.nodes[a]];
        if (da < 0) continue;
        k_v->template segment<Dim>(da) -= (weight * g_v) * angle.gradient[a];
        for (int b = 0; b < 4; ++b) {
          add(&hinge_slots_[(k * 16 + a * 4 + b) * Dim], h_k * weight,
              angle.gradient[a] * angle.gradient[b].transpose());
        }
      }
    }
  }
  if (!scales.penalties) return;
  // ground contact: a penalty spring and damper along the up axis while it pushes
  if (s.ground) {
    const GroundPlane& g = *s.ground;
    constexpr int up = Dim - 1;
    for (int n = 0; n < s.num_nodes(); ++n) {
      if (dof_[n] < 0) continue;
      const double depth = g.height - q(up, n);
      const double push = g.omega * g.omega * depth - 2.0 * g.damping_ratio * g.omega * v(up, n);
      if (depth > 0.0 && push > 0.0) {
        const double stiffness = s.mass(n) * g.omega * g.omega;
        const double damping = s.mass(n) * 2.0 * g.damping_ratio * g.omega;
        values[diagonal_slots_[dof_[n] + up]] += h_d * damping + h_k * stiffness;
        (*k_v)[dof_[n] + up] -= stiffness * v(up, n);
      }
    }
  }
  // contacts: diagonal blocks that bound them from above, in the pattern whatever touches
  // what (collision.hpp)
  std::vector<ContactJacobian<Dim>> blocks;
  if constexpr (Dim > 1) blocks = contact_jacobians<Dim>(s, q, v);
  contacts_ = contact_set<Dim>(s, q, blocks);
  if constexpr (Dim > 1) {
    for (const auto& block : blocks) {
      const int d = dof_[block.node];
      if (d < 0) continue;
      const Block c = -(h_d * block.d_velocity + h_k * block.d_position);
      for (int col = 0; col < Dim; ++col) {
        const int column_start = diagonal_slots_[d + col] - col;
        for (int r = 0; r < Dim; ++r) values[column_start + r] += c(r, col);
      }
      k_v->template segment<Dim>(d) += block.d_position * v.col(block.node);
    }
  }
}

template <int Dim>
std::vector<int> contact_set(const MassSpringSystem<Dim>& s,
                             const typename MassSpringSystem<Dim>::Points& q,
                             const std::vector<ContactJacobian<Dim>>& blocks) {
  std::vector<int> nodes;
  if (s.ground) {
    for (int n = 0; n < s.num_nodes(); ++n) {
      if (q(Dim - 1, n) < s.ground->height) nodes.push_back(n);
    }
  }
  for (const auto& block : blocks) nodes.push_back(block.node + s.num_nodes());
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

template std::vector<int> contact_set<1>(const MassSpringSystem<1>&,
                                         const MassSpringSystem<1>::Points&,
                                         const std::vector<ContactJacobian<1>>&);
template std::vector<int> contact_set<2>(const MassSpringSystem<2>&,
                                         const MassSpringSystem<2>::Points&,
                                         const std::vector<ContactJacobian<2>>&);
template std::vector<int> contact_set<3>(const MassSpringSystem<3>&,
                                         const MassSpringSystem<3>::Points&,
                                         const std::vector<ContactJacobian<3>>&);
template class StepMatrix<1>;
template class StepMatrix<2>;
template class StepMatrix<3>;

}  // namespace gencoord::deformable::detail
