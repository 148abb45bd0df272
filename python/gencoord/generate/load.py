# SPDX-License-Identifier: BSD-3-Clause
"""Runs a model file and returns the `Model` it builds, turning failures into ModelErrors."""

from __future__ import annotations

import contextlib
import os
import re
import sys

from gencoord.errors import ModelError, model_file_line
from gencoord.generate.limits import LoadTimeout, wall_clock_limit
from gencoord.options import GenerateOptions
from gencoord.dsl.build_options import requesting_options
from gencoord.dsl.model import Model
from gencoord.naming import model_name, type_name
from gencoord.cxx.reserved_names import model_name_problem
from gencoord.urdf.load import urdf_model


def suggested_name(name: str) -> str:
    """A C++ identifier close to `name`, for the error that refuses it."""
    # leading digits move to the end: 1pendulum -> pendulum_1
    words = [re.sub(r"^([0-9]+)(.+)$", r"\2_\1", w)
             for w in re.split(r"[^A-Za-z0-9]+", name) if w]
    suggestion = "_".join(words) or "model"
    if not suggestion[0].isalpha():
        suggestion = "model_" + suggestion
    if model_name_problem(suggestion, type_name(suggestion)):
        suggestion += "_model"
    return suggestion


def _check_model_name(path: str, name: str, given: str | None) -> None:
    problem = model_name_problem(name, type_name(name))
    if problem:
        origin = "given with --name" if given else "from the file name"
        raise ModelError(f"the model's name '{name}' ({origin}) {problem}, so it cannot name "
                         f"the header and the C++ type; "
                         f"{'give another --name' if given else 'rename the file or give'} "
                         f"--name {suggested_name(name)}", filename=path)


def _compiled(path: str):
    """The model file's code object; its bytes are decoded as Python does (UTF-8, or the
    encoding its first lines declare)."""
    try:
        with open(path, "rb") as handle:
            source = handle.read()
    except OSError as error:
        raise ModelError(f"cannot read the model file: {error.strerror}", filename=path) from None
    try:
        return compile(source, path, "exec")
    except SyntaxError as error:
        if "unicode error" in str(error.msg) or "codec" in str(error.msg):
            raise ModelError(f"the file is not UTF-8 text ({error.msg}); save it as UTF-8, or "
                             "declare its encoding on its first line: # -*- coding: latin-1 -*-",
                             filename=path, line=error.lineno) from None
        raise ModelError(f"Python syntax error: {error.msg}; fix the line shown",
                         filename=path, line=error.lineno) from None
    except ValueError as error:  # null bytes, in Python versions before 3.12
        raise ModelError(f"not a Python source file ({error})", filename=path) from None


_END_PROCESS = os._exit  # the real one, which _exits_reported replaces while a model file runs


class _ProcessExit(BaseException):
    """os._exit called by a model file; a BaseException, which its `except Exception`
    cannot swallow."""

    def __init__(self, status):
        super().__init__(status)
        self.status = status


@contextlib.contextmanager
def _exits_reported():
    """While a model file runs, os._exit raises instead of ending the process at once with
    no header and no word."""
    original = os._exit

    def refuse(status):
        raise _ProcessExit(status)
    os._exit = refuse  # type: ignore[assignment]  # restored below; typed NoReturn in typeshed
    try:
        yield
    finally:
        os._exit = original


def _hung(path: str, timeout: float | None) -> None:
    """The end of a model file that does not stop at its time limit: one line, exit 1."""
    print(f"{path}: error: the model file still ran {timeout:g} s after it started and did "
          "not stop when told to (it ignores SIGALRM or catches every exception); look for "
          "an endless loop, or raise the limit with --load-timeout", file=sys.stderr, flush=True)
    _END_PROCESS(1)


def _run(path: str, code, options: dict[str, str], timeout: float | None) -> dict:
    """The namespace the model file (or URDF) leaves, every failure a ModelError."""
    namespace: dict = {"__name__": "gencoord_model", "__file__": path}
    # a URDF runs no user code: the wall-clock limit, meant for runaway model programs,
    # would only refuse a large robot on a loaded machine
    limit = None if code is None else timeout
    try:
        with requesting_options(options), _exits_reported(), \
                wall_clock_limit(limit, on_hang=lambda: _hung(path, limit)):
            if code is None:
                namespace["model"] = urdf_model(path)
            else:
                exec(code, namespace)  # noqa: S102 - running the user's model file is the point
    except LoadTimeout as error:
        raise ModelError(f"the model file still ran after {timeout:g} s (here when stopped); "
                         "a model file should take seconds: look for an endless loop or an "
                         "option too large, or raise the limit with --load-timeout",
                         filename=path, line=model_file_line(path, error)) from None
    except ModelError as error:
        line = error.line if error.line else model_file_line(path, error)
        raise error.located(path, line) from None
    except (SystemExit, _ProcessExit) as error:
        # a model that exits would otherwise end generation with status 0 and no header
        how = (f"called os._exit({error.status!r})" if isinstance(error, _ProcessExit)
               else f"exited (SystemExit({error.code!r}))")
        raise ModelError(f"the model file {how} before it finished; a model file must run "
                         "to its end and assign 'model'", filename=path,
                         line=model_file_line(path, error)) from None
    except Exception as error:  # the model file's own bug: report it at its line
        raise ModelError(f"{type(error).__name__}: {error}", filename=path,
                         line=model_file_line(path, error)) from None
    return namespace


def load_model(path: str, options: dict[str, str] | None = None, name: str | None = None,
               timeout: float | None = GenerateOptions.load_timeout) -> tuple[Model, str, str]:
    """Executes `path` and returns (model, name, docstring); `name` replaces the file's stem
    in the model's name; the file may run `timeout` seconds (None: no limit).

    The file must assign a `Model` to a module-level variable named `model`; a robot
    description (a path ending in .urdf) is read into a model instead.
    """
    if not os.path.isfile(path):
        raise ModelError("no such model file; give the path of a models/<name>.py file or of a "
                         "robot description <name>.urdf", filename=path)
    is_urdf = path.lower().endswith(".urdf")
    code = None if is_urdf else _compiled(path)

    namespace = _run(path, code, options or {}, timeout)
    model = namespace.get("model")
    if not isinstance(model, Model):
        raise ModelError("the file must assign a gencoord Model to a variable named 'model' "
                         "(model = Model(dim=2))", filename=path)
    unknown = set(options or {}) - set(model.options)
    if unknown:
        raise ModelError(f"--set {', '.join(sorted(unknown))}: not an option of this model "
                         f"(its options: {', '.join(model.options) or 'none'})", filename=path)
    if model.description is not None and not isinstance(model.description, str):
        raise ModelError(f"description is {model.description!r}, not text; give a string",
                         item="Model", filename=path, line=model.line)
    docstring = model.description or namespace.get("__doc__") or ""
    full_name = model_name(path, model.options, name)
    _check_model_name(path, full_name, name)
    return model, full_name, docstring.strip()
