# SPDX-License-Identifier: BSD-3-Clause
"""Writes reference_values.hpp: every tested model's outputs at a few seeded random states,
evaluated in 40-digit mpmath arithmetic straight from the unoptimized `derive()` and
`derive_maximal()` results: every kernel of the reduced model and of its Maximal model.

reference_values_test.cc compares the generated kernels (after CSE and the C++ printer) with
these values, so a printing or CSE bug shows up as a mismatch. The models are the ones
gencoord/tool/model_list.py lists (the tests' type list), atlas charts included.

    make_reference_values.py <output.hpp> [--cache DIR]

With --cache, the text is kept in DIR (gencoord's generation cache) under a key of this
script, every file of models/ and the generator, and reused while none of them changes.
"""

from __future__ import annotations

import argparse
import os
import random
import sys
import zlib

import mpmath
import sympy as sp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path[:0] = [os.path.join(ROOT, "python"), ROOT]

from gencoord.dsl.bodies import inertia_problem  # noqa: E402
from gencoord.derive.dense import Kinematics, derive  # noqa: E402
from gencoord.derive.kinematic_constraints import derive_kinematic_constraints  # noqa: E402
from gencoord.generate.load import load_model  # noqa: E402
from gencoord.derive.maximal import (KAPPA, PENALTY_DAMPING, derive_maximal,  # noqa: E402
                                     has_maximal_model)
from gencoord.generate.output_cache import OutputCache, cache_key  # noqa: E402
from gencoord.tool.model_list import MODELS, Variant, variants  # noqa: E402
from tests.python.graph_values import GraphFunction  # noqa: E402

STATES = 5
DIGITS = 40
# Jacobians (of the residual, of the Maximal forces) are forward differences in DIGITS-digit
# arithmetic: the step's truncation error (~STEP) and round-off (~10^-DIGITS / STEP) stay
# near 1e-20, far below double's round-off. (Symbolic Jacobians of the Maximal forces are
# too large to evaluate in mpmath in reasonable time.)
STEP = mpmath.mpf("1e-20")
# The residual Jacobians of models with more coordinates than this (whose plain derivation is
# large) only at the first state: each difference evaluates Mt and the forces again.
JACOBIAN_MAX_NQ = 6
# the reference values each state holds, in ReferenceState's order
REDUCED = ["mass_matrix", "applied_forces", "inertial_forces", "generalized_forces",
           "kinetic_energy", "potential_energy", "generalized_potential_energy", "positions",
           "velocities", "jacobian", "bias_acceleration", "linear_momentum", "angular_momentum",
           "particle_masses", "fixed_point_positions"]
SUMS = ["forces", "energy"]  # summed from the values above
ACCELERATIONS = ["inverse_dynamics", "dr_dq", "dr_dv", "qddot"]
MAXIMAL = ["maximal_external_forces", "maximal_penalty_forces", "maximal_force_jacobian_x",
           "maximal_force_jacobian_xdot", "maximal_potential_energy", "maximal_penalty_energy",
           "maximal_constraint_violations"]
# the kinematic constraints' kernels (empty for a model without them)
CONSTRAINTS = ["holonomic_constraints", "holonomic_jacobian", "constraint_jacobian",
               "constraint_velocities", "constraint_bias"]
OUTPUTS = REDUCED + SUMS + ACCELERATIONS + MAXIMAL + CONSTRAINTS
INPUTS = ["q", "v", "qdd", "params", "pos", "vel"]


def constraint_outputs(c) -> dict[str, sp.Matrix]:
    """The ConstraintDerivation's outputs of (q, v, t, params); none without constraints."""
    if c is None:
        return {}
    return {"holonomic_constraints": c.holonomic, "holonomic_jacobian": c.holonomic_jacobian,
            "constraint_jacobian": c.jacobian, "constraint_velocities": c.velocity,
            "constraint_bias": c.bias}


def outputs(d) -> dict[str, sp.Matrix]:
    """The Derivation's outputs of (q, v, t, params)."""
    return {
        "mass_matrix": d.mass_matrix,
        "applied_forces": d.applied_forces,
        "inertial_forces": d.inertial_forces,
        "generalized_forces": d.generalized_forces,
        "kinetic_energy": sp.Matrix([d.kinetic_energy]),
        "potential_energy": sp.Matrix([d.potential_energy]),
        "generalized_potential_energy": sp.Matrix([d.generalized_potential]),
        "positions": d.positions,
        "velocities": d.velocities,
        "jacobian": d.jacobian,
        "bias_acceleration": d.bias_acceleration,
        "linear_momentum": d.linear_momentum,
        "angular_momentum": d.angular_momentum,
        "particle_masses": sp.Matrix(d.masses),
        "fixed_point_positions": d.fixed_point_positions,
    }


def maximal_outputs(md) -> dict[str, sp.Matrix]:
    """The MaximalDerivation's outputs of (x, xdot, t, kappa, penalty_damping, params); the
    force Jacobians are differences of external + penalty forces, later."""
    return {
        "maximal_external_forces": md.external_forces,
        "maximal_penalty_forces": md.penalty_forces,
        "maximal_potential_energy": sp.Matrix([md.potential_energy]),
        "maximal_penalty_energy": sp.Matrix([md.penalty_energy]),
        "maximal_constraint_violations": md.violations,
    }


def lambdified(arguments: list, exprs: dict, name: str) -> dict:
    """One mpmath function per output, of `arguments`; row-major entries."""
    for key, matrix in exprs.items():
        extra = set().union(*(sp.sympify(e).free_symbols for e in matrix)) - set(arguments)
        if extra:
            raise SystemExit(f"{name}: {key} depends on unknown symbols {extra}")
    # over the expressions' graph of shared nodes: the large models' expression trees take
    # minutes to print (lambdify), and as long to search for common subexpressions
    return {key: GraphFunction(arguments, list(matrix)) for key, matrix in exprs.items()}


def difference(function, point: list, value: list, k: int) -> list:
    """d function / d point[k], by a forward difference of step STEP (value: at point)."""
    moved = list(point)
    moved[k] += STEP
    return [(a - b) / STEP for a, b in zip(function(*moved), value)]


def number(x) -> str:
    """A double with 17 significant digits (round-trips exactly)."""
    return f"{float(x):.17g}"


def array(values) -> str:
    return "{" + ", ".join(number(x) for x in values) + "}"


def reference_models(variant: Variant, seed: int) -> list[str]:
    """The entries of one header: its model, and each further chart of an atlas."""
    model, name, _ = load_model(variant.path, dict(variant.options))
    assert name == variant.name, (name, variant.name)
    return [reference_model(name if chart is model else f"{name}_{chart.chart}", chart,
                            seed + 1000 * k)
            for k, chart in enumerate([model, *model.charts])]


def sampled_parameters(model, rng: random.Random) -> list[float]:
    """Parameters around the defaults (zero defaults, such as dampers, drag or an applied
    force, get a small value), drawn again until every body's mass and inertia are a real
    body's: scaling the entries of an inertia tensor one by one can break the triangle
    inequality."""
    for _ in range(1000):
        params = [p.default * rng.uniform(0.7, 1.3) if p.default != 0 else rng.uniform(0.1, 0.5)
                  for p in model.parameters]
        values = {p.symbol: sp.Float(value) for p, value in zip(model.parameters, params)}
        if not any(inertia_problem(sp.sympify(body.mass).xreplace(values),
                                   body.inertia.xreplace(values)) for body in model.bodies):
            return params
    raise RuntimeError("no parameters near the defaults make every body physical")


def maximal_values(md, maximal: dict, values: list[float]) -> dict[str, list]:
    """The Maximal model's outputs at (pos, vel, t, kappa, damping, params): each kernel's,
    and its force Jacobians' sparse entries as forward differences."""
    nx = len(md.x)
    inputs = [mpmath.mpf(x) for x in values]

    def total_forces(*arguments):
        return [a + b for a, b in zip(maximal["maximal_external_forces"](*arguments),
                                      maximal["maximal_penalty_forces"](*arguments))]

    results = {key: f(*inputs) for key, f in maximal.items()}
    total = total_forces(*inputs)
    for key, pattern, offset in [("maximal_force_jacobian_x", md.force_jacobian_x, 0),
                                 ("maximal_force_jacobian_xdot", md.force_jacobian_xdot, nx)]:
        columns = {c: difference(total_forces, inputs, total, offset + c)
                   for c in sorted({c for _, c in pattern})}
        results[key] = [columns[c][r] for r, c in pattern]
    return results


def reference_model(name: str, model, seed: int) -> str:
    kin = Kinematics(model)
    d = derive(model, kin)
    constraints = derive_kinematic_constraints(model, kin)
    # a model without a Maximal struct (generated_speeds, kinematic constraints) gets no
    # maximal values: its header has nothing to compare them with
    md = derive_maximal(model, symbolic_jacobians=False) if has_maximal_model(model) else None
    nq = len(d.q)
    arguments = [*d.q, *d.v, d.t, *d.params]
    functions = lambdified(arguments, {**outputs(d), **constraint_outputs(constraints)}, name)
    maximal = lambdified([*md.x, *md.xdot, d.t, KAPPA, PENALTY_DAMPING, *d.params],
                         maximal_outputs(md), name) if md else {}

    def residual(qdd, *arguments, mass=None):
        """Inverse-dynamics residual r = Mt qdd - Ft - Fi at (q, v, t, params); `mass`: Mt
        there, when known (it does not depend on v)."""
        mass = mass or functions["mass_matrix"](*arguments)
        force = [a + b for a, b in zip(functions["applied_forces"](*arguments),
                                       functions["inertial_forces"](*arguments))]
        return [sum(mass[r * nq + c] * qdd[c] for c in range(nq)) - force[r]
                for r in range(nq)]

    rng = random.Random(seed)
    states = []
    for _ in range(STATES):
        q = [rng.uniform(0.3, 1.3) for _ in d.q]
        v = [rng.uniform(-1.0, 1.0) for _ in d.v]
        qdd = [rng.uniform(-1.0, 1.0) for _ in d.q]
        t = rng.uniform(0.0, 2.0)
        params = sampled_parameters(model, rng)
        # the maximal model near the reduced state, off its constraints so penalties act
        kappa, damping = rng.uniform(1e2, 1e4), rng.uniform(0.1, 1.0)
        with mpmath.workdps(DIGITS):
            values = [mpmath.mpf(x) for x in [*q, *v, t, *params]]  # the doubles, exactly
            results = {key: [] for key in CONSTRAINTS}
            results.update({key: f(*values) for key, f in functions.items()})
            results["forces"] = [a + b for a, b in zip(results["applied_forces"],
                                                       results["inertial_forces"])]
            results["energy"] = [results["kinetic_energy"][0] + results["potential_energy"][0]]
            qdd_values = [mpmath.mpf(x) for x in qdd]
            r = results["inverse_dynamics"] = residual(qdd_values, *values,
                                                       mass=results["mass_matrix"])
            results["dr_dq"] = results["dr_dv"] = []
            # a constrained model has no residual_jacobians kernel (kernel_set.py)
            if constraints is None and (nq <= JACOBIAN_MAX_NQ or not states):
                columns = [difference(lambda *at: residual(qdd_values, *at), values, r, k)
                           for k in range(nq)]
                columns += [difference(lambda *at: residual(qdd_values, *at,
                                                            mass=results["mass_matrix"]),
                                       values, r, k) for k in range(nq, 2 * nq)]
                results["dr_dq"] = [columns[c][i] for i in range(nq) for c in range(nq)]
                results["dr_dv"] = [columns[nq + c][i] for i in range(nq) for c in range(nq)]
            mass = mpmath.matrix(nq, nq)
            for k, entry in enumerate(results["mass_matrix"]):
                mass[k // nq, k % nq] = entry
            results["qddot"] = list(mpmath.lu_solve(mass, mpmath.matrix(results["forces"])))
            pos = [float(x) + rng.uniform(-0.05, 0.05) for x in results["positions"]]
            vel = [float(x) + rng.uniform(-0.05, 0.05) for x in results["velocities"]]
            results.update({key: [] for key in MAXIMAL})
            if md:
                results.update(maximal_values(md, maximal, [*pos, *vel, t, kappa, damping,
                                                            *params]))
        fields = [f"/* t */ {number(t)}", f"/* kappa */ {number(kappa)}",
                  f"/* penalty_damping */ {number(damping)}"]
        fields += [f"/* {key} */ {array(value)}" for key, value in
                   zip(INPUTS, [q, v, qdd, params, pos, vel])]
        fields += [f"/* {key} */ {array(results[key])}" for key in OUTPUTS]
        states.append("      {" + ",\n       ".join(fields) + "}")
    names = ", ".join(f'"{p.name}"' for p in model.parameters)
    return (f'  {{"{name}",\n   {{{names}}},\n   {{\n' + ",\n".join(states) + "\n   }}")


def reference_header() -> str:
    # each model's seed comes from its name, so adding a model leaves the others' states
    models = ",\n".join(entry for variant in variants()
                        for entry in reference_models(variant, zlib.crc32(variant.name.encode())))
    fields = "\n".join(f"  std::vector<double> {key};" for key in OUTPUTS)
    text = f"""\
// Generated by tests/models/make_reference_values.py. Do NOT modify by hand.
// Each model's outputs at {STATES} random states, evaluated in {DIGITS}-digit arithmetic from the
// unoptimized derive() and derive_maximal() results (Jacobians as forward differences in
// that arithmetic); matrices are stored row-major.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace gencoord::testing {{

struct ReferenceState {{
  double t, kappa, penalty_damping;
  std::vector<double> q, v, qdd;
  std::vector<double> params;  // in ReferenceModel::parameter_names order
  std::vector<double> pos, vel;  // the Maximal model's state, near X(q) and J v + X_t
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
    return text


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", help="the header to write")
    parser.add_argument("--cache", metavar="DIR", help="gencoord's generation cache")
    args = parser.parse_args()
    inputs = [os.path.abspath(__file__)] + sorted(
        os.path.join(MODELS, name) for name in os.listdir(MODELS)
        if os.path.isfile(os.path.join(MODELS, name)))

    def make() -> dict:
        return {"text": reference_header()}

    entry = (OutputCache(args.cache).cached(cache_key("reference values", inputs, []), make)[0]
             if args.cache else make())
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as handle:
        handle.write(entry["text"])


if __name__ == "__main__":
    main()
