// SPDX-License-Identifier: BSD-3-Clause
// Every integrator on every kind of system, through the one integrator core
// (gencoord/integrate/): the measured order of accuracy (fitted log-log slope of the error
// against the step size, nominal within 0.2) and the energy behaviour over a long run
// (forward Euler gains energy, backward Euler loses it, the symplectic and second-order
// implicit methods keep it bounded, RK4 nearly exact).
//
// Systems: the reduced pendulum; the double pendulum with its first angle scripted to stay
// put (a conservative system of one free coordinate); the pendulum's maximal penalty model at
// a soft kappa (its stiff mode resolved by every step tried); a pinned elastic rod under
// gravity (deformable mass-spring object, 1D).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/rod.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/state.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/numerics/loglog_fit.hpp"
#include "gencoord/scripted/model.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/pendulum.hpp"

namespace gencoord::testing {
// a namespace of its own: its helpers share names with its neighbours', which compile in
// the same batch (cmake/unity.cmake)
namespace every_system {
namespace {

using models::DoublePendulum;
using models::Pendulum;

// --- the systems: each makes its system, initial state, horizon and energy -----------------

struct Reduced {
  using System = ReducedSystem<Pendulum>;
  static constexpr const char* name = "reduced";
  System system() const { return System(Pendulum::Params{}); }
  System::State initial() const {
    System::State s;
    s.q[0] = 1.0;
    s.v[0] = 0.5;
    return s;
  }
  double energy(const System::State& s) const {
    return Pendulum::energy(s.q, s.v, s.t, Pendulum::Params{});
  }
};

struct Scripted {
  using System = ScriptedModel<DoublePendulum>;
  static constexpr const char* name = "scripted";
  System system() const {
    // theta1 held at 0.3 rad: a fixed pivot for the second rod
    Script hold = Script::from_function({0}, [](double) {
      ScriptSample at;
      at.q = Eigen::VectorXd::Constant(1, 0.3);
      at.v = Eigen::VectorXd::Zero(1);
      at.a = Eigen::VectorXd::Zero(1);
      return at;
    });
    return System(DoublePendulum::Params{}, std::move(hold));
  }
  System::State initial() const {
    System::State s;
    s.q << 0.3, -0.8;
    s.v << 0.0, 0.4;
    return s;
  }
  double energy(const System::State& s) const {
    return DoublePendulum::energy(s.q, s.v, s.t, DoublePendulum::Params{});
  }
};

struct Maximal {
  using System = MaximalModel<Pendulum>;
  static constexpr const char* name = "maximal";
  System system() const { return System(Pendulum::Params{}, 400.0); }
  System::State initial() const {
    State<Pendulum> s;
    s.q[0] = 1.0;
    s.v[0] = 0.5;
    return to_maximal<Pendulum>(Pendulum::Params{}, s);
  }
  double energy(const System::State& s) const { return system().energy(s); }
};

// a rod of 4 springs along x, pinned at x = 0, stretched by gravity along x
struct Deformable {
  using Rod = deformable::MassSpringSystem<1>;
  using System = deformable::MassSpringIntegration<1>;
  static constexpr const char* name = "deformable";
  Deformable() {
    deformable::Material m;
    m.youngs_modulus = 4.0;
    rod = deformable::make_rod(deformable::uniform_rod_nodes(4), m);
    rod.pinned[0] = 1;
    rod.gravity[0] = 1.0;
    rod.v(0, 4) = 0.3;
  }
  System system() const {
    deformable::ImplicitOptions direct;
    direct.solver = deformable::LinearSolver::kSparseCholesky;
    return System(rod, direct);
  }
  System::State initial() const { return system().state(); }
  double energy(const System::State& s) const {
    Rod at = rod;
    at.x = s.q;
    at.v = s.v;
    return deformable::total_energy(at);
  }
  Rod rod;
};

// --- order of accuracy --------------------------------------------------------------------

constexpr double kDuration = 1.0;
constexpr long long kSamples = 5;
constexpr long long kReferenceSteps = kSamples << 13;

template <class Case>
using StateOf = typename Case::System::State;

// the states at kSamples equally spaced times of a run of `steps` steps
template <class Case>
std::vector<StateOf<Case>> sampled_run(const Case& c, Integrator integrator, long long steps) {
  std::vector<StateOf<Case>> samples;
  long long k = 0;
  SimulateOptions o;
  o.integrator = integrator;
  o.dt = kDuration / static_cast<double>(steps);
  o.duration = kDuration;
  simulate(c.system(), c.initial(), o, [&](const StateOf<Case>& s) {
    if (k > 0 && k % (steps / kSamples) == 0) samples.push_back(s);
    ++k;
  });
  return samples;
}

template <class Case>
double trajectory_error(const std::vector<StateOf<Case>>& run,
                        const std::vector<StateOf<Case>>& reference) {
  double worst = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k)
    worst = std::max(worst, std::sqrt((run[k].q - reference[k].q).squaredNorm() +
                                      (run[k].v - reference[k].v).squaredNorm()));
  return worst;
}

struct OrderCase {
  Integrator integrator;
  long long coarsest_steps;
};

const std::vector<OrderCase> kOrderCases = {
    {Integrator::ForwardEuler, 400},    {Integrator::SymplecticEuler, 400},
    {Integrator::BackwardEuler, 400},   {Integrator::Trapezoidal, 50},
    {Integrator::ImplicitMidpoint, 50}, {Integrator::RK4, 40},
};

template <class Case>
class EverySystem : public ::testing::Test {};

using Systems = ::testing::Types<Reduced, Scripted, Maximal, Deformable>;
TYPED_TEST_SUITE(EverySystem, Systems);

TYPED_TEST(EverySystem, EveryIntegratorHasItsNominalOrder) {
  const TypeParam c;
  const std::vector<StateOf<TypeParam>> reference =
      sampled_run(c, Integrator::RK4, kReferenceSteps);
  for (const OrderCase& oc : kOrderCases) {
    std::vector<double> dts, errors;
    for (int k = 0; k < 5; ++k) {
      const long long steps = oc.coarsest_steps << k;
      dts.push_back(kDuration / static_cast<double>(steps));
      errors.push_back(
          trajectory_error<TypeParam>(sampled_run(c, oc.integrator, steps), reference));
    }
    const double slope = fit_loglog(dts, errors).slope;
    std::printf("[ order    ] %s, %s: fitted slope %.3f (nominal %d), errors %.3e .. %.3e\n",
                TypeParam::name, to_string(oc.integrator), slope, order(oc.integrator),
                errors.front(), errors.back());
    EXPECT_NEAR(slope, order(oc.integrator), 0.2)
        << TypeParam::name << ", " << to_string(oc.integrator);
    EXPECT_GT(errors.back(), 1e-11) << "finest step too small to measure the order";
  }
}

// --- energy behaviour ---------------------------------------------------------------------

// E(end) - E(0) and max |E - E(0)| of a run of 2000 steps of 0.01 s
struct EnergyRun {
  double change = 0.0;
  double max_deviation = 0.0;
  double scale = 0.0;  // |E(0)| + 1: what the deviations are measured against
};

template <class Case>
EnergyRun energy_run(const Case& c, Integrator integrator) {
  SimulateOptions o;
  o.integrator = integrator;
  o.dt = 0.01;
  o.duration = 20.0;
  EnergyRun r;
  const double e0 = c.energy(c.initial());
  r.scale = std::abs(e0) + 1.0;
  double e = e0;
  simulate(c.system(), c.initial(), o, [&](const StateOf<Case>& s) {
    e = c.energy(s);
    r.max_deviation = std::max(r.max_deviation, std::abs(e - e0));
  });
  r.change = e - e0;
  std::printf("[ energy   ] %s, %s: E(end) - E(0) %.4e, max |E - E(0)| %.4e\n", Case::name,
              to_string(integrator), r.change, r.max_deviation);
  return r;
}

TYPED_TEST(EverySystem, EnergyBehavesAsEachMethodPromises) {
  const TypeParam c;
  EXPECT_GT(energy_run(c, Integrator::ForwardEuler).change, 0.0) << "forward Euler gains";
  EXPECT_LT(energy_run(c, Integrator::BackwardEuler).change, 0.0) << "backward Euler loses";
  for (const Integrator bounded :
       {Integrator::SymplecticEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    const EnergyRun r = energy_run(c, bounded);
    EXPECT_LT(r.max_deviation, 0.05 * r.scale) << to_string(bounded) << " stays bounded";
  }
  const EnergyRun rk4 = energy_run(c, Integrator::RK4);
  EXPECT_LT(rk4.max_deviation, 1e-4 * rk4.scale) << "RK4 nearly exact";
}

}  // namespace
}  // namespace every_system
}  // namespace gencoord::testing
