# SPDX-License-Identifier: BSD-3-Clause
"""The switches between supported SymPy and Jinja2 versions (gencoord/library_versions.py), and the
printer output they must leave the same under every supported version."""

from __future__ import annotations

import unittest

import jinja2
import sympy as sp

from gencoord import library_versions as compat
from gencoord.cxx.printer import ScalarCxxPrinter, UnsupportedExpression


class VersionTupleTest(unittest.TestCase):

    def test_numeric_fields(self):
        self.assertEqual(compat.version_tuple("3.1.2"), (3, 1, 2))
        self.assertEqual(compat.version_tuple("1.14"), (1, 14))

    def test_stops_at_the_first_field_that_is_not_a_number(self):
        self.assertEqual(compat.version_tuple("1.14.0rc1"), (1, 14, 0))
        self.assertEqual(compat.version_tuple("3.1.dev0"), (3, 1))
        self.assertEqual(compat.version_tuple("dev"), ())

    def test_orders_like_the_releases(self):
        self.assertLess(compat.version_tuple("3.0.3"), (3, 1, 2))
        self.assertLess(compat.version_tuple("3.1.1"), (3, 1, 2))
        self.assertGreaterEqual(compat.version_tuple("3.1.10"), (3, 1, 2))

    def test_jinja2_cache_switch_follows_the_installed_version(self):
        self.assertEqual(compat.JINJA2_CACHE_IS_SAFE,
                         compat.version_tuple(jinja2.__version__) >= (3, 1, 2))


class CodePrinterSettingsTest(unittest.TestCase):

    class _WithStrict:
        _default_settings = {"order": None, "strict": None}

    class _WithoutStrict:
        _default_settings = {"order": None}

    def test_strict_kept_where_the_printer_knows_it(self):
        self.assertEqual(compat.code_printer_settings(self._WithStrict, strict=True,
                                                      order="none"),
                         {"strict": True, "order": "none"})

    def test_strict_dropped_where_the_printer_does_not_know_it(self):
        self.assertEqual(compat.code_printer_settings(self._WithoutStrict, strict=True,
                                                      order="none"),
                         {"order": "none"})

    def test_other_unknown_settings_still_reach_the_printer(self):
        settings = compat.code_printer_settings(self._WithoutStrict, ordr="none")
        self.assertEqual(settings, {"ordr": "none"}, "a misspelt setting must not vanish")


class PrinterOutputTest(unittest.TestCase):
    """Literals print the same whatever SymPy prints for them by default."""

    def setUp(self):
        self.printer = ScalarCxxPrinter({sp.Symbol("x"): "x"})

    def test_integer_constants(self):
        for value, text in ((0, "Scalar(0)"), (1, "Scalar(1)"), (-1, "Scalar(-1)"),
                            (7, "Scalar(7)")):
            self.assertEqual(self.printer.expression(sp.Integer(value)), text)

    def test_rationals(self):
        self.assertEqual(self.printer.expression(sp.Rational(1, 2)), "Scalar(0.5)")
        self.assertEqual(self.printer.expression(sp.Rational(1, 3)),
                         "(Scalar(1)/Scalar(3))")

    def test_unknown_functions_are_refused(self):
        f = sp.Function("f")
        with self.assertRaises(UnsupportedExpression):
            self.printer.expression(f(sp.Symbol("x")))


if __name__ == "__main__":
    unittest.main()
