// SPDX-License-Identifier: BSD-3-Clause
// deformable_drop: drops a tetrahedral mesh of your own, made of the material you give, onto
// a sphere, a step or a soft block, and writes the frames for ParaView.
//
//   deformable_drop part.msh --youngs 2e5 --density 1000 --onto block --vtk out/drop
//   deformable_drop --help
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/explicit_stepper.hpp"
#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mesh_io.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/scene.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/deformable/vtk_writer.hpp"

namespace gd = gencoord::deformable;

namespace {

struct Options {
  std::string mesh;
  gd::Material material{2e5, 1000.0, 20.0};
  std::string onto = "block";
  double height = -1.0;  // < 0: half the mesh's size
  double friction = 0.5;
  double damping_ratio = 0.3;
  double duration = 1.0;
  int frames = 60;
  std::string elements = "springs";
  bool implicit = false;
  double dt = -1.0;  // < 0: half the CFL limit (explicit), 10 times it (implicit)
  std::string vtk;
};

void PrintHelp() {
  std::printf(
      "usage: deformable_drop MESH [options]\n\n"
      "Drops the tetrahedral mesh MESH (Gmsh .msh 2.2 or 4.1, TetGen .node/.ele, or a closed\n"
      "Wavefront .obj surface, filled with tetrahedra by tetgen; lengths in m), made of the\n"
      "material you give, from above onto something resting on the ground\n"
      "(z = 0, gravity along -z), with contact, friction and self-contact, and prints what\n"
      "happened. With --vtk DIR it writes every frame for ParaView (File > Open DIR/frames.pvd):\n"
      "the dropped mesh and, for --onto block, the block.\n\n"
      "options:\n"
      "  --youngs E         Young's modulus in Pa (default 2e5)\n"
      "  --density RHO      density in kg/m^3 (default 1000)\n"
      "  --damping D        material damping in Pa s (default 20)\n"
      "  --poisson NU       Poisson's ratio (default: the spring network's 0.25); springs take\n"
      "                     [0.25, 0.5), adding volume terms above 0.25, elements [0, 0.5)\n"
      "  --elements MODEL   the dropped mesh's material model: springs (default), linear\n"
      "                     (co-rotated linear tetrahedra) or quadratic (10-node co-rotated\n"
      "                     tetrahedra, a node added at the middle of every edge)\n"
      "  --onto TARGET      sphere, step (a box whose edge is under the mesh's centre) or block\n"
      "                     (a soft block of the same material glued to the ground, of linear\n"
      "                     elements where the part has quadratic ones; default)\n"
      "  --height H         gap between the mesh and the target's top in m (default: half the\n"
      "                     mesh's size)\n"
      "  --friction MU      Coulomb friction coefficient of every contact (default 0.5)\n"
      "  --duration T       simulated time in s (default 1)\n"
      "  --frames N         frames written, evenly spaced (default 60)\n"
      "  --integrator NAME  explicit (symplectic Euler, default) or implicit (backward Euler)\n"
      "  --dt DT            time step in s (default: half the CFL limit when explicit, 10 times\n"
      "                     it when implicit)\n"
      "  --vtk DIR          write the frames for ParaView into DIR\n"
      "  --help             this text\n");
}

double Number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value))
    throw std::invalid_argument(option + " needs a number, not '" + text + "'");
  return value;
}

Options Parse(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++a];
    };
    if (arg == "--help" || arg == "-h") {
      PrintHelp();
      std::exit(0);
    } else if (arg == "--youngs") {
      o.material.youngs_modulus = Number(arg, value());
    } else if (arg == "--density") {
      o.material.density = Number(arg, value());
    } else if (arg == "--damping") {
      o.material.damping = Number(arg, value());
    } else if (arg == "--poisson") {
      o.material.poisson_ratio = Number(arg, value());
    } else if (arg == "--elements") {
      o.elements = value();
      if (o.elements != "springs" && o.elements != "linear" && o.elements != "quadratic")
        throw std::invalid_argument("--elements is springs, linear or quadratic, not '" +
                                    o.elements + "'");
    } else if (arg == "--onto") {
      o.onto = value();
      if (o.onto != "sphere" && o.onto != "step" && o.onto != "block")
        throw std::invalid_argument("--onto is sphere, step or block, not '" + o.onto + "'");
    } else if (arg == "--height") {
      o.height = Number(arg, value());
    } else if (arg == "--friction") {
      o.friction = Number(arg, value());
    } else if (arg == "--duration") {
      o.duration = Number(arg, value());
    } else if (arg == "--frames") {
      o.frames = static_cast<int>(Number(arg, value()));
    } else if (arg == "--integrator") {
      const std::string name = value();
      if (name != "explicit" && name != "implicit")
        throw std::invalid_argument("--integrator is explicit or implicit, not '" + name + "'");
      o.implicit = name == "implicit";
    } else if (arg == "--dt") {
      o.dt = Number(arg, value());
    } else if (arg == "--vtk") {
      o.vtk = value();
    } else if (!arg.empty() && arg[0] == '-') {
      throw std::invalid_argument("unknown option " + arg + " (see --help)");
    } else if (o.mesh.empty()) {
      o.mesh = arg;
    } else {
      throw std::invalid_argument("unexpected argument " + arg + " (one mesh file)");
    }
  }
  if (o.mesh.empty()) throw std::invalid_argument("no mesh file given (see --help)");
  if (o.frames < 2) throw std::invalid_argument("--frames must be >= 2");
  if (!(o.duration > 0.0)) throw std::invalid_argument("--duration must be positive");
  if (!(o.friction >= 0.0)) throw std::invalid_argument("--friction must be >= 0");
  return o;
}

// The mesh's shortest edge (m), for the block's cells.
double ShortestEdge(const gd::SimplexMesh<3>& mesh) {
  double shortest = INFINITY;
  for (const auto& [i, j] : gd::mesh_edges(mesh))
    shortest = std::min(shortest, (mesh.nodes.col(j) - mesh.nodes.col(i)).norm());
  return shortest;
}

int Run(const Options& o) {
  gd::SimplexMesh<3> part = gd::read_mesh<3>(o.mesh);
  const Eigen::Vector3d lower = part.nodes.rowwise().minCoeff();
  const Eigen::Vector3d upper = part.nodes.rowwise().maxCoeff();
  const Eigen::Vector3d size = upper - lower;
  const double width = size.head<2>().maxCoeff();
  const double gap = o.height >= 0.0 ? o.height : 0.5 * size.maxCoeff();

  // the part's material, and the block's (linear elements where the part has quadratic ones)
  gd::Material material = o.material;
  if (o.elements != "springs") material.elasticity = gd::Elasticity::kCorotated;

  // the target, resting on the ground with its top at z = top
  gd::MassSpringSystem<3> scene;
  gd::SimplexMesh<3> frames_mesh;  // what the frames show: the block (if any), then the part
  double top = 0.0;
  gd::Collisions<3> obstacles;
  if (o.onto == "sphere") {
    obstacles.spheres.push_back({Eigen::Vector3d(0.0, 0.0, 0.6 * width), 0.6 * width});
    top = 1.2 * width;
  } else if (o.onto == "step") {
    top = 0.5 * size.z();
    obstacles.boxes.push_back({Eigen::Vector3d(-10.0 * width, -10.0 * width, -1.0),
                               Eigen::Vector3d(0.0, 10.0 * width, top)});
  } else {
    const double side = 2.0 * width, cell = std::max(ShortestEdge(part), side / 12.0);
    const int cells = std::max(2, static_cast<int>(std::round(side / cell)));
    const int layers = std::max(2, static_cast<int>(std::round(0.5 * side / cell)));
    frames_mesh = gd::box_mesh(side, side, 0.5 * side, cells, cells, layers,
                               Eigen::Vector3d(-0.5 * side, -0.5 * side, 0.0));
    scene = gd::make_mass_spring(frames_mesh, material);
    gd::pin_nodes_where(scene, 2, 0.0);  // glued to the ground
    gd::enable_collisions<3>(scene, gd::boundary_triangles(frames_mesh), o.friction,
                             o.damping_ratio);
    top = 0.5 * side;
  }

  // the part, centred over the target, `gap` above its top
  const Eigen::Vector3d shift(-0.5 * (lower.x() + upper.x()), -0.5 * (lower.y() + upper.y()),
                              top + gap - lower.z());
  part.nodes.colwise() += shift;
  // `shown`: the linear tetrahedra on the part's nodes, which the frames draw and whose
  // boundary collides (a quadratic element's eight)
  gd::MassSpringSystem<3> dropped;
  gd::SimplexMesh<3> shown = part;
  if (o.elements == "quadratic") {
    const gd::QuadraticMesh<3> quadratic = gd::quadratic_mesh(part);
    dropped = gd::make_mass_spring(quadratic, material);
    shown = gd::subdivided_mesh(quadratic);
  } else {
    dropped = gd::make_mass_spring(part, material);
  }
  const double thickness =
      gd::enable_collisions<3>(dropped, gd::boundary_triangles(shown), o.friction, o.damping_ratio)
          .params.thickness;
  const int first = gd::append_object(scene, dropped);
  const int count = dropped.num_nodes();
  for (auto& element : shown.elements) {
    for (int& n : element) n += first;
  }
  frames_mesh.nodes.conservativeResize(3, scene.num_nodes());
  frames_mesh.nodes.rightCols(count) = shown.nodes;
  frames_mesh.elements.insert(frames_mesh.elements.end(), shown.elements.begin(),
                              shown.elements.end());
  gd::Collisions<3>& contact = *scene.collisions;
  contact.spheres = obstacles.spheres;
  contact.boxes = obstacles.boxes;
  // the ground as a box, so that it has friction too
  const double far = 100.0 * size.maxCoeff();
  contact.boxes.push_back({Eigen::Vector3d(-far, -far, -far), Eigen::Vector3d(far, far, 0.0)});
  scene.gravity << 0.0, 0.0, -9.81;

  const double cfl = gd::cfl_limit(scene);
  double dt = o.dt > 0.0 ? o.dt : (o.implicit ? 10.0 : 0.5) * cfl;
  const long steps = static_cast<long>(std::ceil(o.duration / dt));
  dt = o.duration / static_cast<double>(steps);
  std::printf("%s: %d nodes, %zu tetrahedra (%s), %.4g x %.4g x %.4g m, dropped %.4g m onto a %s\n",
              o.mesh.c_str(), count, part.elements.size(), o.elements.c_str(), size.x(), size.y(),
              size.z(), gap, o.onto.c_str());
  std::printf("  E = %.4g Pa, rho = %.4g kg/m^3: c = %.4g m/s; its contact thickness %.4g m\n",
              o.material.youngs_modulus, o.material.density, o.material.wave_speed(), thickness);
  std::printf("  %s Euler, dt = %.4g s (%.3g x CFL), %ld steps, %.3g s\n",
              o.implicit ? "backward" : "symplectic", dt, dt / cfl, steps, o.duration);

  std::optional<gd::VtkSeriesWriter> vtk;
  if (!o.vtk.empty()) {
    vtk.emplace(o.vtk);
    vtk->write_frame(scene, &frames_mesh);
  }
  const double energy0 = gd::total_energy(scene);
  double lowest = INFINITY;  // the part's lowest node over the whole run
  gd::BackwardEulerStepper<3> stepper;
  gd::ExplicitStepper<3> explicit_stepper;
  int written = 1;
  for (long k = 1; k <= steps; ++k) {
    if (o.implicit) {
      stepper.step(scene, dt);
    } else {
      explicit_stepper.step(scene, dt);
    }
    lowest = std::min(lowest, scene.x.rightCols(count).row(2).minCoeff());
    const int due = static_cast<int>(k * (o.frames - 1) / steps);
    if (vtk && due >= written) {
      vtk->write_frame(scene, &frames_mesh);
      ++written;
    }
  }
  const Eigen::Vector3d centre = scene.x.rightCols(count).rowwise().mean();
  std::printf(
      "  energy %.5g J -> %.5g J; the part's centre ends at (%.4g, %.4g, %.4g) m, its\n"
      "  lowest node went down to z = %.4g m (the target's top is at %.4g m)\n",
      energy0, gd::total_energy(scene), centre.x(), centre.y(), centre.z(), lowest, top);
  if (vtk) std::printf("  wrote %s (%zu frames)\n", vtk->pvd_path().c_str(), vtk->frames().size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(Parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deformable_drop: %s\n", e.what());
    return 1;
  }
}
