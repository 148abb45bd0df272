# SPDX-License-Identifier: BSD-3-Clause
"""Property tests of the sweep-file reader (Hypothesis): a good sweep file of the double
pendulum with up to three mutations (a value replaced by junk: a string, a number too large,
too small or not finite, a negative or fractional count, an array, a table, an expression; or
a key taken out) is read, its names checked and its first samples drawn, or it is refused
with one line that names the file, never with another exception. A sample is a finite
number. Run by CTest as `property_tests` (see test_urdf_fuzz.py).
"""

from __future__ import annotations

import itertools
import math
import os
import tempfile
import unittest

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gencoord.sweep import samples, spec
from gencoord.sweep.source import SweepFileError, read_source

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL = os.path.join(REPOSITORY, "models", "double_pendulum.py")
COORDINATES = ["theta1", "theta2"]
PARAMETERS = ["l1", "l2", "m1", "m2", "g"]


def good() -> dict:
    """A good sweep file, as TOML data."""
    return {
        "model": {"file": MODEL, "parameters": {"g": 9.81}},
        "integration": {"integrator": "rk4", "dt": 0.01, "t_end": 2.0},
        "event": {"when": "abs(theta1) > pi or abs(theta2) > pi"},
        "samples": {"method": "grid", "chunk": 4,
                    "q": {"theta1": {"from": "-pi", "to": "pi", "points": 3},
                          "theta2": {"values": [0.0, 0.5]}},
                    "v": {"theta1": {"from": 0.0, "to": 1.0, "points": 2}}},
        "record": {"trajectory_every": 50},
    }


JUNK = st.one_of(
    st.sampled_from(["", "x", "pi/0", "1e999", "-pi", "2**2000", "theta1", "rk5", "grid",
                     "monte_carlo", "latin_hypercube", "abs(theta1) >", "sqrt(-1)",
                     "1" * 400, "(" * 200 + "1" + ")" * 200]),
    st.sampled_from([0, -1, 1, 2**63, 2**64 + 1, 10**12, 0.5, -0.0, 1e-300, 1e308,
                     math.inf, -math.inf, math.nan, True, [], [1, "a"], {}, {"from": 0}]),
    st.integers(), st.floats())


def toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(item) for item in value) + "]"
    return "{ " + ", ".join(f"{key} = {toml_value(item)}" for key, item in value.items()) + " }"


def toml(data: dict) -> str:
    """The data as TOML: top-level tables as [sections], values inside them inline."""
    # keys that are no table come before the first [section], or they would join it
    lines = [f"{key} = {toml_value(value)}" for key, value in data.items()
             if not isinstance(value, dict)]
    for section, table in data.items():
        if isinstance(table, dict):
            lines.append(f"[{section}]")
            lines += [f"{key} = {toml_value(value)}" for key, value in table.items()]
    return "\n".join(lines) + "\n"


def paths(data, prefix=()):
    """Every key path of the nested tables."""
    for key, value in data.items():
        yield prefix + (key,)
        if isinstance(value, dict):
            yield from paths(value, prefix + (key,))


@st.composite
def sweep_file(draw) -> str:
    data = good()
    if draw(st.booleans()):
        data["samples"] = {"method": draw(st.sampled_from(["monte_carlo", "latin_hypercube"])),
                           "count": 10, "seed": 7, "chunk": 4,
                           "q": {"theta1": {"from": -1.0, "to": 1.0}}}
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(sorted(paths(data))))
        parent = data
        for key in path[:-1]:
            parent = parent[key]
        if draw(st.integers(0, 4)) == 0:
            del parent[path[-1]]
        else:
            parent[path[-1]] = draw(JUNK)
    return toml(data)


class SweepFuzzTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory(prefix="gencoord-sweep-fuzz-")
        cls.path = os.path.join(cls.folder.name, "sweep.toml")

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    @settings(max_examples=1000, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow])
    @given(sweep_file())
    def test_a_file_is_read_or_refused_in_one_line_naming_it(self, text: str):
        with open(self.path, "w", encoding="utf-8") as handle:
            handle.write(text)
        try:
            sweep = spec.check_names(spec.parse(read_source(self.path)), COORDINATES,
                                     PARAMETERS)
            drawn = list(itertools.islice(samples.rows(sweep), 50))
        except SweepFileError as error:
            message = str(error)
            self.assertTrue(message.startswith(self.path), message)
            self.assertNotIn("\n", message.rstrip("\n"))
            self.assertNotIn("internal error", message)
            return
        self.assertTrue(drawn, text)
        self.assertTrue(all(math.isfinite(value) for row in drawn for value in row), text)


if __name__ == "__main__":
    unittest.main()
