# SPDX-License-Identifier: BSD-3-Clause
"""Where gencoord's parts are: a source checkout, or an installation under a prefix."""

from __future__ import annotations

import os
import shutil
from dataclasses import dataclass


# the gencoord package: this file is <package>/tool/layout.py
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@dataclass(frozen=True)
class Layout:
    root: str                 # holds drivers/, bindings/, cmake/ and the script generate
    source_dir: str | None    # a CMake project that builds the runtime, when there is one
    prefix: str | None        # the installation prefix when installed with cmake --install

    @property
    def drivers_dir(self) -> str:
        return os.path.join(self.root, "drivers")

    @property
    def fingerprint_dirs(self) -> list[str]:
        """Folders whose content decides what a driver build produces."""
        dirs = [PACKAGE_DIR] + [os.path.join(self.root, d) for d in ("drivers", "bindings")]
        if self.source_dir:
            dirs += [os.path.join(self.source_dir, "runtime", "include"),
                     os.path.join(self.source_dir, "runtime", "src"),
                     os.path.join(self.source_dir, "cmake")]
        else:
            assert self.prefix is not None  # without a source_dir, an installation's prefix
            dirs += [os.path.join(self.prefix, "include", "gencoord")]
        return dirs


def find_layout() -> Layout:
    """A checkout (the package in <root>/python), a pip install (the C++ parts in the package's
    _data, a CMake project like the checkout's) or a CMake install (<prefix>/share/gencoord)."""
    data = os.path.join(PACKAGE_DIR, "_data")
    if os.path.isfile(os.path.join(data, "CMakeLists.txt")):
        return Layout(root=data, source_dir=data, prefix=None)
    root = os.path.dirname(os.path.dirname(PACKAGE_DIR))
    if os.path.isfile(os.path.join(root, "CMakeLists.txt")):
        return Layout(root=root, source_dir=root, prefix=None)
    return Layout(root=root, source_dir=None, prefix=os.path.dirname(os.path.dirname(root)))


def cache_dir() -> str:
    """The per-user cache of built drivers: $GENCOORD_CACHE_DIR, else $XDG_CACHE_HOME/gencoord,
    else ~/.cache/gencoord."""
    explicit = os.environ.get("GENCOORD_CACHE_DIR")
    if explicit:
        return os.path.abspath(explicit)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "gencoord")


def compiler() -> str:
    """The C++ compiler CMake will pick: $CXX, else c++ on PATH."""
    return os.environ.get("CXX") or shutil.which("c++") or shutil.which("g++") or ""
