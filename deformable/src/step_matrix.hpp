// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler's step matrix A = M - dt D - dt^2 K over the free nodes of a mass-spring
// object, kept between steps: its sparsity pattern is built once per set of springs and
// pinned nodes, and each step writes the values into it in place. Private to the library.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "contact_forces.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable::detail {

/// The contacts at positions q, as the sorted list of the nodes in them: the nodes below the
/// ground, then those of `blocks` (contact_jacobians() at q), offset by the node count.
template <int Dim>
std::vector<int> contact_set(const MassSpringSystem<Dim>& s,
                             const typename MassSpringSystem<Dim>::Points& q,
                             const std::vector<ContactJacobian<Dim>>& blocks);

template <int Dim>
class StepMatrix {
 public:
  using Points = typename MassSpringSystem<Dim>::Points;

  /// Whether the pattern was built for these springs (nodes, broken flags), hinges (nodes)
  /// and pinned nodes.
  bool matches(const MassSpringSystem<Dim>& s) const;

  /// Builds the pattern of `s` (values zero): the Dim x Dim diagonal block of every free node
  /// (so a ground contact that starts or ends does not change it), the four blocks of every
  /// unbroken spring and the sixteen of every active hinge between free nodes, both
  /// triangles; and where each block's entries lie in the value array.
  void build(const MassSpringSystem<Dim>& s);

  /// Writes A at (q, v) into the pattern (definite spring and volume term Jacobians, the
  /// hinges' Gauss-Newton blocks, the ground penalty while it pushes, the contacts' diagonal
  /// blocks), the free masses into `masses`, and K v over the free nodes (v of the pinned
  /// ones left out, as their motion is in the force at their end positions) into `k_v`.
  void assemble(const MassSpringSystem<Dim>& s, const Points& q, const Points& v, double dt,
                Eigen::VectorXd* masses, Eigen::VectorXd* k_v);

  /// Writes -K at q into the pattern, K the stiffness of the springs (definite), volume terms,
  /// continuum elements and hinges, without mass, damping, ground or contacts (so contacts()
  /// keeps its value); the free masses into `masses`.
  void assemble_stiffness(const MassSpringSystem<Dim>& s, const Points& q, Eigen::VectorXd* masses);

  const Eigen::SparseMatrix<double>& matrix() const { return a_; }
  /// The contacts the last assemble() included, as contact_set() of its (q, v).
  const std::vector<int>& contacts() const { return contacts_; }
  /// First free unknown of node n, -1 if it is pinned.
  int dof(int n) const { return dof_[n]; }
  int unknowns() const { return static_cast<int>(a_.rows()); }

 private:
  struct Scales {
    double mass, damping, stiffness;  // A = mass M - damping D - stiffness K
    bool penalties;                   // the ground's and the contacts' terms too
  };
  void fill(const MassSpringSystem<Dim>& s, const Points& q, const Points& v, const Scales& scales,
            Eigen::VectorXd* masses, Eigen::VectorXd* k_v);
  // where the (a, b) block of node rows a and node columns b starts in column c of the block
  int slot(int a, int b, int c) const;

  Eigen::SparseMatrix<double> a_;
  std::vector<int> contacts_;
  std::vector<int> dof_;
  std::vector<char> pinned_;
  std::vector<int> spring_nodes_;  // i, j and broken of each spring, as built
  // per spring, 4 blocks (ii, jj, ij, ji) x Dim columns: index of the block column's first
  // entry in a_'s values, -1 where the block is not stored (a pinned node)
  std::vector<int> spring_slots_;
  std::vector<int> diagonal_slots_;  // index of (k, k) in a_'s values, per unknown
  std::vector<int> hinge_nodes_;     // the 4 nodes of each hinge, as built
  // per hinge, 16 blocks (a, b over its nodes) x Dim columns, as spring_slots_
  std::vector<int> hinge_slots_;
};

}  // namespace gencoord::deformable::detail
