# SPDX-License-Identifier: BSD-3-Clause
"""setuptools' build step for `pip install .` (pyproject.toml holds the metadata): besides the
Python package it copies what the gencoord command compiles against, the CMake project of the
runtime, the drivers and the Python bindings, into gencoord/_data of the built package."""

import os
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
# relative to the checkout; laid out the same under gencoord/_data
DATA = ("CMakeLists.txt", "LICENSE", "generate", "cmake", "runtime/CMakeLists.txt",
        "runtime/include", "runtime/src", "drivers", "bindings")


class BuildWithData(build_py):
    def run(self):
        super().run()
        target = os.path.join(self.build_lib, "gencoord", "_data")
        for relative in DATA:
            source, destination = os.path.join(HERE, relative), os.path.join(target, relative)
            os.makedirs(os.path.dirname(destination), exist_ok=True)
            if os.path.isdir(source):
                shutil.copytree(source, destination, dirs_exist_ok=True,
                                ignore=shutil.ignore_patterns("__pycache__"))
            else:
                shutil.copy2(source, destination)


setup(cmdclass={"build_py": BuildWithData})
