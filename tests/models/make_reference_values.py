"""Writes reference_values.hpp: every tested model's outputs at a few seeded random states,
evaluated in 40-digit mpmath arithmetic straight from the unoptimized `derive()` result.

reference_values_test.cc compares the generated kernels (after CSE and the C++ printer) with
these values, so a printing or CSE bug shows up as a mismatch. The models are the ones
tests/models/all_models.hpp includes; `n_link_chain_5` is models/n_link_chain.py with its one
option set to 5.

    make_reference_values.py <all_models.hpp> <output.hpp>
"""

from __future__ import annotations

import os
import random
import re
import sys

import mpmath
import sympy as sp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, ROOT)

from generator.derive import derive  # noqa: E402
from generator.loader import load_model  # noqa: E402

STATES = 5
DIGITS = 40
# the reference values each state holds, in ReferenceState's order
OUTPUTS = ["mass_matrix", "applied_forces", "inertial_forces", "forces", "kinetic_energy",
           "potential_energy", "energy", "positions", "velocities", "jacobian",
           "bias_acceleration", "linear_momentum", "angular_momentum", "particle_masses"]


def model_file_and_options(name: str) -> tuple[str, dict[str, str]]:
    """`pendulum` -> models/pendulum.py; `n_link_chain_5` -> models/n_link_chain.py, n=5."""
    models = os.path.join(ROOT, "models")
    stems = sorted((f[:-3] for f in os.listdir(models) if f.endswith(".py")), key=len,
                   reverse=True)
    for stem in stems:
        path = os.path.join(models, stem + ".py")
        if name == stem:
            return path, {}
        if name.startswith(stem + "_"):
            option_names = list(load_model(path)[0].options)
            values = name[len(stem) + 1:].split("_")
            if len(values) == len(option_names):
                return path, dict(zip(option_names, values))
    raise SystemExit(f"make_reference_values: no model file for generated/{name}.hpp")


def outputs(d) -> dict[str, sp.Matrix]:
    """The Derivation's outputs; forces and energy are summed later, from these values."""
    return {
        "mass_matrix": d.mass_matrix,
        "applied_forces": d.applied_forces,
        "inertial_forces": d.inertial_forces,
        "kinetic_energy": sp.Matrix([d.kinetic_energy]),
        "potential_energy": sp.Matrix([d.potential_energy]),
        "positions": d.positions,
        "velocities": d.velocities,
        "jacobian": d.jacobian,
        "bias_acceleration": d.bias_acceleration,
        "linear_momentum": d.linear_momentum,
        "angular_momentum": d.angular_momentum,
        "particle_masses": sp.Matrix(d.masses),
    }


def number(x) -> str:
    """A double with 17 significant digits (round-trips exactly)."""
    return f"{float(x):.17g}"


def array(values) -> str:
    return "{" + ", ".join(number(x) for x in values) + "}"


def reference_models(name: str, seed: int) -> list[str]:
    """The entries of one header: its model, and each further chart of an atlas."""
    path, options = model_file_and_options(name)
    model, generated_name, _ = load_model(path, options)
    assert generated_name == name, (generated_name, name)
    return [reference_model(name if chart is model else f"{name}_{chart.chart}", chart,
                            seed + 1000 * k)
            for k, chart in enumerate([model, *model.charts])]


def reference_model(name: str, model, seed: int) -> str:
    d = derive(model)
    arguments = [*d.q, *d.v, d.t, *d.params]
    exprs = outputs(d)
    for key, matrix in exprs.items():
        extra = set().union(*(sp.sympify(e).free_symbols for e in matrix)) - set(arguments)
        if extra:
            raise SystemExit(f"{name}: {key} depends on unknown symbols {extra}")
    # one function per output, evaluated in mpmath at DIGITS digits; row-major entries
    functions = {key: sp.lambdify(arguments, list(matrix), modules="mpmath")
                 for key, matrix in exprs.items()}

    rng = random.Random(seed)
    states = []
    for _ in range(STATES):
        q = [rng.uniform(0.3, 1.3) for _ in d.q]
        v = [rng.uniform(-1.0, 1.0) for _ in d.v]
        t = rng.uniform(0.0, 2.0)
        # around the defaults; zero defaults (dampers, drag, applied force) get a small value
        params = [p.default * rng.uniform(0.7, 1.3) if p.default != 0 else rng.uniform(0.1, 0.5)
                  for p in model.parameters]
        with mpmath.workdps(DIGITS):
            values = [mpmath.mpf(x) for x in [*q, *v, t, *params]]  # the doubles, exactly
            results = {key: f(*values) for key, f in functions.items()}
            results["forces"] = [a + b for a, b in zip(results["applied_forces"],
                                                       results["inertial_forces"])]
            results["energy"] = [results["kinetic_energy"][0] + results["potential_energy"][0]]
        fields = [f"/* t */ {number(t)}", f"/* q */ {array(q)}", f"/* v */ {array(v)}",
                  f"/* params */ {array(params)}"]
        fields += [f"/* {key} */ {array(results[key])}" for key in OUTPUTS]
        states.append("      {" + ",\n       ".join(fields) + "}")
    names = ", ".join(f'"{p.name}"' for p in model.parameters)
    return (f'  {{"{name}",\n   {{{names}}},\n   {{\n' + ",\n".join(states) + "\n   }}")


def main() -> None:
    all_models, output = sys.argv[1:3]
    with open(all_models, encoding="utf-8") as handle:
        names = re.findall(r'#include "generated/(\w+)\.hpp"', handle.read())
    models = ",\n".join(entry for seed, name in enumerate(names, start=1)
                         for entry in reference_models(name, seed))
    fields = "\n".join(f"  std::vector<double> {key};" for key in OUTPUTS)
    text = f"""\
// Generated by tests/models/make_reference_values.py. Do NOT modify by hand.
// Each model's outputs at {STATES} random states, evaluated in {DIGITS}-digit arithmetic from the
// unoptimized derive() result; matrices are stored row-major.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace gencoord::testing {{

struct ReferenceState {{
  double t;
  std::vector<double> q, v;
  std::vector<double> params;  // in ReferenceModel::parameter_names order
{fields}
}};

struct ReferenceModel {{
  std::string name;
  std::vector<std::string> parameter_names;
  std::vector<ReferenceState> states;
}};

/// The reference values of the model called `name`, or nullptr.
inline const ReferenceModel* find_reference(std::string_view name) {{
  static const std::vector<ReferenceModel> models = {{
{models}
  }};
  for (const ReferenceModel& model : models) {{
    if (model.name == name) return &model;
  }}
  return nullptr;
}}

}}  // namespace gencoord::testing
"""
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    with open(output, "w", encoding="utf-8") as handle:
        handle.write(text)


if __name__ == "__main__":
    main()
