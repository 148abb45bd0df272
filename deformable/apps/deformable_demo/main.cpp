// SPDX-License-Identifier: BSD-3-Clause
// deformable_demo: runs one mass-spring scenario and writes CSV frames and SVG pictures, and
// with --vtk the frames for ParaView.
//
//   deformable_demo disk-drop --out out/disk --duration 1.5 --animate
//   deformable_demo --help
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "frame_output.hpp"
#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/vtk_writer.hpp"
#include "scenarios.hpp"
#include "svg_output.hpp"

namespace demo = gencoord::deformable::demo;
namespace gd = gencoord::deformable;

namespace {

struct Options {
  std::string scenario;
  std::string out = "deformable_out";
  double duration = -1.0;  // < 0: the scenario's default
  int frames = 60;
  std::string integrator;  // "", "explicit" or "implicit"
  double dt = -1.0;        // < 0: the scenario's default
  bool allow_cfl_violation = false;
  int resolution = 2;
  std::vector<int> svg_frames;  // empty: four evenly spaced
  bool animate = false;
  std::string sampler = "polar";
  unsigned seed = 1;
  std::string vtk;  // "": no ParaView output
};

void PrintHelp() {
  std::printf(
      "usage: deformable_demo SCENARIO [options]\n\n"
      "Simulates a 2D mass-spring object and writes, into the output folder:\n"
      "  frames.csv     frame,time,node,x,y for every saved frame\n"
      "  springs.csv    spring,i,j,broken_at (time the spring broke, empty if never)\n"
      "  frames.svg     chosen frames side by side\n"
      "  animation.svg  all frames, looping (with --animate)\n"
      "and with --vtk DIR, into DIR, for ParaView (File > Open frames.pvd):\n"
      "  frames.pvd, frames_NNNNNN.vtu  every saved frame: springs with strain and broken\n"
      "                 flags, mesh triangles, node velocities and masses\n\n"
      "scenarios:\n");
  for (const std::string& name : demo::scenario_names()) {
    const demo::Scenario sc = demo::make_scenario(name, 1, "polar", 1);
    std::printf("  %-13s %s\n", name.c_str(), sc.description.c_str());
  }
  std::printf(
      "\noptions:\n"
      "  --out DIR            output folder (created; default deformable_out)\n"
      "  --duration T         simulated time in s (default: per scenario)\n"
      "  --frames N           frames saved, evenly spaced (default 60)\n"
      "  --integrator NAME    explicit (symplectic Euler) or implicit (backward Euler)\n"
      "  --dt DT              time step in s (default: half the CFL limit when explicit)\n"
      "  --allow-cfl-violation  take explicit steps above the CFL limit anyway\n"
      "  --resolution N       mesh resolution (default 2; 1 is coarse)\n"
      "  --svg-frames I,J,..  frame indices drawn in frames.svg (default: 4 evenly spaced)\n"
      "  --animate            also write animation.svg\n"
      "  --sampler NAME       particles: polar (r = R sqrt(u1)) or rejection (default polar)\n"
      "  --seed S             particles: random seed (default 1)\n"
      "  --vtk DIR            also write the frames as VTK files for ParaView into DIR\n"
      "  --help               this text\n");
}

std::vector<int> ParseIndexList(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stoi(item));
  return out;
}

// Returns false after printing a message if the command line is wrong.
bool Parse(int argc, char** argv, Options& o) {
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++a];
    };
    if (arg == "--help" || arg == "-h") {
      PrintHelp();
      std::exit(0);
    } else if (arg == "--out") {
      o.out = value();
    } else if (arg == "--duration") {
      o.duration = std::stod(value());
    } else if (arg == "--frames") {
      o.frames = std::stoi(value());
    } else if (arg == "--integrator") {
      o.integrator = value();
      if (o.integrator != "explicit" && o.integrator != "implicit") {
        throw std::invalid_argument("--integrator is explicit or implicit");
      }
    } else if (arg == "--dt") {
      o.dt = std::stod(value());
    } else if (arg == "--allow-cfl-violation") {
      o.allow_cfl_violation = true;
    } else if (arg == "--resolution") {
      o.resolution = std::stoi(value());
    } else if (arg == "--svg-frames") {
      o.svg_frames = ParseIndexList(value());
    } else if (arg == "--animate") {
      o.animate = true;
    } else if (arg == "--sampler") {
      o.sampler = value();
    } else if (arg == "--vtk") {
      o.vtk = value();
    } else if (arg == "--seed") {
      o.seed = static_cast<unsigned>(std::stoul(value()));
    } else if (!arg.empty() && arg[0] == '-') {
      throw std::invalid_argument("unknown option " + arg + " (see --help)");
    } else if (o.scenario.empty()) {
      o.scenario = arg;
    } else {
      throw std::invalid_argument("unexpected argument " + arg);
    }
  }
  if (o.scenario.empty()) throw std::invalid_argument("no scenario given (see --help)");
  if (o.frames < 2) throw std::invalid_argument("--frames must be >= 2");
  return true;
}

int Run(const Options& o) {
  demo::Scenario sc = demo::make_scenario(o.scenario, o.resolution, o.sampler, o.seed);
  gd::MassSpringSystem<2>& s = sc.system;
  const bool implicit = o.integrator.empty() ? sc.implicit : o.integrator == "implicit";
  const double duration = o.duration > 0 ? o.duration : sc.duration;
  const double cfl = gd::cfl_limit(s);
  double dt = o.dt > 0 ? o.dt : (sc.dt > 0 ? sc.dt : 0.5 * cfl);
  const int steps = static_cast<int>(std::ceil(duration / dt));
  dt = duration / steps;  // land exactly on the duration

  std::printf("%s: %s\n", sc.name.c_str(), sc.description.c_str());
  std::printf(
      "  %d nodes, %zu springs, fastest spring %.4g m/s, CFL limit %.4g s, stable step "
      "%.4g s\n",
      s.num_nodes(), s.springs.size(), s.wave_speed, cfl, gd::stable_step_limit(s));
  std::printf("  %s Euler, dt = %.4g s (%.3g x CFL), %d steps, %.3g s\n",
              implicit ? "backward" : "symplectic", dt, dt / cfl, steps, duration);

  gd::ExplicitOptions explicit_options;
  explicit_options.allow_cfl_violation = o.allow_cfl_violation;
  std::vector<demo::Frame> frames;
  frames.push_back({s.t, s.x});
  std::optional<gd::VtkSeriesWriter> vtk;
  const gd::SimplexMesh<2>* mesh = sc.mesh ? &*sc.mesh : nullptr;
  if (!o.vtk.empty()) {
    vtk.emplace(o.vtk);
    vtk->write_frame(s, mesh);
  }
  const double energy0 = gd::total_energy(s);
  gd::BackwardEulerStepper<2> stepper;  // keeps the step matrix's pattern between steps
  gd::ExplicitStepper<2> explicit_stepper(explicit_options);  // validates once
  for (int k = 1; k <= steps; ++k) {
    if (implicit) {
      stepper.step(s, dt);
    } else {
      explicit_stepper.step(s, dt);
    }
    // save when the step crosses the next frame time
    const int frame_due = static_cast<int>(static_cast<long>(k) * (o.frames - 1) / steps);
    if (frame_due >= static_cast<int>(frames.size())) {
      frames.push_back({s.t, s.x});
      if (vtk) vtk->write_frame(s, mesh);
    }
  }
  std::printf("  energy %.5g J -> %.5g J, %zu springs broke", energy0, gd::total_energy(s),
              s.fractures.size());
  if (!s.fractures.empty()) std::printf(" (first at t = %.4g s)", s.fractures.front().t);
  std::printf("\n  lowest node at y = %.4g m, highest at y = %.4g m\n", s.x.row(1).minCoeff(),
              s.x.row(1).maxCoeff());

  std::filesystem::create_directories(o.out);
  demo::write_csv(o.out, frames, s);
  std::vector<int> chosen = o.svg_frames;
  if (chosen.empty()) {
    const int last = static_cast<int>(frames.size()) - 1;
    chosen = {0, last / 3, 2 * last / 3, last};
  }
  for (int f : chosen) {
    if (f < 0 || f >= static_cast<int>(frames.size())) {
      throw std::invalid_argument("--svg-frames index " + std::to_string(f) + " out of range 0.." +
                                  std::to_string(frames.size() - 1));
    }
  }
  demo::write_svg_panels(o.out + "/frames.svg", sc, s, frames, chosen);
  if (o.animate) demo::write_svg_animation(o.out + "/animation.svg", sc, s, frames);
  std::printf("  wrote %s/frames.csv, springs.csv, frames.svg%s (%zu frames)\n", o.out.c_str(),
              o.animate ? ", animation.svg" : "", frames.size());
  if (vtk) std::printf("  wrote %s (%zu frames)\n", vtk->pvd_path().c_str(), vtk->frames().size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    Parse(argc, argv, options);
    return Run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deformable_demo: %s\n", e.what());
    return 1;
  }
}
