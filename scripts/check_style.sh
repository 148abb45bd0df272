#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Format, lint and type checks: every hand-written C++ file is as clang-format 14 lays it out
# (.clang-format), every Python file passes flake8 (.flake8), and the gencoord package passes
# mypy ([tool.mypy] in pyproject.toml). Installs the three from Debian when missing. Exits
# non-zero listing the offending files.
#   scripts/check_style.sh          check
#   scripts/check_style.sh --fix    rewrite the C++ files in place (Python is fixed by hand)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=()
command -v clang-format-14 >/dev/null 2>&1 || packages+=(clang-format-14)
/usr/bin/python3 -m flake8 --version >/dev/null 2>&1 || packages+=(flake8)
/usr/bin/python3 -m mypy --version >/dev/null 2>&1 || packages+=(mypy)
scripts/install_packages.sh check_style "${packages[@]}"

# the files git tracks and the new ones it does not ignore (a file is checked before its first
# commit); generated/ is written by the generator, which wraps its own lines
files=(git ls-files --cached --others --exclude-standard)
mapfile -t cxx < <("${files[@]}" '*.hpp' '*.cpp' '*.cc' '*.h' | grep -v '^generated/')
mapfile -t python < <("${files[@]}" '*.py'; echo gencoord; echo generate)

if [ "${1:-}" = --fix ]; then
  clang-format-14 -i "${cxx[@]}"
  exit 0
fi

status=0
unformatted=()
for f in "${cxx[@]}"; do
  clang-format-14 --dry-run -Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check_style: not formatted (run scripts/check_style.sh --fix):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  status=1
fi
/usr/bin/python3 -m flake8 "${python[@]}" || status=1
# mypy's own report is printed only when it finds errors; on success it gives the file count
if mypy_report=$(/usr/bin/python3 -m mypy --config-file pyproject.toml python/gencoord 2>&1); then
  typed=$(sed -n 's/^Success: no issues found in \([0-9]*\) source files*$/\1/p' <<<"$mypy_report")
else
  printf '%s\n' "$mypy_report"
  status=1
fi
[ $status -eq 0 ] && echo "check_style: ${#cxx[@]} C++ files formatted, ${#python[@]} Python files lint-free, ${typed:-all} gencoord files type-checked"
exit $status
