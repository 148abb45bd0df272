# SPDX-License-Identifier: BSD-3-Clause
"""Which C++ functions a model gets, with their inputs and symbolic outputs.

This is the generator's side of docs/model_interface.md: each `Kernel` is one static
function of the generated struct. Its outputs are `Block`s (a named Eigen matrix or a scalar)
whose entries are SymPy expressions; `optimize/optimizer.py` runs one CSE over all of them together.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import sympy as sp

from gencoord.derive.dense import Derivation
from gencoord.derive.kinematic_constraints import ConstraintDerivation
from gencoord.derive.maximal import MaximalDerivation
from gencoord.derive.point_recursion import RecursiveDynamics

if TYPE_CHECKING:
    from gencoord.derive.looped import LoopedOutputs


@dataclass
class Block:
    """One output of a kernel: `name(row, col) = expr` for each entry, or `name = expr`.

    An out-parameter block is a pointer argument of its kernel; any other is the value the
    kernel returns. The C++ backend spells its type (cxx/lvalues.cxx_type)."""
    name: str                          # an identifier: "result", "Mt"
    # the model interface's type of its values: "QMatrix", "QVector", "XJacobian", ..., a
    # plain "Scalar", or an "array" of shape[0] values (a sparse Jacobian's)
    storage: str
    shape: tuple[int, int]             # (1, 1) for a plain scalar
    entries: list[tuple[int, int, sp.Expr]]
    symmetric: bool = False            # entries hold the lower triangle; mirror the rest
    # Jacobian blocks: entries are d(of[i]) / d(wrt[j]), computed after CSE (differentiate.py)
    jacobian_of: tuple[list[sp.Expr], list[sp.Symbol]] | None = None
    pattern: list[tuple[int, int]] | None = None  # sparse Jacobian: the (i, j) emitted, in order
    # directional-derivative blocks: entry i is the derivative of of[i] along the direction
    # that seeds[w] gives each input w, computed after CSE (differentiate.py)
    tangent_of: tuple[list[sp.Expr], dict[sp.Symbol, sp.Expr]] | None = None
    out_param: bool = False            # written through the pointer argument `name`

    @property
    def is_scalar(self) -> bool:
        return self.storage == "Scalar"

    @property
    def array(self) -> bool:
        """Values indexed by one number, in the order of `entries` (or `pattern`)."""
        return self.storage == "array"


@dataclass(frozen=True)
class Call:
    """One output of a composed kernel computed by calling another kernel of the model: with
    `inputs` its arguments before params, "unit" standing for the unit vector e_j."""
    output: str
    kernel: str
    inputs: tuple[str, ...]


@dataclass(frozen=True)
class Composed:
    """A kernel computed from others, with no entries of its own (looped.py): each call
    once, or with `columns` once per column j of the outputs, along e_j."""
    calls: tuple[Call, ...]
    columns: int = 0

    def call_counts(self) -> list[tuple[str, int]]:
        """(kernel called, how many times) of each call."""
        return [(call.kernel, self.columns or 1) for call in self.calls]


@dataclass
class Kernel:
    name: str
    summary: str                       # the doc comment's first line
    inputs: tuple[str, ...]            # of INPUT_SYMBOLS' keys; params come after these
    blocks: list[Block]
    notes: list[str] = field(default_factory=list)
    # "recursive": the O(n) alternative to the dense kernel of the same name; after the CSE
    # the cheaper of the two is kept (dynamics_paths.py)
    variant: str = ""
    # a kernel made of calls of others (looped.py): it has no entries of its own
    composed: Composed | None = None

    @property
    def returns(self) -> str | None:
        """The name of the block the kernel returns; None when its blocks are out-parameters."""
        return next((block.name for block in self.blocks if not block.out_param), None)


def _vector(name: str, storage: str, values: sp.Matrix) -> Block:
    return Block(name, storage, (len(values), 1),
                 [(i, 0, values[i]) for i in range(len(values))])


def _lower(name: str, matrix: sp.Matrix) -> Block:
    n = matrix.shape[0]
    return Block(name, "VMatrix", (n, n),
                 [(i, j, matrix[i, j]) for i in range(n) for j in range(i + 1)],
                 symmetric=True)


def _matrix(name: str, storage: str, matrix: sp.Matrix) -> Block:
    return Block(name, storage, matrix.shape,
                 [(i, j, matrix[i, j]) for i in range(matrix.shape[0])
                  for j in range(matrix.shape[1])])


def _jacobian(name: str, storage: str, of: sp.Matrix, wrt: list[sp.Symbol]) -> Block:
    return Block(name, storage, (len(of), len(wrt)), [], jacobian_of=(list(of), wrt))


def _input_matrix(d: Derivation) -> Block:
    """B = dFt/du, nv x (number of inputs)."""
    return Block("result", "InputMatrix", (len(d.applied_forces), len(d.inputs)), [],
                 jacobian_of=(list(d.applied_forces), d.inputs))


def _scalar(name: str, value: sp.Expr) -> Block:
    return Block(name, "Scalar", (1, 1), [(0, 0, value)])


def _out(block: Block) -> Block:
    """The block as an out-parameter of its kernel."""
    block.out_param = True
    return block


def _recursive_kernels(r: RecursiveDynamics) -> dict[str, Kernel]:
    """The tree recursions' kernels, each to follow the dense kernel of its name."""
    return {
        "dynamics": Kernel(
            "qddot", "Generalized accelerations qddot = Mt^-1 (Ft + Fi) by the articulated-body "
            "recursion (O(nq)); NaN or inf entries where Mt is singular.", ("q", "v", "t"),
            [_vector("result", "VVector", r.qddot)], variant="recursive"),
        "inverse_dynamics": Kernel(
            "inverse_dynamics", "Inverse dynamics by the recursive Newton-Euler algorithm "
            "(O(nq)): the residual r = Mt qdd - Ft - Fi, i.e. the generalized force that "
            "produces qdd.", ("q", "v", "qdd", "t"),
            [_vector("result", "VVector", r.residual)], variant="recursive"),
    }


def build_kernels(d: Derivation, recursive: RecursiveDynamics | None = None,
                  tree_derived: bool = False, looped: LoopedOutputs | None = None
                  ) -> list[Kernel]:
    """The kernels of one model, in the order they appear in the generated header.

    With the tree recursions, their kernels follow the dense ones they may replace. A model
    whose derivation came from its recursions (`tree_derived`) gets the residual's Jacobians
    in closed form where its joints allow (tree_derivatives.py), else by forward mode through
    Newton-Euler's residual (n directions of O(n) operations each, where Mt qdd takes n^2
    each), and no dense inverse dynamics: Newton-Euler is it. With `looped` (a large
    tree, looped.py) its loops replace the kernels of n^2 entries, and its products follow
    the others."""
    residual = None if tree_derived else d.residual()
    differentiated = residual
    if tree_derived:
        assert recursive is not None  # a tree-derived model comes with its recursions
        differentiated = recursive.residual
    replacing = dict(looped.replacing) if looped else {}
    if (tree_derived and recursive is not None and recursive.residual_jacobians
            and "residual_jacobians" not in replacing):
        dr_dq, dr_dv = recursive.residual_jacobians
        replacing["residual_jacobians"] = _residual_jacobians(
            _matrix("dr_dq", "VQMatrix", dr_dq), _matrix("dr_dv", "VMatrix", dr_dv))
    kernels = _dense_kernels(d, residual, differentiated, replacing)
    if looped:
        kernels += looped.products
    if d.constraints is not None:
        kernels += _constraint_kernels(d.constraints)
    if recursive is None:
        return kernels
    alternatives = _recursive_kernels(recursive)
    follow = {name: [kernel] for name, kernel in alternatives.items()}
    if not any(k.name == "inverse_dynamics" for k in kernels):
        follow["dynamics"].append(follow.pop("inverse_dynamics")[0])
    return [k for dense in kernels for k in [dense, *follow.get(dense.name, [])]]


def _dense_kernels(d: Derivation, residual: sp.Matrix | None,
                   differentiated_residual: sp.Matrix, replacing: dict[str, Kernel]
                   ) -> list[Kernel]:
    """The kernels of the derivation; `inverse_dynamics` only given the dense `residual`;
    each kernel named in `replacing` replaced by that one (the derivation may then lack the
    outputs it would read: a looped tree has no Mt or J)."""
    def unless_replaced(name: str, make) -> Kernel:
        return replacing[name] if name in replacing else make()

    return (_dynamics_kernels(d, residual, differentiated_residual, unless_replaced)
            + _state_kernels(d, unless_replaced))


def _dynamics_kernels(d: Derivation, residual: sp.Matrix | None,
                      differentiated_residual: sp.Matrix, unless_replaced) -> list[Kernel]:
    """Mt, the forces, the dynamics, the inverse dynamics and their Jacobians."""
    total_force = d.applied_forces + d.inertial_forces
    return [
        unless_replaced("mass_matrix", lambda: Kernel(
            "mass_matrix", "Reduced mass matrix Mt = J^T M J (symmetric).", ("q", "t"),
            [_lower("result", d.mass_matrix)])),
        Kernel("applied_forces", "Applied generalized forces Ft = J^T F + Q.",
               ("q", "v", "t"), [_vector("result", "VVector", d.applied_forces)]),
        Kernel("generalized_forces", "Forces acting directly on q (joint torques, joint "
               "springs).", ("q", "v", "t"),
               [_vector("result", "VVector", d.generalized_forces)]),
        Kernel("inertial_forces", "Inertial (Coriolis, centrifugal, moving-frame) forces "
               "Fi = -J^T M gamma.", ("q", "v", "t"),
               [_vector("result", "VVector", d.inertial_forces)]),
        Kernel("forces", "Right-hand side Ft + Fi of Mt qddot = Ft + Fi.", ("q", "v", "t"),
               [_vector("result", "VVector", total_force)]),
        unless_replaced("dynamics", lambda: Kernel(
            "dynamics", "Mt and Ft + Fi in one pass, sharing their common terms.",
            ("q", "v", "t"),
            [_out(_lower("Mt", d.mass_matrix)), _out(_vector("f", "VVector", total_force))],
            notes=["Mt and f must not be null."])),
        *([Kernel("inverse_dynamics", "Inverse dynamics: the residual r = Mt qdd - Ft - Fi, "
                  "i.e. the generalized force that produces qdd.", ("q", "v", "qdd", "t"),
                  [_vector("result", "VVector", residual)])]
          if residual is not None else []),
        # a constrained model's implicit steps difference its constrained acceleration, which
        # this residual leaves out (the bicycle's would be 40% of its header)
        *([unless_replaced("residual_jacobians", lambda: _residual_jacobians(
            _jacobian("dr_dq", "VQMatrix", differentiated_residual, d.q),
            _jacobian("dr_dv", "VMatrix", differentiated_residual, d.v)))]
          if d.constraints is None else []),
        *([Kernel("input_matrix", "Input matrix B = dFt/du: the generalized force per unit of "
                  "each control input (Ft = B u + the rest when u enters linearly).",
                  ("q", "v", "t"), [_input_matrix(d)])] if d.inputs else []),
    ]


def _residual_jacobians(dr_dq: Block, dr_dv: Block) -> Kernel:
    return Kernel("residual_jacobians", "Jacobians dr/dq and dr/dv of the residual "
                  "(dr/dqdd = Mt), for Newton steps.", ("q", "v", "qdd", "t"),
                  [_out(dr_dq), _out(dr_dv)], notes=["dr_dq and dr_dv must not be null."])


def _state_kernels(d: Derivation, unless_replaced) -> list[Kernel]:
    """Energies, positions, velocities, J, gamma, momenta, masses and fixed points."""
    return [
        *([Kernel("coordinate_rates", "Kinematic equation dq/dt = G(q) v: the rates of the "
                  "coordinates, linear in the speeds.", ("q", "v", "t"),
                  [_vector("result", "QVector", d.rates)])] if d.rates is not None else []),
        Kernel("kinetic_energy", "Kinetic energy T = 1/2 xdot^T M xdot.", ("q", "v", "t"),
               [_scalar("result", d.kinetic_energy)]),
        Kernel("potential_energy", "Potential energy V (gravity, springs, given potentials).",
               ("q", "t"), [_scalar("result", d.potential_energy)]),
        Kernel("generalized_potential_energy", "The part of V given with generalized forces.",
               ("q", "t"), [_scalar("result", d.generalized_potential)]),
        Kernel("energy", "Total energy E = T + V.", ("q", "v", "t"),
               [_scalar("result", d.kinetic_energy + d.potential_energy)]),
        Kernel("positions", "Particle positions x = X(q, t), stacked.", ("q", "t"),
               [_vector("result", "XVector", d.positions)]),
        Kernel("velocities", "Particle velocities xdot = J v + X_t, stacked.", ("q", "v", "t"),
               [_vector("result", "XVector", d.velocities)]),
        unless_replaced("jacobian", lambda: Kernel(
            "jacobian", "Jacobian J = dX/dq." if d.rates is None else "Jacobian J = d xdot / d v "
            "(xdot = J v + X_t).", ("q", "t"),
            [_matrix("result", "XJacobian", d.jacobian)])),
        Kernel("bias_acceleration", "Velocity-product acceleration gamma (xddot at qddot = 0).",
               ("q", "v", "t"), [_vector("result", "XVector", d.bias_acceleration)]),
        Kernel("linear_momentum", "Linear momentum p = sum m_i xdot_i.", ("q", "v", "t"),
               [_vector("result", "SpaceVector", d.linear_momentum)]),
        Kernel("angular_momentum", "Angular momentum L = sum m_i x_i x xdot_i about the "
               "origin (z component in 2D).", ("q", "v", "t"),
               [_vector("result", "AngularVector", d.angular_momentum)]),
        Kernel("particle_masses", "Particle masses, in particle order.", (),
               [_vector("result", "ParticleVector", sp.Matrix(d.masses))]),
        Kernel("fixed_point_positions", "Fixed-point positions (anchors, prescribed pivots), "
               "stacked.", ("t",),
               [_vector("result", "FixedPointVector", d.fixed_point_positions)]),
    ]


def _constraint_kernels(c: ConstraintDerivation) -> list[Kernel]:
    """The kinematic constraints: C and dC/dq where some are holonomic, then A, A v + b and
    gamma of all of them (kinematic_constraints.py)."""
    holonomic = [
        Kernel("holonomic_constraints", "Holonomic constraint residuals C(q, t) (0 on the "
               "constraints).", ("q", "t"), [_vector("result", "HVector", c.holonomic)]),
        Kernel("holonomic_jacobian", "dC/dq (num_holonomic_constraints x nq): the Newton "
               "steps that put q back on the constraints.", ("q", "t"),
               [_matrix("result", "HJacobian", c.holonomic_jacobian)]),
    ] if c.num_holonomic else []
    return holonomic + [
        Kernel("constraint_jacobian", "Constraint Jacobian A (num_constraints x nv): every "
               "constraint at the velocity level is A v + b = 0.", ("q", "t"),
               [_matrix("result", "CJacobian", c.jacobian)]),
        Kernel("constraint_velocities", "Constraint residuals at the velocity level, A v + b "
               "(0 on the constraints).", ("q", "v", "t"),
               [_vector("result", "CVector", c.velocity)]),
        Kernel("constraint_bias", "Acceleration-level bias gamma: A dv/dt + gamma = 0 along "
               "every motion that keeps the constraints.", ("q", "v", "t"),
               [_vector("result", "CVector", c.bias)]),
    ]


def _sparse_jacobian(name: str, of: sp.Matrix, wrt: list[sp.Symbol],
                     pattern: list[tuple[int, int]], values: list[sp.Expr] | None) -> Block:
    """The entries of d of / d wrt at `pattern`, as an array in that order.

    Given `values`, those are emitted; otherwise optimize/optimizer.py takes them by forward mode.
    """
    if values is not None:
        return Block(name, "array", (len(values), 1),
                     [(k, 0, expr) for k, expr in enumerate(values)])
    return Block(name, "array", (len(pattern), 1), [],
                 jacobian_of=(list(of), wrt), pattern=pattern)


def build_maximal_kernels(m: MaximalDerivation) -> list[Kernel]:
    """The maximal-coordinate model's kernels (nested struct Maximal)."""
    return [
        Kernel("external_forces", "External forces F(x, xdot, t): gravity, springs, dampers, "
               "user forces.", ("pos", "vel", "t"),
               [_vector("result", "XVector", m.external_forces)]),
        Kernel("penalty_forces", "Penalty forces: the declared constraints as stiff "
               "damped springs.",
               ("pos", "vel", "t", "kappa", "penalty_damping"),
               [_vector("result", "XVector", m.penalty_forces)]),
        Kernel("force_jacobian_x", "Nonzero entries of d(F + F_penalty)/dx (see "
               "jacobian_x_rows, _cols).",
               ("pos", "vel", "t", "kappa", "penalty_damping"),
               [_sparse_jacobian("result", m.total_forces, m.x, m.force_jacobian_x,
                                 m.force_jacobian_x_values)]),
        Kernel("force_jacobian_xdot", "Nonzero entries of d(F + F_penalty)/dxdot (see "
               "jacobian_xdot_rows, _cols).",
               ("pos", "vel", "t", "kappa", "penalty_damping"),
               [_sparse_jacobian("result", m.total_forces, m.xdot, m.force_jacobian_xdot,
                                 m.force_jacobian_xdot_values)]),
        Kernel("potential_energy", "x-space potential energy (joint-spring potentials live "
               "in q).", ("pos", "t"),
               [_scalar("result", m.potential_energy)]),
        Kernel("penalty_energy", "Energy stored in the penalty springs.", ("pos", "t", "kappa"),
               [_scalar("result", m.penalty_energy)]),
        Kernel("constraint_violations", "Constraint violations: rod |d| - L, pin |x - anchor|, "
               "plane distance.", ("pos", "t"),
               [_vector("result", "ConstraintVector", m.violations)]),
    ]
