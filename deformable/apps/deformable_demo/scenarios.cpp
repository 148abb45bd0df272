// SPDX-License-Identifier: BSD-3-Clause
// Demo scenarios: elastic disk dropped on the ground, cantilever sagging under gravity,
// brittle beam breaking under a load, particles seeded in a disk falling as a heap.
#include "scenarios.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "gencoord/deformable/disk_sampling.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable::demo {

namespace {

constexpr double kGravity = 9.81;  // (m/s^2)

Scenario DiskDrop(int resolution) {
  Scenario sc;
  sc.name = "disk-drop";
  sc.description = "elastic disk (R = 0.2 m, E = 5000 N/m) dropped from 0.3 m onto the ground";
  sc.mesh = disk_mesh(0.2, 3 * resolution, {0.0, 0.5});
  sc.system = make_mass_spring(*sc.mesh, Material{5000.0, 1.0, 0.5});
  sc.system.gravity << 0.0, -kGravity;
  with_ground(sc.system, 0.0, 0.05);
  sc.duration = 1.5;
  sc.view_min_x = -0.5, sc.view_max_x = 0.5, sc.view_min_y = -0.05, sc.view_max_y = 0.75;
  return sc;
}

Scenario Cantilever(int resolution) {
  Scenario sc;
  sc.name = "cantilever";
  sc.description = "cantilever beam 1 m x 0.1 m clamped at x = 0, sagging under gravity";
  sc.mesh = rectangle_mesh(1.0, 0.1, 20 * resolution, 2 * resolution);
  sc.system = make_mass_spring(*sc.mesh, Material{2e4, 1.0, 2.0});
  pin_nodes_where(sc.system, 0, 0.0);
  sc.system.gravity << 0.0, -kGravity;
  sc.duration = 3.0;
  sc.implicit = true;  // low modes barely damped: backward Euler's damping settles it
  sc.dt = 0.005;
  sc.view_min_x = -0.05, sc.view_max_x = 1.1, sc.view_min_y = -0.35, sc.view_max_y = 0.15;
  return sc;
}

Scenario BrittleBeam(int resolution) {
  Scenario sc;
  sc.name = "brittle-beam";
  sc.description =
      "brittle beam 1 m x 0.1 m clamped at both ends, a 3 kg load in the middle; springs "
      "break at 3% strain";
  sc.mesh = rectangle_mesh(1.0, 0.1, 20 * resolution, 2 * resolution);
  MassSpringSystem<2> s = make_mass_spring(*sc.mesh, Material{2e4, 1.0, 1.0});
  pin_nodes_where(s, 0, 0.0);
  pin_nodes_where(s, 0, 1.0);
  // the load: 3 kg spread over the top nodes within 5 cm of the middle
  std::vector<int> loaded;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (std::abs(s.x(0, n) - 0.5) <= 0.05 + 1e-9 && std::abs(s.x(1, n) - 0.1) < 1e-9) {
      loaded.push_back(n);
    }
  }
  for (int n : loaded) s.mass(n) += 3.0 / loaded.size();
  s.gravity << 0.0, -kGravity;
  s.inelastic.fracture_strain = 0.03;
  sc.system = std::move(s);
  sc.duration = 0.4;
  sc.view_min_x = -0.05, sc.view_max_x = 1.05, sc.view_min_y = -0.9, sc.view_max_y = 0.15;
  return sc;
}

Scenario Particles(int resolution, const std::string& sampler, unsigned seed) {
  Scenario sc;
  sc.name = "particles";
  sc.description = "free particles seeded uniformly in a disk (" + sampler +
                   " sampling), falling onto the ground without springs";
  const int count = 100 * resolution * resolution;
  std::mt19937_64 rng(seed);
  const Eigen::Vector2d center(0.0, 0.5);
  Eigen::Matrix2Xd points;
  if (sampler == "polar") {
    points = sample_disk_polar(0.2, count, rng, center);
  } else if (sampler == "rejection") {
    points = sample_disk_rejection(0.2, count, rng, center).points;
  } else {
    throw std::invalid_argument("unknown sampler '" + sampler + "' (polar or rejection)");
  }
  MassSpringSystem<2>& s = sc.system;
  s.x = points;
  s.v = Eigen::Matrix2Xd::Zero(2, count);
  s.mass = Eigen::VectorXd::Constant(count, 1e-3);
  s.pinned.assign(count, 0);
  s.gravity << 0.0, -kGravity;
  s.ground = GroundPlane{0.0, 300.0, 0.2};
  sc.dt = 1e-3;  // no springs, so no CFL limit; the ground needs omega dt << 2
  sc.duration = 0.6;
  sc.view_min_x = -0.5, sc.view_max_x = 0.5, sc.view_min_y = -0.05, sc.view_max_y = 0.75;
  return sc;
}

}  // namespace

std::vector<std::string> scenario_names() {
  return {"disk-drop", "cantilever", "brittle-beam", "particles"};
}

Scenario make_scenario(const std::string& name, int resolution, const std::string& sampler,
                       unsigned seed) {
  if (resolution < 1) throw std::invalid_argument("resolution must be >= 1");
  if (name == "disk-drop") return DiskDrop(resolution);
  if (name == "cantilever") return Cantilever(resolution);
  if (name == "brittle-beam") return BrittleBeam(resolution);
  if (name == "particles") return Particles(resolution, sampler, seed);
  throw std::invalid_argument("unknown scenario '" + name + "' (see --help)");
}

}  // namespace gencoord::deformable::demo
