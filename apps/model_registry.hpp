// Every built-in generated model, looked up by name, for command-line tools.
#pragma once

#include <string>
#include <string_view>

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

namespace gencoord::apps {

template <class... Models>
struct ModelList {
  /// Calls visitor(Model{}) for the model called `name`; false when there is none.
  template <class Visitor>
  static bool visit(std::string_view name, Visitor&& visitor) {
    return ((name == Models::name ? (visitor(Models{}), true) : false) || ...);
  }
  static std::string names() {
    std::string out;
    ((out += (out.empty() ? "" : ", ") + std::string(Models::name)), ...);
    return out;
  }
};

using BuiltinModels =
    ModelList<models::Pendulum, models::Pendulum3d, models::SphericalPendulum,
              models::DoublePendulum, models::BeadOnRotatingHoop, models::CartPole,
              models::SpringPendulum, models::NLinkChain1, models::NLinkChain2,
              models::NLinkChain3, models::NLinkChain5, models::NLinkChain10,
              models::KapitzaPendulum, models::FallingCat,
              models::RigidBodyEuler, models::StiffChain3, models::StiffChain10>;

}  // namespace gencoord::apps
