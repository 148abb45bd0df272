// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers of the integrator tests on generated models: fixed-step runs, the error of
// a run against a reference state, and the measured order of accuracy (fitted log-log slope
// of error against step size).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/numerics/loglog_fit.hpp"

namespace gencoord::testing {

/// Number of equally spaced times (after the start) at which a run is compared with its
/// reference; every step count used must be a multiple of it.
inline constexpr long long kSamples = 5;

/// The states at t0 + k duration / kSamples, k = 1..kSamples, of a run of `steps` fixed steps.
/// \throws std::invalid_argument if steps is not a multiple of kSamples.
template <class M>
std::vector<State<M>> sampled_run(const ParamsOf<M>& p, const State<M>& initial,
                                  Integrator integrator, double duration, long long steps) {
  if (steps % kSamples != 0)
    throw std::invalid_argument("sampled_run: steps must be a multiple of kSamples");
  std::vector<State<M>> samples;
  long long k = 0;
  simulate(ReducedSystem<M>(p), initial,
           {integrator, duration / static_cast<double>(steps), duration}, [&](const State<M>& s) {
             if (k > 0 && k % (steps / kSamples) == 0) samples.push_back(s);
             ++k;
           });
  return samples;
}

/// |(q - q_ref, v - v_ref)|_2, maximized over the sample times: the global error of a run.
/// The maximum over several times, not the end state alone, so that an error component that
/// happens to cross zero near the end cannot fake a high order.
template <class M>
double trajectory_error(const std::vector<State<M>>& run, const std::vector<State<M>>& reference) {
  double worst = 0.0;
  for (std::size_t k = 0; k < run.size() && k < reference.size(); ++k)
    worst = std::max(worst, std::sqrt((run[k].q - reference[k].q).squaredNorm() +
                                      (run[k].v - reference[k].v).squaredNorm()));
  return worst;
}

/// A measured order of accuracy: the step sizes, the errors, and the fitted slope.
struct OrderMeasurement {
  std::vector<double> dts;
  std::vector<double> errors;
  double slope = 0.0;
};

/// Errors (trajectory_error()) for `levels` step sizes duration / (coarsest_steps 2^k)
/// against `reference` (sampled_run() of a much finer run), and the least-squares slope of
/// log(error) against log(dt). Prints one line per step size (dt, error, local slope against the
/// previous size) under a header naming `label`, so a failure shows where the asymptotic regime
/// starts or ends.
template <class M>
OrderMeasurement measure_order(const std::string& label, const ParamsOf<M>& p,
                               const State<M>& initial, const std::vector<State<M>>& reference,
                               Integrator integrator, double duration, long long coarsest_steps,
                               int levels = 5) {
  OrderMeasurement m;
  for (int k = 0; k < levels; ++k) {
    const long long steps = coarsest_steps << k;
    m.dts.push_back(duration / static_cast<double>(steps));
    m.errors.push_back(
        trajectory_error<M>(sampled_run<M>(p, initial, integrator, duration, steps), reference));
  }
  m.slope = fit_loglog(m.dts, m.errors).slope;
  std::printf("[ order    ] %s, %s: fitted slope %.3f (nominal %d)\n", label.c_str(),
              to_string(integrator), m.slope, order(integrator));
  for (std::size_t k = 0; k < m.dts.size(); ++k) {
    if (k == 0) {
      std::printf("[          ]   dt %.4e  error %.4e\n", m.dts[k], m.errors[k]);
    } else {
      const double local =
          std::log(m.errors[k] / m.errors[k - 1]) / std::log(m.dts[k] / m.dts[k - 1]);
      std::printf("[          ]   dt %.4e  error %.4e  local slope %.3f\n", m.dts[k], m.errors[k],
                  local);
    }
  }
  return m;
}

}  // namespace gencoord::testing
