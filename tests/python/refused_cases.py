# SPDX-License-Identifier: BSD-3-Clause
"""Model files the generator must refuse, each with the key words its error must contain.

A case is (model source, key words); `# <- error` marks the line the message must name (a
case without a mark must name the file). Sources are dedented and start from PREAMBLE
unless they import the generator themselves.
"""

from __future__ import annotations

from .support import BOB, MARK

PREAMBLE = """\
import sympy
from gencoord import Model, cos, sin, sqrt, tan
model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)")
"""


def _position(x: str, before: str = "") -> str:
    """A model whose bob's x-coordinate is `x` (the marked line)."""
    return (PREAMBLE + before + f'bob = model.particle("bob", mass=1, position=[{x}, '
            f"-cos(theta)])  {MARK}\n")


def _parameter(name: str, default: str = "1.0") -> str:
    """A model with one parameter `name` (the marked line) scaling the bob's position."""
    return (PREAMBLE + f'k = model.parameter("{name}", {default}, "a length (m)")  {MARK}\n'
            'bob = model.particle("bob", mass=1, position=[k * sin(theta), -k * cos(theta)])\n')


# --- the model file ends early or cannot be read --------------------------------------------
EXITS = {
    "sys_exit_0": (PREAMBLE + BOB + f"import sys\nsys.exit(0)  {MARK}\n", ["exited"]),
    "raise_system_exit": (PREAMBLE + BOB + f"raise SystemExit  {MARK}\n", ["exited"]),
    "exit_with_message": (PREAMBLE + BOB + f'raise SystemExit("done")  {MARK}\n',
                          ["exited", "done"]),
    "os_exit_0": (PREAMBLE + BOB + f"import os\ntry:\n    os._exit(0)  {MARK}\n"
                  "except Exception:\n    pass\n", ["called os._exit(0)"]),
}

# --- names: keywords, library macros, what the generated code declares -----------------------
RESERVED = ["double", "M_PI", "M_E", "INFINITY", "NAN", "HUGE_VAL", "errno", "EDOM", "ERANGE",
            "EOF", "NULL", "BUFSIZ", "stdout", "assert", "offsetof", "linux", "unix",
            "INT_MAX", "DBL_EPSILON", "RAND_MAX", "EIGEN_NAME", "GENCOORD_NAME", "find", "key",
            "QMatrix", "QVector", "XJacobian", "Params", "Maximal", "coordinate_names",
            "parameter_names", "num_parameters", "initial_q", "nq", "qddot", "solve", "result",
            "Mt", "carried", "params", "tmp3", "Parts0", "sin", "std"]
NAMES = {f"parameter_{name}": (_parameter(name), [f"parameter '{name}'", name])
         for name in RESERVED}
NAMES.update({
    "coordinate_M_PI": (PREAMBLE.replace('"theta"', '"M_PI"').replace("theta = ", "M = ")
                        .replace('(rad)")', f'(rad)")  {MARK}') + BOB.replace("theta", "M"),
                        ["coordinate 'M_PI'", "macro"]),
    "particle_EOF": (PREAMBLE + BOB.replace('"bob"', '"EOF"').rstrip() + f"  {MARK}\n",
                     ["particle 'EOF'", "macro"]),
})

# --- numbers that are not finite, and the values derived from them ----------------------------
NON_FINITE = {
    "mass_oo": (PREAMBLE + 'bob = model.particle("bob", mass=sympy.oo, position=[sin(theta), '
                f"-cos(theta)])  {MARK}\n", ["particle 'bob' mass", "oo", "finite"]),
    "mass_nan": (PREAMBLE + 'bob = model.particle("bob", mass=sympy.nan, position=[sin(theta), '
                 f"-cos(theta)])  {MARK}\n", ["particle 'bob' mass", "nan", "finite"]),
    "mass_float_inf": (PREAMBLE + 'bob = model.particle("bob", mass=float("inf"), '
                       f"position=[sin(theta), -cos(theta)])  {MARK}\n", ["mass", "oo"]),
    "mass_infinite_at_the_defaults": (
        PREAMBLE + 'k = model.parameter("k", 0.0, "a stiffness")\n'
        'bob = model.particle("bob", mass=1 / k, position=[sin(theta), -cos(theta)])  '
        f"{MARK}\n", ["particle 'bob'", "mass", "positive"]),
    "position_nan": (_position("sympy.nan * sin(theta)"), ["position", "nan"]),
    "position_oo": (_position("sympy.oo * sin(theta)"), ["position", "oo"]),
    "position_zoo": (_position("sympy.zoo + sin(theta)"), ["position", "zoo"]),
    "position_division_by_zero": (_position("sin(theta) / sympy.Integer(0)"),
                                  ["position", "zoo"]),
    "default_nan": (_parameter("k", 'float("nan")'), ["parameter 'k'", "nan", "finite"]),
    "default_inf": (_parameter("k", 'float("inf")'), ["parameter 'k'", "inf", "finite"]),
    "default_minus_inf": (_parameter("k", '-1e400'), ["parameter 'k'", "inf", "finite"]),
    "initial_nan": (PREAMBLE.replace('(rad)")', '(rad)", initial=float("nan"))  ' + MARK)
                    + BOB, ["coordinate 'theta'", "finite"]),
    "initial_rate_inf": (PREAMBLE.replace('(rad)")', '(rad)", initial_rate=1e999)  ' + MARK)
                         + BOB, ["coordinate 'theta'", "finite"]),
    "gravity_inf": (PREAMBLE + BOB + f"model.gravity([0, -sympy.oo])  {MARK}\n",
                    ["gravity", "oo"]),
}

# --- expressions that are not smooth functions of q, v and t, or not closed forms --------------
NOT_SMOOTH = {
    "sign": (_position("sympy.sign(theta)"), ["position", "sign", "smooth"]),
    "piecewise": (_position("sympy.Piecewise((theta, theta > 0), (0, True))"),
                  ["position", "Piecewise", "smooth"]),
    "floor": (_position("sympy.floor(theta)"), ["position", "floor", "smooth"]),
    "ceiling": (_position("sympy.ceiling(theta)"), ["position", "ceiling", "smooth"]),
    "heaviside": (_position("sympy.Heaviside(theta)"), ["position", "Heaviside", "smooth"]),
    "abs": (_position("sympy.Abs(theta)"), ["position", "Abs", "smooth"]),
    "max": (_position("sympy.Max(theta, 0)"), ["position", "Max", "smooth"]),
    "abs_of_time": (_position("sin(theta) * sympy.Abs(model.t)"), ["Abs", "t", "smooth"]),
    "imaginary_unit": (_position("sympy.I * sin(theta)"), ["position", "imaginary unit I"]),
    "python_complex": (_position("1j * sin(theta)"), ["position", "imaginary unit I"]),
    "sqrt_of_negative": (_position("sympy.sqrt(-2) * sin(theta)"), ["imaginary unit I"]),
    "mod": (_position("sympy.Mod(theta, 1)"), ["position", "Mod", "smooth"]),
    "derivative": (_position("sympy.Derivative(sin(theta), theta)"),
                   ["position", "unevaluated Derivative", "doit"]),
    "integral": (_position("sympy.Integral(sin(theta), theta)"),
                 ["position", "unevaluated Integral", "doit"]),
    "undefined_function": (_position("sympy.Function('f')(theta)"),
                           ["position", "f(theta)", "cannot evaluate"]),
    "coulomb_friction": (PREAMBLE + BOB + "model.generalized_force(theta, "
                         f"-sympy.sign(model.rate(theta)))  {MARK}\n",
                         ["generalized force", "sign", "theta_dot", "smooth"]),
    "velocity_in_a_position": (_position("model.rate(theta)"),
                               ["position", "may not depend on velocities", "theta_dot",
                                "model.rate(theta)"]),
    "spring_of_rest_length_zero": (
        PREAMBLE + BOB + 'pivot = model.fixed_point("pivot", [0, 0])\n'
        f"model.spring(pivot, bob, 10, 0)  {MARK}\n", ["spring 'pivot-bob'", "rest length", "0",
                                                       "positive"]),
    "spring_of_negative_rest_length": (
        PREAMBLE + BOB + 'L = model.parameter("L", -1.0, "rest length (m)")\n'
        'pivot = model.fixed_point("pivot", [0, 0])\n'
        f"model.spring(pivot, bob, 10, L)  {MARK}\n", ["spring 'pivot-bob'", "L = -1",
                                                       "positive"]),
}

# --- rigid bodies that no mass distribution has, and torques on what is not a body -----------
BODY_PREAMBLE = """\
from gencoord import Frame, Matrix, Model, rotation_z
model = Model(dim=3)
phi = model.coordinate("phi", "angle about the vertical (rad)")
"""


def _body(name: str, inertia: str, mass: str = "1", before: str = "") -> str:
    """A model of one body `name` (the marked line) turning about the vertical."""
    return (BODY_PREAMBLE + before + f'{name} = model.body("{name}", mass={mass}, '
            f"inertia={inertia}, frame=Frame(rotation_z(phi), [1, 0, 0]))  {MARK}\n")


def _torque_on(target: str, before: str) -> str:
    return BODY_PREAMBLE + before + f"model.torque({target}, [0, 0, 1])  {MARK}\n"


BODIES = {
    "inertia_not_positive_definite": (_body("slab", "Matrix.diag(1, 2, -3)"),
                                      ["body 'slab'", "principal moments -3, 1, 2",
                                       "positive definite"]),
    "inertia_zero": (_body("dot", "Matrix.zeros(3, 3)"), ["body 'dot'", "not all positive"]),
    "inertia_breaks_the_triangle_inequality": (
        _body("needle", "Matrix.diag(1, 1, 3)"),
        ["body 'needle'", "1, 1, 3", "not less than the sum of the other two"]),
    "inertia_of_a_body_without_thickness": (_body("sheet", "Matrix.diag(1, 1, 2)"),
                                            ["body 'sheet'", "1, 1, 2", "thickness"]),
    "default_parameters_break_the_triangle_inequality": (
        _body("disc", "Matrix.diag(1, 1, C)",
              before='C = model.parameter("C", 3.0, "axial moment of inertia (kg m^2)")\n'),
        ["body 'disc'", "1, 1, 3", "not less than", "with the default parameters"]),
    "inertia_not_symmetric": (_body("plate", "Matrix([[1, 0.1, 0], [0, 1, 0], [0, 0, 1]])"),
                              ["body 'plate'", "not symmetric", "I[i, j] = I[j, i]"]),
    "inertia_of_the_wrong_shape": (_body("lump", "Matrix.diag(1, 1)"),
                                   ["body 'lump'", "2x2", "3x3"]),
    "mass_that_depends_on_q": (_body("lump", "Matrix.diag(1, 1, 1)", mass="1 + phi**2"),
                               ["body 'lump'", "mass depends on phi", "constants or parameters"]),
    "mass_that_depends_on_t": (_body("lump", "Matrix.diag(1, 1, 1)", mass="1 + model.t"),
                               ["body 'lump'", "mass depends on t"]),
    "inertia_that_depends_on_q": (_body("lump", "Matrix.diag(1, 1, 1 + phi**2)"),
                                  ["body 'lump'", "inertia depends on phi"]),
    "mass_negative": (_body("lump", "Matrix.diag(1, 1, 1)", mass="-2"),
                      ["body 'lump'", "mass is -2", "positive"]),
    "mass_negative_at_the_defaults": (
        _body("lump", "Matrix.diag(1, 1, 1)", mass="m",
              before='m = model.parameter("m", -1.0, "mass (kg)")\n'),
        ["body 'lump'", "mass is -1", "positive", "with the default parameters"]),
    "planar_inertia_negative": (
        'from gencoord import Frame, Model\nmodel = Model(dim=2)\n'
        'theta = model.coordinate("theta", "angle from the downward vertical (rad)")\n'
        f'bar = model.body("bar", mass=1, inertia=-0.5, frame=Frame(theta, [0, -1]))  {MARK}\n',
        ["body 'bar'", "inertia is -0.5", "positive"]),
    "frame_scaled_rotation": (
        BODY_PREAMBLE.replace("rotation_z\n", "rotation_x, rotation_z\n")
        + 'top = model.body("top", mass=1, inertia=Matrix.diag(1, 1, 1.5), '
        f"frame=Frame(2 * rotation_z(phi) * rotation_x(0.3), [1, 0, 0]))  {MARK}\n",
        ["body 'top'", "rotation is not orthonormal", "rotation_x/y/z"]),
    "frame_reflection": (_body("mirror", "Matrix.diag(1, 1, 1.5)").replace(
        "Frame(rotation_z(phi), ", "Frame(Matrix.diag(1, 1, -1) * rotation_z(phi), "),
        ["body 'mirror'", "a reflection", "det R = -1"]),
    "planar_frame_sheared": (
        'from gencoord import Frame, Matrix, Model\nmodel = Model(dim=2)\n'
        'theta = model.coordinate("theta", "angle from the downward vertical (rad)")\n'
        'bar = model.body("bar", mass=1, inertia=0.5, '
        f"frame=Frame(Matrix([[1, theta], [0, 1]]), [0, -1]))  {MARK}\n",
        ["body 'bar'", "not orthonormal"]),
    "torque_on_a_particle": (
        _torque_on("bob", 'bob = model.particle("bob", mass=1, position=[1, phi, 0])\n'),
        ["torque 'on bob'", "not on particle 'bob'", "model.force()"]),
    "torque_on_a_body_point": (
        _torque_on("knob", 'lump = model.body("lump", mass=1, inertia=Matrix.diag(1, 1, 1), '
                   "frame=Frame(rotation_z(phi), [1, 0, 0]))\n"
                   'knob = lump.point([0, 0, 1], name="knob")\n'),
        ["torque 'on knob'", "not on point 'knob'"]),
    "torque_on_a_name": (
        _torque_on('"lump"', 'lump = model.body("lump", mass=1, inertia=Matrix.diag(1, 1, 1), '
                   "frame=Frame(rotation_z(phi), [1, 0, 0]))\n"),
        ["torque 'on lump'", "acts on a body", "not on 'lump'"]),
}

# --- declarations that make no sense, and descriptions that cannot be printed -----------------
DECLARATIONS = {
    "gravity_as_a_word": (PREAMBLE + BOB + f'model.gravity("down")  {MARK}\n',
                          ["gravity", "'down', not a vector", "a list of 2"]),
    "spring_to_itself": (PREAMBLE + BOB + f"model.spring(bob, bob, 10, 1)  {MARK}\n",
                         ["spring 'bob-bob'", "to itself"]),
    "damper_to_itself": (PREAMBLE + BOB + f"model.damper(bob, bob, 0.5)  {MARK}\n",
                         ["to itself"]),
    "description_with_a_line_break": (
        PREAMBLE + f'phi = model.coordinate("phi", "first line\\nsecond")  {MARK}\n'
        + BOB.replace("theta", "theta + phi"), ["coordinate 'phi'", "line break"]),
    "description_ending_in_a_backslash": (
        PREAMBLE + f'phi = model.coordinate("phi", "an angle \\\\")  {MARK}\n'
        + BOB.replace("theta", "theta + phi"), ["coordinate 'phi'", "backslash"]),
    "description_not_text": (
        PREAMBLE + f'k = model.parameter("k", 1.0, 3.5)  {MARK}\n' + BOB.replace(
            "mass=1", "mass=k"), ["parameter 'k'", "description is 3.5, not text"]),
    "model_description_not_text": (
        PREAMBLE.replace("model = Model(dim=2)", f"model = Model(dim=2, description=42)  {MARK}")
        + BOB, ["Model", "description is 42, not text"]),
    # found by tests/properties/test_model_fuzz.py: each was an internal error, a SymPy
    # warning of many lines, or a message that quoted an object's repr over many lines
    "a_name_that_is_not_text": (_position("sin(theta)").replace('"bob"', "{}"),
                                ["particle", "the name is {}, not text"]),
    "a_point_where_a_number_goes": (PREAMBLE + BOB + f"model.gravity([0, bob])  {MARK}\n",
                                    ["gravity[1]", "particle 'bob', not a number"]),
    "a_coordinate_where_a_point_goes": (PREAMBLE + BOB + f"model.damper(bob, theta, 1)  {MARK}\n",
                                        ["damper", "acts on points", "not theta"]),
    "sin_of_a_point": (_position("sin(bob0)", 'bob0 = model.fixed_point("o", [0, 0])\n'),
                       ["fixed point 'o'", "not a number or an expression"]),
    "sin_of_the_model": (_position("sin(model)"), ["the model is not a number"]),
    "cos_of_infinity": (_position("sin(theta) + cos(1e400)"),
                        ["position[0]", "AccumBounds", "infinite number"]),
    "none_in_a_position": (_position("None"), ["position[0]", "is None"]),
    "text_in_a_position": (_position("'x'"), ["position[0]", "the text 'x'"]),
}

# --- accepted: each must generate, and its header compile (test_name_clashes.py) -------------
# names next to reserved ones, and functions that are smooth where they are defined
ACCEPTED = {
    "near_names": PREAMBLE + "".join(
        f'{name} = model.parameter("{name}", 1.0, "a length (m)")\n'
        for name in ("finds", "key2", "Qmatrix", "QVectors", "M_PI2", "Infinity", "nan",
                     "inf", "errno2", "linux2", "EOF2", "Null", "asserted", "results",
                     "tmp", "tmp_1", "Parts_a", "params2", "I", "E", "pi", "y0", "j1",
                     "gamma", "isnan", "Scalars", "nq2", "Maximal2", "names", "data"))
    + 'bob = model.particle("bob", mass=finds * key2, position=[Qmatrix * sin(theta) + '
      "QVectors + M_PI2 + Infinity + nan + inf + errno2 + linux2 + EOF2 + Null + asserted "
      "+ results + tmp + tmp_1 + Parts_a + params2 + I + E + pi + y0 + j1 + gamma + isnan + "
      "Scalars + nq2 + Maximal2 + names + data, -cos(theta)])\n",
    "abs_of_a_parameter": PREAMBLE + 'k = model.parameter("k", -2.0, "a signed length (m)")\n'
                                     'bob = model.particle("bob", mass=1, position=['
                                     "sympy.Abs(k) * sin(theta), -cos(theta)])\n",
    "sqrt_domain": _position("sqrt(1 - theta**2)").replace(f"  {MARK}", ""),
    "pole": _position("1 / theta").replace(f"  {MARK}", ""),
    "tangent": _position("tan(theta)").replace(f"  {MARK}", ""),
    "huge_power": _position("sin(theta)**100000").replace(f"  {MARK}", ""),
}
