# SPDX-License-Identifier: BSD-3-Clause
"""Generated files keep within LINE_WIDTH columns, and wrapping changes only whitespace."""

from __future__ import annotations

import re
import tempfile
import unittest
from pathlib import Path

from gencoord.cxx.line_wrap import LINE_WIDTH, wrap_line, wrap_long_lines
from gencoord.generate.stages import generate

from .support import GENERATED

LONG_SUM = "    const Scalar tmp7 = " + " + ".join(f"tmp{k}*(q{k} - v{k})" for k in range(30)) + ";"
NAMES = ("  static constexpr std::array<const char*, nq> names{{"
         + ", ".join(f'"theta{k}"' for k in range(40)) + "}};")


def render_model_of_docstring(docstring: str) -> str:
    """The header of a one-particle model whose file has `docstring`."""
    with tempfile.TemporaryDirectory(prefix="gencoord-docstring-") as scratch:
        path = Path(scratch) / "documented.py"
        path.write_text(f'"""{docstring}"""\n' + PARTICLE, encoding="utf-8")
        return generate(str(path)).header


PARTICLE = """from gencoord import Model
model = Model(dim=2)
x = model.coordinate("x", "position (m)")
model.particle("p", mass=1, position=[x, 0])
"""


def _tokens(text: str) -> str:
    return re.sub(r"\s+", "", text)


class GeneratedWidthTest(unittest.TestCase):
    def test_every_generated_file_is_within_the_width(self):
        files = sorted(p for p in GENERATED.iterdir() if p.is_file())
        self.assertTrue(files)
        for path in files:
            with self.subTest(file=path.name):
                lines = path.read_text(encoding="utf-8").split("\n")
                widest = max(range(len(lines)), key=lambda k: len(lines[k]))
                self.assertLessEqual(len(lines[widest]), LINE_WIDTH,
                                     f"{path.name}:{widest + 1}: {lines[widest]}")


class WrapTest(unittest.TestCase):
    def assert_wrapped(self, line: str) -> list[str]:
        lines = wrap_line(line)
        self.assertGreater(len(lines), 1)
        self.assertLessEqual(max(map(len, lines)), LINE_WIDTH)
        self.assertEqual(_tokens("".join(lines)), _tokens(line))
        return lines

    def test_sum_breaks_before_operators(self):
        lines = self.assert_wrapped(LONG_SUM)
        self.assertTrue(all(line.startswith("        + ") for line in lines[1:]))

    def test_initializer_breaks_after_commas_outside_strings(self):
        lines = self.assert_wrapped(NAMES)
        self.assertTrue(all(line.rstrip().endswith((",", "}};")) for line in lines))

    def test_nested_group_is_broken_inside(self):
        self.assert_wrapped("    result(0) = tmp1*(" + " + ".join(f"tmp{k}" for k in range(40))
                            + ");")

    def test_comment_keeps_its_prefix(self):
        lines = wrap_line("  /// " + " ".join(["word"] * 40))
        self.assertLessEqual(max(map(len, lines)), LINE_WIDTH)
        self.assertTrue(all(line.startswith("  /// word") for line in lines))
        self.assertEqual(sum(line.count("word") for line in lines), 40)

    def test_a_long_docstring_line_stays_in_its_comment(self):
        # a model file's docstring line wider than a header line: wrapped between words,
        # every piece still a " * " line of the /* */ comment
        docstring = "Title.\n\n    " + ", ".join(f"item {k} (kg, m)" for k in range(20)) + "."
        header = render_model_of_docstring(docstring)
        comment = header[header.index("/*\n"):header.index(" */", header.index("/*\n"))]
        lines = comment.splitlines()[1:]
        self.assertTrue(all(line == " *" or line.startswith(" * ") for line in lines), lines)
        self.assertLessEqual(max(map(len, lines)), LINE_WIDTH)
        self.assertTrue(all(line.startswith(" *     ") for line in lines[2:]), lines)
        self.assertEqual(sum(line.count("item") for line in lines), 20)

    def test_banner_command_stays_one_line(self):
        line = "//   regenerate: gencoord generate models/pendulum.py" + " --set a=1" * 12
        self.assertEqual(wrap_line(line), [line])

    def test_strings_and_trailing_comments_are_not_broken(self):
        line = '    x = "a + b, c + d' + " + e" * 40 + '";  // p + q'
        self.assertEqual(wrap_line(line), [line])

    def test_single_token_stays(self):
        line = "    " + "x" * 120 + ";"
        self.assertEqual(wrap_line(line), [line])

    def test_deterministic_and_stable(self):
        text = "\n".join([LONG_SUM, NAMES, "short"])
        once = wrap_long_lines(text)
        self.assertEqual(once, wrap_long_lines(text))
        self.assertEqual(once, wrap_long_lines(once))


if __name__ == "__main__":
    unittest.main()
