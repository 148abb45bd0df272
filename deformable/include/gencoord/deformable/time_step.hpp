// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file time_step.hpp
/// Time stepping: symplectic Euler (explicit, limited by the CFL condition) and backward Euler
/// (implicit, one linearized sparse solve per step, not limited by it), the runtime's methods
/// (gencoord/integrate/) on the object (mass_spring_integration.hpp). Both advance s.t and
/// s.steps and then apply fracture and plasticity (inelastic.hpp).

#include <stdexcept>

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

/// Damping ratio zeta = (d / k) c / L_min of the stiffest mode (omega = 2 c / L_min); 0 when
/// the springs are undamped.
template <int Dim>
double damping_ratio_at_cfl(const MassSpringSystem<Dim>& s);

/// CFL limit of the explicit step (s): dt <= L_min / c, so that no step moves information
/// further than one (shortest) spring (c = s.wave_speed, raised for volume terms by
/// add_volume_terms() and for a sheet's bending hinges, bending.hpp, so that the limit holds
/// for them too); for a uniform rod it is exactly the stability limit of symplectic Euler, and
/// for continuum elements 2 / omega_max from an estimate of their highest frequency, within
/// 5% of the true limit (continuum_highest_frequency()).
/// With damping it is multiplied by sqrt(1 + zeta^2) - zeta (<= 1), the stability bound for a
/// damped mode. Infinity when no spring is left.
template <int Dim>
double cfl_limit(const MassSpringSystem<Dim>& s);

/// An estimate from above of the highest angular frequency omega_max (1/s) of the undamped
/// object about its current shape, over its free nodes: sqrt of the largest eigenvalue of
/// M^-1 K (K the definite stiffness of the springs, volume terms, continuum elements and
/// hinges; M the lumped masses) by 60 Lanczos iterations, raised by 5% for what they have not
/// converged. It costs one assembly of the step matrix and 60 products with it. 0 when
/// nothing is stiff.
template <int Dim>
double highest_frequency(const MassSpringSystem<Dim>& s);

/// The step up to which symplectic Euler is stable (s): the larger of cfl_limit(s) and
/// 2 / omega (omega: highest_frequency(s), raised to sqrt(omega^2 + omega_p^2) by the ground's
/// or the contacts' penalty omega_p) times sqrt(1 + zeta^2) - zeta for the damping ratio
/// zeta of that mode. Within 6% of the true limit on the meshes the tests measure, where
/// cfl_limit(s) is 0.3 to 0.8 of it in 2D and 3D; ExplicitStepper checks its steps against
/// it. Infinity when nothing is stiff.
template <int Dim>
double stable_step_limit(const MassSpringSystem<Dim>& s);

/// Thrown by symplectic_euler_step() for a step above the CFL limit; what() gives the limit.
struct CflViolation : std::domain_error {
  using std::domain_error::domain_error;
};

struct ExplicitOptions {
  bool allow_cfl_violation = false;  ///< take a step above the CFL limit anyway
};

/// One symplectic Euler step of dt (s): v += dt M^-1 f(x, v); x += dt v (pinned nodes just move
/// with their v). Throws CflViolation if dt > cfl_limit(s) unless options allow it;
/// gencoord::StepSizeError unless dt is positive and finite; ObjectError if the object is not
/// valid (validate_object()) or the step diverged (s is then left unchanged).
template <int Dim>
void symplectic_euler_step(MassSpringSystem<Dim>& s, double dt,
                           const ExplicitOptions& options = {});

enum class LinearSolver {
  kConjugateGradient,  ///< Jacobi-preconditioned CG: memory and cost linear in the size
  kSparseCholesky,     ///< SimplicialLDLT: direct, fill-in grows faster than linear in 2D/3D
};

struct ImplicitOptions {
  LinearSolver solver = LinearSolver::kConjugateGradient;
  /// CG stopping rule: the residual r = b - A dv of the step's solve, in the inverse-mass norm
  /// (|r|^2 = sum r_k^2 / m_k over the free unknowns), at most `tolerance` times the right-hand
  /// side's norm, or at most the floor 64 eps |v| (|v|^2 = sum m_k v_k^2, the state's
  /// velocities; eps the double epsilon), below which adding dv to v is lost in rounding v.
  /// Since the step matrix is at least the mass matrix, the error of dv in the kinetic-energy
  /// norm is at most the bound. A zero right-hand side gives dv = 0 without iterating.
  double tolerance = 1e-8;
  int max_iterations = 2000;
  /// CG starts from the previous step's velocity change (BackwardEulerStepper keeps it)
  /// instead of zero.
  bool warm_start = true;
  /// When a contact begins or ends during a step, at most this many Newton iterations of the
  /// nonlinear backward Euler equation follow the linearized solve (see
  /// backward_euler_step()); 0 keeps the linearized step always.
  int max_contact_iterations = 20;
  /// They stop when the equation's residual |M (v1 - v) - dt f(x1, v1)|_{M^-1} is at most
  /// this times |dt f(x1, v1)|_{M^-1}.
  double contact_tolerance = 1e-6;
};

/// What one backward Euler solve did.
struct ImplicitStats {
  int iterations = 0;     ///< CG iterations, over all solves (0 for Cholesky and a zero right side)
  double residual = 0.0;  ///< CG relative residual |r| / |b| (inverse-mass norms, as above)
  int unknowns = 0;       ///< free degrees of freedom
  /// Builds of the step matrix's pattern (with Cholesky, each with its symbolic analysis)
  /// by the stepper so far, this step's included: 1 while no spring breaks.
  int pattern_analyses = 0;
  /// Newton iterations after the linearized solve, for contacts that began or ended during
  /// the step (0 when the linearized step saw every contact)
  int contact_iterations = 0;
};

/// One backward Euler step of dt (s), linearized (one Newton update from v1 = v):
///     (M - dt D - dt^2 K) dv = dt (f + dt K v),  v += dv,  x += dt v,
/// with f, K = df/dx, D = df/dv over the free nodes at (x, v); K uses the definite spring
/// Jacobian, the volume terms' Gauss-Newton part (volume_terms.hpp) and the hinges'
/// Gauss-Newton blocks (bending.hpp), so the matrix is symmetric positive definite. When the
/// contacts at the step's end (ground, obstacles, surfaces) are not those at its start, the
/// matrix lacked a contact's stiffness, and a penalty that begins unseen inside a step gives
/// back more energy than the step stored in it; the step then continues with Newton's method
/// on the nonlinear equation M (v1 - v) = dt f(x + dt v1, v1), each iteration linearized at
/// the last iterate's end, until its residual meets ImplicitOptions::contact_tolerance (or
/// max_contact_iterations). Throws
/// LinearSolveError if the solve fails; StepSizeError and ObjectError as
/// symplectic_euler_step(). Each call builds the matrix's pattern anew; BackwardEulerStepper
/// (implicit_stepper.hpp) keeps it between steps.
template <int Dim>
ImplicitStats backward_euler_step(MassSpringSystem<Dim>& s, double dt,
                                  const ImplicitOptions& options = {});

}  // namespace gencoord::deformable
