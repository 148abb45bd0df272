// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/errors.hpp"

#include <sstream>
#include <utility>

namespace gencoord {
namespace {

void write_vector(std::ostream& os, const std::vector<double>& x) {
  os << '[';
  for (std::size_t i = 0; i < x.size(); ++i) os << (i ? ", " : "") << x[i];
  os << ']';
}

// what went wrong, then what to do about it
const char* describe(DynamicsError::Reason reason) {
  switch (reason) {
    case DynamicsError::Reason::kNotPositiveDefinite:
      return "the mass matrix Mt is not positive definite (Cholesky factorization failed). "
             "The coordinates are probably at a singularity where the Jacobian J loses rank "
             "(e.g. gimbal lock, a pole of spherical coordinates), or a mass or length "
             "parameter is zero or negative. Check the parameters, or choose coordinates or an "
             "initial state that avoid this configuration";
    case DynamicsError::Reason::kNonFiniteMassMatrix:
      return "the mass matrix Mt contains NaN or inf entries. Check the parameters and the "
             "state for NaN/inf; if this appears during a simulation, the solution has "
             "diverged: reduce the step size or use an implicit integrator";
    case DynamicsError::Reason::kNonFiniteForces:
      return "the generalized forces Ft + Fi contain NaN or inf entries. Check the parameters "
             "and the state for NaN/inf; if this appears during a simulation, the solution has "
             "diverged: reduce the step size or use an implicit integrator";
    case DynamicsError::Reason::kNonFiniteAcceleration:
      return "the acceleration Mt^-1 (Ft + Fi) contains NaN or inf entries although Mt and the "
             "forces are finite: Mt is numerically singular. The coordinates are probably at "
             "or very near a singularity (J loses rank); choose coordinates or an initial state "
             "that avoid it";
    case DynamicsError::Reason::kDependentConstraints:
      return "the kinematic constraints are dependent here (A Mt^-1 A^T is singular: a row of "
             "the constraint Jacobian A is a combination of the others). The mechanism is at "
             "a singular configuration of its loops (a four-bar folded flat), or a constraint "
             "is declared twice; avoid the configuration or remove the redundant constraint";
    case DynamicsError::Reason::kNonFiniteConstraints:
      return "the constraint Jacobian A or the bias gamma contains NaN or inf entries. Check "
             "the parameters and the state for NaN/inf; if this appears during a simulation, "
             "the solution has diverged: reduce the step size";
  }
  return "unknown failure";
}

std::string dynamics_message(const std::string& model, DynamicsError::Reason reason, double t,
                             const std::vector<double>& q, const std::vector<double>& v) {
  std::ostringstream os;
  os.precision(17);
  os << "gencoord: dynamics of model '" << model << "' failed at t = " << t << ", q = ";
  write_vector(os, q);
  os << ", v = ";
  write_vector(os, v);
  os << ": " << describe(reason) << '.';
  return os.str();
}

std::string newton_message(const std::string& model, double t, double h, int iterations,
                           double update_norm, double residual_norm, double tolerance,
                           double residual_scale, double residual_tolerance) {
  std::ostringstream os;
  os << "gencoord: Newton's method did not converge in an implicit step of model '" << model
     << "' (step from t = " << t << ", h = " << h << ") after " << iterations
     << " iterations: last update norm " << update_norm << " (tolerance " << tolerance
     << " relative to 1 + |v|), residual norm " << residual_norm << " = "
     << residual_norm / residual_scale << " of its scale " << residual_scale << " (tolerance "
     << residual_tolerance
     << "). Reduce the step size, raise NewtonOptions::max_iterations, or loosen "
        "NewtonOptions::tolerance or NewtonOptions::residual_tolerance.";
  return os.str();
}

std::string diverged_message(const std::string& model, const std::string& integrator, double t,
                             double h) {
  std::ostringstream os;
  os << "gencoord: the " << integrator << " step of model '" << model << "' from t = " << t
     << " with h = " << h
     << " ended at a state that is not finite (NaN or inf): the step is unstable at this "
        "size. Reduce the step size or use an implicit integrator.";
  return os.str();
}

}  // namespace

DivergedError::DivergedError(std::string model, std::string integrator, double t, double h)
    : std::runtime_error(diverged_message(model, integrator, t, h)),
      model_(std::move(model)),
      integrator_(std::move(integrator)),
      t_(t),
      h_(h) {}

DynamicsError::DynamicsError(std::string model, Reason reason, double t, std::vector<double> q,
                             std::vector<double> v)
    : std::runtime_error(dynamics_message(model, reason, t, q, v)),
      model_(std::move(model)),
      reason_(reason),
      t_(t),
      q_(std::move(q)),
      v_(std::move(v)) {}

NewtonError::NewtonError(std::string model, double t, double h, int iterations, double update_norm,
                         double residual_norm, double tolerance, double residual_scale,
                         double residual_tolerance)
    : std::runtime_error(newton_message(model, t, h, iterations, update_norm, residual_norm,
                                        tolerance, residual_scale, residual_tolerance)),
      model_(std::move(model)),
      t_(t),
      h_(h),
      iterations_(iterations),
      update_norm_(update_norm),
      residual_norm_(residual_norm),
      tolerance_(tolerance),
      residual_scale_(residual_scale),
      residual_tolerance_(residual_tolerance) {}

namespace detail {

void throw_dynamics_error(const char* model, DynamicsError::Reason reason, double t,
                          const double* q, const double* v, int nq, int nv) {
  throw DynamicsError(model, reason, t, std::vector<double>(q, q + nq),
                      std::vector<double>(v, v + (nv < 0 ? nq : nv)));
}

void throw_newton_error(const char* model, double t, double h, int iterations, double update_norm,
                        double residual_norm, double tolerance, double residual_scale,
                        double residual_tolerance) {
  throw NewtonError(model, t, h, iterations, update_norm, residual_norm, tolerance, residual_scale,
                    residual_tolerance);
}

void throw_diverged_error(const char* model, const char* integrator, double t, double h) {
  throw DivergedError(model, integrator, t, h);
}

}  // namespace detail
}  // namespace gencoord
