// SPDX-License-Identifier: BSD-3-Clause
// Implicit drops in contact and the explicit step's limits against a dense eigensolve
// (figures.hpp).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "explicit_stability.hpp"
#include "figures.hpp"
#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/sheet.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable::validation {

namespace {

constexpr double kGravity = 9.81;

// a 0.2 m cube of 4^3 cells, its bottom at `height`, under gravity, over the ground at 0
MassSpringSystem<3> cube_over(double height, const Material& material) {
  const double edge = 0.2;
  MassSpringSystem<3> s = make_mass_spring(
      box_mesh(edge, edge, edge, 4, 4, 4, Eigen::Vector3d(-0.5 * edge, -0.5 * edge, height)),
      material);
  s.gravity << 0.0, 0.0, -kGravity;
  with_ground(s, 0.0, 0.3);
  return s;
}

// a sheet standing on one edge, tilted, that falls over and folds onto itself on the ground
MassSpringSystem<3> folding_sheet() {
  const int cells = 12;
  TriangleSurface cloth =
      triangle_lattice_sheet(0.6, 0.6, cells, cells, Eigen::Vector3d(-0.3, -0.3, 0.0));
  for (int n = 0; n < cloth.nodes.cols(); ++n) {  // into the plane x-z, leaning 0.2 rad
    const double y = cloth.nodes(1, n) + 0.3;
    cloth.nodes(1, n) = std::sin(0.2) * y;
    cloth.nodes(2, n) = std::cos(0.2) * y + 0.01;
  }
  MassSpringSystem<3> s = make_sheet(cloth, Material{100.0, 0.2, 0.05}, 1e-5);
  s.gravity << 0.0, 0.0, -kGravity;
  with_ground(s, 0.0, 0.3);
  enable_collisions<3>(s, cloth.triangles, 0.3, 0.3, Sides::kBoth);
  return s;
}

// the drop's object, its name and how long it runs (s)
MassSpringSystem<3> scenario(Drop drop, std::string* name, double* duration) {
  switch (drop) {
    case Drop::kCubeOnGround:
      *name = "cube on the ground";
      *duration = 0.5;
      return cube_over(0.3, Material{2e5, 1000.0, 20.0});
    case Drop::kSoftCubeOnSphere: {
      *name = "soft cube on a sphere";
      *duration = 0.6;
      MassSpringSystem<3> s = cube_over(0.45, Material{5e4, 1000.0, 5.0});
      enable_collisions<3>(s, {}, 0.3, 0.3)
          .spheres.push_back({Eigen::Vector3d(0.03, 0.02, 0.15), 0.15});
      return s;
    }
    case Drop::kSoftElementsThrown: {
      // a soft cube of co-rotated elements, fast onto the ground: it squashes and springs back
      *name = "soft elements, fast";
      *duration = 0.4;
      Material rubber{2e4, 1000.0, 2.0};
      rubber.poisson_ratio = 0.45;
      rubber.elasticity = Elasticity::kCorotated;
      MassSpringSystem<3> s = cube_over(0.05, rubber);
      s.v.row(2).setConstant(-4.0);
      return s;
    }
    case Drop::kFoldingSheet:
      *name = "folding sheet";
      *duration = 0.6;
      return folding_sheet();
  }
  return {};
}

}  // namespace

DropOutcome implicit_drop(Drop drop, double cfl_multiple, const ImplicitOptions& options) {
  DropOutcome out;
  double duration = 0.0;
  MassSpringSystem<3> s = scenario(drop, &out.name, &duration);
  out.shortest = min_rest_length(s);
  BackwardEulerStepper<3> stepper(options);
  const double dt = cfl_multiple * cfl_limit(s), e0 = total_energy(s);
  out.highest = -1.0;
  while (s.t < duration) {
    out.newton += stepper.step(s, dt).contact_iterations;
    ++out.steps;
    out.highest = std::max(out.highest, total_energy(s) / e0 - 1.0);
    out.deepest = std::max(out.deepest, -s.x.row(2).minCoeff());
  }
  out.e_end = total_energy(s) / e0;
  for (const auto& e : s.elements) out.inverted += signed_measure<3>(corners_of(e, s.x)) < 0.0;
  return out;
}

template <int Dim>
StableStepRatios stable_step_ratios(const MassSpringSystem<Dim>& s) {
  const double omega = testing::dense_highest_frequency(s);
  double d_over_k = 0.0;
  for (const Spring& sp : s.springs) {
    if (sp.params.stiffness > 0.0)
      d_over_k = std::max(d_over_k, sp.params.damping / sp.params.stiffness);
  }
  const double zeta = d_over_k * omega / 2.0;
  const double true_limit = 2.0 / omega / (std::hypot(1.0, zeta) + zeta);
  return {stable_step_limit(s) / true_limit, cfl_limit(s) / true_limit,
          highest_frequency(s) / omega};
}

template StableStepRatios stable_step_ratios<1>(const MassSpringSystem<1>&);
template StableStepRatios stable_step_ratios<2>(const MassSpringSystem<2>&);
template StableStepRatios stable_step_ratios<3>(const MassSpringSystem<3>&);

}  // namespace gencoord::deformable::validation
