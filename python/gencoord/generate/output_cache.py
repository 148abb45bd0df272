# SPDX-License-Identifier: BSD-3-Clause
"""A folder of earlier generations' outputs, found again by a hash of everything they depend on.

Generation is deterministic: the same model file (and the files it reads), the same arguments,
the same generator sources and the same Python, SymPy, mpmath and Jinja2 give the same bytes.
A build that generates the same models again (a second checkout, a fresh build folder, CI)
reuses the earlier outputs instead of deriving them for minutes, as ccache reuses compiled
objects. The key covers the inputs a generation is known to read; a model file that reads
other files must name them (`generate --depends`, DEPENDS of gencoord_add_model), as it must
for CMake to regenerate it when they change.

An entry is one JSON file, written to a temporary name and renamed, so parallel builds never
read half of one. Entries are touched when used, and the least recently used go once the
folder passes its size limit.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.metadata
import json
import os
import sys
import tempfile
from typing import Callable, Iterable

from gencoord import __version__

PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# what a generation's result depends on besides its inputs: the generator's code and
# templates, and the libraries that compute and print it
_PACKAGE_SUFFIXES = (".py", ".j2", ".txt")
_LIBRARIES = ("sympy", "mpmath", "jinja2", "numpy")
SIZE_LIMIT = 1 << 30   # bytes; past it the least recently used entries are removed


def _library_version(name: str) -> str:
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return "absent"


def _generator_fingerprint(digest) -> None:
    """Feeds every source and template of the gencoord package, by relative path, and the
    versions of the interpreter and the libraries into `digest`."""
    for directory, subdirectories, files in os.walk(PACKAGE_DIR):
        # _data: a pip install's C++ sources, which no generation reads
        subdirectories[:] = sorted(d for d in subdirectories if d not in ("__pycache__", "_data"))
        for name in sorted(files):
            if name.endswith(_PACKAGE_SUFFIXES):
                path = os.path.join(directory, name)
                _feed(digest, "source", os.path.relpath(path, PACKAGE_DIR))
                _feed_file(digest, path)
    _feed(digest, "gencoord", __version__)
    _feed(digest, "python", sys.version)
    for library in _LIBRARIES:
        _feed(digest, library, _library_version(library))
    _feed(digest, "PYTHONHASHSEED", os.environ.get("PYTHONHASHSEED", ""))


def _feed(digest, label: str, value: str) -> None:
    data = value.encode("utf-8", "surrogateescape")
    digest.update(f"{label}:{len(data)}:".encode())
    digest.update(data)


def _feed_file(digest, path: str) -> None:
    with open(path, "rb") as handle:
        data = handle.read()
    digest.update(f"file:{len(data)}:".encode())
    digest.update(data)


def cache_key(kind: str, files: Iterable[str], values: Iterable[str]) -> str:
    """The hash of a `kind` of output made from `files` (their bytes, in this order) and
    `values` (its arguments), by this generator and these libraries."""
    digest = hashlib.sha256()
    _feed(digest, "kind", kind)
    _generator_fingerprint(digest)
    for path in files:
        _feed_file(digest, path)
    for value in values:
        _feed(digest, "value", value)
    return digest.hexdigest()


class OutputCache:
    """Entries under `directory`, each a JSON object of an output's texts and notes."""

    def __init__(self, directory: str, size_limit: int = SIZE_LIMIT):
        self.directory = os.path.abspath(directory)
        self.size_limit = size_limit

    def _path(self, key: str) -> str:
        return os.path.join(self.directory, key[:2], key + ".json")

    def load(self, key: str) -> dict | None:
        """The entry stored under `key`, or None; an unreadable entry counts as missing."""
        path = self._path(key)
        try:
            with open(path, encoding="utf-8") as handle:
                entry = json.load(handle)
            os.utime(path)  # recently used: trimmed last
        except (OSError, ValueError):
            return None
        return entry if isinstance(entry, dict) else None

    def cached(self, key: str, make: Callable[[], dict]) -> tuple[dict, bool]:
        """The entry under `key` and True, or else make()'s, stored under `key`, and False."""
        entry = self.load(key)
        if entry is not None:
            return entry, True
        entry = make()
        self.store(key, entry)
        return entry, False

    def store(self, key: str, entry: dict) -> None:
        """Stores `entry` under `key`. A cache that cannot be written (a full disk, no
        permission) only means generating again next time, so failures pass silently."""
        path = self._path(key)
        with contextlib.suppress(OSError):
            os.makedirs(os.path.dirname(path), exist_ok=True)
            descriptor, temporary = tempfile.mkstemp(prefix=".entry-", dir=os.path.dirname(path))
            try:
                with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
                    json.dump(entry, handle)
                os.replace(temporary, path)
            finally:
                if os.path.exists(temporary):
                    os.unlink(temporary)
            self._trim()

    def _trim(self) -> None:
        """Removes the least recently used entries while the folder is over its limit."""
        entries = []
        for directory, _, files in os.walk(self.directory):
            for name in files:
                if name.endswith(".json"):
                    path = os.path.join(directory, name)
                    with contextlib.suppress(OSError):
                        status = os.stat(path)
                        entries.append((status.st_mtime, status.st_size, path))
        total = sum(size for _, size, _ in entries)
        for _, size, path in sorted(entries):
            if total <= self.size_limit:
                break
            with contextlib.suppress(OSError):
                os.unlink(path)
                total -= size
