// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/integrate/integrator.hpp"

#include <array>
#include <cctype>
#include <stdexcept>
#include <string>

namespace gencoord {
namespace {

constexpr std::array<Integrator, 6> kAll = {
    Integrator::ForwardEuler,  Integrator::SymplecticEuler, Integrator::RK4,
    Integrator::BackwardEuler, Integrator::Trapezoidal,     Integrator::ImplicitMidpoint,
};

}  // namespace

const char* to_string(Integrator integrator) {
  switch (integrator) {
    case Integrator::ForwardEuler:
      return "forward_euler";
    case Integrator::SymplecticEuler:
      return "symplectic_euler";
    case Integrator::RK4:
      return "rk4";
    case Integrator::BackwardEuler:
      return "backward_euler";
    case Integrator::Trapezoidal:
      return "trapezoidal";
    case Integrator::ImplicitMidpoint:
      return "implicit_midpoint";
  }
  return "invalid";
}

std::string integrator_names() {
  std::string names;
  for (const Integrator i : kAll) names += (names.empty() ? "" : ", ") + std::string(to_string(i));
  return names;
}

Integrator parse_integrator(std::string_view name) {
  // normalize: lower case, '-' and ' ' as '_'
  std::string key(name);
  for (char& c : key) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c == '-' || c == ' ') c = '_';
  }
  for (const Integrator i : kAll)
    if (key == to_string(i)) return i;
  throw std::invalid_argument("gencoord: unknown integrator '" + std::string(name) +
                              "'; valid names: " + integrator_names());
}

int order(Integrator integrator) {
  switch (integrator) {
    case Integrator::ForwardEuler:
    case Integrator::SymplecticEuler:
    case Integrator::BackwardEuler:
      return 1;
    case Integrator::Trapezoidal:
    case Integrator::ImplicitMidpoint:
      return 2;
    case Integrator::RK4:
      return 4;
  }
  return 0;
}

bool is_implicit(Integrator integrator) {
  return integrator == Integrator::BackwardEuler || integrator == Integrator::Trapezoidal ||
         integrator == Integrator::ImplicitMidpoint;
}

}  // namespace gencoord
