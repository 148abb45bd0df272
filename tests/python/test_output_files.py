# SPDX-License-Identifier: BSD-3-Clause
"""generate writes its files all or none: a write that fails (a full disk) is one line naming
the file, and no output file changes, not even those written before it."""

from __future__ import annotations

import errno
import os
import tempfile
import unittest
from unittest import mock

from gencoord.errors import ModelError
from gencoord.generate import cli


class FullDiskTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.addCleanup(self.folder.cleanup)
        self.header = os.path.join(self.folder.name, "m.hpp")
        self.scene = os.path.join(self.folder.name, "m.scene.json")
        cli.write_all_atomically({self.header: "old header", self.scene: "old scene"})

    def test_a_failed_write_changes_no_file_and_names_the_file(self):
        real_fdopen = os.fdopen
        opened = []

        def fdopen(descriptor, *args, **kwargs):  # the second file meets a full disk
            opened.append(descriptor)
            handle = real_fdopen(descriptor, *args, **kwargs)
            if len(opened) == 2:
                full = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
                handle.write = mock.Mock(side_effect=full)
            return handle

        with mock.patch.object(cli.os, "fdopen", fdopen):
            with self.assertRaises(ModelError) as caught:
                cli.write_all_atomically({self.header: "new header", self.scene: "new scene"})
        self.assertEqual(str(caught.exception),
                         f"{self.scene}: error: writing failed: No space left on device; no "
                         "output file was changed")
        for path, text in ((self.header, "old header"), (self.scene, "old scene")):
            with open(path, encoding="utf-8") as handle:
                self.assertEqual(handle.read(), text)
        self.assertEqual(sorted(os.listdir(self.folder.name)), ["m.hpp", "m.scene.json"])

    def test_unchanged_files_are_not_rewritten(self):
        before = os.stat(self.header).st_mtime_ns
        self.assertFalse(cli.write_all_atomically({self.header: "old header"}))
        self.assertEqual(os.stat(self.header).st_mtime_ns, before)
        self.assertTrue(cli.write_all_atomically({self.header: "new"}))


if __name__ == "__main__":
    unittest.main()
