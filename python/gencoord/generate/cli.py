# SPDX-License-Identifier: BSD-3-Clause
"""`./generate models/<name>.py [-o DIR] [--set key=value]`: writes DIR/<name>.hpp, the scene
a viewer draws DIR/<name>.scene.json (scene.py) and, with --translation-units N,
DIR/<name>_double_0.cpp ... <name>_double_<N-1>.cpp; DIR defaults to generated/ in the
current directory."""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time
from typing import Any, Container

from gencoord.cxx.escapes import shell_word
from gencoord.errors import ModelError
from gencoord.generate.output_cache import OutputCache, cache_key
from gencoord.options import DYNAMICS_CHOICES, GenerateOptions, knobs

# Relative to the directory generate runs in: output lands next to the user, never in the
# gencoord checkout (unless run from there).
DEFAULT_OUTPUT = "generated"
TRUST = ("A model file is a Python program: it runs with your rights, as a build runs its "
         "build scripts. Run only model files you trust.")


def _parse_options(pairs: list[str]) -> dict[str, str]:
    options = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise ModelError(f"--set expects key=value, got '{pair}'")
        options[key] = value
    return options


def _output_flags(args) -> list[str]:
    """The banner's `-o DIR` (relative to the working directory), none for the default."""
    if os.path.abspath(args.output_dir) == os.path.abspath(DEFAULT_OUTPUT):
        return []
    return ["-o " + shell_word(
        os.path.relpath(os.path.abspath(args.output_dir)).replace(os.sep, "/"))]


def _add_knob_flags(parser: argparse.ArgumentParser) -> None:
    """A flag per GenerateOptions field that has one, with the field's documentation."""
    for knob in knobs():
        flag = knob.metadata["flag"]
        if not flag:
            continue
        extra: dict[str, Any] = {"choices": DYNAMICS_CHOICES} if knob.name == "dynamics" else {
            "type": knob.metadata["parse"], "metavar": knob.metadata["metavar"]}
        if isinstance(knob.default, bool):
            extra = {"action": "store_true"}
        default = ("" if knob.default is None or isinstance(knob.default, bool)
                   else f" (default {knob.default})")
        parser.add_argument(flag, dest=knob.name, default=knob.default,
                            help=knob.metadata["help"] + default, **extra)


def options_of(args, parser: argparse.ArgumentParser) -> GenerateOptions:
    """The GenerateOptions of parsed arguments; an error for values the options refuse."""
    values = {knob.name: getattr(args, knob.name) for knob in knobs() if knob.metadata["flag"]}
    values["load_timeout"] = values["load_timeout"] or None
    try:
        return GenerateOptions(**values)
    except ValueError as error:  # named by its flags here, not by the fields
        message = str(error)
        for knob in knobs():
            if knob.metadata["flag"]:
                message = message.replace(knob.name, knob.metadata["flag"])
        parser.error(message)


def write_atomically(path: str, text: str) -> bool:
    """Writes `text` to `path` via a temporary file and a rename; False if unchanged."""
    return write_all_atomically({path: text})


def write_all_atomically(files: dict[str, str]) -> bool:
    """Writes each path's text: every changed file goes to a temporary file first, and only
    when all are written are they renamed into place, so a failure (a full disk) changes no
    file. False if none changed. \raises ModelError naming the file that could not be written.
    """
    changed = {path: text for path, text in files.items() if not _holds(path, text)}
    temporaries: dict[str, str] = {}
    try:
        for path, text in changed.items():
            temporaries[path] = _written_temporary(path, text)
        for path, temporary in temporaries.items():
            _write_step(path, lambda: os.replace(temporary, path))
    finally:
        for temporary in temporaries.values():
            if os.path.exists(temporary):
                os.unlink(temporary)
    return bool(changed)


def _holds(path: str, text: str) -> bool:
    if not os.path.isfile(path):
        return False
    with open(path, encoding="utf-8") as handle:
        return handle.read() == text


def _written_temporary(path: str, text: str) -> str:
    """A temporary file beside `path` (same file system, so the rename is atomic) holding
    `text`, with an ordinary file's permissions."""
    directory = os.path.dirname(os.path.abspath(path))
    _write_step(path, lambda: os.makedirs(directory, exist_ok=True))
    descriptor, temporary = _write_step(
        path, lambda: tempfile.mkstemp(prefix=".gencoord-", dir=directory))
    try:
        def write() -> None:
            with os.fdopen(descriptor, "w", encoding="utf-8", newline="\n") as handle:
                handle.write(text)
        _write_step(path, write)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp makes 0600; headers are ordinary files
    except BaseException:
        os.unlink(temporary)
        raise
    return temporary


def _write_step(path: str, step):
    """Runs one step of writing `path`; an OSError (a full disk, no permission) becomes a
    one-line error naming the file."""
    try:
        return step()
    except OSError as error:
        reason = error.strerror or str(error)
        raise ModelError(f"writing failed: {reason}; no output file was changed",
                         filename=path) from None


def build_parser(prog: str = "generate") -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=prog,
        description="Derive the reduced equations of motion of a gencoord model file and emit "
                    "them as a C++ header (DIR/<name>.hpp). Nothing is written unless every "
                    "stage succeeds. " + TRUST)
    parser.add_argument("model", help="the model file, e.g. models/double_pendulum.py")
    parser.add_argument("-o", "--output-dir", default=DEFAULT_OUTPUT,
                        help="where to write <name>.hpp (default: generated/ in the current "
                             "directory)")
    parser.add_argument("--set", dest="options", action="append", default=[],
                        metavar="KEY=VALUE", help="a model option, e.g. --set n=5")
    _add_knob_flags(parser)
    parser.add_argument("--cache", metavar="DIR",
                        help="reuse the outputs of an earlier generation with the same inputs "
                             "from DIR, and keep this one's there (a build's cache: the key "
                             "is the model file, the files named by --depends, the arguments, "
                             "the generator's sources and the Python, SymPy, mpmath and Jinja2 "
                             "versions)")
    parser.add_argument("--depends", action="append", default=[], metavar="FILE",
                        help="a file the model file reads (a URDF its load_urdf() loads), part "
                             "of the --cache key; repeat for each")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="print every stage's timing even when generation is fast, and the "
                             "traceback of an error")
    parser.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    return parser


def main(argv: list[str] | None = None, prog: str = "generate") -> int:
    parser = build_parser(prog)
    args = parser.parse_args(argv)
    options = options_of(args, parser)

    started = time.perf_counter()

    def report(label: str, seconds: float) -> None:
        # a line per stage once generation is slow enough for someone to wonder
        if not args.quiet and (args.verbose or time.perf_counter() - started > 1.0):
            print(f"  {label:<28} {seconds:8.2f} s", flush=True)

    try:
        return _generate_and_write(args, options, report, started)
    except (Exception, KeyboardInterrupt) as error:
        # imported here: it imports SymPy, which a generation found in --cache never needs
        from gencoord.generate.failures import report_failure
        return report_failure(error, args.model, prog, verbose=args.verbose)


def _generate_and_write(args, options: GenerateOptions, report, started: float) -> int:
    def warn(text: str) -> None:  # even with --quiet: it comes before a long wait
        print(f"{args.model}: warning: {text}", file=sys.stderr, flush=True)

    def make() -> dict:
        return _generated_entry(args, options, report, warn)

    key = _cache_key(args, options) if args.cache else ""
    entry, from_cache = OutputCache(args.cache).cached(key, make) if key else (make(), False)
    if from_cache:
        for text in entry["warnings"]:
            warn(text)
    if not args.quiet:
        for line in entry["analysis"]:
            print(f"  {line}")
    name, sources = entry["name"], entry["sources"]
    path = os.path.join(args.output_dir, f"{name}.hpp")
    changed = write_all_atomically({os.path.join(args.output_dir, file_name): text
                                    for file_name, text in entry["files"].items()})
    removed = _remove_stale_sources(args.output_dir, name, sources)
    if not args.quiet:
        elapsed = time.perf_counter() - started
        state = "wrote" if changed or removed else "unchanged"
        extra = f" and {len(sources)} source files" if sources else ""
        origin = ", from the cache" if from_cache else ""
        print(f"generate: {state} {os.path.relpath(path)}{extra} ({elapsed:.2f} s{origin})")
    return 0


def _generated_entry(args, options: GenerateOptions, report, warn) -> dict:
    """Generates the model: the output files' names (in the output folder) and texts, the
    analysis lines and the warnings, as the cache keeps them."""
    from gencoord.generate.stages import generate  # SymPy: only when generating

    warnings: list[str] = []

    def warn_and_keep(text: str) -> None:
        warnings.append(text)
        warn(text)

    generated = generate(args.model, _parse_options(args.options), options, on_stage=report,
                         on_warning=warn_and_keep, output_flags=_output_flags(args))
    files = {f"{generated.name}.hpp": generated.header,
             f"{generated.name}.scene.json": generated.scene, **generated.sources}
    return {"name": generated.name, "files": files, "sources": sorted(generated.sources),
            "analysis": generated.analysis, "warnings": warnings}


def _cache_key(args, options: GenerateOptions) -> str:
    """What decides the outputs: the model file and the files it reads, and every argument
    that reaches them (the banner names the model and -o relative to the working folder).
    Empty when the model file cannot be read: generating then says why."""
    for path in args.depends:
        if not os.path.isfile(path):
            raise ModelError("--depends names no readable file; name the files the model "
                             "file reads", filename=path)
    if not os.path.isfile(args.model):
        return ""
    values = [os.path.relpath(os.path.abspath(args.model)), *_output_flags(args),
              repr(args.options), repr(options)]
    return cache_key("generate", [args.model, *args.depends], values)


def _remove_stale_sources(directory: str, name: str, keep: Container[str]) -> list[str]:
    """Deletes <name>_double_K.cpp files an earlier --translation-units left that this
    generation did not write (they would instantiate parts the header no longer has)."""
    pattern = re.compile(re.escape(name) + r"_double_[0-9]+\.cpp")
    stale = sorted(f for f in os.listdir(directory) if pattern.fullmatch(f) and f not in keep)
    for file_name in stale:
        os.unlink(os.path.join(directory, file_name))
    return stale
