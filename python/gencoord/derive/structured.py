# SPDX-License-Identifier: BSD-3-Clause
"""The reduced dynamics as named intermediates, so no output grows like n^3.

`derive.derive` writes every output as one flat expression: for an n-link chain each entry
of Fi = -J^T M gamma holds O(n^2) terms and Mt repeats a link's column in every particle's
contribution; CSE then has to rediscover the structure in trees of size n^3. Here each
particle's position, velocity and gamma, each force component and each entry of Mt, Ft and
Fi is a named intermediate (a fresh symbol with its definition), and the sums over particles
are grouped by equal Jacobian entries, so the masses of all particles sharing a column are
added first: the chain's Mt[a, b] becomes (m_max(a,b) + ... + m_n) (l_a cos a l_b cos b + ...).

The values are those of derive/dense.py, unchanged; `derive.derive` stays the plain
reference the tests compare the generated code against.
"""

from __future__ import annotations

import sympy as sp

from gencoord.dsl.bodies import inertial_terms
from gencoord.derive.dense import (Derivation, Kinematics, _cross, bias_acceleration,
                                   fixed_point_positions, generalized_potential, gravity_force,
                                   particle_forces, x_space_potential)
from gencoord.derive.speed_forces import generalized_force_vector
from gencoord.dsl.model import Model
from gencoord.dsl.items import Point
from gencoord.symbolic.sums import dot


class Intermediates:
    """Definitions `symbol = expr` in dependency order; atoms and repeats get no new name.

    A sum that contains every term of an already named sum is written as that sum plus
    the rest, so nested sums become recurrences: the chain's x_k = x_(k-1) + l_k sin
    theta_k, and the masses beyond link k in Mt = (m_k + masses beyond k+1). Their
    derivatives (forward mode, differentiate.py) stay as short as the sums themselves.
    """

    def __init__(self, prefix: str = "__w") -> None:
        # '__' cannot start a model name (validate.py); optimize renames these
        self.prefix = prefix
        self.definitions: list[tuple[sp.Symbol, sp.Expr]] = []
        self._named: dict[sp.Expr, sp.Symbol] = {}
        self._sums: list[tuple[frozenset, sp.Symbol]] = []   # named sums by their terms
        self._sums_with: dict[sp.Expr, list[int]] = {}       # term -> indices in _sums

    def name(self, expr: sp.Expr) -> sp.Expr:
        expr = sp.sympify(expr)
        if expr.is_Atom:
            return expr
        if expr not in self._named:
            symbol = sp.Symbol(f"{self.prefix}{len(self.definitions)}")
            self._named[expr] = symbol
            self.definitions.append((symbol, self._reusing_sums(expr, symbol)))
        return self._named[expr]

    def vector(self, values: sp.Matrix) -> sp.Matrix:
        return sp.Matrix([self.name(e) for e in values])

    def matrix(self, values: sp.Matrix) -> sp.Matrix:
        """Every entry named, in the matrix's shape."""
        return values.applyfunc(self.name)

    def symmetric(self, values: sp.Matrix) -> sp.Matrix:
        """Names the lower triangle and mirrors it, so equal entries are computed once."""
        n = values.shape[0]
        result = sp.zeros(n, n)
        for i in range(n):
            for j in range(i + 1):
                result[i, j] = result[j, i] = self.name(values[i, j])
        return result

    def sums(self, term_lists: list[list[sp.Expr]]) -> list[sp.Expr]:
        """Names each sum, the ones with fewer terms first, so larger ones can reuse them."""
        order = sorted(range(len(term_lists)), key=lambda k: len(term_lists[k]))
        named = [sp.Integer(0)] * len(term_lists)
        for k in order:
            named[k] = self.name(sp.Add(*term_lists[k]))
        return named

    def _reusing_sums(self, expr: sp.Expr, symbol: sp.Symbol) -> sp.Expr:
        """`expr`, with the largest named sum whose terms it contains replaced by its name.

        Any named expression counts as a sum of one term.
        """
        args = expr.args if expr.is_Add else (expr,)
        terms = frozenset(args)
        candidates = {k for term in args for k in self._sums_with.get(term, ())}
        best = max((k for k in candidates if self._sums[k][0] < terms),
                   key=lambda k: (len(self._sums[k][0]), -k), default=None)
        for term in args:
            self._sums_with.setdefault(term, []).append(len(self._sums))
        self._sums.append((terms, symbol))
        if best is None:
            return expr
        inner, name = self._sums[best]
        return sp.Add(name, *[term for term in args if term not in inner])


class NamedKinematics:
    """Every point's position and velocity as given; the interface forces and potentials
    read (`of`, `position`, `point_substitution`)."""

    def __init__(self, model: Model, t: sp.Symbol, position: dict[str, sp.Matrix],
                 velocity: dict[str, sp.Matrix]):
        self.t = t
        self.position, self.velocity = position, velocity
        self.point_substitution: dict[sp.Symbol, sp.Expr] = {}
        for point in model.points:
            self.point_substitution.update(zip(point.x, self.position[point.name]))
            self.point_substitution.update(zip(point.xdot, self.velocity[point.name]))

    @classmethod
    def particles_named(cls, model: Model, kin: Kinematics,
                        names: Intermediates) -> "NamedKinematics":
        """The particles' positions and velocities as intermediates; fixed points stay
        expressions."""
        particles = {p.name for p in model.particles}
        position: dict[str, sp.Matrix] = {}
        velocity: dict[str, sp.Matrix] = {}
        for point in model.points:
            x, xdot = kin.of(point)
            if point.name in particles:
                x, xdot = names.vector(x), names.vector(xdot)
            position[point.name], velocity[point.name] = x, xdot
        return cls(model, kin.t, position, velocity)

    def of(self, point: Point) -> tuple[sp.Matrix, sp.Matrix]:
        return self.position[point.name], self.velocity[point.name]


def _grouped_sums(groups: list[dict[sp.Expr, list[sp.Expr]]], names: Intermediates
                  ) -> list[sp.Expr]:
    """For each group, sum over keys of key * (sum of its terms), the inner sums named.

    This is J^T (...) with the terms of equal Jacobian entries collected.
    """
    keys = [(g, key) for g, group in enumerate(groups) for key in group]
    inner = names.sums([groups[g][key] for g, key in keys])
    products: list[list[sp.Expr]] = [[] for _ in groups]
    for (g, key), total in zip(keys, inner):
        products[g].append(key * total)
    return [sp.Add(*terms) for terms in products]


class _TermSums:
    """The sums over inertial terms (particles, and rotating bodies) that the outputs are made
    of, grouped by equal Jacobian entries so that each is computed once."""

    def __init__(self, model: Model, kin: Kinematics, names: Intermediates,
                 local: NamedKinematics):
        self.model, self.kin, self.names, self.local = model, kin, names, local
        nv, dim = model.nv, model.dim
        # (a, b) -> {(column a, column b): weights}; a -> {J entry: (w gamma terms, F terms)}
        self.mass_groups: dict[tuple[int, int], dict[tuple, list[sp.Expr]]] = {}
        self.projections: dict[int, dict[sp.Expr, tuple[list, list]]] = {a: {} for a in range(nv)}
        self.gammas: dict[str, sp.Matrix] = {}
        self.kinetic = sp.Integer(0)
        self.gravity_at: list[tuple[sp.Expr, sp.Matrix]] = []
        self.momentum = sp.zeros(dim, 1)
        self.angular = sp.zeros(3 if dim == 3 else 1, 1)

    def project(self, jac: sp.Matrix, vector: sp.Matrix, slot: int) -> None:
        """Adds J^T vector's terms to the projections, grouped by J entry."""
        for a in range(self.model.nv):
            for k in range(self.model.dim):
                if jac[k, a] != 0 and vector[k] != 0:
                    self.projections[a].setdefault(jac[k, a], ([], []))[slot].append(vector[k])

    def add(self, term) -> None:
        kin, names, local, dim = self.kin, self.names, self.local, self.model.dim
        raw_y, jac, raw_ydot = kin.of_term(term)
        if term.name in local.position:  # a particle, named already
            y, ydot = local.position[term.name], local.velocity[term.name]
        else:
            y, ydot = names.vector(raw_y), names.vector(raw_ydot)
        w = term.weight
        gamma = self.gammas[term.name] = names.vector(
            bias_acceleration(raw_ydot, kin.q, kin.rates, kin.t))
        columns = {a: tuple(jac[k, a] for k in range(dim)) for a in range(self.model.nv)
                   if any(jac[k, a] != 0 for k in range(dim))}
        for a, column_a in columns.items():
            for b, column_b in columns.items():
                if b > a:
                    break
                self.mass_groups.setdefault((a, b), {}).setdefault((column_a, column_b),
                                                                   []).append(w)
        self.project(jac, w * gamma, 0)
        self.project(jac, gravity_force(self.model, term), 1)
        self.kinetic += w * dot(ydot, ydot) / 2
        self.angular += w * _cross(y, ydot)
        if term.translational:
            self.momentum += w * ydot
            self.gravity_at.append((w, y))

    def mass_matrix(self) -> sp.Matrix:
        nv = self.model.nv
        mass_matrix = sp.zeros(nv, nv)
        entries = list(self.mass_groups)
        dots: list[dict[sp.Expr, list[sp.Expr]]] = [{} for _ in entries]
        for products, entry in zip(dots, entries):  # different column pairs: equal products
            for columns, masses in self.mass_groups[entry].items():
                products.setdefault(dot(*columns), []).extend(masses)
        for (a, b), value in zip(entries, _grouped_sums(dots, self.names)):
            mass_matrix[a, b] = mass_matrix[b, a] = self.names.name(value)
        return mass_matrix

    def forces(self, generalized: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
        """(Ft, Fi): the applied forces with the `generalized` ones, the inertial forces."""
        nv, names, projections = self.model.nv, self.names, self.projections
        applied_sums = _grouped_sums([{e: terms[1] for e, terms in projections[a].items()}
                                      for a in range(nv)], names)
        inertial_sums = _grouped_sums([{e: terms[0] for e, terms in projections[a].items()}
                                       for a in range(nv)], names)
        applied = sp.Matrix([names.name(applied_sums[a] + generalized[a]) for a in range(nv)])
        inertial = sp.Matrix([names.name(-inertial_sums[a]) for a in range(nv)])
        return applied, inertial


def derive_structured(model: Model, kin: Kinematics
                      ) -> tuple[Derivation, list[tuple[sp.Symbol, sp.Expr]]]:
    """(the Derivation in terms of intermediates, their definitions in dependency order)."""
    q, v, t = kin.q, kin.v, kin.t
    names = Intermediates()
    local = NamedKinematics.particles_named(model, kin, names)
    force = {name: names.vector(f)
             for name, f in particle_forces(model, local, gravity=False).items()}
    sums = _TermSums(model, kin, names, local)
    for term in inertial_terms(model):
        sums.add(term)
    for p in model.particles:
        sums.project(kin.jacobian[p.name], force[p.name], 1)
    mass_matrix = sums.mass_matrix()
    generalized = generalized_force_vector(model, q)
    applied, inertial = sums.forces(generalized)
    particles = model.particles
    derivation = Derivation(
        q=q, v=v, a=[s.acceleration for s in model.speeds], t=t,
        rates=sp.Matrix(kin.rates) if model.has_generalized_speeds else None,
        params=[prm.symbol for prm in model.parameters],
        inputs=[prm.symbol for prm in model.inputs],
        masses=[p.mass for p in particles],
        positions=sp.Matrix.vstack(*[local.position[p.name] for p in particles]),
        fixed_point_positions=fixed_point_positions(model, kin),
        velocities=sp.Matrix.vstack(*[local.velocity[p.name] for p in particles]),
        jacobian=sp.Matrix.vstack(*[kin.jacobian[p.name] for p in particles]),
        bias_acceleration=sp.Matrix.vstack(*[
            sums.gammas[p.name] if p.name in sums.gammas
            else names.vector(bias_acceleration(kin.velocity[p.name], q, kin.rates, t))
            for p in particles]),
        mass_matrix=mass_matrix, applied_forces=applied, inertial_forces=inertial,
        generalized_forces=generalized, kinetic_energy=sums.kinetic,
        potential_energy=(x_space_potential(model, local, sums.gravity_at)
                          + generalized_potential(model)),
        generalized_potential=generalized_potential(model),
        linear_momentum=sums.momentum, angular_momentum=sums.angular)
    return derivation, names.definitions
