// SPDX-License-Identifier: BSD-3-Clause
// Co-rotated linear triangles and tetrahedra (continuum_elements.hpp), element by element:
// rest and rigid motions cost nothing, forces are minus the energy's gradient and the
// stiffness their Jacobian (central differences, inverted shapes included), the definite
// stiffness is negative semi-definite where the exact one is not, the damping is linear in
// the velocities and leaves rigid rotations alone, and small strains give the linear
// isotropic stress.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "gencoord/deformable/continuum_elements.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {
namespace {

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Flat = Eigen::Matrix<double, Dim*(Dim + 1), 1>;

// a well-shaped rest simplex: the unit corner simplex, sheared a little
template <int Dim>
Corners<Dim> rest_corners() {
  Corners<Dim> x;
  x[0] = Vec<Dim>::Zero();
  for (int a = 1; a <= Dim; ++a) {
    x[a] = 0.1 * Vec<Dim>::Unit(a - 1);
    x[a](0) += 0.02 * a;
  }
  return x;
}

template <int Dim>
ContinuumElement<Dim> make_element(const Corners<Dim>& rest, double beta = 0.0) {
  ContinuumElement<Dim> e;
  for (int a = 0; a <= Dim; ++a) e.nodes[a] = a;
  Mat<Dim> dm;
  for (int a = 1; a <= Dim; ++a) dm.col(a - 1) = rest[a] - rest[0];
  e.rest_inverse = dm.inverse();
  e.rest_measure = std::abs(signed_measure<Dim>(rest));
  e.mu = 3.0e4;
  e.lambda = 5.0e4;
  e.damping_time = beta;
  return e;
}

template <int Dim>
Flat<Dim> flatten(const Corners<Dim>& x) {
  Flat<Dim> out;
  for (int a = 0; a <= Dim; ++a) out.template segment<Dim>(Dim * a) = x[a];
  return out;
}

template <int Dim>
Corners<Dim> unflatten(const Flat<Dim>& y) {
  Corners<Dim> out;
  for (int a = 0; a <= Dim; ++a) out[a] = y.template segment<Dim>(Dim * a);
  return out;
}

template <int Dim>
Eigen::Matrix<double, Dim*(Dim + 1), Dim*(Dim + 1)> assemble(const ElementJacobian<Dim>& j) {
  Eigen::Matrix<double, Dim*(Dim + 1), Dim*(Dim + 1)> out;
  for (int a = 0; a <= Dim; ++a)
    for (int b = 0; b <= Dim; ++b) out.template block<Dim, Dim>(Dim * a, Dim * b) = j[a][b];
  return out;
}

template <int Dim>
Mat<Dim> rotation(double angle) {
  if constexpr (Dim == 2) {
    return Eigen::Rotation2Dd(angle).toRotationMatrix();
  } else {
    return Eigen::AngleAxisd(angle, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  }
}

// deformed shapes: stretched, sheared, compressed to a tenth, and inverted (a node pushed
// through the opposite side)
template <int Dim>
std::vector<Corners<Dim>> deformed_shapes() {
  std::vector<Corners<Dim>> out;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  const Corners<Dim> rest = rest_corners<Dim>();
  for (int k = 0; k < 3; ++k) {
    Corners<Dim> x = rest;
    for (auto& p : x)
      for (int d = 0; d < Dim; ++d) p(d) += jitter(random);
    out.push_back(x);
  }
  Corners<Dim> squashed = rest;
  for (auto& p : squashed) p(Dim - 1) *= 0.1;
  out.push_back(squashed);
  Corners<Dim> inverted = rest;
  inverted[Dim](Dim - 1) = -0.05;  // the last node through the base
  out.push_back(inverted);
  Corners<Dim> rotated_inverted = inverted;
  for (auto& p : rotated_inverted) p = rotation<Dim>(0.7) * p;
  out.push_back(rotated_inverted);
  return out;
}

template <class T>
class ContinuumElementTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(ContinuumElementTest, Dims);

TYPED_TEST(ContinuumElementTest, RestAndRigidMotionsStoreNothing) {
  constexpr int Dim = TypeParam::value;
  const Corners<Dim> rest = rest_corners<Dim>();
  const ContinuumElement<Dim> e = make_element<Dim>(rest, 0.01);
  Corners<Dim> moved = rest, zero;
  for (auto& z : zero) z = Vec<Dim>::Zero();
  for (auto& p : moved) p = rotation<Dim>(2.5) * p + Vec<Dim>::Constant(0.3);
  for (const Corners<Dim>& x : {rest, moved}) {
    EXPECT_NEAR(continuum_element_energy(e, x), 0.0, 1e-18);
    for (const auto& f : continuum_element_forces(e, x, zero)) EXPECT_LT(f.norm(), 1e-9);
  }
}

TYPED_TEST(ContinuumElementTest, ForcesAreMinusTheEnergyGradient) {
  constexpr int Dim = TypeParam::value;
  const ContinuumElement<Dim> e = make_element<Dim>(rest_corners<Dim>());
  Corners<Dim> zero;
  for (auto& z : zero) z = Vec<Dim>::Zero();
  const double h = 1e-7;
  for (const Corners<Dim>& x : deformed_shapes<Dim>()) {
    const Flat<Dim> forces = flatten<Dim>(continuum_element_forces(e, x, zero));
    Flat<Dim> numeric;
    for (int i = 0; i < numeric.size(); ++i) {
      Flat<Dim> plus = flatten<Dim>(x), minus = plus;
      plus(i) += h;
      minus(i) -= h;
      numeric(i) = -(continuum_element_energy(e, unflatten<Dim>(plus)) -
                     continuum_element_energy(e, unflatten<Dim>(minus))) /
                   (2.0 * h);
    }
    EXPECT_LT((forces - numeric).norm(), 1e-6 * forces.norm()) << forces.transpose();
  }
}

TYPED_TEST(ContinuumElementTest, StiffnessIsTheForceJacobian) {
  constexpr int Dim = TypeParam::value;
  const ContinuumElement<Dim> e = make_element<Dim>(rest_corners<Dim>());
  Corners<Dim> zero;
  for (auto& z : zero) z = Vec<Dim>::Zero();
  const double h = 1e-7;
  for (const Corners<Dim>& x : deformed_shapes<Dim>()) {
    const auto exact = assemble<Dim>(continuum_element_stiffness(e, x, /*definite=*/false));
    Eigen::Matrix<double, Dim*(Dim + 1), Dim*(Dim + 1)> numeric;
    for (int i = 0; i < numeric.cols(); ++i) {
      Flat<Dim> plus = flatten<Dim>(x), minus = plus;
      plus(i) += h;
      minus(i) -= h;
      numeric.col(i) = (flatten<Dim>(continuum_element_forces(e, unflatten<Dim>(plus), zero)) -
                        flatten<Dim>(continuum_element_forces(e, unflatten<Dim>(minus), zero))) /
                       (2.0 * h);
    }
    EXPECT_LT((exact - numeric).norm(), 1e-6 * exact.norm());
  }
}

// the definite blocks are the exact ones at rest, negative semi-definite everywhere; the exact
// stiffness of the squashed and the inverted shapes has a positive eigenvalue (the clamp acts)
TYPED_TEST(ContinuumElementTest, DefiniteStiffnessIsNegativeSemidefinite) {
  constexpr int Dim = TypeParam::value;
  const Corners<Dim> rest = rest_corners<Dim>();
  const ContinuumElement<Dim> e = make_element<Dim>(rest);
  const auto at_rest = assemble<Dim>(continuum_element_stiffness(e, rest, true));
  EXPECT_LT((at_rest - assemble<Dim>(continuum_element_stiffness(e, rest, false))).norm(),
            1e-12 * at_rest.norm());
  int indefinite = 0;
  for (const Corners<Dim>& x : deformed_shapes<Dim>()) {
    const auto definite = assemble<Dim>(continuum_element_stiffness(e, x, true));
    const auto exact = assemble<Dim>(continuum_element_stiffness(e, x, false));
    const Eigen::SelfAdjointEigenSolver<decltype(definite)> eig_definite(definite);
    const Eigen::SelfAdjointEigenSolver<decltype(exact)> eig_exact(exact);
    const double scale = eig_exact.eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_LT(eig_definite.eigenvalues().maxCoeff(), 1e-10 * scale);
    EXPECT_LT((definite - definite.transpose()).norm(), 1e-12 * scale);
    if (eig_exact.eigenvalues().maxCoeff() > 1e-6 * scale) ++indefinite;
  }
  EXPECT_GE(indefinite, 2);
}

TYPED_TEST(ContinuumElementTest, DampingIsLinearAndLeavesRigidRotationAlone) {
  constexpr int Dim = TypeParam::value;
  const ContinuumElement<Dim> e = make_element<Dim>(rest_corners<Dim>(), 0.02);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Corners<Dim> zero, v;
  for (auto& z : zero) z = Vec<Dim>::Zero();
  for (auto& w : v)
    for (int d = 0; d < Dim; ++d) w(d) = uniform(random);
  for (const Corners<Dim>& x : deformed_shapes<Dim>()) {
    const Flat<Dim> damping_force = flatten<Dim>(continuum_element_forces(e, x, v)) -
                                    flatten<Dim>(continuum_element_forces(e, x, zero));
    const auto d = assemble<Dim>(continuum_element_damping(e, x));
    EXPECT_LT((damping_force - d * flatten<Dim>(v)).norm(), 1e-9 * damping_force.norm());
    const Eigen::SelfAdjointEigenSolver<decltype(d)> eig(d);
    EXPECT_LT(eig.eigenvalues().maxCoeff(), 1e-10 * eig.eigenvalues().cwiseAbs().maxCoeff());
    // a rigid rotation's velocities v_a = W x_a, W skew
    Mat<Dim> w = Mat<Dim>::Zero();
    w(0, 1) = -1.0;
    w(1, 0) = 1.0;
    Corners<Dim> spin;
    for (int a = 0; a <= Dim; ++a) spin[a] = w * x[a];
    EXPECT_LT((d * flatten<Dim>(spin)).norm(), 1e-9 * d.norm() * flatten<Dim>(spin).norm());
  }
}

// F = I + eps, eps small and symmetric: P = 2 mu eps + lambda tr(eps) I to first order
TYPED_TEST(ContinuumElementTest, SmallStrainsGiveTheLinearIsotropicStress) {
  constexpr int Dim = TypeParam::value;
  const Corners<Dim> rest = rest_corners<Dim>();
  const ContinuumElement<Dim> e = make_element<Dim>(rest);
  Mat<Dim> eps = Mat<Dim>::Zero();
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j) eps(i, j) = 1e-6 * (1.0 + i + 2 * j + i * j);
  eps = 0.5 * (eps + eps.transpose()).eval();
  Corners<Dim> x, zero;
  for (int a = 0; a <= Dim; ++a) {
    x[a] = (Mat<Dim>::Identity() + eps) * rest[a];
    zero[a] = Vec<Dim>::Zero();
  }
  const Mat<Dim> stress = 2.0 * e.mu * eps + e.lambda * eps.trace() * Mat<Dim>::Identity();
  // f_a = -V0 P g_a with g_a the shape gradients: the rows of Dm^-1 and minus their sum
  const Corners<Dim> forces = continuum_element_forces(e, x, zero);
  Vec<Dim> g0 = Vec<Dim>::Zero();
  for (int a = 1; a <= Dim; ++a) {
    const Vec<Dim> g = e.rest_inverse.row(a - 1).transpose();
    g0 -= g;
    const Vec<Dim> expected = -e.rest_measure * stress * g;
    EXPECT_LT((forces[a] - expected).norm(), 1e-5 * expected.norm());
  }
  EXPECT_LT((forces[0] + e.rest_measure * stress * g0).norm(), 1e-5 * forces[0].norm());
}

// The energy in the principal frame: a stretch s along one axis stores V0 (mu + lambda / 2)
// (s - 1)^2, also when s < 0 (inverted), where it pushes the node back.
TYPED_TEST(ContinuumElementTest, InvertedElementsPushBack) {
  constexpr int Dim = TypeParam::value;
  const Corners<Dim> rest = rest_corners<Dim>();
  const ContinuumElement<Dim> e = make_element<Dim>(rest);
  for (const double s : {1.5, 0.5, -0.5}) {
    Corners<Dim> x = rest, zero;
    for (int a = 0; a <= Dim; ++a) {
      x[a](Dim - 1) *= s;
      zero[a] = Vec<Dim>::Zero();
    }
    const double expected = e.rest_measure * (e.mu + 0.5 * e.lambda) * (s - 1.0) * (s - 1.0);
    EXPECT_NEAR(continuum_element_energy(e, x), expected, 1e-9 * expected) << s;
    // the last node, the one off the base, is pushed toward its rest height
    const double push = continuum_element_forces(e, x, zero)[Dim](Dim - 1);
    EXPECT_GT(push * (rest[Dim](Dim - 1) - x[Dim](Dim - 1)), 0.0) << s;
  }
}

// The tetrahedron's polar decomposition F = R S (rotation-variant: an inverted F keeps a proper
// R and a negative stretch) against one from Eigen's JacobiSVD, through the energy and the
// forces of an element whose rest shape is the unit corner tetrahedron (so F is its corners):
// random, near-rest, inverted and reflected gradients, repeated and vanishing stretches. Where
// two stretches vanish, or all three are equal with F inverted, R is not unique, but the
// energy is.
double reference_energy(const ContinuumElement<3>& e, const Mat<3>& f, Mat<3>* stress) {
  // dynamic size: GCC 12 warns of an uninitialized value inside the fixed-size 3 x 3 JacobiSVD
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(f),
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat<3> u = svd.matrixU(), v = svd.matrixV();
  Vec<3> s = svd.singularValues();
  if (u.determinant() < 0.0) {
    u.col(2) *= -1.0;
    s(2) *= -1.0;
  }
  if (v.determinant() < 0.0) {
    v.col(2) *= -1.0;
    s(2) *= -1.0;
  }
  const Mat<3> r = u * v.transpose();
  *stress = 2.0 * e.mu * (f - r) + e.lambda * (s.sum() - 3.0) * r;
  return e.rest_measure *
         (e.mu * (f - r).squaredNorm() + 0.5 * e.lambda * std::pow(s.sum() - 3.0, 2));
}

TEST(ContinuumElement3D, PolarDecompositionMatchesEigensJacobiSvd) {
  Corners<3> rest;
  rest[0] = Vec<3>::Zero();
  for (int a = 1; a <= 3; ++a) rest[a] = Vec<3>::Unit(a - 1);
  const ContinuumElement<3> e = make_element<3>(rest);
  std::mt19937 random(3);
  std::normal_distribution<double> entry(0.0, 1.0);
  const Mat<3> turn = rotation<3>(0.7);
  std::vector<std::pair<Mat<3>, bool>> cases;  // F, whether R is unique
  for (int k = 0; k < 200; ++k) {
    Mat<3> f;
    for (int i = 0; i < 9; ++i) f.data()[i] = entry(random) * (k < 100 ? 0.05 : 1.0);
    if (k < 100) f += Mat<3>::Identity();  // near rest
    if (k % 4 == 3) f.col(0) *= -1.0;      // inverted or reflected
    cases.emplace_back(f, true);
  }
  cases.emplace_back(Mat<3>::Identity(), true);
  cases.emplace_back(turn, true);
  cases.emplace_back(turn * Vec<3>(2.0, 2.0, 0.5).asDiagonal() * rotation<3>(-1.1), true);
  cases.emplace_back(turn * Vec<3>(1.5, 0.5, 0.5).asDiagonal(), true);
  cases.emplace_back(turn * Vec<3>(1.0, 1.0, -1e-7).asDiagonal(), true);
  cases.emplace_back(turn * Vec<3>(1.0, 0.0, 0.0).asDiagonal(), false);
  cases.emplace_back(-turn, false);  // which stretch turns negative is any
  cases.emplace_back(Mat<3>::Zero(), false);
  const Corners<3> still{};
  for (const auto& [f, unique] : cases) {
    Corners<3> x;
    x[0] = Vec<3>::Zero();
    for (int a = 1; a <= 3; ++a) x[a] = f.col(a - 1);
    Mat<3> stress;
    const double expected = reference_energy(e, f, &stress);
    EXPECT_NEAR(continuum_element_energy(e, x), expected, 1e-12 * (1.0 + expected)) << f;
    if (!unique) continue;
    const Corners<3> forces = continuum_element_forces(e, x, still);
    for (int a = 1; a <= 3; ++a) {  // f_a = -V0 P g_a, g_a = e_(a-1)
      EXPECT_LT((forces[a] + e.rest_measure * stress.col(a - 1)).norm(),
                e.rest_measure * (1e-14 * (e.mu + e.lambda) + 1e-12 * stress.norm()))
          << f;
    }
  }
}

}  // namespace
}  // namespace gencoord::deformable
