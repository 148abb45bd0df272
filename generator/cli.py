"""`./generate models/<name>.py [-o DIR] [--set key=value]`: writes DIR/<name>.hpp, the scene
a viewer draws DIR/<name>.scene.json (scene.py) and, with --translation-units N,
DIR/<name>_double_0.cpp ... <name>_double_<N-1>.cpp; DIR defaults to generated/ in the
current directory."""

from __future__ import annotations

import argparse
import os
import re
import shlex
import sys
import tempfile
import time

from .dynamics_paths import DYNAMICS_CHOICES
from .errors import ModelError
from .failures import report_failure
from .limits import LOAD_TIMEOUT
from .looped import LOOP_MIN_NQ
from .pipeline import generate
from .split import LARGE_TREE_PART_STATEMENTS, MAX_PART_STATEMENTS

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


def _banner_options(args) -> list[str]:
    """The banner's `--name NAME` and `-o DIR` (relative to the working directory), none for
    the defaults."""
    options = ["--name " + shlex.quote(args.name)] if args.name else []
    if args.dynamics != "auto":
        options.append("--dynamics " + args.dynamics)
    if os.path.abspath(args.output_dir) != os.path.abspath(DEFAULT_OUTPUT):
        options.append("-o " + shlex.quote(
            os.path.relpath(os.path.abspath(args.output_dir)).replace(os.sep, "/")))
    return options


def write_atomically(path: str, text: str) -> bool:
    """Writes `text` to `path` via a temporary file and a rename; False if unchanged."""
    if os.path.exists(path):
        with open(path, encoding="utf-8") as handle:
            if handle.read() == text:
                return False
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(prefix=".gencoord-", dir=directory)
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp makes 0600; headers are ordinary files
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
    return True


def main(argv: list[str] | None = None, prog: str = "generate") -> int:
    parser = argparse.ArgumentParser(
        prog=prog,
        description="Derive the reduced equations of motion of a gencoord model file and emit "
                    "them as a C++ header (DIR/<name>.hpp). Nothing is written unless every "
                    "stage succeeds. " + TRUST)
    parser.add_argument("model", help="the model file, e.g. models/double_pendulum.py")
    parser.add_argument("-o", "--output-dir", default=DEFAULT_OUTPUT,
                        help="where to write <name>.hpp (default: generated/ in the current "
                             "directory)")
    parser.add_argument("--name", help="the model's name instead of the file's stem (the "
                        "header NAME.hpp, the C++ type; option values are still appended): a "
                        "C++ identifier")
    parser.add_argument("--set", dest="options", action="append", default=[],
                        metavar="KEY=VALUE", help="a model option, e.g. --set n=5")
    parser.add_argument("--max-function-statements", type=int, default=None, metavar="N",
                        help="emit a kernel of more statements as several functions, which "
                             "keeps C++ compile time near linear (default "
                             f"{MAX_PART_STATEMENTS}, {LARGE_TREE_PART_STATEMENTS} for a tree "
                             "of --loop-min-nq coordinates or more; 0: never)")
    parser.add_argument("--translation-units", type=int, default=0, metavar="N",
                        help="compile the kernels for double in N source files of their own "
                             "(DIR/<name>_double_K.cpp), which build in parallel; the header "
                             "declares them extern template (default 0: header only)")
    parser.add_argument("--dynamics", choices=DYNAMICS_CHOICES, default="auto",
                        help="qddot and inverse_dynamics of a model that is a tree (of "
                             "particles, or of bodies joined by joints): by the O(nq) "
                             "recursions, dense (Mt, Ft + Fi), or auto: whichever takes fewer "
                             "operations (default %(default)s)")
    parser.add_argument("--loop-min-nq", type=int, default=LOOP_MIN_NQ, metavar="N",
                        help="a tree of N coordinates or more gets Mt, J and the residual "
                             "Jacobians as loops over O(nq) products, so that their code grows "
                             "like nq, not nq^2 (default %(default)s)")
    parser.add_argument("--load-timeout", type=float, default=LOAD_TIMEOUT, metavar="SECONDS",
                        help="stop with an error when running the model file takes longer "
                             "(default %(default)g; 0: no limit)")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="print every stage's timing even when generation is fast, and the "
                             "traceback of an error")
    parser.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    args = parser.parse_args(argv)
    if args.max_function_statements is not None and args.max_function_statements < 0:
        parser.error("--max-function-statements must be 0 (never split) or positive")
    if args.loop_min_nq < 1:
        parser.error("--loop-min-nq must be positive")
    if args.load_timeout < 0:
        parser.error("--load-timeout must be 0 (no limit) or positive")
    if args.translation_units < 0:
        parser.error("--translation-units must be 0 (header only) or positive")

    started = time.perf_counter()

    def report(label: str, seconds: float) -> None:
        # a line per stage once generation is slow enough for someone to wonder
        if not args.quiet and (args.verbose or time.perf_counter() - started > 1.0):
            print(f"  {label:<28} {seconds:8.2f} s", flush=True)

    try:
        return _generate_and_write(args, report, started)
    except (Exception, KeyboardInterrupt) as error:
        return report_failure(error, args.model, prog, verbose=args.verbose)


def _generate_and_write(args, report, started: float) -> int:
    def warn(text: str) -> None:  # even with --quiet: it comes before a long wait
        print(f"{args.model}: warning: {text}", file=sys.stderr, flush=True)

    generated = generate(args.model, _parse_options(args.options), report,
                         max_part_statements=args.max_function_statements,
                         translation_units=args.translation_units, dynamics=args.dynamics,
                         regenerate_options=_banner_options(args), name=args.name,
                         load_timeout=args.load_timeout or None, on_warning=warn,
                         loop_min_nq=args.loop_min_nq)
    if not args.quiet:
        for line in generated.analysis:
            print(f"  {line}")
    path = os.path.join(args.output_dir, f"{generated.name}.hpp")
    changed = write_atomically(path, generated.header)
    changed = write_atomically(os.path.join(args.output_dir, f"{generated.name}.scene.json"),
                               generated.scene) or changed
    for file_name, text in generated.sources.items():
        changed = write_atomically(os.path.join(args.output_dir, file_name), text) or changed
    removed = _remove_stale_sources(args.output_dir, generated.name, generated.sources)
    if not args.quiet:
        elapsed = time.perf_counter() - started
        state = "wrote" if changed or removed else "unchanged"
        extra = f" and {len(generated.sources)} source files" if generated.sources else ""
        print(f"generate: {state} {os.path.relpath(path)}{extra} ({elapsed:.2f} s)")
    return 0


def _remove_stale_sources(directory: str, name: str, keep: dict[str, str]) -> list[str]:
    """Deletes <name>_double_K.cpp files an earlier --translation-units left that this
    generation did not write (they would instantiate parts the header no longer has)."""
    pattern = re.compile(re.escape(name) + r"_double_[0-9]+\.cpp")
    stale = sorted(f for f in os.listdir(directory) if pattern.fullmatch(f) and f not in keep)
    for file_name in stale:
        os.unlink(os.path.join(directory, file_name))
    return stale
