# SPDX-License-Identifier: BSD-3-Clause
"""Small symbolic helpers the stages share: sums without matrix arithmetic, numeric evaluation
that may leave the domain, what a user expression may contain, trigonometric polynomials."""
