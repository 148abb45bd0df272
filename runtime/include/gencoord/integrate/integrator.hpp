// SPDX-License-Identifier: BSD-3-Clause
// The integration methods by name, and what each one is.
#pragma once

#include <string>
#include <string_view>

namespace gencoord {

enum class Integrator {
  ForwardEuler,
  SymplecticEuler,
  RK4,
  BackwardEuler,
  Trapezoidal,
  ImplicitMidpoint,
};

/// Integrator from its name: "forward_euler", "symplectic_euler", "rk4", "backward_euler",
/// "trapezoidal" or "implicit_midpoint" (case-insensitive; '-' and ' ' read as '_').
/// \throws std::invalid_argument naming the valid names if `name` is none of them.
Integrator parse_integrator(std::string_view name);

/// The canonical name of an integrator, as accepted by parse_integrator().
const char* to_string(Integrator integrator);

/// The valid names, comma separated ("forward_euler, symplectic_euler, ...").
std::string integrator_names();

/// Order of accuracy of the global error (1, 2 or 4).
int order(Integrator integrator);

/// Whether the integrator solves a nonlinear system (Newton) each step.
bool is_implicit(Integrator integrator);

}  // namespace gencoord
