// The generated models every model test runs on, as a GoogleTest type list.
#pragma once

#include <gtest/gtest.h>

#include "generated/bead_on_rotating_hoop.hpp"
#include "generated/cart_pole.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/falling_cat.hpp"
#include "generated/kapitza_pendulum.hpp"
#include "generated/n_link_chain_1.hpp"
#include "generated/n_link_chain_10.hpp"
#include "generated/n_link_chain_2.hpp"
#include "generated/n_link_chain_3.hpp"
#include "generated/n_link_chain_5.hpp"
#include "generated/pendulum.hpp"
#include "generated/pendulum_3d.hpp"
#include "generated/rigid_body_euler.hpp"
#include "generated/spherical_pendulum.hpp"
#include "generated/spring_pendulum.hpp"
#include "generated/stiff_chain_10.hpp"
#include "generated/stiff_chain_3.hpp"

namespace gencoord::testing {

using AllModels = ::testing::Types<
    models::Pendulum, models::Pendulum3d, models::SphericalPendulum, models::DoublePendulum,
    models::BeadOnRotatingHoop, models::CartPole, models::SpringPendulum, models::NLinkChain1,
    models::NLinkChain2, models::NLinkChain3, models::NLinkChain5, models::NLinkChain10,
    models::KapitzaPendulum, models::FallingCat, models::RigidBodyEuler, models::StiffChain3,
    models::StiffChain10, models::SphericalPendulumPoleX, models::RigidBodyEulerYzx>;

/// Prints a model type as its name in test output (TypedTest/pendulum, ...).
struct ModelNames {
  template <class M>
  static std::string GetName(int) {
    return M::name;
  }
};

}  // namespace gencoord::testing
