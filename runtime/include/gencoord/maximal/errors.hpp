// SPDX-License-Identifier: BSD-3-Clause
// Exceptions of the maximal-coordinate side: the inverse map (x, xdot) -> (q, v) and the
// maximal (penalty) model's simulations. Header-only: each message is built where it is thrown.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace gencoord {

/// The inverse map found no (q, v) for a maximal state (x, xdot): Gauss-Newton did not
/// converge, the point is farther from the manifold x = X(q, t) than allowed, or the
/// Jacobian J (or Mt = J^T M J) is singular there.
class InverseMapError : public std::runtime_error {
 public:
  enum class Reason {
    kNotConverged,  // Gauss-Newton hit max_iterations, or its step control found no descent
    kOffManifold,   // converged, but |x - X(q, t)| > InverseMapOptions::max_residual
    kSingular,      // J or Mt singular (coordinate singularity, zero masses) or non-finite
  };

  /// \param[in] model       The model's name.
  /// \param[in] reason      What failed.
  /// \param[in] t           The time of the maximal state.
  /// \param[in] residual    |x - X(q, t)|_2 at the last iterate.
  /// \param[in] iterations  Gauss-Newton iterations performed.
  /// \param[in] tolerance   The residual allowed (InverseMapOptions::max_residual).
  InverseMapError(const std::string& model, Reason reason, double t, double residual,
                  int iterations, double tolerance)
      : std::runtime_error(message(model, reason, t, residual, iterations, tolerance)),
        reason_(reason),
        t_(t),
        residual_(residual),
        iterations_(iterations) {}

  Reason reason() const { return reason_; }
  double time() const { return t_; }
  double residual() const { return residual_; }  // |x - X(q, t)|_2 at the last iterate
  int iterations() const { return iterations_; }

 private:
  static std::string message(const std::string& model, Reason reason, double t, double residual,
                             int iterations, double tolerance) {
    std::ostringstream os;
    os.precision(6);
    os << "gencoord: inverse map of model '" << model << "' failed at t = " << t << " after "
       << iterations << " Gauss-Newton iterations, residual |x - X(q, t)| = " << residual << ": ";
    switch (reason) {
      case Reason::kNotConverged:
        os << "Gauss-Newton did not converge; give a closer initial guess q0 or raise "
              "InverseMapOptions::max_iterations";
        break;
      case Reason::kOffManifold:
        os << "the point is off the manifold x = X(q, t) (allowed residual " << tolerance
           << "); it is not a state of the reduced model";
        break;
      case Reason::kSingular:
        os << "the Jacobian J or the mass matrix Mt is singular or not finite there (a "
              "coordinate singularity, zero masses, or a diverged state)";
        break;
    }
    os << '.';
    return os.str();
  }

  Reason reason_;
  double t_, residual_;
  int iterations_;
};

/// A maximal-model simulation produced NaN or inf: the step is above the stability limit of
/// an explicit integrator, or the state diverged.
class MaximalDivergedError : public std::runtime_error {
 public:
  /// \param[in] model  The model's name.
  /// \param[in] t      The time of the first non-finite state.
  /// \param[in] dt     The step size used.
  /// \param[in] kappa  The penalty stiffness.
  MaximalDivergedError(const std::string& model, double t, double dt, double kappa)
      : std::runtime_error(message(model, t, dt, kappa)), t_(t) {}

  double time() const { return t_; }

 private:
  static std::string message(const std::string& model, double t, double dt, double kappa) {
    std::ostringstream os;
    os << "gencoord: the maximal model of '" << model << "' (kappa = " << kappa
       << ") diverged at t = " << t << " with dt = " << dt
       << ": the step is probably above the explicit stability limit; use "
          "stable_step() or backward Euler.";
    return os.str();
  }
  double t_;
};

}  // namespace gencoord
