// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The measurements behind the deformable library's published figures: a material's stretch,
// a cantilever's tip, a pulse's speed, the energy of implicit drops in contact and the
// explicit stable step against a dense eigensolve. The program deformable_validation prints
// them as the tables of deformables.md; the tests call the same functions and hold each figure
// to a tolerance.

#include <string>

#include "gencoord/deformable/implicit_stepper.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/material.hpp"
#include "gencoord/deformable/mesh.hpp"
#include "gencoord/deformable/stretch_modulus.hpp"

namespace gencoord::deformable::validation {

/// How an object carries its material.
enum class Model {
  kSprings,    ///< calibrated springs, with area or volume terms above the network's nu
  kLinear,     ///< co-rotated linear triangles or tetrahedra
  kQuadratic,  ///< co-rotated quadratic ones, on the mesh with its edge midpoints added
};

/// "springs", "linear elements" or "quadratic elements".
const char* model_name(Model model);

/// `material` (its elasticity ignored) carried by `model` on `mesh`, at rest.
template <int Dim>
MassSpringSystem<Dim> make_object(const SimplexMesh<Dim>& mesh, Material material, Model model);

/// The mesh with every node moved by up to `fraction` of `h` along each axis (seeded), except
/// along the axes of the bounding box's faces it lies on: an irregular mesh of the same prism.
template <int Dim>
SimplexMesh<Dim> jittered(SimplexMesh<Dim> mesh, double h, double fraction, unsigned seed);

/// E and nu of a relaxed stretch along x (stretch_response()) of `mesh` (a strip or bar along
/// x) of Young's modulus `youngs` and Poisson's ratio `nu`, carried by `model`.
template <int Dim>
StretchResponse stretch(const SimplexMesh<Dim>& mesh, double youngs, double nu, Model model);

/// Tip deflection of a cantilever of length 1 and depth 0.1 (square in 3D), `across` cells
/// through its depth and 10 times as many along it, clamped at every node of x = 0 and loaded
/// at its tip, in a linear static solve with the stiffness at rest, over Timoshenko's
/// P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6 (E = 1e5 Pa, nu = 0.3).
template <int Dim>
double cantilever_tip_ratio(int across, Model model);

/// Speed (m/s) of a Gaussian pulse of axial displacement `width` wide along a strip (2D) or
/// bar (3D) of length 3 along x with free sides, from the arrival times of its peak at x =
/// 1.2 and 2.0 (the mean displacement of the nodes within h / 2 of each); symplectic Euler
/// at half the CFL limit. With `stretched` the springs are calibrated to the body's static
/// stretch (calibrate_to_stretch()). NaN if no node is near a probe.
template <int Dim>
double pulse_speed(const SimplexMesh<Dim>& mesh, double h, const Material& material, Model model,
                   double width, bool stretched = false);

/// The implicit drops whose energy deformables.md tabulates.
enum class Drop {
  kCubeOnGround,        ///< a cube of springs (E = 2e5 Pa) onto the ground
  kSoftCubeOnSphere,    ///< a soft one (E = 5e4 Pa) onto a sphere
  kSoftElementsThrown,  ///< a soft cube of co-rotated elements thrown at 4 m/s
  kFoldingSheet,        ///< a sheet falling over and folding onto itself on the ground
};
inline constexpr Drop kDrops[] = {Drop::kCubeOnGround, Drop::kSoftCubeOnSphere,
                                  Drop::kSoftElementsThrown, Drop::kFoldingSheet};

/// What a drop shows.
struct DropOutcome {
  std::string name;       ///< what was dropped, onto what
  long steps = 0;         ///< backward Euler steps
  long newton = 0;        ///< Newton iterations for contacts, over all steps
  double highest = 0.0;   ///< the largest (E - E0) / E0 after any step
  double deepest = 0.0;   ///< the deepest any node went below the ground (m)
  double e_end = 0.0;     ///< E / E0 at the end
  int inverted = 0;       ///< elements inverted at the end
  double shortest = 0.0;  ///< the object's shortest rest length (m)
};

/// The drop, in backward Euler steps of `cfl_multiple` times its CFL limit.
DropOutcome implicit_drop(Drop drop, double cfl_multiple, const ImplicitOptions& options = {});

/// The explicit step's limits against the true one, 2 / omega_max from a dense eigensolve of
/// the linearized forces (times the damping factor of that mode when the springs are damped).
struct StableStepRatios {
  double stable_step = 0.0;  ///< stable_step_limit() / the true limit
  double cfl = 0.0;          ///< cfl_limit() (L_min / c) / the true limit
  double frequency = 0.0;    ///< highest_frequency() / the true omega_max
};
template <int Dim>
StableStepRatios stable_step_ratios(const MassSpringSystem<Dim>& s);

}  // namespace gencoord::deformable::validation
