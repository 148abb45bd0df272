# SPDX-License-Identifier: BSD-3-Clause
"""GenerateOptions (gencoord/options.py): one frozen, documented set of knobs that the
command line, the docs and the stages share."""

from __future__ import annotations

import dataclasses
import unittest
from pathlib import Path

from gencoord.generate import cli
from gencoord.options import GenerateOptions, knobs, markdown_table

REPOSITORY = Path(__file__).resolve().parents[2]


class GenerateOptionsTest(unittest.TestCase):

    def test_frozen_and_every_field_documented(self):
        options = GenerateOptions()
        with self.assertRaises(dataclasses.FrozenInstanceError):
            options.loop_min_nq = 3
        for knob in knobs():
            self.assertGreater(len(knob.metadata["help"]), 20, knob.name)

    def test_bad_values_are_refused_with_the_field_named(self):
        for field, value in (("max_part_statements", -1), ("loop_min_nq", 0),
                             ("translation_units", -2), ("load_timeout", -1.0),
                             ("load_timeout", float("nan")), ("load_timeout", float("inf")),
                             ("dynamics", "fast")):
            with self.assertRaisesRegex(ValueError, field.split("_")[0]):
                GenerateOptions(**{field: value})

    def test_the_command_line_sets_every_flagged_field(self):
        parser = cli.build_parser()
        args = parser.parse_args(["model.py", "--max-function-statements", "300",
                                  "--loop-min-nq", "7", "--translation-units", "2",
                                  "--name", "arm", "--dynamics", "dense",
                                  "--load-timeout", "0"])
        self.assertEqual(cli.options_of(args, parser), GenerateOptions(
            max_part_statements=300, loop_min_nq=7, translation_units=2, name="arm",
            dynamics="dense", load_timeout=None))
        flags = {option for action in parser._actions for option in action.option_strings}
        self.assertLessEqual({k.metadata["flag"] for k in knobs() if k.metadata["flag"]}, flags)
        defaults = parser.parse_args(["model.py"])
        self.assertEqual(cli.options_of(defaults, parser), GenerateOptions())

    def test_banner_flags_repeat_what_differs_from_the_defaults(self):
        self.assertEqual(GenerateOptions().banner_flags(), [])
        flags = GenerateOptions(max_part_statements=300, loop_min_nq=7, translation_units=2,
                                name="arm one", dynamics="dense").banner_flags()
        self.assertEqual(flags, ["--max-function-statements 300", "--loop-min-nq 7",
                                 "--translation-units 2", "--name 'arm one'",
                                 "--dynamics dense"])

    def test_part_statements_default_by_tree_size(self):
        options = GenerateOptions()
        self.assertEqual(options.part_statements_for(False), options.part_statements)
        self.assertEqual(options.part_statements_for(True), options.large_tree_part_statements)
        self.assertEqual(GenerateOptions(max_part_statements=0).part_statements_for(True), 0)

    def test_the_docs_table_is_the_code_s(self):
        docs = (REPOSITORY / "docs" / "generator.md").read_text(encoding="utf-8")
        start = docs.index("<!-- GenerateOptions table")
        start = docs.index("\n", start) + 1
        end = docs.index("<!-- end of the GenerateOptions table -->")
        self.assertEqual(docs[start:end], markdown_table(),
                         "regenerate it with: PYTHONPATH=python python3 -m gencoord.options")


if __name__ == "__main__":
    unittest.main()
