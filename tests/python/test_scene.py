# SPDX-License-Identifier: BSD-3-Clause
"""The scene a viewer draws (gencoord/viewer/scene.py): what each item becomes, the body shapes'
inertia, body points as affine combinations of the point masses, parameter values."""

from __future__ import annotations

import json
import unittest

import sympy as sp

from gencoord.generate.load import load_model
from gencoord.viewer.scene import FORMAT, scene, scene_json

from .support import GENERATED, MODELS


def loaded(name: str):
    model, model_name, _ = load_model(str(MODELS / f"{name}.py"))
    return model, model_name


class SceneTest(unittest.TestCase):
    def test_double_pendulum(self):
        model, name = loaded("double_pendulum")
        drawn = scene(model, name)
        self.assertEqual(drawn["format"], FORMAT)
        self.assertEqual((drawn["dim"], drawn["up"]), (2, [0.0, 1.0]))
        self.assertEqual([p["name"] for p in drawn["particles"]], ["bob1", "bob2"])
        self.assertEqual(drawn["fixed_points"], ["pivot"])
        self.assertEqual(drawn["links"], [
            {"kind": "rod", "name": "pivot-bob1", "a": [["fixed:pivot", 1.0]],
             "b": [["bob1", 1.0]], "length": 1.0},
            {"kind": "rod", "name": "bob1-bob2", "a": [["bob1", 1.0]], "b": [["bob2", 1.0]],
             "length": 1.0}])

    def test_parameter_values_replace_the_defaults(self):
        model, name = loaded("double_pendulum")
        drawn = scene(model, name, {"l1": 2.5, "m2": 8.0})
        self.assertEqual(drawn["links"][0]["length"], 2.5)
        self.assertEqual([p["mass"] for p in drawn["particles"]], [1.0, 8.0])

    def test_a_spring(self):
        model, name = loaded("spring_pendulum")
        (link,) = scene(model, name)["links"]
        self.assertEqual((link["kind"], link["rest_length"]), ("spring", 1.0))

    def test_a_bodys_ellipsoid_has_its_inertia(self):
        """A solid ellipsoid of mass m and semi-axes a_k along orthonormal axes e_k has the
        second moment sum m a_k^2 / 5 e_k e_k^T: the body's (from its inertia tensor), but
        for a semi-axis widened to stay visible (a thin bar's)."""
        for model_name in ("heavy_top", "furuta_pendulum", "rigid_body_euler"):
            model, name = loaded(model_name)
            defaults = {p.symbol: p.default for p in model.parameters}
            for body, drawn in zip(model.bodies, scene(model, name)["bodies"]):
                moment = body.second_moment.subs(defaults)
                axes = [sp.Matrix(axis) for axis in drawn["shape"]["axes"]]
                semi = drawn["shape"]["semi_axes"]
                mass = drawn["mass"]
                for j, axis in enumerate(axes):
                    for k, other in enumerate(axes):
                        self.assertAlmostEqual(float(axis.dot(other)), float(j == k), places=10)
                        along = float((axis.T * moment * other)[0])
                        if j != k:
                            self.assertAlmostEqual(along, 0.0, places=10)
                        elif semi[k] > 0.05 * max(semi) * (1 + 1e-9):
                            self.assertAlmostEqual(along, mass * semi[k] ** 2 / 5, places=10,
                                                   msg=f"{model_name}: {body.name}")
                        else:
                            self.assertLessEqual(along, mass * semi[k] ** 2 / 5 * (1 + 1e-9))
                self.assertEqual(len(drawn["points"]), 4)
                self.assertEqual(len(drawn["offsets"]), 4)

    def test_a_disk_in_2d(self):
        model, name = loaded("compound_pendulum")
        (body,) = scene(model, name)["bodies"]
        inertia = float(model.bodies[0].inertia[0].subs(
            {p.symbol: p.default for p in model.parameters}))
        # a disk's moment of inertia about its centre is m r^2 / 2
        self.assertAlmostEqual(body["mass"] * body["shape"]["radius"] ** 2 / 2, inertia,
                               places=10)
        self.assertEqual(scene(model, name)["pivots"], [{"name": "pivot",
                                                         "position": [0.0, 0.0],
                                                         "body": "bar"}])

    def test_a_rolling_wheel_is_its_disk_on_the_ground(self):
        model, name = loaded("whipple_bicycle")
        drawn = scene(model, name)
        wheels = {body["name"]: body["shape"] for body in drawn["bodies"]
                  if body["shape"]["kind"] == "wheel"}
        self.assertEqual(sorted(wheels), ["front_wheel", "rear_wheel"])
        defaults = {p.name: p.default for p in model.parameters}
        self.assertEqual(wheels["rear_wheel"]["radius"], defaults["r_r"])
        self.assertEqual(wheels["front_wheel"]["radius"], defaults["r_f"])
        for shape in wheels.values():
            self.assertEqual(shape["axle"], [0.0, 1.0, 0.0])
            self.assertEqual(shape["center"], [0.0, 0.0, 0.0])  # the wheels' centres of mass
        self.assertIn({"name": "ground", "particle": None, "normal": [0.0, 0.0, 1.0],
                       "offset": 0.0}, drawn["planes"])
        # the rear frame is no wheel: its inertia ellipsoid
        kinds = {body["name"]: body["shape"]["kind"] for body in drawn["bodies"]}
        self.assertEqual(kinds["rear_frame"], "ellipsoid")
        model, name = loaded("four_bar")
        self.assertEqual(scene(model, name)["planes"], [])  # no wheel, no ground

    def test_a_body_point_is_an_affine_combination_of_the_point_masses(self):
        model, name = loaded("furuta_pendulum")
        drawn = scene(model, name)
        offsets = {p: r for body in drawn["bodies"] for p, r in zip(body["points"],
                                                                    body["offsets"])}
        pins = [link for link in drawn["links"] if link["kind"] == "pin"]
        self.assertEqual([link["name"] for link in pins], ["pivot", "axle"])
        # the pendulum's pivot, at offset (0, 0, L_p / 2) on it
        length = next(p.default for p in model.parameters if p.name == "L_p")
        weights = pins[0]["a"]
        self.assertAlmostEqual(sum(w for _, w in weights), 1.0, places=12)
        point = [sum(w * offsets[p][k] for p, w in weights) for k in range(3)]
        for got, want in zip(point, [0.0, 0.0, length / 2]):
            self.assertAlmostEqual(got, want, places=10)

    def test_up_is_against_gravity(self):
        model, name = loaded("heavy_top")
        self.assertEqual(scene(model, name)["up"], [0.0, 0.0, 1.0])

    def test_the_checked_in_scenes_are_what_generation_writes(self):
        for model_name in ("double_pendulum", "heavy_top"):
            model, name = loaded(model_name)
            text = scene_json(model, name)
            self.assertEqual(text, (GENERATED / f"{name}.scene.json").read_text("utf-8"))
            self.assertEqual(json.loads(text)["name"], model_name)


if __name__ == "__main__":
    unittest.main()
