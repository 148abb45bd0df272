# SPDX-License-Identifier: BSD-3-Clause
"""A CSV of numbered columns (a trajectory, a time series) read with an error that names the
file and the line for anything else: a header row with a `t` column, then rows of numbers.
Standard library only."""
from __future__ import annotations

import csv

from gencoord.tool.errors import ToolError


def read_columns(path: str) -> dict[str, list[float]]:
    """The CSV's columns by name, in file order; a ToolError naming the file if it is not a
    header row with a `t` column followed by rows of numbers."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            return parse_columns(csv.reader(handle, skipinitialspace=True), path)
    except OSError as error:
        raise ToolError(f"{path}: {error.strerror or error}") from None
    except (csv.Error, UnicodeDecodeError) as error:
        raise ToolError(f"{path}: not a CSV file ({error})") from None


def parse_columns(reader, path: str) -> dict[str, list[float]]:
    header = next((row for row in reader if any(cell.strip() for cell in row)), None)
    if header is None:
        raise ToolError(f"{path}: empty file; expected a header row with a 't' column")
    header = [name.strip() for name in header]
    for name in header:
        if header.count(name) > 1:
            raise ToolError(f"{path}: column {name!r} appears more than once")
    if "t" not in header:
        raise ToolError(f"{path}: no column 't' (columns: {', '.join(header)})")
    columns: dict[str, list[float]] = {name: [] for name in header}
    for row in reader:
        if not any(cell.strip() for cell in row):
            continue
        line = reader.line_num
        if len(row) != len(header):
            raise ToolError(f"{path}:{line}: {len(row)} values for {len(header)} columns")
        for name, cell in zip(header, row):
            try:
                columns[name].append(float(cell))
            except ValueError:
                raise ToolError(f"{path}:{line}: column {name!r}: {cell!r} is not a number"
                                ) from None
    if not columns["t"]:
        raise ToolError(f"{path}: no rows of data after the header")
    return columns
