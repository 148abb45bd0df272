"""Runs a model file and returns the `Model` it builds, turning failures into ModelErrors."""

from __future__ import annotations

import os
import re
import traceback

from .errors import ModelError
from .model import Model, requesting_options


def model_name(path: str, options: dict) -> str:
    """The generated model's name: the file stem, plus each option's value (`chain_5`)."""
    stem = os.path.splitext(os.path.basename(path))[0]
    suffix = "".join(f"_{value}" for value in options.values())
    return re.sub(r"[^A-Za-z0-9_]", "_", stem + suffix)


def _line_in(path: str, error: BaseException) -> int | None:
    """The deepest line of the model file in an exception's traceback."""
    line = None
    for frame in traceback.extract_tb(error.__traceback__):
        if os.path.abspath(frame.filename) == os.path.abspath(path):
            line = frame.lineno
    return line


def load_model(path: str, options: dict[str, str] | None = None) -> tuple[Model, str, str]:
    """Executes `path` and returns (model, name, docstring).

    The file must assign a `Model` to a module-level variable named `model`.
    """
    if not os.path.isfile(path):
        raise ModelError("no such model file; give the path of a models/<name>.py file",
                         filename=path)
    with open(path, encoding="utf-8") as handle:
        source = handle.read()
    try:
        code = compile(source, path, "exec")
    except SyntaxError as error:
        raise ModelError(f"Python syntax error: {error.msg}; fix the line shown",
                         filename=path, line=error.lineno) from None

    namespace: dict = {"__name__": "gencoord_model", "__file__": path}
    try:
        with requesting_options(options or {}):
            exec(code, namespace)  # noqa: S102 - running the user's model file is the point
    except ModelError as error:
        raise error.located(path, error.line if error.line else _line_in(path, error)) from None
    except Exception as error:  # the model file's own bug: report it at its line
        raise ModelError(f"{type(error).__name__}: {error}", filename=path,
                         line=_line_in(path, error)) from None

    model = namespace.get("model")
    if not isinstance(model, Model):
        raise ModelError("the file must assign a gencoord Model to a variable named 'model' "
                         "(model = Model(dim=2))", filename=path)
    unknown = set(options or {}) - set(model.options)
    if unknown:
        raise ModelError(f"--set {', '.join(sorted(unknown))}: not an option of this model "
                         f"(its options: {', '.join(model.options) or 'none'})", filename=path)
    docstring = model.description or namespace.get("__doc__") or ""
    return model, model_name(path, model.options), docstring.strip()
