// SPDX-License-Identifier: BSD-3-Clause
// Simulating through coordinate singularities with an atlas of charts.
//
// A generated atlas (e.g. models::SphericalPendulumAtlas) lists several charts of the same
// particles. AtlasSimulation integrates in one chart; after each step it estimates cond(Mt)
// from the Cholesky factor and, past a threshold, moves the state (through x and xdot, see
// chart_transfer.hpp) to the best-conditioned chart and goes on. Each switch is recorded.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "gencoord/atlas/chart_transfer.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// When and how an AtlasSimulation changes chart.
struct AtlasOptions {
  /// The simulation looks for a better chart when cond(Mt) (estimated from the Cholesky
  /// factor) passes switch_ratio times the reference conditioning: the best estimate over
  /// the charts' suggested initial states (Chart::initial_q), i.e. what the model's
  /// conditioning looks like away from singularities (1 for a unit spherical pendulum, ~20
  /// for the rigid body, whose Mt mixes masses and inertias). Coordinates curve strongly near
  /// their singular set even before cond(Mt) is large, so the default switches early: for
  /// spherical coordinates 4 means 30 degrees from the pole (measured by
  /// `atlas_pendulum --ratio R`: the looping pendulum's max |E - E0| / (m g l) at RK4,
  /// h = 1e-3, is 1.6e-11 with 4, 2.8e-10 with 10, 7.9e-9 with 30 and 3.0e-7 with 100).
  double switch_ratio = 4.0;
  /// An absolute threshold instead of switch_ratio times the reference; 0 = use the ratio.
  double switch_threshold = 0.0;
  /// A chart is taken only if its estimate is below the current one divided by this, so
  /// the simulation does not flip between two charts of similar conditioning.
  double min_improvement = 2.0;
  /// First guesses tried by the inverse map beyond the chart's last and initial states.
  int guess_spread = 64;
  /// The inverse map's settings; max_residual is the accepted mismatch of the particles.
  InverseMapOptions inverse_map = [] {
    InverseMapOptions options;
    options.max_residual = 1e-9;
    return options;
  }();
};

/// One change of chart.
struct ChartSwitch {
  double t = 0.0;              // when
  int from = 0, to = 0;        // chart indices (Atlas::chart_names)
  double estimate_from = 0.0;  // cond(Mt) estimate in the chart left
  double estimate_to = 0.0;    // and in the chart taken
  bool requested = false;      // by switch_to() rather than by the threshold
};

namespace detail {
template <class Tuple>
struct StatesOf;
template <class... Charts>
struct StatesOf<std::tuple<Charts...>> {
  using type = std::tuple<std::optional<State<Charts>>...>;
};

/// Calls f(std::integral_constant<int, I>{}) for the I equal to `index` (0 <= index < N).
template <int N, int I = 0, class F>
void with_index(int index, F&& f) {
  if constexpr (I < N) {
    if (index == I) {
      f(std::integral_constant<int, I>{});
    } else {
      with_index<N, I + 1>(index, std::forward<F>(f));
    }
  }
}

// whether any chart of an atlas has generalized speeds
template <class Charts>
struct any_generalized_speeds;
template <class... Charts>
struct any_generalized_speeds<std::tuple<Charts...>>
    : std::bool_constant<(has_generalized_speeds_v<Charts> || ...)> {};
}  // namespace detail

/// Integrates a generated atlas A, switching charts near coordinate singularities.
template <class A>
class AtlasSimulation {
 public:
  using Charts = typename A::Charts;
  template <int I>
  using Chart = std::tuple_element_t<I, Charts>;
  static_assert(!detail::any_generalized_speeds<Charts>::value,
                "gencoord: the atlas does not support models with generalized speeds (free or ball "
                "joints) yet");
  using Params = typename A::Params;
  static constexpr int num_charts = A::num_charts;
  static constexpr int nx = Chart<0>::nx;
  using XVector = Eigen::Matrix<double, nx, 1>;
  using AngularVector = Eigen::Matrix<double, Chart<0>::angular_dim, 1>;

  /// Starts in chart I at state s, or in a better chart if s is past the threshold.
  template <int I>
  AtlasSimulation(const Params& p, const State<Chart<I>>& s, std::integral_constant<int, I>,
                  const AtlasOptions& options = {})
      : p_(p), options_(options), current_(I) {
    std::get<I>(states_) = s;
    threshold_ = options.switch_threshold > 0.0
                     ? options.switch_threshold
                     : options.switch_ratio *
                           reference_condition(
                               std::make_index_sequence<static_cast<std::size_t>(num_charts)>{});
    update_chart();
  }

  /// Starts in the first chart at s.
  AtlasSimulation(const Params& p, const State<Chart<0>>& s, const AtlasOptions& options = {})
      : AtlasSimulation(p, s, std::integral_constant<int, 0>{}, options) {}

  int chart() const { return current_; }
  const char* chart_name() const { return A::chart_names[static_cast<std::size_t>(current_)]; }
  const std::vector<ChartSwitch>& switches() const { return switches_; }
  const Params& params() const { return p_; }
  /// The condition estimate past which the simulation looks for a better chart.
  double threshold() const { return threshold_; }

  /// The state in chart I, which must be the current chart.
  template <int I>
  const State<Chart<I>>& state() const {
    if (I != current_)
      throw std::logic_error(std::string("gencoord: the atlas is in chart '") + chart_name() +
                             "', not '" + A::chart_names[I] + "'");
    return *std::get<I>(states_);
  }

  double time() const {
    double t = 0.0;
    visit([&](const auto& s, auto) { t = s.t; });
    return t;
  }
  XVector positions() const {
    return evaluate([](const auto& s, const Params& p, auto chart) {
      return XVector(decltype(chart)::positions(s.q, s.t, p));
    });
  }
  XVector velocities() const {
    return evaluate([](const auto& s, const Params& p, auto chart) {
      return XVector(decltype(chart)::velocities(s.q, s.v, s.t, p));
    });
  }
  double energy() const {
    return evaluate([](const auto& s, const Params& p, auto chart) {
      return double(decltype(chart)::energy(s.q, s.v, s.t, p));
    });
  }
  AngularVector angular_momentum() const {
    return evaluate([](const auto& s, const Params& p, auto chart) {
      return AngularVector(decltype(chart)::angular_momentum(s.q, s.v, s.t, p));
    });
  }
  /// The condition estimate of the current chart's Mt.
  double condition() const {
    return evaluate([](const auto& s, const Params& p, auto chart) {
      return chart_condition<decltype(chart)>(p, s.q, s.t);
    });
  }

  /// One step of `integrator` in the current chart, then a chart switch if it is needed.
  void step(Integrator integrator, double dt, const NewtonOptions& newton = {}) {
    with_current([&](auto index) {
      constexpr int I = decltype(index)::value;
      auto& s = *std::get<I>(states_);
      s = gencoord::step(ReducedSystem<Chart<I>>(p_), integrator, s, dt, newton);
    });
    update_chart();
  }

  /// Switches to the best-conditioned chart if the current one is past the threshold and
  /// another is at least min_improvement times better. Returns whether it switched.
  bool update_chart() {
    const double current = condition();
    if (current <= threshold_) return false;
    States candidates;  // each chart's mapped state, so the one taken is not mapped twice
    int best = current_;
    double best_estimate = current / options_.min_improvement;
    for (int k = 0; k < num_charts; ++k) {
      if (k == current_) continue;
      const std::optional<double> estimate = transfer_into(k, &candidates);
      if (estimate && *estimate < best_estimate) {
        best = k;
        best_estimate = *estimate;
      }
    }
    if (best == current_) return false;
    detail::with_index<num_charts>(best, [&](auto index) {
      constexpr int K = decltype(index)::value;
      std::get<K>(states_) = std::get<K>(candidates);
    });
    record_switch(best, current, best_estimate, false);
    return true;
  }

  /// Moves to chart k now, whatever the conditioning (tests and tools).
  /// \throws std::runtime_error if the state cannot be mapped into chart k.
  void switch_to(int k) {
    if (k < 0 || k >= num_charts) throw std::out_of_range("gencoord: no such chart");
    if (k == current_) return;
    const double estimate_from = condition();
    const std::optional<double> estimate_to = transfer_into(k, &states_);
    if (!estimate_to)
      throw std::runtime_error(std::string("gencoord: cannot map the state at t = ") +
                               std::to_string(time()) + " from chart '" + chart_name() +
                               "' into chart '" + A::chart_names[k] + "' (inverse map failed)");
    record_switch(k, estimate_from, *estimate_to, true);
  }

  /// Steps to t_end (about (t_end - t) / dt steps of size dt), calling observer(*this) at
  /// the start and after each step.
  template <class Observer>
  void simulate(Integrator integrator, double dt, double t_end, Observer&& observer,
                const NewtonOptions& newton = {}) {
    observer(*this);
    const long steps = std::lround((t_end - time()) / dt);
    for (long k = 0; k < steps; ++k) {
      step(integrator, dt, newton);
      observer(*this);
    }
  }

 private:
  using States = typename detail::StatesOf<Charts>::type;

  // the best condition estimate over the charts' suggested initial states
  template <std::size_t... I>
  double reference_condition(std::index_sequence<I...>) const {
    return std::min({chart_condition<Chart<static_cast<int>(I)>>(
        p_, initial_q_of<Chart<static_cast<int>(I)>>(), 0.0)...});
  }

  template <class F>
  void with_current(F&& f) const {
    detail::with_index<num_charts>(current_, std::forward<F>(f));
  }
  // f(state, chart instance tag) on the current chart's state
  template <class F>
  void visit(F&& f) const {
    with_current([&](auto index) {
      constexpr int I = decltype(index)::value;
      f(*std::get<I>(states_), Chart<I>{});
    });
  }
  template <class F>
  auto evaluate(F&& f) const {
    using Result = decltype(f(std::declval<const State<Chart<0>>&>(), p_, Chart<0>{}));
    Result result{};
    visit([&](const auto& s, auto chart) { result = f(s, p_, chart); });
    return result;
  }

  // Maps the current state into chart k and stores it in (*into)'s slot k. Returns k's
  // condition estimate at the mapped state, or nothing when the inverse map fails.
  std::optional<double> transfer_into(int k, States* into) {
    std::optional<double> estimate;
    with_current([&](auto from_index) {
      constexpr int F = decltype(from_index)::value;
      detail::with_index<num_charts>(k, [&](auto to_index) {
        constexpr int T = decltype(to_index)::value;
        if constexpr (F != T) {
          using To = Chart<T>;
          const auto& last = std::get<T>(states_);
          const auto guesses = chart_guesses<To>(
              last ? std::optional<QVec<To>>(last->q) : std::nullopt, options_.guess_spread);
          const auto mapped = transfer_state<Chart<F>, To>(p_, *std::get<F>(states_), guesses,
                                                           options_.inverse_map);
          if (!mapped) return;
          estimate = chart_condition<To>(p_, mapped->q, mapped->t);
          std::get<T>(*into) = *mapped;
        }
      });
    });
    return estimate;
  }

  void record_switch(int k, double estimate_from, double estimate_to, bool requested) {
    switches_.push_back(ChartSwitch{time(), current_, k, estimate_from, estimate_to, requested});
    current_ = k;
  }

  Params p_;
  AtlasOptions options_;
  int current_;
  double threshold_ = 0.0;
  States states_;
  std::vector<ChartSwitch> switches_;
};

}  // namespace gencoord
