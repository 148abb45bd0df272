# SPDX-License-Identifier: BSD-3-Clause
"""generate --cache: a generation found in the cache writes exactly what generating would, and
any change to what the key covers (the model file, a --depends file, an argument) generates
again; a damaged entry counts as missing; the folder keeps to its size limit."""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from gencoord.generate import cli
from gencoord.generate.output_cache import OutputCache, cache_key

from .support import MODELS, describe, run_generate

FROM_CACHE = "from the cache"


class GenerationCacheTest(unittest.TestCase):
    def setUp(self):
        folder = tempfile.TemporaryDirectory()
        self.addCleanup(folder.cleanup)
        self.folder = Path(folder.name)
        self.model = self.folder / "swing.py"
        shutil.copy(MODELS / "pendulum.py", self.model)
        self.data = self.folder / "data.txt"
        self.data.write_text("first\n")
        self.cache = self.folder / "cache"

    def generate(self, *extra: str, output: str = "out") -> str:
        result = run_generate(self.model, "-o", output, "--cache", self.cache, "--depends",
                              self.data, *extra, cwd=self.folder)
        self.assertEqual(result.returncode, 0, describe(result))
        return result.stdout

    def header(self, output: str = "out") -> bytes:
        return (self.folder / output / "swing.hpp").read_bytes()

    def test_a_cached_generation_writes_what_generating_writes(self):
        self.assertNotIn(FROM_CACHE, self.generate())
        first = self.header()
        shutil.rmtree(self.folder / "out")
        output = self.generate()
        self.assertIn(FROM_CACHE, output)
        self.assertIn("Singular configurations", output)  # the analysis is shown again
        self.assertEqual(self.header(), first)
        self.assertTrue((self.folder / "out" / "swing.scene.json").is_file())
        uncached = run_generate(self.model, "-o", "out", cwd=self.folder)
        self.assertEqual(uncached.returncode, 0, describe(uncached))
        self.assertEqual(self.header(), first)

    def test_what_the_key_covers_generates_again(self):
        self.generate()
        self.data.write_text("second\n")
        self.assertNotIn(FROM_CACHE, self.generate())
        self.assertNotIn(FROM_CACHE, self.generate("--max-function-statements", "50"))
        self.assertNotIn(FROM_CACHE, self.generate(output="elsewhere"))  # the banner's -o
        self.model.write_text(self.model.read_text().replace('"l", 1.0', '"l", 2.5'))
        self.assertNotIn(FROM_CACHE, self.generate())
        self.assertIn(b"2.5", self.header())
        self.assertIn(FROM_CACHE, self.generate())

    def test_a_damaged_entry_is_generated_again(self):
        self.generate()
        entries = list(self.cache.rglob("*.json"))
        self.assertEqual(len(entries), 1)
        entries[0].write_text('{"name": "sw')  # cut short
        self.assertNotIn(FROM_CACHE, self.generate())
        self.assertIn(FROM_CACHE, self.generate())

    def test_a_missing_dependency_is_a_one_line_error(self):
        result = run_generate(self.model, "--cache", self.cache, "--depends", "absent.urdf",
                              cwd=self.folder)
        self.assertEqual(result.returncode, 1, describe(result))
        self.assertEqual(result.stderr.strip().splitlines(),
                         ["absent.urdf: error: --depends names no readable file; name the "
                          "files the model file reads"])
        self.assertFalse((self.folder / "generated").exists())


class WarningReplayTest(unittest.TestCase):
    def test_a_generation_from_the_cache_repeats_its_warnings(self):
        class Generated:
            name, header, scene, sources, analysis = "m", "// m", "{}", {}, ["a line"]

        def fake_generate(*args, on_warning, **kwargs):
            on_warning("this takes minutes")
            return Generated()

        with tempfile.TemporaryDirectory() as folder:
            model = os.path.join(folder, "m.py")
            Path(model).write_text("# a model\n")
            argv = [model, "-o", os.path.join(folder, "out"), "--cache",
                    os.path.join(folder, "cache")]
            errors = []
            for _ in range(2):
                stderr = io.StringIO()
                with mock.patch("gencoord.generate.stages.generate", fake_generate), \
                        contextlib.redirect_stdout(io.StringIO()), \
                        contextlib.redirect_stderr(stderr):
                    self.assertEqual(cli.main(argv), 0)
                errors.append(stderr.getvalue())
            self.assertEqual(errors[0], errors[1])
            self.assertIn("warning: this takes minutes", errors[1])


class OutputCacheTest(unittest.TestCase):
    def test_the_key_depends_on_every_file_and_value(self):
        with tempfile.TemporaryDirectory() as folder:
            a, b = os.path.join(folder, "a"), os.path.join(folder, "b")
            Path(a).write_text("x")
            Path(b).write_text("y")
            keys = {cache_key("k", [a], ["1"]), cache_key("k", [a, b], ["1"]),
                    cache_key("k", [b, a], ["1"]), cache_key("k", [a], ["2"]),
                    cache_key("other", [a], ["1"]), cache_key("k", [a], ["1", ""])}
            self.assertEqual(len(keys), 6)
            self.assertEqual(cache_key("k", [a], ["1"]), cache_key("k", [a], ["1"]))

    def test_the_least_recently_used_entries_go_past_the_limit(self):
        with tempfile.TemporaryDirectory() as folder:
            entry = {"text": "x" * 1000}
            size = len(json.dumps(entry))
            cache = OutputCache(folder, size_limit=2 * size)
            for number, key in enumerate(["aa1", "bb2"]):
                cache.store(key, entry)
                os.utime(cache._path(key), (1000 + number, 1000 + number))
            self.assertEqual(cache.load("aa1"), entry)  # now the most recently used
            cache.store("cc3", entry)
            self.assertIsNone(cache.load("bb2"))
            self.assertEqual(cache.load("aa1"), entry)
            self.assertEqual(cache.load("cc3"), entry)


if __name__ == "__main__":
    unittest.main()
