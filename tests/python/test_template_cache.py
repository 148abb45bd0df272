# SPDX-License-Identifier: BSD-3-Clause
"""The cache of compiled Jinja2 templates (gencoord/cxx/render.py): a damaged or unwritable entry
only means compiling again, and a change of Jinja2 or of our environment options is a
different entry, never the old compiled code."""

from __future__ import annotations

import shutil
import tempfile
import unittest
from pathlib import Path
from unittest import mock

import jinja2

from gencoord.cxx import render as emit


class TemplateCacheTest(unittest.TestCase):

    def setUp(self):
        self.scratch = Path(tempfile.mkdtemp(prefix="gencoord-jinja-"))
        self.templates = self.scratch / "templates"
        self.templates.mkdir()
        (self.templates / "t.j2").write_text("{% for x in xs %}[{{ x }}]{% endfor %}\n",
                                             encoding="utf-8")
        self.cache_dir = self.scratch / "cache"
        self.cache_dir.mkdir()

    def tearDown(self):
        shutil.rmtree(self.scratch)

    def render(self, cache_dir: Path) -> str:
        environment = jinja2.Environment(
            loader=jinja2.FileSystemLoader(str(self.templates)),
            bytecode_cache=emit._TemplateCache(str(cache_dir)), **emit._ENVIRONMENT_OPTIONS)
        return environment.get_template("t.j2").render(xs=[1, 2])

    def test_entries_are_written_then_reused(self):
        self.assertEqual(self.render(self.cache_dir), "[1][2]")
        entries = list(self.cache_dir.iterdir())
        self.assertEqual(len(entries), 1, entries)
        self.assertFalse(entries[0].name.endswith(".tmp"))
        self.assertEqual(self.render(self.cache_dir), "[1][2]")

    def test_a_truncated_entry_is_compiled_again(self):
        self.render(self.cache_dir)
        for entry in self.cache_dir.iterdir():
            content = entry.read_bytes()
            entry.write_bytes(content[:len(content) // 2])
        self.assertEqual(self.render(self.cache_dir), "[1][2]")

    def test_an_unwritable_cache_is_no_error(self):
        gone = self.scratch / "removed"
        self.assertEqual(self.render(gone), "[1][2]")
        self.assertFalse(gone.exists())

    @mock.patch.object(emit, "JINJA2_CACHE_IS_SAFE", True)
    def test_the_key_follows_jinja2_and_our_options(self):
        pattern = emit._bytecode_cache().pattern
        self.assertEqual(pattern, emit._bytecode_cache().pattern)
        with mock.patch.dict(emit._ENVIRONMENT_OPTIONS, trim_blocks=False):
            self.assertNotEqual(pattern, emit._bytecode_cache().pattern)
        with mock.patch.object(jinja2, "__version__", "0.0.1"):
            self.assertNotEqual(pattern, emit._bytecode_cache().pattern)

    @mock.patch.object(emit, "JINJA2_CACHE_IS_SAFE", False)
    def test_no_cache_where_jinja2_cannot_share_it(self):
        self.assertIsNone(emit._bytecode_cache())


if __name__ == "__main__":
    unittest.main()
