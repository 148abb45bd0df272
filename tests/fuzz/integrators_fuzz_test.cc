// SPDX-License-Identifier: BSD-3-Clause
// Random states and step sizes (huge, tiny, zero, negative, NaN, inf) to every integrator on
// generated models and on a maximal penalty model: each step ends in a typed error or in a
// finite state at t + h; an accepted backward Euler step solves its equation (checked here,
// independently of the solver); small steps of the non-stiff models keep the energy.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "fuzz_values.hpp"
#include "gencoord/errors.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/maximal/errors.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/pendulum.hpp"
#include "generated/stiff_chain_3.hpp"

namespace gencoord::fuzz {
namespace {

constexpr Integrator kIntegrators[] = {Integrator::ForwardEuler, Integrator::SymplecticEuler,
                                       Integrator::RK4,          Integrator::BackwardEuler,
                                       Integrator::Trapezoidal,  Integrator::ImplicitMidpoint};

// What happened to the cases of one run, for the report and for "the fuzz reached both".
struct Outcomes {
  int accepted = 0, refused = 0;
};

// Runs one step; returns true if accepted. Any exception other than the runtime's typed ones
// fails the test.
template <class S, class Check>
bool try_step(const S& system, Integrator integrator, const typename S::State& s, double h,
              const std::string& what, Outcomes* out, Check&& check) {
  try {
    const typename S::State end = step(system, integrator, s, h);
    ++out->accepted;
    EXPECT_TRUE(end.q.allFinite() && end.v.allFinite()) << what;
    EXPECT_EQ(end.t, s.t + h) << what;
    check(end);
    return true;
  } catch (const StepSizeError&) {
    EXPECT_FALSE(h > 0.0 && std::isfinite(h) && std::isfinite(s.t)) << what;
  } catch (const DynamicsError&) {
  } catch (const NewtonError& e) {
    EXPECT_GT(e.iterations(), 0) << what;
  } catch (const DivergedError& e) {
    EXPECT_EQ(e.step_size(), h) << what;
  } catch (const MaximalDivergedError&) {
  } catch (const InverseMapError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": untyped error: " << e.what();
  }
  ++out->refused;
  return false;
}

template <class M>
std::string describe(const State<M>& s, Integrator integrator, double h) {
  std::string out =
      std::string(M::name) + " " + to_string(integrator) + " h = " + std::to_string(h) + " q =";
  for (int i = 0; i < M::nq; ++i) out += " " + std::to_string(s.q[i]);
  out += " v =";
  for (int i = 0; i < M::nq; ++i) out += " " + std::to_string(s.v[i]);
  return out;
}

// |g| / scale of backward Euler's equation at an accepted step (NewtonOptions' scale)
template <class M>
double scaled_residual(const ParamsOf<M>& p, const State<M>& s0, const State<M>& s1, double h) {
  const QVec<M> a = acceleration<M>(p, s1);
  const double g = (s1.v - s0.v - h * a).cwiseAbs().maxCoeff();
  return g / (1.0 + s0.v.cwiseAbs().maxCoeff() + s1.v.cwiseAbs().maxCoeff() +
              h * a.cwiseAbs().maxCoeff());
}

template <class M>
void fuzz_reduced(std::uint64_t seed, int cases, bool check_energy) {
  Values values(seed);
  const typename M::Params p;
  const ReducedSystem<M> system(p);
  Outcomes out;
  for (int c = 0; c < cases; ++c) {
    State<M> s;
    s.t = values.chance(0.05) ? values.maybe_bad(1e3, 1.0) : values.uniform(0.0, 10.0);
    for (int i = 0; i < M::nq; ++i) {
      s.q[i] = values.maybe_bad(3.0, 0.03);
      s.v[i] = values.maybe_bad(3.0, 0.03);
    }
    const Integrator integrator = kIntegrators[values.integer(0, 5)];
    const double h = values.step_size();
    const std::string what = describe(s, integrator, h);
    try_step(system, integrator, s, h, what, &out, [&](const State<M>& end) {
      if (integrator == Integrator::BackwardEuler) {
        EXPECT_LE(scaled_residual<M>(p, s, end, h), 1e-6) << what;
      }
      const bool ordinary = s.q.cwiseAbs().maxCoeff() <= 3.0 && s.v.cwiseAbs().maxCoeff() <= 3.0 &&
                            std::isfinite(s.t);
      if (check_energy && ordinary && h <= 1e-4) {
        const double e0 = M::energy(s.q, s.v, s.t, p), e1 = M::energy(end.q, end.v, end.t, p);
        EXPECT_LE(std::abs(e1 - e0), 1e-3 * (1.0 + std::abs(e0))) << what;
      }
    });
  }
  std::printf("[ fuzz ] %s: %d steps accepted, %d refused with a typed error\n", M::name,
              out.accepted, out.refused);
  EXPECT_GT(out.accepted, cases / 4);
  EXPECT_GT(out.refused, cases / 50);
}

TEST(IntegratorsFuzz, Pendulum) { fuzz_reduced<models::Pendulum>(1, 1500, true); }
TEST(IntegratorsFuzz, DoublePendulum) { fuzz_reduced<models::DoublePendulum>(2, 1000, true); }
TEST(IntegratorsFuzz, StiffChain3) { fuzz_reduced<models::StiffChain3>(3, 800, false); }

TEST(IntegratorsFuzz, MaximalPendulum) {
  Values values(4);
  const models::Pendulum::Params p;
  Outcomes out;
  for (int c = 0; c < 300; ++c) {
    const double kappa = std::pow(10.0, values.uniform(0.0, 6.0));
    std::unique_ptr<MaximalModel<models::Pendulum>> system;
    system = std::make_unique<MaximalModel<models::Pendulum>>(p, kappa);
    MaximalState<models::Pendulum> s;
    s.t = values.uniform(0.0, 10.0);
    for (int i = 0; i < s.q.size(); ++i) {
      s.q[i] = values.maybe_bad(2.0, 0.03);
      s.v[i] = values.maybe_bad(3.0, 0.03);
    }
    const Integrator integrator = kIntegrators[values.integer(0, 5)];
    const double h = values.step_size();
    const std::string what = "maximal pendulum kappa = " + std::to_string(kappa) + " " +
                             to_string(integrator) + " h = " + std::to_string(h);
    try_step(*system, integrator, s, h, what, &out, [](const auto&) {});
  }
  std::printf("[ fuzz ] maximal pendulum: %d steps accepted, %d refused with a typed error\n",
              out.accepted, out.refused);
  EXPECT_GT(out.accepted, 50);
  EXPECT_GT(out.refused, 5);
}

TEST(IntegratorsFuzz, MaximalModelRefusesBadPenalties) {
  Values values(5);
  for (int c = 0; c < 200; ++c) {
    const double kappa = values.maybe_bad(1e3, 0.5), damping = values.maybe_bad(1.0, 0.5);
    const bool valid =
        std::isfinite(kappa) && kappa >= 0.0 && std::isfinite(damping) && damping >= 0.0;
    if (valid) {
      EXPECT_NO_THROW(MaximalModel<models::Pendulum>(models::Pendulum::Params{}, kappa, damping));
    } else {
      EXPECT_THROW(MaximalModel<models::Pendulum>(models::Pendulum::Params{}, kappa, damping),
                   std::invalid_argument)
          << kappa << " " << damping;
    }
  }
}

}  // namespace
}  // namespace gencoord::fuzz
