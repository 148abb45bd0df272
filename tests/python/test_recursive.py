# SPDX-License-Identifier: BSD-3-Clause
"""The O(n) recursions against the dense derivation.

A model that is a translational tree of particles (point_tree.py, point_recursion.py) or a joint
tree of rigid bodies (body_tree.py, body_recursion.py) gets qddot by the articulated-body
algorithm and the inverse dynamics by Newton-Euler. This checks which models are found to be
trees and with what structure, that both recursions equal Mt^-1 (Ft + Fi) and Mt qdd - Ft - Fi
of derive/dense.py at random states in extended precision on every tree of models/, and how
generation picks between the recursive and the dense kernels. The C++ model tests check the
same after CSE and printing, and the robot tests against MuJoCo.
"""

from __future__ import annotations

import random
import re
import subprocess
import sys
import unittest
from pathlib import Path

import mpmath
import sympy as sp

from gencoord.derive.body_recursion import body_recursive_dynamics
from gencoord.derive.body_tree import body_tree
from gencoord.derive.dense import Kinematics, derive
from gencoord.errors import ModelError
from gencoord.generate.load import load_model
from gencoord.dsl.model import Model
from gencoord.generate.stages import generate
from gencoord.options import GenerateOptions
from gencoord.derive.point_tree import PointTree, point_tree
from gencoord.derive.point_recursion import recursive_dynamics

from .graph_values import graph_values
from .support import DIGITS, MODELS, relative_error

BRANCHED = Path(__file__).parent / "tree_models" / "branched_pendulum.py"
FORCED_ARM = Path(__file__).parent / "tree_models" / "forced_arm.py"
MOVING_PIVOT = Path(__file__).parent / "tree_models" / "moving_pivot.py"
FLOATING_LEG = Path(__file__).parents[1] / "robots" / "floating_leg.py"
QUATERNION_TREE = Path(__file__).parent / "tree_models" / "quaternion_tree.py"
SIX_LINKS = (MODELS / "n_link_chain.py", {"n": "6"})
STATES = 3
_SYMPY_AT_LEAST_1_13 = tuple(int(part) for part in sp.__version__.split(".")[:2]) >= (1, 13)


def _load(path: Path, options=None):
    model, name, _ = load_model(str(path), options)
    return model, name


def particle_trees() -> list[tuple[str, Model, PointTree]]:
    """(name, model, tree) of every particle tree in models/ (found by point_tree, so a new
    one is checked too) and of two that models/ lacks: a longer chain and a branched tree."""
    trees = []
    for path, options in [SIX_LINKS, (BRANCHED, None),
                          *((path, None) for path in sorted(MODELS.glob("*.py")))]:
        model, name = _load(path, options)
        tree = point_tree(model)
        if tree is not None:
            trees.append((name, model, tree))
    return trees


def _structure(tree) -> list[tuple[str, str | None, list[int]]]:
    return [(node.particle.name,
             None if node.parent is None else tree.nodes[node.parent].particle.name,
             node.coordinates) for node in tree.nodes]


class PointTreeTest(unittest.TestCase):

    def test_a_chain_is_a_path(self):
        model, _ = _load(MODELS / "n_link_chain.py", {"n": "4"})
        self.assertEqual(_structure(point_tree(model)),
                         [("bob1", None, [0]), ("bob2", "bob1", [1]), ("bob3", "bob2", [2]),
                          ("bob4", "bob3", [3])])

    def test_branches_and_rigid_attachments(self):
        model, _ = _load(BRANCHED)
        self.assertEqual(_structure(point_tree(model)),
                         [("upper", None, [0, 1]), ("lamp", "upper", []),
                          ("tip_left", "upper", [2]), ("tip_right", "upper", [3])])

    def test_models_that_are_not_trees_of_particles(self):
        for path, options in [(MODELS / "stiff_chain.py", {"n": "3"}),  # relative angles
                              (MODELS / "falling_cat.py", None),
                              (MODELS / "compound_pendulum.py", None)]:  # a body
            model, name = _load(path, options)
            self.assertIsNone(point_tree(model), name)


# every output of the derivation; the recursions give each of them (composite bodies for Mt)
FIELDS = ("mass_matrix", "applied_forces", "inertial_forces", "generalized_forces",
          "positions", "velocities", "jacobian", "bias_acceleration", "fixed_point_positions",
          "kinetic_energy", "potential_energy", "generalized_potential", "linear_momentum",
          "angular_momentum")


def _as_list(value) -> list:
    return list(value) if isinstance(value, sp.MatrixBase) else [value]


def _dense_values(dense, fields, numbers: dict) -> dict[str, list]:
    """Each field of the dense derivation at `numbers`, sharing what the fields share (a
    robot's dense expressions take minutes to evaluate by substitution)."""
    entries = {f: _as_list(getattr(dense, f)) for f in fields}
    flat = iter(graph_values([e for f in fields for e in entries[f]], numbers))
    return {f: [next(flat) for _ in entries[f]] for f in fields}


def _assert_equal_to_dense(test: unittest.TestCase, model, kin: Kinematics, name: str,
                           recursive, tolerance=None) -> None:
    """Both recursions and every output of the recursive derivation against the dense
    derivation at random states, in DIGITS digits, to `tolerance` relative (default: 1e8
    units of the last digit)."""
    dense = derive(model, kin)
    inputs = [*dense.q, *dense.v, *dense.a, *dense.params, dense.t]
    rng = random.Random(name)
    with mpmath.workdps(DIGITS):
        tolerance = tolerance or mpmath.mpf(10) ** (8 - DIGITS)
        for state in range(STATES):
            point = {s: sp.Float(rng.uniform(-1.5, 1.5), DIGITS) for s in inputs}
            for start in model.quaternions:  # unit quaternions, in DIGITS digits
                part = dense.q[start:start + 4]
                norm = sp.sqrt(sum(point[s] ** 2 for s in part))
                point.update({s: (point[s] / norm).evalf(DIGITS) for s in part})
            point.update({p.symbol: sp.Float(p.default * rng.uniform(0.8, 1.2), DIGITS)
                          for p in model.parameters})
            arguments = [mpmath.mpf(point[s]) for s in inputs]
            for symbol, expr in recursive.definitions:
                point[symbol] = expr.xreplace(point).evalf(DIGITS)

            def values(matrix):
                return [mpmath.mpf(sp.sympify(e).xreplace(point).evalf(DIGITS))
                        for e in _as_list(matrix)]

            # the outputs at one state; Mt and the forces at every state
            fields = FIELDS if state == 0 else FIELDS[:3]
            expected = _dense_values(dense, fields, dict(zip(inputs, arguments)))
            for field in fields:
                test.assertLess(relative_error(values(getattr(recursive.derivation, field)),
                                               expected[field]), tolerance, f"{name}: {field}")
            mass = mpmath.matrix(model.nv, model.nv)
            for k, value in enumerate(expected["mass_matrix"]):
                mass[k // model.nv, k % model.nv] = value
            force = mpmath.matrix([a + b for a, b in zip(expected["applied_forces"],
                                                         expected["inertial_forces"])])
            acceleration = mpmath.matrix([point[a] for a in dense.a])
            test.assertLess(relative_error(values(recursive.qddot),
                                           list(mpmath.lu_solve(mass, force))),
                            tolerance, f"{name}: qddot")
            test.assertLess(relative_error(values(recursive.residual),
                                           list(mass * acceleration - force)),
                            tolerance, f"{name}: inverse dynamics")


class RecursionsTest(unittest.TestCase):

    def test_recursions_equal_the_dense_dynamics(self):
        trees = particle_trees()
        # models/ holds ten (pendulums, chains, cart-poles, the hoop, Kapitza's pendulum)
        self.assertGreaterEqual(len(trees), 12, [name for name, _, _ in trees])
        for name, model, tree in trees:
            kin = Kinematics(model)
            recursive = recursive_dynamics(model, kin, tree)
            _assert_equal_to_dense(self, model, kin, name, recursive)


def _links(tree) -> list[tuple[str, str | None, list[int]]]:
    return [(node.link.name, None if node.parent is None else tree.nodes[node.parent].link.name,
             node.coordinates) for node in tree.nodes]


class BodyTreeTest(unittest.TestCase):

    def test_links_branches_and_welds(self):
        model, _ = _load(FORCED_ARM)
        self.assertEqual(_links(body_tree(model)),
                         [("turret", None, [0]), ("slider", "turret", [1]),
                          ("wrist", "slider", [2]), ("hand", "wrist", [3]),
                          ("tool", "hand", []), ("side", "turret", [4])])

    def test_a_free_base_is_one_node_of_six_coordinates(self):
        model, _ = _load(FLOATING_LEG)
        tree = body_tree(model)
        self.assertEqual(_links(tree)[:3], [("world", None, []), ("trunk", None, list(range(6))),
                                            ("FR_hip", "trunk", [6])])
        # the translation's rates are the base velocity in its own axes: S_v = E^T
        self.assertEqual(tree.nodes[1].subspace[3:, :3], tree.nodes[1].rotation.T)

    def test_free_and_ball_joints_are_nodes_of_their_speeds(self):
        model, _ = _load(QUATERNION_TREE)
        tree = body_tree(model)
        self.assertEqual(_links(tree), [("base", None, list(range(7))),
                                        ("arm", "base", list(range(7, 11))),
                                        ("hand", "arm", [11])])
        self.assertEqual([node.speeds for node in tree.nodes],
                         [list(range(6)), [6, 7, 8], [9]])
        self.assertEqual((model.nq, model.nv, model.quaternions), (12, 10, [3, 7]))
        # the twist (v; omega) in the link's axes: S a constant permutation
        self.assertEqual(tree.nodes[0].subspace,
                         sp.Matrix.vstack(sp.Matrix.hstack(sp.zeros(3), sp.eye(3)),
                                          sp.Matrix.hstack(sp.eye(3), sp.zeros(3))))
        self.assertEqual(tree.nodes[1].subspace, sp.Matrix.vstack(sp.eye(3), sp.zeros(3)))

    def test_models_that_are_not_joint_trees(self):
        for path, options in [(MODELS / "heavy_top.py", None),     # a body without links
                              (MODELS / "furuta_pendulum.py", None),
                              (MODELS / "n_link_chain.py", {"n": "3"})]:  # particles
            model, name = _load(path, options)
            self.assertIsNone(body_tree(model), name)

    def test_rigid_body_recursions_equal_the_dense_dynamics(self):
        # torques, springs, dampers, a moving anchor, joint springs and damping, a massless
        # link and a welded one; a joint whose pivot moves in time; then a free base in Euler
        # angles
        # (a URDF's numbers are binary floats: the dense form's LDL^T of a body's second
        # moment rounds at 1e-16, which bounds the agreement there)
        # (a floating robot's dense form with a quaternion takes many minutes: the quaternion
        # tree has the same free and ball joints, and tests/robots checks the floating
        # quadruped against MuJoCo. Comparing it takes 19 s of CPU with SymPy 1.14 and 59 s
        # with 1.11, so it is compared under the newer SymPy only: the recursions are the same
        # code under both)
        # (the UR5e-like arm is a revolute chain as the iiwa is; comparing it would add 4 s of
        # CPU under SymPy 1.14 and 7 s under 1.11, and tests/robots checks its kernels against
        # MuJoCo and DART)
        fixed_base = [path for path in sorted(MODELS.glob("*.urdf"))
                      if "floating" not in path.name and path.name != "ur5e.urdf"]
        quaternion_tree = [(QUATERNION_TREE, None)] if _SYMPY_AT_LEAST_1_13 else []
        for path, tolerance in ((FORCED_ARM, None), (MOVING_PIVOT, None), *quaternion_tree,
                                (FLOATING_LEG, 1e-12),
                                *((path, 1e-12) for path in fixed_base)):
            model, name = _load(path)
            kin = Kinematics(model)
            recursive = body_recursive_dynamics(model, kin, body_tree(model))
            _assert_equal_to_dense(self, model, kin, name, recursive, tolerance)
            # the residual's Jacobians in closed form (tree_derivatives.py) for the arm alone:
            # the others have wrenches, a frame moving in time, free or ball joints, or the
            # quadruped's short legs, where forward mode is cheaper
            self.assertEqual(recursive.residual_jacobians is not None,
                             path.name == "iiwa14.urdf", name)


class PathChoiceTest(unittest.TestCase):

    def _header(self, options, dynamics="auto") -> str:
        return generate(str(MODELS / "n_link_chain.py"), options,
                        GenerateOptions(dynamics=dynamics)).header

    def test_short_chains_stay_dense_and_long_ones_recurse(self):
        short, long = self._header({"n": "2"}), self._header({"n": "10"})
        for text, header in [("recursive_qddot = false", short),
                             ("// qddot: Mt, Ft + Fi and an LDL^T solve", short),
                             ("recursive_qddot = true", long),
                             ("// qddot: articulated-body recursion", long),
                             ("// inverse_dynamics: recursive Newton-Euler", long)]:
            self.assertTrue(text in header, text)
        self.assertEqual(long.count("static VVector<Scalar> qddot("), 1)
        self.assertEqual(long.count("static VVector<Scalar> inverse_dynamics("), 1)

    def test_the_choice_can_be_forced(self):
        header = self._header({"n": "2"}, dynamics="recursive")
        self.assertTrue("recursive_qddot = true" in header)
        self.assertTrue("recursive_qddot = false"
                        in self._header({"n": "10"}, dynamics="dense"))

    def test_large_trees_loop_their_square_outputs(self):
        # from loop_min_nq coordinates on, Mt, J and the residual Jacobians are loops over
        # products (looped.py), which tests/models/looped_kernels_test.cc checks in C++
        looped = generate(str(MODELS / "n_link_chain.py"), {"n": "6"},
                          GenerateOptions(loop_min_nq=6)).header
        unrolled = generate(str(MODELS / "n_link_chain.py"), {"n": "5"},
                            GenerateOptions(loop_min_nq=6)).header
        self.assertIn("// Mt, J, dr/dq and dr/dv: loops over their columns", looped)
        for product in ("mass_matrix_product(", "jacobian_product(", "residual_derivative_q(",
                        "residual_derivative_v("):
            self.assertRegex(looped, r"static \w+<Scalar> " + re.escape(product))
            self.assertNotIn(product, unrolled)
        self.assertEqual(looped.count("for (int j = 0; j < nq; ++j) {"), 3)
        self.assertIn("--loop-min-nq 6", looped)
        # the dense derivation keeps every output unrolled whatever the size
        dense = generate(str(MODELS / "n_link_chain.py"), {"n": "6"},
                         GenerateOptions(dynamics="dense", loop_min_nq=6)).header
        self.assertNotIn("mass_matrix_product(", dense)

    def test_a_loop_threshold_below_one_is_refused(self):
        result = subprocess.run([sys.executable, str(MODELS.parent / "generate"),
                                 str(MODELS / "pendulum.py"), "--loop-min-nq", "0"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--loop-min-nq must be positive", result.stderr)

    def test_forcing_the_recursion_on_a_model_that_is_no_tree_is_refused(self):
        with self.assertRaises(ModelError) as caught:
            generate(str(MODELS / "falling_cat.py"), options=GenerateOptions(dynamics="recursive"))
        message = str(caught.exception)
        self.assertIn("falling_cat.py", message)
        self.assertIn("neither a tree of particles", message)
        self.assertIn("--dynamics auto or dense", message)


if __name__ == "__main__":
    unittest.main()
