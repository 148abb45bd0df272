// SPDX-License-Identifier: BSD-3-Clause
// Area (2D) and volume (3D) terms (volume_terms.hpp): forces against the energy's gradient,
// Jacobians against finite differences, rigid motions, the Poisson's ratio, Young's modulus
// and bulk modulus measured on loaded blocks, refusals, the CFL limit and explicit and
// implicit runs.
#include "gencoord/deformable/volume_terms.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/integrate/backward_euler.hpp"

namespace gencoord::deformable {
namespace {

template <int Dim>
using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;
template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

Material Soft(double nu) {
  Material m{1e4, 1e3, 0.0};
  m.poisson_ratio = nu;
  return m;
}

// A simplex with random corners in [-1, 1]^Dim, not flatter than a tenth of a regular one.
template <int Dim>
Corners<Dim> RandomCorners(std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Corners<Dim> x;
    for (auto& p : x)
      for (int i = 0; i < Dim; ++i) p(i) = u(random);
    if (std::abs(signed_measure<Dim>(x)) > (Dim == 2 ? 0.1 : 0.02)) return x;
  }
}

// The same, positively oriented.
template <int Dim>
Corners<Dim> RandomPositiveCorners(std::mt19937& random) {
  Corners<Dim> x = RandomCorners<Dim>(random);
  if (signed_measure<Dim>(x) < 0.0) std::swap(x[0], x[1]);
  return x;
}

template <int Dim>
VolumeTerm<Dim> TermAt(const Corners<Dim>& rest, double stiffness) {
  VolumeTerm<Dim> term;
  for (int a = 0; a <= Dim; ++a) term.nodes[a] = a;
  term.rest_measure = signed_measure<Dim>(rest);
  term.stiffness = stiffness;
  return term;
}

// The forces are minus the central-difference gradient of the energy, and the exact Jacobian
// the central difference of the forces, at random shapes (inverted ones included).
template <int Dim>
void ExpectDerivativesMatchFiniteDifferences() {
  std::mt19937 random(7);
  const double h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const VolumeTerm<Dim> term = TermAt<Dim>(RandomPositiveCorners<Dim>(random), 3.5);
    const Corners<Dim> x = RandomCorners<Dim>(random);
    const Corners<Dim> f = volume_term_forces(term, x);
    const VolumeTermJacobian<Dim> jac = volume_term_jacobian(term, x, /*definite=*/false);
    double scale = 0.0;
    for (const auto& fa : f) scale = std::max(scale, fa.norm());
    for (int b = 0; b <= Dim; ++b) {
      for (int i = 0; i < Dim; ++i) {
        Corners<Dim> plus = x, minus = x;
        plus[b](i) += h;
        minus[b](i) -= h;
        const double gradient =
            (volume_term_energy(term, plus) - volume_term_energy(term, minus)) / (2 * h);
        EXPECT_NEAR(f[b](i), -gradient, 1e-7 * scale) << Dim << "D trial " << trial;
        const Corners<Dim> fp = volume_term_forces(term, plus),
                           fm = volume_term_forces(term, minus);
        for (int a = 0; a <= Dim; ++a) {
          const Vec<Dim> column = (fp[a] - fm[a]) / (2 * h);
          EXPECT_LE((jac[a][b].col(i) - column).norm(), 1e-6 * (1 + column.norm()))
              << Dim << "D trial " << trial << " block " << a << b;
        }
      }
    }
  }
}

TEST(VolumeTermsTest, ForcesAndJacobianMatchFiniteDifferences) {
  ExpectDerivativesMatchFiniteDifferences<2>();
  ExpectDerivativesMatchFiniteDifferences<3>();
}

// The definite Jacobian is symmetric, negative semi-definite at any shape, has no response to
// a translation, and is the exact one where V = V0.
template <int Dim>
void ExpectDefiniteJacobianProperties() {
  constexpr int n = (Dim + 1) * Dim;
  std::mt19937 random(5);
  for (int trial = 0; trial < 20; ++trial) {
    const Corners<Dim> x = RandomPositiveCorners<Dim>(random);
    VolumeTerm<Dim> term = TermAt<Dim>(RandomPositiveCorners<Dim>(random), 2.0);
    const auto flat = [](const VolumeTermJacobian<Dim>& jac) {
      Eigen::Matrix<double, n, n> m;
      for (int a = 0; a <= Dim; ++a)
        for (int b = 0; b <= Dim; ++b) m.template block<Dim, Dim>(a * Dim, b * Dim) = jac[a][b];
      return m;
    };
    const Eigen::Matrix<double, n, n> k = flat(volume_term_jacobian(term, x, true));
    EXPECT_LE((k - k.transpose()).norm(), 1e-14 * k.norm());
    const Eigen::Matrix<double, n, 1> eig =
        Eigen::SelfAdjointEigenSolver<decltype(k)>(k).eigenvalues();
    EXPECT_LE(eig.maxCoeff(), 1e-13 * k.norm()) << Dim << "D trial " << trial;
    for (int i = 0; i < Dim; ++i) {
      Eigen::Matrix<double, n, 1> shift = Eigen::Matrix<double, n, 1>::Zero();
      for (int a = 0; a <= Dim; ++a) shift(a * Dim + i) = 1.0;
      EXPECT_LE((k * shift).norm(), 1e-13 * k.norm());
    }
    term.rest_measure = signed_measure<Dim>(x);  // J = 1
    const Eigen::Matrix<double, n, n> at_rest = flat(volume_term_jacobian(term, x, true));
    EXPECT_LE((flat(volume_term_jacobian(term, x, false)) - at_rest).norm(),
              1e-14 * at_rest.norm());
  }
}

TEST(VolumeTermsTest, DefiniteJacobianIsSymmetricNegativeSemiDefinite) {
  ExpectDefiniteJacobianProperties<2>();
  ExpectDefiniteJacobianProperties<3>();
}

template <int Dim>
SimplexMesh<Dim> Jittered(SimplexMesh<Dim> mesh, double amount, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (int node = 0; node < mesh.nodes.cols(); ++node)
    for (int i = 0; i < Dim; ++i) mesh.nodes(i, node) += u(random);
  return mesh;
}

// The whole object's force (springs and terms through accumulate_forces) is minus the
// gradient of its potential energy, at a random deformed state of a jittered mesh.
template <int Dim>
void ExpectObjectForceIsMinusEnergyGradient(const SimplexMesh<Dim>& mesh) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, Soft(0.45));
  ASSERT_EQ(s.volume_terms.size(), mesh.elements.size());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  for (int node = 0; node < s.num_nodes(); ++node)
    for (int i = 0; i < Dim; ++i) s.x(i, node) += u(random);
  Points<Dim> f = Points<Dim>::Zero(Dim, s.num_nodes());
  accumulate_forces(s, f);
  const double h = 1e-7, scale = f.cwiseAbs().maxCoeff();
  for (int node = 0; node < s.num_nodes(); ++node) {
    for (int i = 0; i < Dim; ++i) {
      MassSpringSystem<Dim> plus = s, minus = s;
      plus.x(i, node) += h;
      minus.x(i, node) -= h;
      const double gradient = (potential_energy(plus) - potential_energy(minus)) / (2 * h);
      ASSERT_NEAR(f(i, node), -gradient, 1e-6 * scale) << Dim << "D node " << node;
    }
  }
}

TEST(VolumeTermsTest, ObjectForceIsMinusEnergyGradient) {
  ExpectObjectForceIsMinusEnergyGradient<2>(Jittered(rectangle_mesh(0.4, 0.3, 4, 3), 0.02, 1));
  ExpectObjectForceIsMinusEnergyGradient<3>(Jittered(box_mesh(0.3, 0.3, 0.3, 2, 2, 2), 0.02, 1));
}

// At rest (every spring at its rest length, every element at V0) the definite Jacobians are
// the exact ones: linearize()'s stiffness is the central difference of the forces.
template <int Dim>
void ExpectLinearizedStiffnessAtRestIsExact(const SimplexMesh<Dim>& mesh) {
  const MassSpringSystem<Dim> s = make_mass_spring(mesh, Soft(0.45));
  const MassSpringIntegration<Dim> system(s);
  Linearization<MassSpringIntegration<Dim>> lin;
  system.linearize({s.t, s.x, s.v}, JacobianSource::Auto, &lin);
  const Eigen::MatrixXd k(lin.force_D_q);
  const double h = 1e-7;
  for (int node = 0; node < s.num_nodes(); ++node) {
    for (int i = 0; i < Dim; ++i) {
      Points<Dim> plus = s.x, minus = s.x;
      plus(i, node) += h;
      minus(i, node) -= h;
      Points<Dim> fp = Points<Dim>::Zero(Dim, s.num_nodes()), fm = fp;
      accumulate_forces(s, plus, s.v, fp);
      accumulate_forces(s, minus, s.v, fm);
      const Eigen::VectorXd column = system.free_part((fp - fm) / (2 * h));
      ASSERT_LE((k.col(node * Dim + i) - column).norm(), 1e-6 * k.norm())
          << Dim << "D node " << node << " axis " << i;
    }
  }
}

TEST(VolumeTermsTest, LinearizedStiffnessAtRestIsExact) {
  ExpectLinearizedStiffnessAtRestIsExact<2>(Jittered(rectangle_mesh(0.4, 0.3, 4, 3), 0.02, 1));
  ExpectLinearizedStiffnessAtRestIsExact<3>(Jittered(box_mesh(0.3, 0.3, 0.3, 2, 2, 2), 0.02, 1));
}

// A rotated and translated object is at rest: no force, no energy.
template <int Dim>
void ExpectRigidMotionIsForceFree(const SimplexMesh<Dim>& mesh,
                                  const Eigen::Matrix<double, Dim, Dim>& rotation) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, Soft(0.45));
  ASSERT_FALSE(s.volume_terms.empty());
  s.x = (rotation * mesh.nodes).colwise() + Vec<Dim>::Constant(0.7);
  Points<Dim> f = Points<Dim>::Zero(Dim, s.num_nodes());
  accumulate_volume_term_forces(s, s.x, f);
  // the force scale: a unit strain's force on an element, kappa times a face
  const double scale = s.volume_terms[0].stiffness * std::pow(0.1, Dim - 1);
  EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-12 * scale) << Dim << "D";
  accumulate_forces(s, f);
  EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-12 * scale) << Dim << "D";
  EXPECT_LE(volume_terms_energy(s), 1e-24 * scale);
}

TEST(VolumeTermsTest, RigidMotionsGiveNoForce) {
  ExpectRigidMotionIsForceFree<2>(rectangle_mesh(0.4, 0.3, 4, 3),
                                  Eigen::Rotation2Dd(0.83).toRotationMatrix());
  ExpectRigidMotionIsForceFree<3>(
      Jittered(box_mesh(0.3, 0.3, 0.3, 3, 3, 3), 0.01, 2),
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix());
}

// An element with a broken edge spring exerts nothing; the others are unaffected.
TEST(VolumeTermsTest, ElementWithABrokenEdgeSpringExertsNothing) {
  const SimplexMesh<3> mesh = box_mesh(0.3, 0.3, 0.3, 2, 2, 2);
  MassSpringSystem<3> s = make_mass_spring(mesh, Soft(0.45));
  s.x *= 1.01;  // every element dilated
  const int broken = 17;
  s.springs[broken].broken = true;
  double expected = 0.0;
  int sharing = 0;
  for (const VolumeTerm<3>& term : s.volume_terms) {
    if (std::find(term.springs.begin(), term.springs.end(), broken) != term.springs.end()) {
      ++sharing;
      EXPECT_FALSE(volume_term_active(s, term));
    } else {
      expected += volume_term_energy(term, corners_of(term, s.x));
    }
  }
  ASSERT_GT(sharing, 0);
  EXPECT_NEAR(volume_terms_energy(s), expected, 1e-14 * expected);
  // the nodes of the broken spring feel only what the active elements give them
  Points<3> f = Points<3>::Zero(3, s.num_nodes()), g = f;
  accumulate_volume_term_forces(s, s.x, f);
  for (const VolumeTerm<3>& term : s.volume_terms) {
    if (!volume_term_active(s, term)) continue;
    const Corners<3> fe = volume_term_forces(term, corners_of(term, s.x));
    for (int a = 0; a < 4; ++a) g.col(term.nodes[a]) += fe[a];
  }
  EXPECT_LE((f - g).cwiseAbs().maxCoeff(), 1e-12 * f.cwiseAbs().maxCoeff());
}

TEST(VolumeTermsTest, SmallStrainEnergyIsLambdaTraceSquared) {
  // kappa = lambda_add: W = (kappa / 2) tr(eps)^2 V0 to first order in eps
  std::mt19937 random(9);
  const Corners<3> rest = RandomPositiveCorners<3>(random);
  const VolumeTerm<3> term = TermAt<3>(rest, 2.5);
  Eigen::Matrix3d eps;
  eps << 1.0, 0.3, -0.2, 0.3, -0.4, 0.5, -0.2, 0.5, 0.7;
  eps *= 1e-5;
  Corners<3> x = rest;
  for (auto& p : x) p += eps * p;
  const double expected = 0.5 * 2.5 * eps.trace() * eps.trace() * term.rest_measure;
  EXPECT_NEAR(volume_term_energy(term, x), expected, 1e-4 * expected);
}

// Under a small affine strain the object (springs and terms) stores the isotropic energy
// density (lambda / 2) tr(eps)^2 + mu eps : eps of the requested E and nu, on structured and
// jittered meshes (whose calibrated networks are exactly isotropic).
template <int Dim>
void ExpectAffineEnergyIsTheMaterials(const SimplexMesh<Dim>& mesh, double nu) {
  const Material material = Soft(nu);
  MassSpringSystem<Dim> s = make_mass_spring(mesh, material);
  const LameSplit split = lame_split<Dim>(material);
  double measure = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e)
    measure += element_measure(mesh, e);
  std::mt19937 random(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::Matrix<double, Dim, Dim> eps;
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j <= i; ++j) eps(i, j) = eps(j, i) = 1e-6 * u(random);
    s.x = mesh.nodes + eps * mesh.nodes;
    const double expected =
        0.5 * split.lambda * eps.trace() * eps.trace() + split.mu * eps.squaredNorm();
    EXPECT_NEAR(potential_energy(s) / measure, expected, 1e-5 * expected)
        << Dim << "D nu " << nu << " trial " << trial;
  }
}

TEST(VolumeTermsTest, AffineStrainStoresTheRequestedMaterialsEnergy) {
  for (double nu : {0.4, 0.7, 0.95}) {
    ExpectAffineEnergyIsTheMaterials<2>(rectangle_mesh(1.0, 0.5, 6, 3), nu);
    ExpectAffineEnergyIsTheMaterials<2>(Jittered(rectangle_mesh(1.0, 0.5, 6, 3), 0.03, 5), nu);
  }
  for (double nu : {0.3, 0.45, 0.499}) {
    ExpectAffineEnergyIsTheMaterials<3>(box_mesh(1.0, 0.5, 0.5, 4, 2, 2), nu);
    ExpectAffineEnergyIsTheMaterials<3>(Jittered(box_mesh(1.0, 0.5, 0.5, 4, 2, 2), 0.03, 5), nu);
  }
}

// ---- measured elastic constants -----------------------------------------------------------

// Boundary faces of a mesh (those of one element only), each with its outward area vector.
template <int Dim>
std::vector<std::pair<std::array<int, Dim>, Vec<Dim>>> BoundaryFaces(const SimplexMesh<Dim>& m) {
  std::map<std::array<int, Dim>, std::pair<int, std::pair<std::array<int, Dim>, Vec<Dim>>>> faces;
  for (const auto& el : m.elements) {
    for (int skip = 0; skip <= Dim; ++skip) {
      std::array<int, Dim> face;
      int k = 0;
      for (int a = 0; a <= Dim; ++a)
        if (a != skip) face[k++] = el[a];
      Vec<Dim> area;
      if constexpr (Dim == 2) {
        const Eigen::Vector2d d = m.nodes.col(face[1]) - m.nodes.col(face[0]);
        area << d.y(), -d.x();
      } else {
        area = 0.5 * (m.nodes.col(face[1]) - m.nodes.col(face[0]))
                         .cross(m.nodes.col(face[2]) - m.nodes.col(face[0]));
      }
      if (area.dot(m.nodes.col(face[0]) - m.nodes.col(el[skip])) < 0) area = -area;
      std::array<int, Dim> key = face;
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      ++entry.first;
      entry.second = {face, area};
    }
  }
  std::vector<std::pair<std::array<int, Dim>, Vec<Dim>>> out;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) out.push_back(entry.second);
  return out;
}

// Node loads of the uniform stress `sigma` on the boundary: the traction sigma n over each
// face, shared equally by its nodes (exact for linear elements).
template <int Dim>
Points<Dim> StressLoads(const SimplexMesh<Dim>& mesh,
                        const Eigen::Matrix<double, Dim, Dim>& sigma) {
  Points<Dim> f = Points<Dim>::Zero(Dim, mesh.nodes.cols());
  for (const auto& [face, area] : BoundaryFaces(mesh))
    for (int node : face) f.col(node) += sigma * area / Dim;
  return f;
}

// Static equilibrium under the loads by chord iterations (Newton's with the first matrix, as
// the strains are small) with the object's stiffness at rest from
// MassSpringIntegration::linearize(). The body is free: its rigid motions (which the
// balanced loads do not drive, but dead loads under compression would turn without bound)
// are projected out of each update's right-hand side, and held by a small stiffness.
template <int Dim>
void SolveStatic(MassSpringSystem<Dim>& s, const Points<Dim>& loads) {
  const MassSpringIntegration<Dim> system(s);
  const int unknowns = s.num_nodes() * Dim;
  Eigen::SparseMatrix<double> identity(unknowns, unknowns);
  identity.setIdentity();
  const double scale = system.free_part(loads).norm();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  for (int iteration = 0; iteration < 30; ++iteration) {
    Linearization<MassSpringIntegration<Dim>> lin;
    system.linearize({s.t, s.x, s.v}, JacobianSource::Auto, &lin);
    Eigen::VectorXd rhs = lin.force + system.free_part(loads);
    // translations and rotations about the centroid at the current positions
    constexpr int kRigid = Dim == 2 ? 3 : 6;
    Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(unknowns, kRigid);
    const Vec<Dim> centroid = s.x.rowwise().mean();
    for (int n = 0; n < s.num_nodes(); ++n) {
      const Vec<Dim> r = s.x.col(n) - centroid;
      for (int i = 0; i < Dim; ++i) rigid(n * Dim + i, i) = 1.0;
      if constexpr (Dim == 2) {
        rigid(n * 2, 2) = -r.y();
        rigid(n * 2 + 1, 2) = r.x();
      } else {
        for (int axis = 0; axis < 3; ++axis)
          rigid.block<3, 1>(n * 3, 3 + axis) = Eigen::Vector3d::Unit(axis).cross(r);
      }
    }
    const Eigen::MatrixXd basis = Eigen::HouseholderQR<Eigen::MatrixXd>(rigid).householderQ() *
                                  Eigen::MatrixXd::Identity(unknowns, kRigid);
    rhs -= basis * (basis.transpose() * rhs);
    if (rhs.norm() < 1e-9 * scale) return;
    if (iteration == 0) {
      const double hold = 1e-6 * lin.force_D_q.diagonal().cwiseAbs().maxCoeff();
      ldlt.compute(-lin.force_D_q + hold * identity);
      ASSERT_EQ(ldlt.info(), Eigen::Success);
    }
    system.add_to_free(ldlt.solve(rhs), &s.x);
  }
  FAIL() << "no static equilibrium after 30 Newton steps";
}

// The displacement gradient of the least-squares affine fit u = A X + b over the nodes at
// least margin(i) inside the body's bounding box along each axis i (end effects left out).
template <int Dim>
Eigen::Matrix<double, Dim, Dim> FitGradient(const Points<Dim>& rest, const Points<Dim>& x,
                                            const Vec<Dim>& margin) {
  const Vec<Dim> lo = rest.rowwise().minCoeff() + margin, hi = rest.rowwise().maxCoeff() - margin;
  std::vector<int> inside;
  for (int n = 0; n < rest.cols(); ++n) {
    const Vec<Dim> p = rest.col(n);
    if ((p.array() >= lo.array() - 1e-12).all() && (p.array() <= hi.array() + 1e-12).all())
      inside.push_back(n);
  }
  Eigen::MatrixXd design(inside.size(), Dim + 1), u(inside.size(), Dim);
  for (std::size_t k = 0; k < inside.size(); ++k) {
    design.row(k) << rest.col(inside[k]).transpose(), 1.0;
    u.row(k) = (x.col(inside[k]) - rest.col(inside[k])).transpose();
  }
  const Eigen::MatrixXd coefficients = design.colPivHouseholderQr().solve(u);  // (Dim+1) x Dim
  return coefficients.topRows(Dim).transpose();
}

struct Measured {
  double poisson = 0.0, youngs = 0.0;
};

// A block pulled along x by the uniform stress sigma_xx = 1e-4 E on its end faces, free
// otherwise: nu = -eps_yy / eps_xx (and eps_zz), E = sigma / eps_xx.
template <int Dim>
Measured PullBlock(const SimplexMesh<Dim>& mesh, const Material& material, double margin) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, material);
  Eigen::Matrix<double, Dim, Dim> sigma = Eigen::Matrix<double, Dim, Dim>::Zero();
  sigma(0, 0) = 1e-4 * material.youngs_modulus;
  SolveStatic(s, StressLoads(mesh, sigma));
  Vec<Dim> margins = Vec<Dim>::Zero();
  margins(0) = margin;
  const Eigen::Matrix<double, Dim, Dim> grad = FitGradient<Dim>(mesh.nodes, s.x, margins);
  const Eigen::Matrix<double, Dim, Dim> eps = 0.5 * (grad + grad.transpose());
  Measured out;
  for (int i = 1; i < Dim; ++i) out.poisson -= eps(i, i) / eps(0, 0) / (Dim - 1);
  out.youngs = sigma(0, 0) / eps(0, 0);
  return out;
}

TEST(VolumeTermsTest, MeasuredPoissonsRatioAndYoungsModulusAreTheRequested) {
  const SimplexMesh<2> sheet = rectangle_mesh(2.0, 1.0, 16, 8);
  const SimplexMesh<3> block = box_mesh(2.0, 1.0, 1.0, 16, 8, 8);
  const struct {
    int dim;
    double nu;
  } cases[] = {{2, std::nan("")}, {2, 0.45}, {2, 0.6},  {2, 0.9},
               {3, std::nan("")}, {3, 0.35}, {3, 0.45}, {3, 0.49}};
  for (const auto& c : cases) {
    const Material material = Soft(c.nu);
    const double expected = std::isnan(c.nu) ? (c.dim == 2 ? 1.0 / 3.0 : 0.25) : c.nu;
    const Measured m =
        c.dim == 2 ? PullBlock<2>(sheet, material, 0.5) : PullBlock<3>(block, material, 0.5);
    EXPECT_NEAR(m.poisson, expected, 0.03 * expected) << c.dim << "D nu " << c.nu;
    EXPECT_NEAR(m.youngs, material.youngs_modulus, 0.04 * material.youngs_modulus)
        << c.dim << "D nu " << c.nu;
    std::printf("[ poisson ] %dD nu requested %.4f: measured nu %.4f, E / E_requested %.4f\n",
                c.dim, expected, m.poisson, m.youngs / material.youngs_modulus);
  }
}

// Uniform pressure p on the whole boundary: the relative change of area or volume dV / V is
// -p / K, K = lambda + mu (2D) or lambda + 2 mu / 3 (3D). The network alone is softer than its
// affine estimate in a small body (its free surface relaxes: the 8 x 8 square's K is 10% low,
// the 4 x 4 x 4 cube's 31%); the terms, exact under a dilation, take over as nu approaches 1
// (2D) or 1/2 (3D), where dV shrinks toward zero and K reaches the closed form.
template <int Dim>
double MeasuredBulkModulus(const SimplexMesh<Dim>& mesh, const Material& material) {
  MassSpringSystem<Dim> s = make_mass_spring(mesh, material);
  const double p = 1e-4 * material.youngs_modulus;
  SolveStatic(s, StressLoads<Dim>(mesh, -p * Eigen::Matrix<double, Dim, Dim>::Identity()));
  double before = 0.0, after = 0.0;
  for (const auto& el : mesh.elements) {
    Corners<Dim> rest, now;
    for (int a = 0; a <= Dim; ++a) {
      rest[a] = mesh.nodes.col(el[a]);
      now[a] = s.x.col(el[a]);
    }
    const double sign = signed_measure<Dim>(rest) > 0.0 ? 1.0 : -1.0;  // the mesh's orientation
    before += sign * signed_measure<Dim>(rest);
    after += sign * signed_measure<Dim>(now);
  }
  return -p / ((after - before) / before);
}

// The network alone: under a dilation its interior nodes are in equilibrium (only the free
// surface pulls), and its bulk modulus under pressure approaches the affine estimate as the
// mesh is refined.
TEST(VolumeTermsTest, NetworksBulkSoftnessIsASurfaceEffect) {
  const Material plain = Soft(std::nan(""));
  const SimplexMesh<3> cube = box_mesh(1.0, 1.0, 1.0, 4, 4, 4);
  MassSpringSystem<3> s = make_mass_spring(cube, plain);
  s.x = 1.001 * cube.nodes;
  Points<3> f = Points<3>::Zero(3, s.num_nodes());
  accumulate_forces(s, f);
  double interior = 0.0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    const Eigen::Array3d p = cube.nodes.col(n).array();
    if ((p > 0.1).all() && (p < 0.9).all()) interior = std::max(interior, f.col(n).norm());
  }
  EXPECT_LE(interior, 1e-12 * f.cwiseAbs().maxCoeff());
  double previous = 0.0;
  const double affine = lame_split<3>(plain).lambda + 2.0 * lame_split<3>(plain).mu / 3.0;
  for (int cells : {2, 4, 6}) {
    const double bulk = MeasuredBulkModulus<3>(box_mesh(1.0, 1.0, 1.0, cells, cells, cells), plain);
    EXPECT_GT(bulk, previous);
    EXPECT_LT(bulk, affine);
    previous = bulk;
    std::printf("[ poisson ] 3D network alone, cube of %d cells a side: K / E %.4f (affine %.4f)\n",
                cells, bulk / plain.youngs_modulus, affine / plain.youngs_modulus);
  }
}

TEST(VolumeTermsTest, VolumeChangeUnderPressureShrinksAsNuApproachesTheLimit) {
  const SimplexMesh<2> sheet = rectangle_mesh(1.0, 1.0, 8, 8);
  const SimplexMesh<3> block = box_mesh(1.0, 1.0, 1.0, 4, 4, 4);
  for (int dim : {2, 3}) {
    double previous_bulk = 0.0, previous_error = HUGE_VAL;
    const std::vector<double> ratios = dim == 2
                                           ? std::vector<double>{1.0 / 3.0, 0.5, 0.7, 0.9, 0.98}
                                           : std::vector<double>{0.25, 0.35, 0.45, 0.49, 0.499};
    for (double nu : ratios) {
      const Material material = Soft(nu);
      const LameSplit split = dim == 2 ? lame_split<2>(material) : lame_split<3>(material);
      const double expected =
          dim == 2 ? split.lambda + split.mu : split.lambda + 2.0 * split.mu / 3.0;
      const double bulk = dim == 2 ? MeasuredBulkModulus<2>(sheet, material)
                                   : MeasuredBulkModulus<3>(block, material);
      const double error = std::abs(bulk - expected) / expected;
      EXPECT_GT(bulk, 1.3 * previous_bulk) << dim << "D nu " << nu;  // dV shrinks
      EXPECT_LT(error, previous_error) << dim << "D nu " << nu;
      if (nu >= (dim == 2 ? 0.9 : 0.49)) {
        EXPECT_LT(error, 0.01) << dim << "D nu " << nu;
      }
      previous_bulk = bulk;
      previous_error = error;
      std::printf("[ poisson ] %dD nu %.4f under pressure: K / E measured %.4f, closed form %.4f\n",
                  dim, nu, bulk / material.youngs_modulus, expected / material.youngs_modulus);
    }
  }
}

// ---- material ------------------------------------------------------------------------------

TEST(VolumeTermsTest, PoissonsRatioOutsideTheRangeIsRefused) {
  const SimplexMesh<2> sheet = rectangle_mesh(1.0, 1.0, 2, 2);
  const SimplexMesh<3> block = box_mesh(1.0, 1.0, 1.0, 1, 1, 1);
  for (double nu : {0.3, 1.0, 1.5, -0.5, HUGE_VAL}) {
    try {
      make_mass_spring(sheet, Soft(nu));
      ADD_FAILURE() << "2D nu " << nu << " accepted";
    } catch (const MaterialError& e) {
      EXPECT_NE(std::string(e.what()).find("outside [1/3, 1) for a 2D sheet"), std::string::npos)
          << e.what();
    }
  }
  for (double nu : {0.2, 0.5, 0.7, -HUGE_VAL}) {
    try {
      make_mass_spring(block, Soft(nu));
      ADD_FAILURE() << "3D nu " << nu << " accepted";
    } catch (const MaterialError& e) {
      EXPECT_NE(std::string(e.what()).find("outside [1/4, 1/2) for a 3D solid"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(make_mass_spring(sheet, Soft(0.999)).volume_terms.size(), sheet.elements.size());
  EXPECT_EQ(make_mass_spring(block, Soft(0.4999)).volume_terms.size(), block.elements.size());
}

// The network's own ratio, given or left NaN, is the plain spring network: no terms, the same
// springs and wave speed.
TEST(VolumeTermsTest, TheNetworksOwnRatioAddsNothing) {
  const SimplexMesh<3> block = box_mesh(1.0, 1.0, 1.0, 2, 2, 2);
  const MassSpringSystem<3> plain = make_mass_spring(block, Soft(std::nan("")));
  const MassSpringSystem<3> own = make_mass_spring(block, Soft(0.25));
  EXPECT_TRUE(own.volume_terms.empty());
  EXPECT_EQ(own.wave_speed, plain.wave_speed);
  for (std::size_t k = 0; k < own.springs.size(); ++k)
    EXPECT_EQ(own.springs[k].params.stiffness, plain.springs[k].params.stiffness);
  const LameSplit split = lame_split<3>(Soft(0.45));
  EXPECT_NEAR(split.volume_stiffness, split.lambda - split.mu, 1e-12 * split.lambda);
  EXPECT_NEAR(split.p_wave_speed, std::sqrt((split.lambda + 2 * split.mu) / 1e3), 1e-12);
}

TEST(VolumeTermsTest, BadVolumeTermsAreRefusedByTheSteps) {
  const MassSpringSystem<2> good = make_mass_spring(rectangle_mesh(1.0, 1.0, 2, 2), Soft(0.5));
  const auto refuse = [&](auto edit, const char* what) {
    MassSpringSystem<2> s = good;
    edit(s);
    try {
      symplectic_euler_step(s, 1e-6);
      ADD_FAILURE() << what << " accepted";
    } catch (const ObjectError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refuse([](auto& s) { s.volume_terms[1].nodes[2] = 99; }, "out of range");
  refuse([](auto& s) { s.volume_terms[1].springs[0] = s.volume_terms[2].springs[2]; },
         "does not join");
  refuse([](auto& s) { s.volume_terms[0].rest_measure = 0.0; }, "rest measure");
  refuse([](auto& s) { s.volume_terms[0].stiffness = -1.0; }, "stiffness");
}

// ---- time steps ----------------------------------------------------------------------------

// The largest omega of the undamped object at rest, from M^-1 K (dense).
template <int Dim>
double HighestFrequency(const MassSpringSystem<Dim>& s) {
  const MassSpringIntegration<Dim> system(s);
  Linearization<MassSpringIntegration<Dim>> lin;
  system.linearize({s.t, s.x, s.v}, JacobianSource::Auto, &lin);
  const Eigen::VectorXd scale = system.masses().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd k =
      -(scale.asDiagonal() * Eigen::MatrixXd(lin.force_D_q) * scale.asDiagonal());
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues().maxCoeff());
}

// The CFL limit keeps omega_max dt <= 2 (symplectic Euler's stability bound) with the terms,
// up to nu = 0.499; the springs' speed alone would not.
TEST(VolumeTermsTest, CflLimitCoversTheStiffestModeWithTheTerms) {
  const SimplexMesh<2> sheet = Jittered(rectangle_mesh(1.0, 1.0, 6, 6), 0.03, 4);
  const SimplexMesh<3> block = Jittered(box_mesh(1.0, 1.0, 1.0, 3, 3, 3), 0.05, 4);
  for (double nu : {0.45, 0.49, 0.499}) {
    const MassSpringSystem<3> s = make_mass_spring(block, Soft(nu));
    const double product = HighestFrequency(s) * cfl_limit(s);
    EXPECT_LE(product, 2.0) << "3D nu " << nu;
    std::printf("[ poisson ] 3D nu %.3f: omega_max x CFL limit = %.3f (stable up to 2)\n", nu,
                product);
  }
  for (double nu : {0.6, 0.9, 0.99}) {
    const MassSpringSystem<2> s = make_mass_spring(sheet, Soft(nu));
    const double product = HighestFrequency(s) * cfl_limit(s);
    EXPECT_LE(product, 2.0) << "2D nu " << nu;
    std::printf("[ poisson ] 2D nu %.3f: omega_max x CFL limit = %.3f (stable up to 2)\n", nu,
                product);
  }
  // the same springs without the terms: their CFL limit is too long for nu = 0.49
  const Material soft = Soft(0.49);
  const MassSpringSystem<3> with = make_mass_spring(block, soft);
  const MassSpringSystem<3> springs =
      make_mass_spring(block, Material{lame_split<3>(soft).network_youngs, soft.density, 0.0});
  EXPECT_GT(HighestFrequency(with) * cfl_limit(springs), 2.0);
  const double plain = cfl_limit(make_mass_spring(block, Soft(std::nan(""))));
  std::printf(
      "[ poisson ] 3D CFL limit of the plain network over that with nu 0.45 / 0.49: "
      "%.2f / %.2f\n",
      plain / cfl_limit(make_mass_spring(block, Soft(0.45))), plain / cfl_limit(with));
}

// Undamped explicit steps at the CFL limit with nu = 0.49 stay bounded and keep the energy of
// a bar's first longitudinal mode (a slow one, so that symplectic Euler's O(omega dt)
// oscillation of the measured energy is small); noise of 1e-9 m seeds every mode, the
// stiffest included. At the springs' own limit the same run blows up.
TEST(VolumeTermsTest, ExplicitRunAtTheCflLimitConservesEnergy) {
  const SimplexMesh<3> bar = box_mesh(2.0, 0.5, 0.5, 8, 2, 2);
  const Material soft = Soft(0.49);
  MassSpringSystem<3> s = make_mass_spring(bar, soft);
  std::mt19937 random(8);
  std::uniform_real_distribution<double> u(-1e-9, 1e-9);
  for (int n = 0; n < s.num_nodes(); ++n) {
    s.v(0, n) = 0.01 * std::cos(3.14159265358979 * s.x(0, n) / 2.0);
    for (int i = 0; i < 3; ++i) s.x(i, n) += u(random);
  }
  MassSpringSystem<3> forced = s;
  const double e0 = total_energy(s);
  const double dt = cfl_limit(s);
  const int steps = 20000, window = 2000;
  double worst = 0.0, early = 0.0, late = 0.0;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(s, dt);
    const double e = total_energy(s);
    worst = std::max(worst, std::abs(e - e0) / e0);
    if (k < window) early += e / window;
    if (k >= steps - window) late += e / window;
  }
  EXPECT_LT(worst, 0.05);               // the oscillation about the mean, as the rod's at 0.9 x CFL
  EXPECT_NEAR(late, early, 1e-3 * e0);  // no drift
  std::printf(
      "[ poisson ] 3D nu 0.49, 2e4 undamped explicit steps at the CFL limit: "
      "max |E - E0| / E0 = %.3g, mean E / E0 first and last 2000 steps %.6f, %.6f\n",
      worst, early / e0, late / e0);
  // the springs' own limit
  const MassSpringSystem<3> springs =
      make_mass_spring(bar, Material{lame_split<3>(soft).network_youngs, soft.density, 0.0});
  ExplicitOptions allow;
  allow.allow_cfl_violation = true;
  const double too_long = cfl_limit(springs);
  bool blew_up = false;
  for (int k = 0; k < steps && !blew_up; ++k) {
    try {
      symplectic_euler_step(forced, too_long, allow);
      blew_up = !(total_energy(forced) < 10 * e0);
    } catch (const ObjectError&) {
      blew_up = true;
    }
  }
  EXPECT_TRUE(blew_up) << "steps of " << too_long << " s (the springs' limit, " << too_long / dt
                       << " x the limit with the terms) stayed bounded";
}

// Backward Euler at 10 x the CFL limit with nu = 0.49: finite, and undamped its energy never
// rises (its numerical damping); the object settles back to its rest volume.
TEST(VolumeTermsTest, ImplicitRunIsStableAndDissipative) {
  const SimplexMesh<3> block = box_mesh(1.0, 1.0, 1.0, 3, 3, 3);
  MassSpringSystem<3> s = make_mass_spring(block, Soft(0.49));
  s.x = 1.01 * block.nodes;
  BackwardEulerStepper<3> stepper;
  const double dt = 10 * cfl_limit(s);
  const double start = total_energy(s);
  double previous = start;
  for (int k = 0; k < 300; ++k) {
    stepper.step(s, dt);
    const double e = total_energy(s);
    ASSERT_TRUE(std::isfinite(e));
    ASSERT_LE(e, previous + 1e-12 * start) << "step " << k;
    previous = e;
  }
  EXPECT_LT(previous, 1e-3 * start);
}

// The stepper's matrix (terms' blocks written into the kept pattern) gives the runtime's
// linearized backward Euler on MassSpringIntegration (terms' triplets), to rounding, with
// pinned nodes and a spring that breaks (the elements around it drop out).
TEST(VolumeTermsTest, StepperMatchesTheRuntimesLinearizedBackwardEuler) {
  MassSpringSystem<2> s =
      make_mass_spring(rectangle_mesh(0.5, 0.2, 5, 2), Material{2e3, 1.0, 1.0, 0.45});
  pin_nodes_where(s, 0, 0.0);
  s.gravity << 0.0, -9.81;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.x(0, n) > 0.45) s.v(1, n) = -5.0;  // a blow to the free end
  }
  s.inelastic.fracture_strain = 0.02;
  ImplicitOptions cholesky;
  cholesky.solver = LinearSolver::kSparseCholesky;
  const double dt = 5e-3;
  MassSpringSystem<2> runtime = s;
  BackwardEulerStepper<2> stepper(cholesky);
  for (int k = 0; k < 40; ++k) {
    const MassSpringIntegration<2> system(runtime, cholesky);
    NewtonOptions linearized;
    linearized.linearized = true;
    finish_step<2>(gencoord::backward_euler_step(system, system.state(), dt, linearized), dt,
                   &runtime);
    stepper.step(s, dt);
    ASSERT_LE((s.v - runtime.v).cwiseAbs().maxCoeff(), 1e-10) << "step " << k;
    ASSERT_LE((s.x - runtime.x).cwiseAbs().maxCoeff(), 1e-12) << "step " << k;
  }
  EXPECT_FALSE(s.fractures.empty()) << "no spring broke";
}

}  // namespace
}  // namespace gencoord::deformable
