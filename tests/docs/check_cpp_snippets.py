#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Compiles every ```cpp block of the given Markdown files, each as a translation unit of its
own, and exits with status 1 if any fails or none was compiled.

    check_cpp_snippets.py --compiler g++ [--flag=-I...]... README.md docs/*.md

A block preceded by the line `<!-- excerpt -->` (blank lines between are allowed) is an
excerpt, not meant to compile, and is skipped; a marker not followed by a ```cpp block is an
error, so markers cannot go stale unnoticed.
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

EXCERPT = "<!-- excerpt -->"


def cpp_blocks(path):
    """(line number of the opening fence, code, is_excerpt) for each ```cpp block."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks, i, excerpt_line = [], 0, None
    while i < len(lines):
        line = lines[i].strip()
        if line == EXCERPT:
            excerpt_line = i + 1
        elif re.fullmatch(r"```\s*(cpp|c\+\+)\s*", line):
            start = i + 1
            i += 1
            body = []
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            if i == len(lines):
                raise SystemExit(f"{path}:{start}: ```cpp block is never closed")
            blocks.append((start, "\n".join(body) + "\n", excerpt_line is not None))
            excerpt_line = None
        elif line.startswith("```"):  # a block of another language: skip it whole
            if excerpt_line is not None:
                raise SystemExit(f"{path}:{excerpt_line}: {EXCERPT} is not followed by "
                                 "a ```cpp block")
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                i += 1
        elif line and excerpt_line is not None:
            raise SystemExit(f"{path}:{excerpt_line}: {EXCERPT} is not followed by a ```cpp block")
        i += 1
    if excerpt_line is not None:
        raise SystemExit(f"{path}:{excerpt_line}: {EXCERPT} is not followed by a ```cpp block")
    return blocks


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--compiler", required=True)
    parser.add_argument("--flag", action="append", default=[],
                        help="a compiler flag, e.g. --flag=-Iruntime/include (repeatable)")
    parser.add_argument("--jobs", type=int, default=2, help="compilers run at once")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()

    snippets, skipped = [], 0
    for path in args.files:
        for line, code, excerpt in cpp_blocks(path):
            where = f"{os.path.relpath(path)}:{line}"
            if excerpt:
                print(f"{where}: excerpt, skipped")
                skipped += 1
            else:
                snippets.append((where, code))

    with tempfile.TemporaryDirectory() as scratch:
        def compile_snippet(index):
            where, code = snippets[index]
            source = os.path.join(scratch, f"snippet_{index}.cpp")
            with open(source, "w", encoding="utf-8") as f:
                f.write(code)
            command = [args.compiler, "-std=c++17", "-fsyntax-only", "-Wall", "-Wextra",
                       "-Werror", *args.flag, source]
            return subprocess.run(command, capture_output=True, text=True)

        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            results = list(pool.map(compile_snippet, range(len(snippets))))

    failed = []
    for (where, code), result in zip(snippets, results):
        if result.returncode == 0:
            print(f"{where}: compiles")
        else:
            print(f"{where}: does not compile:\n{code}\n{result.stderr}")
            failed.append(where)
    compiled = len(snippets) - len(failed)
    print(f"{compiled} blocks compile, {len(failed)} do not, {skipped} excerpts skipped")
    if failed:
        print("failed: " + ", ".join(failed))
    return 1 if failed or compiled == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
