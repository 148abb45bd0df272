# SPDX-License-Identifier: BSD-3-Clause
"""The names a model may not give its coordinates, parameters, particles and fixed points,
and the check of the model's own (header and type) name.

A user name becomes a C++ local in every kernel and a member of struct Params, so it must
not be a keyword, a macro any including file may see (cxx_macros.txt, listed from the
compiler by scripts/list_cxx_macros.sh), an identifier the kernels' code uses, or a member
the generated structs declare. The last two are read from the templates themselves, so a
member added there is reserved with no list to update; the names the Python side prints
into kernel bodies are collected here (generated_in_kernels) from the modules that print
them.
"""

from __future__ import annotations

import functools
import os
import re

CXX_KEYWORDS = frozenset("""
alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
co_return co_yield decltype default delete do double dynamic_cast else enum explicit export
extern false float for friend goto if inline int long mutable namespace new noexcept not
not_eq nullptr operator or or_eq private protected public register reinterpret_cast requires
return short signed sizeof static static_assert static_cast struct switch template this
thread_local throw true try typedef typeid typename union unsigned using virtual void volatile
wchar_t while xor xor_eq final override restrict
""".split())

# the names of the kernels' output blocks (derive/kernel_set.py)
_KERNEL_OUTPUTS = ("result", "Mt", "f", "dr_dq", "dr_dv")


@functools.lru_cache(maxsize=None)
def generated_in_kernels() -> frozenset[str]:
    """What the generator prints into kernel bodies besides the templates' own text: the
    kernels' inputs and outputs (signatures.py, derive/kernel_set.py), the raw output
    pointers of kernel parts (lvalues.data_pointer), the math functions (printer.py), the
    locals of the batched sines and cosines (sin_cos.py), the parts' `carried` array and the
    namespaces and scalar type the printed code names."""
    # imported here: those modules import SymPy, and validate.py imports this one
    from gencoord.cxx.printer import MATH_FUNCTIONS
    from gencoord.cxx.signatures import INPUT_TYPES
    from gencoord.cxx.sin_cos import SIN_COS_LOCALS
    return frozenset({*INPUT_TYPES, "params", *_KERNEL_OUTPUTS,
                      *(f"{name}_data" for name in _KERNEL_OUTPUTS), *MATH_FUNCTIONS,
                      *SIN_COS_LOCALS,
                      "carried", "Scalar", "std", "Eigen"})


# generated names with a number: intermediates (tmp12) and part groups (Parts3)
_NUMBERED = re.compile(r"^(tmp|Parts)[0-9]+$")
_PREFIXES = ("EIGEN_", "GENCOORD_")
IDENTIFIER = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")

_HERE = os.path.dirname(os.path.abspath(__file__))
# the Jinja2 templates of the C++ backend (render.py renders them)
TEMPLATE_DIR = os.path.join(_HERE, "templates")
_WORD = re.compile(r"\b[A-Za-z_][A-Za-z0-9_]*\b")
# a member a struct declares: `static constexpr int nq =`, `using QVector =`, `struct Params {`,
# `static QVector<Scalar> qddot(`
_DECLARATION = re.compile(r"^\s*(?:static\s+(?:constexpr\s+)?[\w:<>,* ]+?\s+|using\s+|struct\s+)"
                          r"(\w+)\s*(?:=|\{|\(|;|$)", re.MULTILINE)


def _cxx_text(template: str) -> str:
    """A template's C++ text: without Jinja tags and expressions, comments, strings."""
    with open(os.path.join(TEMPLATE_DIR, template), encoding="utf-8") as handle:
        text = handle.read()
    quoted = r"""(?:'[^']*'|"[^"]*"|[^'"])*?"""  # Jinja code, which may quote braces
    for pattern in (r"\{#.*?#\}", r"\{%" + quoted + r"%\}", r"\{\{" + quoted + r"\}\}",
                    r"//[^\n]*", r'"[^"\n]*"', r"(?m)^[ \t]*#[^\n]*"):
        text = re.sub(pattern, " ", text, flags=re.DOTALL)
    return text


@functools.lru_cache(maxsize=None)
def template_identifiers() -> frozenset[str]:
    """Every identifier of the kernels' code (kernel.j2), where user names are locals; every
    member the generated structs declare; every identifier of struct Params, whose members
    the parameters are."""
    names = set(_WORD.findall(_cxx_text("kernel.j2")))
    for template in ("model_struct.j2", "model.hpp.j2", "solve.j2"):
        text = _cxx_text(template)
        names.update(_DECLARATION.findall(text))
        params = re.search(r"struct Params \{(.*?)\n  \};", text, re.DOTALL)
        if params:
            names.update(_WORD.findall(params.group(1)))
    return frozenset(names)


@functools.lru_cache(maxsize=None)
def library_macros() -> frozenset[str]:
    with open(os.path.join(_HERE, "cxx_macros.txt"), encoding="utf-8") as handle:
        return frozenset(line.strip() for line in handle
                         if line.strip() and not line.startswith("#"))


def name_problem(name: str) -> str | None:
    """Why `name` cannot name a coordinate, parameter or point in generated C++ (None: it can)."""
    if not isinstance(name, str) or not IDENTIFIER.match(name):
        return ("names must start with a letter and contain only letters, digits and "
                "underscores, so they can be C++ identifiers")
    if name in CXX_KEYWORDS:
        return f"'{name}' is a C++ keyword and cannot name generated code; rename it"
    if name in library_macros() or name.startswith(_PREFIXES):
        return (f"'{name}' is a macro of the C or C++ library, the compiler or Eigen, which "
                "would replace it in the generated code; rename it")
    if (name in generated_in_kernels() or name in template_identifiers() or _NUMBERED.match(name)
            or "__" in name):
        return f"'{name}' is reserved by the generated code; rename it"
    return None


def model_name_problem(name: str, type_name: str) -> str | None:
    """Why a model called `name` (header <name>.hpp, C++ type `type_name`) cannot be
    generated (None: it can)."""
    if not IDENTIFIER.match(name) or "__" in name:
        return ("is not a C++ identifier (a letter first, then letters, digits and single "
                "underscores)")
    if name in CXX_KEYWORDS or name in library_macros() or name.startswith(_PREFIXES):
        return "is a C++ keyword or library macro"
    if type_name in template_identifiers() or type_name in library_macros():
        return f"gives the C++ type {type_name}, which a generated struct uses for a member"
    return None
