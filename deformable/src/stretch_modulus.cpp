// SPDX-License-Identifier: BSD-3-Clause
// A spring network's Young's modulus in a relaxed static stretch (stretch_modulus.hpp).
#include "gencoord/deformable/stretch_modulus.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/volume_terms.hpp"
#include "message.hpp"

namespace gencoord::deformable {

using detail::message;

namespace {
// the end zones held at the uniform strain, as a fraction of the length
constexpr double kEndFraction = 0.05;
}  // namespace

template <int Dim>
StretchResponse stretch_response(const MassSpringSystem<Dim>& s,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest,
                                 double measure, int axis) {
  using Block = Eigen::Matrix<double, Dim, Dim>;
  const int count = static_cast<int>(rest.cols());
  if (count != s.num_nodes())
    throw ObjectError(
        message("stretch: ", count, " rest positions for an object of ", s.num_nodes(),
                " nodes; give the rest positions of its own nodes (for quadratic "
                "elements, those of the quadratic mesh)"),
        -1, -1);
  const double low = rest.row(axis).minCoeff(), high = rest.row(axis).maxCoeff();
  const double length = high - low, end = kEndFraction * length;
  const double eps = 1e-6;
  // unknowns: every coordinate but the axis coordinate of the nodes in the end zones, which
  // move with the uniform strain eps (so the strain between the zones is eps too)
  std::vector<int> index(static_cast<std::size_t>(Dim) * count, -1);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(Dim * count);
  int unknowns = 0;
  for (int n = 0; n < count; ++n) {
    const double p = rest(axis, n);
    for (int d = 0; d < Dim; ++d) {
      if (d == axis && (p <= low + end || p >= high - end)) {
        u(Dim * n + d) = eps * (p - low);
      } else {
        index[Dim * n + d] = unknowns++;
      }
    }
  }
  // K = -df/dx at rest, block by block: the springs' (k / L) n n^T and the volume terms'
  std::vector<Block> spring_blocks;
  spring_blocks.reserve(s.springs.size());
  for (const Spring& sp : s.springs) {
    const Eigen::Matrix<double, Dim, 1> d = rest.col(sp.j) - rest.col(sp.i);
    spring_blocks.push_back(sp.broken ? Block::Zero()
                                      : Block((sp.params.stiffness / sp.params.rest_length) * d *
                                              d.transpose() / d.squaredNorm()));
  }
  auto for_each_block = [&](auto&& visit) {
    for (std::size_t k = 0; k < s.springs.size(); ++k) {
      const int i = s.springs[k].i, j = s.springs[k].j;
      visit(i, i, spring_blocks[k]);
      visit(j, j, spring_blocks[k]);
      visit(i, j, Block(-spring_blocks[k]));
      visit(j, i, Block(-spring_blocks[k]));
    }
    for_each_volume_term_block(s, rest, /*definite=*/true, [&](int a, int b, const Block& d_force) {
      visit(a, b, Block(-d_force));
    });
    for_each_continuum_block(s, rest, [&](int a, int b, const Block& d_force, const Block&) {
      visit(a, b, Block(-d_force));
    });
  };
  // K_ff u_f = -K_fp u_p
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
  double largest = 0.0;
  for_each_block([&](int a, int b, const Block& block) {
    for (int r = 0; r < Dim; ++r) {
      const int row = index[Dim * a + r];
      if (row < 0) continue;
      for (int c = 0; c < Dim; ++c) {
        const int column = index[Dim * b + c];
        if (column >= 0) {
          triplets.emplace_back(row, column, block(r, c));
          largest = std::max(largest, std::abs(block(r, c)));
        } else {
          rhs(row) -= block(r, c) * u(Dim * b + c);
        }
      }
    }
  });
  // the lateral rigid motions are free: a tiny diagonal fixes them without moving the rest
  for (int i = 0; i < unknowns; ++i) triplets.emplace_back(i, i, 1e-12 * largest);
  Eigen::SparseMatrix<double> k_ff(unknowns, unknowns);
  k_ff.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k_ff);
  const Eigen::VectorXd u_f = solver.solve(rhs);
  for (int i = 0; i < Dim * count; ++i) {
    if (index[i] >= 0) u(i) = u_f(index[i]);
  }
  // the force that holds the high end zone: (K u) along the axis summed over its nodes (the
  // zone's inner forces cancel in the sum, what the rest of the body pulls with remains)
  double force = 0.0;
  for_each_block([&](int a, int b, const Block& block) {
    if (rest(axis, a) >= high - end) force += block.row(axis).dot(u.template segment<Dim>(Dim * b));
  });
  if (!(force > 0.0))
    throw ObjectError("stretch_modulus: no spring carries a stretch from one end to the other", -1,
                      -1);
  StretchResponse out;
  out.youngs_modulus = force / (measure / length) / eps;
  // each lateral displacement's least-squares slope in its own coordinate over the middle
  // half of the length, where the ends' constraint has decayed
  double slopes = 0.0;
  for (int d = 0; d < Dim; ++d) {
    if (d == axis) continue;
    double n = 0.0, sp = 0.0, su = 0.0, spp = 0.0, spu = 0.0;
    for (int k = 0; k < count; ++k) {
      if (std::abs(rest(axis, k) - 0.5 * (low + high)) > 0.25 * length) continue;
      const double p = rest(d, k), disp = u(Dim * k + d);
      n += 1.0;
      sp += p;
      su += disp;
      spp += p * p;
      spu += p * disp;
    }
    slopes += (n * spu - sp * su) / (n * spp - sp * sp);
  }
  out.poisson_ratio = -slopes / (Dim - 1) / eps;
  return out;
}

template <int Dim>
double stretch_modulus(const MassSpringSystem<Dim>& s,
                       const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double measure,
                       int axis) {
  return stretch_response(s, rest, measure, axis).youngs_modulus;
}

template <int Dim>
double calibrate_to_stretch(MassSpringSystem<Dim>& s, const SimplexMesh<Dim>& mesh,
                            double youngs_modulus, int axis) {
  if (!(std::isfinite(youngs_modulus) && youngs_modulus > 0.0))
    throw MaterialError("calibrate_to_stretch: Young's modulus must be positive and finite");
  double measure = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e)
    measure += element_measure(mesh, e);
  const double factor = youngs_modulus / stretch_modulus(s, mesh.nodes, measure, axis);
  for (Spring& sp : s.springs) {
    sp.params.stiffness *= factor;
    sp.params.damping *= factor;
  }
  for (VolumeTerm<Dim>& term : s.volume_terms) term.stiffness *= factor;
  for (ContinuumElement<Dim>& element : s.elements) {
    element.mu *= factor;
    element.lambda *= factor;
  }
  for (QuadraticElement<Dim>& element : s.quadratic_elements) {
    element.mu *= factor;
    element.lambda *= factor;
  }
  s.wave_speed *= std::sqrt(factor);
  return factor;
}

template StretchResponse stretch_response<2>(const MassSpringSystem<2>&, const Eigen::Matrix2Xd&,
                                             double, int);
template StretchResponse stretch_response<3>(const MassSpringSystem<3>&, const Eigen::Matrix3Xd&,
                                             double, int);
template double stretch_modulus<2>(const MassSpringSystem<2>&, const Eigen::Matrix2Xd&, double,
                                   int);
template double stretch_modulus<3>(const MassSpringSystem<3>&, const Eigen::Matrix3Xd&, double,
                                   int);
template double calibrate_to_stretch<2>(MassSpringSystem<2>&, const SimplexMesh<2>&, double, int);
template double calibrate_to_stretch<3>(MassSpringSystem<3>&, const SimplexMesh<3>&, double, int);

}  // namespace gencoord::deformable
