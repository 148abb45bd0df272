# SPDX-License-Identifier: BSD-3-Clause
"""Property tests of the URDF reader (Hypothesis): random robot files, from well formed to
broken in any attribute or element, load into a model or are refused with one line that
names the file and a line of it, never with another exception and never with a traceback.

Each file is a well-formed robot of up to four links (inertials, visuals, every joint type
the reader takes, origins, axes, limits, damping and friction, mimic joints), then up to
three mutations: any value replaced by junk (not a number, not finite, out of range, the
wrong count, a name of nothing), an attribute or an element taken out. Few mutations per
file let each one reach the check that must catch it. Run by CTest as `property_tests` with
an interpreter that has Hypothesis (Debian's python3-hypothesis, which `scripts/setup.sh
--property-tests` installs).
"""

from __future__ import annotations

import math
import os
import re
import tempfile
import unittest
import xml.etree.ElementTree as ET

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gencoord import Model, ModelError, load_urdf

JUNK = st.sampled_from(["nan", "inf", "-inf", "1e400", "x", "", "1 2", "-1", "0", "0 0 0",
                        "a b c", "1 2 3 4", "j0", "j9", "base", "nowhere", "revolute",
                        "floating", "planar", "ball"])
FLOATS = st.floats(min_value=-3, max_value=3, allow_nan=False).map(lambda v: f"{v:.3g}")
TRIPLES = st.lists(st.floats(min_value=-1, max_value=1, allow_nan=False), min_size=3,
                   max_size=3).map(lambda v: " ".join(f"{c:.3g}" for c in v))
UNIT = st.sampled_from(["0 0 1", "1 0 0", "0 1 0", "0.6 0.8 0"])
LINKS = ["base", "a", "b", "c", "d", "e"]
ATTRIBUTES = ["name", "type", "link", "value", "xyz", "rpy", "lower", "upper", "effort",
              "velocity", "damping", "friction", "joint", "multiplier", "offset", "ixx", "ixy",
              "size"]
NOT_A_LINE = re.compile(r"\n.")


@st.composite
def inertial(draw) -> ET.Element:
    element = ET.Element("inertial")
    if draw(st.booleans()):
        ET.SubElement(element, "origin", xyz=draw(TRIPLES), rpy=draw(TRIPLES))
    ET.SubElement(element, "mass", value=draw(st.sampled_from(["1.5", "0.2", "3"])))
    moments = draw(st.sampled_from([("0.1", "0.1", "0.1"), ("0.02", "0.03", "0.04")]))
    ET.SubElement(element, "inertia", ixx=moments[0], iyy=moments[1], izz=moments[2],
                  ixy=draw(st.sampled_from(["0", "0.001"])), ixz="0", iyz="0")
    return element


@st.composite
def joint(draw, index: int) -> ET.Element:
    """A well-formed joint joining link index + 1 to an earlier link."""
    kind = draw(st.sampled_from(["revolute", "continuous", "prismatic", "fixed"]))
    element = ET.Element("joint", name=f"j{index}", type=kind)
    ET.SubElement(element, "parent", link=draw(st.sampled_from(LINKS[:index + 1])))
    ET.SubElement(element, "child", link=LINKS[index + 1])
    if draw(st.booleans()):
        ET.SubElement(element, "origin", xyz=draw(TRIPLES), rpy=draw(TRIPLES))
    if kind != "fixed":
        ET.SubElement(element, "axis", xyz=draw(UNIT))
        if draw(st.booleans()):
            ends = sorted(draw(st.lists(st.floats(-3, 3), min_size=2, max_size=2)))
            ET.SubElement(element, "limit", lower=f"{ends[0]:.3g}", upper=f"{ends[1]:.3g}",
                          effort="10", velocity="2")
        if draw(st.booleans()):
            ET.SubElement(element, "dynamics", damping=draw(st.sampled_from(["0", "0.5"])),
                          friction="0.1")
        if index and draw(st.integers(0, 3)) == 0:
            ET.SubElement(element, "mimic", joint=f"j{draw(st.integers(0, index - 1))}",
                          multiplier=draw(FLOATS), offset=draw(FLOATS))
    return element


@st.composite
def robot(draw) -> str:
    """A well-formed robot of one to four links, then up to three mutations of elements that
    have attributes: a value replaced by junk, an attribute or the element taken out."""
    root = ET.Element("robot", name="fuzzed")
    count = draw(st.integers(1, 4))
    for name in LINKS[:count]:
        link = ET.SubElement(root, "link", name=name)
        if name != "base" or draw(st.booleans()):
            link.append(draw(inertial()))
        if draw(st.integers(0, 3)) == 0:
            visual = ET.SubElement(link, "visual")
            ET.SubElement(ET.SubElement(visual, "geometry"), "box", size=draw(TRIPLES))
    for index in range(count - 1):
        root.append(draw(joint(index)))
    for _ in range(draw(st.integers(0, 3))):
        elements = [element for element in root.iter() if element.attrib]
        if not elements:
            break
        victim = draw(st.sampled_from(elements))
        action = draw(st.sampled_from(["junk", "junk", "junk", "drop attribute", "drop"]))
        if action == "junk":
            victim.set(draw(st.sampled_from(sorted(victim.attrib) or ATTRIBUTES)), draw(JUNK))
        elif action == "drop attribute" and victim.attrib:
            del victim.attrib[draw(st.sampled_from(sorted(victim.attrib)))]
        elif victim is not root:
            for parent in root.iter():
                if victim in list(parent):
                    parent.remove(victim)
                    break
    ET.indent(root)
    return ET.tostring(root, encoding="unicode")


class UrdfFuzzTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory(prefix="gencoord-urdf-fuzz-")
        cls.path = os.path.join(cls.folder.name, "fuzzed.urdf")

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    @settings(max_examples=1500, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow])
    @given(robot())
    def test_a_file_loads_or_is_refused_in_one_line_naming_it(self, text: str):
        with open(self.path, "w", encoding="utf-8") as handle:
            handle.write(text)
        try:
            model = Model(dim=3)
            load_urdf(model, self.path)
        except ModelError as error:
            message = str(error)
            self.assertTrue(message.startswith(self.path + ":"), message)
            self.assertIsNone(NOT_A_LINE.search(message.rstrip("\n")), message)
            self.assertNotIn("Traceback", message)
            self.assertNotIn("internal error", message)
            return
        # loaded: every coordinate starts at a finite value, every limit is ordered
        self.assertTrue(all(math.isfinite(c.initial) for c in model.coordinates), text)
        self.assertTrue(all(limit.lower <= limit.upper for limit in model.limits), text)


if __name__ == "__main__":
    unittest.main()
