// SPDX-License-Identifier: BSD-3-Clause
// Conditioning monitor: warns about or stops at coordinate singularities (gimbal lock, the
// poles of spherical coordinates) before the dynamics turn into garbage.
#pragma once

#include <Eigen/Cholesky>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// Thrown by a ConditioningMonitor with policy Stop.
class SingularityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Estimate of the 2-norm condition number of an SPD matrix from its Cholesky factor L:
/// (max_i L_ii / min_i L_ii)^2. It is a lower bound of cond(Mt), cheap (the factor is
/// already there), and grows like 1/sigma_min(J)^2 as the Jacobian loses rank. Infinity if
/// the factorization failed.
template <class Matrix>
double condition_estimate(const Eigen::LLT<Matrix>& llt) {
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const auto diagonal = llt.matrixLLT().diagonal().cwiseAbs();
  const double ratio = diagonal.maxCoeff() / diagonal.minCoeff();
  return ratio * ratio;
}

/// What a ConditioningMonitor does when the estimate passes its threshold.
enum class ConditioningPolicy {
  Ignore,    // only record the worst estimate
  WarnOnce,  // print one warning (configuration and estimate) to stderr, then record
  Stop,      // throw SingularityError with the configuration and the estimate
};

/// Observer for simulate(): estimates cond(Mt) at every state it sees.
/// \tparam M a generated model.
template <class M>
class ConditioningMonitor {
 public:
  /// \param[in] p          model parameters (copied)
  /// \param[in] policy     what to do past the threshold
  /// \param[in] threshold  condition estimate that counts as near-singular (default 1e8:
  ///                       about half the digits of a double lost in the solve)
  explicit ConditioningMonitor(const ParamsOf<M>& p,
                               ConditioningPolicy policy = ConditioningPolicy::WarnOnce,
                               double threshold = 1e8)
      : p_(p), policy_(policy), threshold_(threshold) {}

  /// Checks one state. \throws SingularityError (policy Stop) past the threshold.
  void operator()(const State<M>& s) {
    const VMat<M> Mt = M::mass_matrix(s.q, s.t, p_);
    const double estimate = condition_estimate(Eigen::LLT<PlainOf<VMat<M>>>(Mt));
    if (!(estimate <= worst_)) {  // also records NaN/inf as the worst
      worst_ = estimate;
      worst_time_ = s.t;
    }
    if (estimate <= threshold_ || policy_ == ConditioningPolicy::Ignore) return;
    if (policy_ == ConditioningPolicy::Stop) throw SingularityError(describe(s, estimate));
    if (!warned_) {
      warned_ = true;
      std::fprintf(stderr, "gencoord: warning: %s\n", describe(s, estimate).c_str());
    }
  }

  double worst() const { return worst_; }  ///< largest estimate seen
  double worst_time() const { return worst_time_; }
  bool warned() const { return warned_; }

 private:
  std::string describe(const State<M>& s, double estimate) const {
    std::ostringstream out;
    out << "model '" << M::name << "' is near a coordinate singularity at t = " << s.t
        << ": the mass matrix condition estimate is " << estimate << " (threshold " << threshold_
        << ") at";
    for (int i = 0; i < M::nq; ++i) out << ' ' << M::coordinate_names[i] << " = " << s.q[i];
    out << ". The parameterization loses rank here (see the singular configurations in the "
           "generated header); use another chart or coordinates that avoid it.";
    return out.str();
  }

  ParamsOf<M> p_;
  ConditioningPolicy policy_;
  double threshold_;
  double worst_ = 0.0;
  double worst_time_ = 0.0;
  bool warned_ = false;
};

}  // namespace gencoord
