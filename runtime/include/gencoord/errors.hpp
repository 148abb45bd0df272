// SPDX-License-Identifier: BSD-3-Clause
// Exceptions thrown by the runtime. Each message names the model, the time and what to do.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace gencoord {

/// The dynamics could not be evaluated: the mass matrix is not symmetric positive definite, or
/// the mass matrix, the forces or the resulting acceleration contain NaN or inf.
class DynamicsError : public std::runtime_error {
 public:
  enum class Reason {
    kNotPositiveDefinite,    // Cholesky factorization of Mt failed
    kNonFiniteMassMatrix,    // NaN or inf in Mt
    kNonFiniteForces,        // NaN or inf in Ft + Fi
    kNonFiniteAcceleration,  // NaN or inf in Mt^-1 (Ft + Fi), e.g. Mt nearly singular
    kDependentConstraints,   // A Mt^-1 A^T singular: kinematic constraints dependent here
    kNonFiniteConstraints,   // NaN or inf in the constraint Jacobian A or the bias gamma
  };

  DynamicsError(std::string model, Reason reason, double t, std::vector<double> q,
                std::vector<double> v);

  const std::string& model() const { return model_; }
  Reason reason() const { return reason_; }
  double time() const { return t_; }
  const std::vector<double>& q() const { return q_; }
  const std::vector<double>& v() const { return v_; }

 private:
  std::string model_;
  Reason reason_;
  double t_;
  std::vector<double> q_, v_;
};

/// Newton's method in an implicit step did not converge within NewtonOptions::max_iterations:
/// the update or the residual test (NewtonOptions) still failed, or an update was not finite.
class NewtonError : public std::runtime_error {
 public:
  NewtonError(std::string model, double t, double h, int iterations, double update_norm,
              double residual_norm, double tolerance, double residual_scale = 1.0,
              double residual_tolerance = 0.0);

  const std::string& model() const { return model_; }
  double time() const { return t_; }                         // start time of the implicit (sub)step
  double step_size() const { return h_; }                    // size of the implicit (sub)step
  int iterations() const { return iterations_; }             // Newton updates performed
  double update_norm() const { return update_norm_; }        // inf-norm of the last update
  double residual_norm() const { return residual_norm_; }    // inf-norm of the last residual
  double tolerance() const { return tolerance_; }            // of the update test
  double residual_scale() const { return residual_scale_; }  // the residual test's scale
  double residual_tolerance() const { return residual_tolerance_; }
  /// residual_norm() / residual_scale(): the relative imbalance of the implicit equation.
  double scaled_residual() const { return residual_norm_ / residual_scale_; }

 private:
  std::string model_;
  double t_, h_;
  int iterations_;
  double update_norm_, residual_norm_, tolerance_, residual_scale_, residual_tolerance_;
};

/// A step size or duration that cannot be used (non-positive, non-finite, or a duration that
/// is not a whole number of steps).
class StepSizeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A step ended at a state that is not finite (NaN or inf): it was unstable at its size.
class DivergedError : public std::runtime_error {
 public:
  DivergedError(std::string model, std::string integrator, double t, double h);

  const std::string& model() const { return model_; }
  const std::string& integrator() const { return integrator_; }
  double time() const { return t_; }  // start time of the step
  double step_size() const { return h_; }

 private:
  std::string model_, integrator_;
  double t_, h_;
};

namespace detail {

// Cold paths, out of line so the inlined hot paths stay small.
// nv: the size of v where it differs from nq (generalized speeds); -1 for nq
[[noreturn]] void throw_dynamics_error(const char* model, DynamicsError::Reason reason, double t,
                                       const double* q, const double* v, int nq, int nv = -1);
[[noreturn]] void throw_newton_error(const char* model, double t, double h, int iterations,
                                     double update_norm, double residual_norm, double tolerance,
                                     double residual_scale, double residual_tolerance);
[[noreturn]] void throw_diverged_error(const char* model, const char* integrator, double t,
                                       double h);

}  // namespace detail

}  // namespace gencoord
