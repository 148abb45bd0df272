// SPDX-License-Identifier: BSD-3-Clause
// deformable_validation: the figures of deformables.md's tables, measured on structured,
// jittered and Gmsh meshes and printed as Markdown: a material's E and nu in a stretch, wave
// speed, a cantilever's tip, energy in implicit contact, the explicit step's limits against
// a dense eigensolve and the explicit step's cost against the force sum.
//
//   build/deformable/validation/deformable_validation                  # every section
//   build/deformable/validation/deformable_validation --section cantilever --section cfl
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "figures.hpp"
#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/deformable/sheet.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "mesh_files.hpp"

namespace gd = gencoord::deformable;
namespace gv = gencoord::deformable::validation;

namespace {

const char* const kSections[] = {"stretch", "waves", "cantilever", "contact", "cfl", "costs"};

template <int Dim>
struct NamedMesh {
  std::string name;
  gd::SimplexMesh<Dim> mesh;
  double h = 0.0;  // the cell size, for the wave's probes
};

std::vector<NamedMesh<2>> strips(const std::string& dir) {
  return {{"structured 120 x 4", gd::rectangle_mesh(3.0, 0.1, 120, 4), 0.025},
          {"jittered 120 x 4", gv::jittered(gd::rectangle_mesh(3.0, 0.1, 120, 4), 0.025, 0.2, 5),
           0.025},
          {"Gmsh h = 0.025", gd::read_gmsh<2>(dir + "/strip_h025.msh"), 0.025},
          {"Gmsh h = 0.0125", gd::read_gmsh<2>(dir + "/strip_h0125.msh"), 0.0125}};
}

std::vector<NamedMesh<3>> bars(const std::string& dir) {
  return {{"structured 60 x 2 x 2", gd::box_mesh(3.0, 0.1, 0.1, 60, 2, 2), 0.05},
          {"jittered 60 x 2 x 2", gv::jittered(gd::box_mesh(3.0, 0.1, 0.1, 60, 2, 2), 0.05, 0.2, 5),
           0.05},
          {"Gmsh h = 0.05", gd::read_gmsh<3>(dir + "/bar_h050.msh"), 0.05},
          {"Gmsh h = 0.033", gd::read_gmsh<3>(dir + "/bar_h033.msh"), 0.033}};
}

constexpr gv::Model kModels[] = {gv::Model::kSprings, gv::Model::kLinear, gv::Model::kQuadratic};

template <int Dim>
void StretchRows(const std::vector<NamedMesh<Dim>>& meshes) {
  for (const auto& named : meshes) {
    for (const gv::Model model : kModels) {
      std::printf("| %dD %s | %s |", Dim, named.name.c_str(), gv::model_name(model));
      for (const double nu : {0.3, 0.45, 0.49}) {
        // the springs' 2D network starts at nu = 1/3
        const double asked = model == gv::Model::kSprings && Dim == 2 ? std::max(nu, 1.0 / 3) : nu;
        const gd::StretchResponse r = gv::stretch(named.mesh, 1e5, asked, model);
        std::printf(" %.4f, %.4f |", r.youngs_modulus / 1e5, r.poisson_ratio);
      }
      std::printf("\n");
    }
  }
}

void Stretch(const std::string& dir) {
  std::printf(
      "## E / E0 and nu in a relaxed stretch (strip 3 x 0.1, bar 3 x 0.1 x 0.1)\n\n"
      "| mesh | model | nu = 0.30 asked | 0.45 | 0.49 |\n|---|---|---|---|---|\n");
  StretchRows<2>(strips(dir));
  StretchRows<3>(bars(dir));
  std::printf("\n(The springs' 2D network cannot go below nu = 1/3; 1/3 is asked for 0.30.)\n\n");
}

template <int Dim>
void WaveRows(const std::vector<NamedMesh<Dim>>& meshes, const gd::Material& material) {
  for (const auto& named : meshes) {
    std::printf("| %dD %s |", Dim, named.name.c_str());
    for (const gv::Model model : kModels) {
      gd::Material carried = material;  // the springs: the network's own Poisson's ratio
      if (model == gv::Model::kSprings) carried.poisson_ratio = gd::Material{}.poisson_ratio;
      std::printf(" %.4f |", gv::pulse_speed(named.mesh, named.h, carried, model, 0.3));
    }
    std::printf("\n");
  }
}

void Waves(const std::string& dir) {
  gd::Material material{2.25, 1.0, 0.0};  // c = 1.5 m/s
  material.poisson_ratio = 0.3;
  std::printf(
      "## Wave speed (m/s) of a pulse 0.3 m wide, c = 1.5 m/s, nu = 0.3 (the springs: their "
      "network's own)\n\n"
      "| mesh | springs | linear elements | quadratic elements |\n|---|---|---|---|\n");
  WaveRows<2>(strips(dir), material);
  WaveRows<3>(bars(dir), material);
  std::printf("\n");
}

void Cantilever() {
  std::printf(
      "## Cantilever (length 1, depth 0.1, tip load): tip deflection / Timoshenko's\n\n"
      "| cells through the depth | 2D linear | 2D quadratic | 3D linear | 3D quadratic |\n"
      "|---|---|---|---|---|\n");
  for (const int across : {1, 2, 4, 8}) {
    std::printf("| %d | %.4f |", across, gv::cantilever_tip_ratio<2>(across, gv::Model::kLinear));
    if (across <= 4) {
      std::printf(" %.4f |", gv::cantilever_tip_ratio<2>(across, gv::Model::kQuadratic));
    } else {
      std::printf(" |");
    }
    if (across >= 2 && across <= 4) {
      std::printf(" %.4f | %.4f |\n", gv::cantilever_tip_ratio<3>(across, gv::Model::kLinear),
                  gv::cantilever_tip_ratio<3>(across, gv::Model::kQuadratic));
    } else {
      std::printf(" | |\n");
    }
  }
  std::printf("\n");
}

void Contact() {
  std::printf(
      "## Implicit drops: the largest (E - E0) / E0 after any backward Euler step\n\n"
      "| drop | 1 x CFL | 5 x CFL | 10 x CFL | Newton iterations per step (1 / 5 / 10 x) |\n"
      "|---|---|---|---|---|\n");
  for (const gv::Drop drop : gv::kDrops) {
    std::string name, iterations;
    std::vector<double> highest;
    for (const double multiple : {1.0, 5.0, 10.0}) {
      const gv::DropOutcome got = gv::implicit_drop(drop, multiple);
      name = got.name;
      highest.push_back(got.highest);
      char per_step[32];
      std::snprintf(per_step, sizeof per_step, "%.2f", double(got.newton) / got.steps);
      iterations += (iterations.empty() ? "" : " / ") + std::string(per_step);
    }
    std::printf("| %s | %+.1e | %+.1e | %+.1e | %s |\n", name.c_str(), highest[0], highest[1],
                highest[2], iterations.c_str());
  }
  std::printf("\n");
}

template <int Dim>
void CflRow(const char* name, const gd::MassSpringSystem<Dim>& s) {
  const gv::StableStepRatios r = gv::stable_step_ratios(s);
  std::printf("| %s | %.4f | %.4f | %.4f |\n", name, r.stable_step, r.cfl, r.frequency);
}

void Cfl(const std::string& dir) {
  const gd::Material springs{1e5, 1000.0, 0.0};
  gd::Material damped = springs, elements = springs;
  damped.damping = 20.0;
  elements.poisson_ratio = 0.3;
  const gd::SimplexMesh<3> block = gd::read_gmsh<3>(dir + "/block_v41.msh");
  std::printf(
      "## The explicit step's limits over the true limit 2 / omega_max (dense eigensolve)\n\n"
      "| object | stable_step_limit | cfl_limit (L_min / c) | omega_max estimate / true |\n"
      "|---|---|---|---|\n");
  CflRow("uniform rod", gd::make_rod(gd::uniform_rod_nodes(50), springs));
  CflRow("jittered rod", gd::make_rod(gd::jittered_rod_nodes(50, 0.5, 3), springs));
  CflRow("2D strip, springs", gd::make_mass_spring(gd::rectangle_mesh(1.0, 0.2, 20, 4), springs));
  CflRow("Gmsh strip, springs",
         gd::make_mass_spring(gd::read_gmsh<2>(dir + "/strip_h025.msh"), springs));
  CflRow("3D bar, springs", gd::make_mass_spring(gd::box_mesh(0.4, 0.1, 0.1, 8, 2, 2), springs));
  CflRow("Gmsh block, springs", gd::make_mass_spring(block, springs));
  CflRow("Gmsh block, damped springs", gd::make_mass_spring(block, damped));
  CflRow("Gmsh block, linear elements", gv::make_object(block, elements, gv::Model::kLinear));
  CflRow("2D strip, quadratic elements",
         gv::make_object(gd::rectangle_mesh(1.0, 0.2, 10, 2), elements, gv::Model::kQuadratic));
  CflRow("sheet with hinges",
         gd::make_sheet(gd::rectangle_sheet(1.0, 1.0, 8, 8), gd::Material{100.0, 1.0}, 0.5));
  std::printf("\n");
}

// appends the seconds of one call of f, averaged over `calls` calls, to samples
template <class F>
void Sample(F&& f, int calls, std::vector<double>* samples) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < calls; ++k) f();
  samples->push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / calls);
}

template <int Dim>
void CostRow(const char* name, gd::MassSpringSystem<Dim> s) {
  gd::ExplicitStepper<Dim> stepper;
  const double dt = 0.5 * gd::stable_step_limit(s);
  Eigen::Matrix<double, Dim, Eigen::Dynamic> f(Dim, s.num_nodes());
  // interleaved: a round of steps, then a round of force sums, 15 times each
  std::vector<double> steps, sums;
  for (int round = 0; round < 15; ++round) {
    Sample([&] { stepper.step(s, dt); }, 20, &steps);
    Sample(
        [&] {
          f.setZero();
          gd::accumulate_forces(s, f);
        },
        20, &sums);
  }
  std::sort(steps.begin(), steps.end());
  std::sort(sums.begin(), sums.end());
  std::printf("| %s | %.1f / %.1f | %.1f / %.1f | %.2f / %.2f |\n", name, 1e6 * steps.front(),
              1e6 * steps[steps.size() / 2], 1e6 * sums.front(), 1e6 * sums[sums.size() / 2],
              steps.front() / sums.front(), steps[steps.size() / 2] / sums[sums.size() / 2]);
}

void Costs(const std::string& dir) {
  gd::Material elements{1e5, 1000.0, 10.0};
  elements.poisson_ratio = 0.3;
  gd::MassSpringSystem<2> sheet =
      gd::make_mass_spring(gd::rectangle_mesh(1.0, 1.0, 100, 100), gd::Material{1e4, 1.0, 1.0});
  gd::pin_nodes_where(sheet, 0, 0.0);
  sheet.gravity << 0.0, -9.81;
  const gd::SimplexMesh<3> block = gd::read_gmsh<3>(dir + "/block_v41.msh");
  gd::MassSpringSystem<3> springs = gd::make_mass_spring(block, gd::Material{1e5, 1000.0, 10.0});
  gd::MassSpringSystem<3> linear = gv::make_object(block, elements, gv::Model::kLinear);
  gd::MassSpringSystem<3> quadratic = gv::make_object(block, elements, gv::Model::kQuadratic);
  for (gd::MassSpringSystem<3>* s : {&springs, &linear, &quadratic}) {
    gd::pin_nodes_where(*s, 0, s->x.row(0).minCoeff());
    s->gravity << 0.0, 0.0, -9.81;
  }
  std::printf(
      "## An explicit step (ExplicitStepper) against the force sum alone: microseconds, "
      "minimum / median of 15 interleaved rounds of 20 calls (pin the program to one core)\n\n"
      "| object | step | force sum | step / force sum |\n|---|---|---|---|\n");
  CostRow("2D sheet, 100 x 100 cells of springs", sheet);
  CostRow("Gmsh block, springs", springs);
  CostRow("Gmsh block, linear elements", linear);
  CostRow("Gmsh block, quadratic elements", quadratic);
  std::printf("\n");
}

int Run(int argc, char** argv) {
  std::set<std::string> chosen;
  std::string dir = gd::test_meshes_dir();
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: deformable_validation [--section NAME]... [--meshes DIR]\n\n"
          "Prints the deformable library's measured figures as Markdown tables. Sections:\n"
          "stretch, waves, cantilever, contact, cfl, costs (default: all). --meshes: the\n"
          "folder of the Gmsh meshes (default: deformable/tests/meshes of this checkout).\n");
      return 0;
    }
    if (arg == "--section" || arg == "--meshes") {
      if (a + 1 >= argc) throw std::invalid_argument(arg + " needs a value (see --help)");
      const std::string value = argv[++a];
      if (arg == "--meshes") {
        dir = value;
      } else if (std::find(std::begin(kSections), std::end(kSections), value) ==
                 std::end(kSections)) {
        throw std::invalid_argument(
            "--section is stretch, waves, cantilever, contact, cfl or "
            "costs, not '" +
            value + "'");
      } else {
        chosen.insert(value);
      }
    } else {
      throw std::invalid_argument("unknown argument " + arg + " (see --help)");
    }
  }
  auto wanted = [&](const char* name) { return chosen.empty() || chosen.count(name) > 0; };
  if (wanted("stretch")) Stretch(dir);
  if (wanted("waves")) Waves(dir);
  if (wanted("cantilever")) Cantilever();
  if (wanted("contact")) Contact();
  if (wanted("cfl")) Cfl(dir);
  if (wanted("costs")) Costs(dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deformable_validation: %s\n", e.what());
    return 1;
  }
}
