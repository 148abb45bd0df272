// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The demo's scenarios: each builds a 2D mass-spring object and says how to step it.

#include <optional>
#include <string>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable::demo {

struct Scenario {
  std::string name;
  std::string description;
  MassSpringSystem<2> system;
  std::optional<SimplexMesh<2>> mesh;  ///< the mesh the system was made from, if any
  double duration = 1.0;               ///< default simulated time (s)
  bool implicit = false;               ///< default integrator: backward Euler if true
  double dt = 0.0;                     ///< default step (s); 0: half the CFL limit
  double view_min_x = -1.0;            ///< picture bounds (m)
  double view_max_x = 1.0;
  double view_min_y = -0.1;
  double view_max_y = 1.0;
};

/// Names accepted by make_scenario, in the order --help lists them.
std::vector<std::string> scenario_names();

/// Builds the named scenario; `resolution` scales the mesh (1 = coarse, default 2).
/// `sampler` is "polar" or "rejection" (particles only). Throws std::invalid_argument.
Scenario make_scenario(const std::string& name, int resolution, const std::string& sampler,
                       unsigned seed);

}  // namespace gencoord::deformable::demo
