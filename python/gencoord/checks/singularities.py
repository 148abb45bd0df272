# SPDX-License-Identifier: BSD-3-Clause
"""Where the parameterization loses rank: gimbal lock, the poles of spherical coordinates.

J = dX/dq losing rank at a configuration means some direction of q moves no particle there;
Mt = J^T M J is singular and the accelerations are undefined. Two complementary analyses:

- symbolic: for small models, det(J^T J) is factored and each factor that depends on q and
  changes sign is a singular set (`sin(theta) = 0` for spherical coordinates); with J
  rational (1 / q, tan q, sqrt), the factors of its denominator are where J is infinite;
- candidates: for each coordinate inside sin/cos, J is evaluated with that coordinate at the
  zeros of sin (0, pi) and of cos (+-pi/2) and the others random; a rank drop at every sample
  is reported as `sin(q) = 0` or `cos(q) = 0` (finds Z-Y-X Euler angles' pitch singularity
  without a 6 x 6 symbolic determinant);
- sampling: the smallest singular value of J relative to its largest over many random
  configurations, with the worst configuration found;
- redundancy (redundancy.py): distinct configurations with the same particle positions.
Samples where J is not finite (outside the domain of sqrt, at a pole) are skipped and
counted. Each part has a CPU-time budget (budget.py); one that runs out stops, and the
report says so in a line, as it does for anything skipped.
The report goes to the generate output and into the generated header's doc comment.
"""

from __future__ import annotations

import math
import textwrap
import random
from dataclasses import dataclass, field

import sympy as sp
from sympy.polys.polyerrors import BasePolynomialError

from gencoord.checks.budget import Budget, BudgetSpent
from gencoord.checks.conditioning import smallest_direction
from gencoord.derive.dense import Kinematics
from gencoord.symbolic.finite import finite_or_none
from gencoord.dsl.model import Model
from gencoord.symbolic.trig_polynomial import circle_symbols, reduce_on_circles
from gencoord.checks.redundancy import find_redundancy

SYMBOLIC_MAX_NQ = 3        # det(J^T J) symbolically only up to this many coordinates
SAMPLES = 200
CANDIDATE_SAMPLES = 12
# Each sample costs about nq^3 operations: beyond SAMPLED_FULLY_NQ coordinates the number of
# samples shrinks to keep the analysis as cheap as for that size (at least MIN_SAMPLES), and
# the per-coordinate candidate search (2 nq samples at least) is skipped.
SAMPLED_FULLY_NQ = 6
MIN_SAMPLES = 8
# beyond this many coordinates a single sample takes seconds: conditioning is not sampled
CONDITIONING_MAX_NQ = 200
SYMBOLIC_SECONDS = 1.0     # CPU budget of det(J^T J) and its factors
SAMPLING_SECONDS = 0.4     # CPU budget of the random conditioning samples
# sigma_min / sigma_max below this counts as rank lost (J^T J is diagonalized, so round-off
# alone leaves about sqrt(eps) = 1e-8)
RANK_DROP = 1e-6


@dataclass
class SingularityReport:
    singular_sets: list[str] = field(default_factory=list)   # e.g. "sin(theta) = 0"
    method: str = ""                                          # how they were found
    worst_ratio: float = 1.0                                  # sigma_min / sigma_max sampled
    worst_configuration: str = ""
    redundancy: str | None = None                             # redundancy.find_redundancy
    samples: int = SAMPLES
    candidates_searched: bool = True
    why_sampled_only: str = f"nq > {SAMPLED_FULLY_NQ}"
    notes: list[str] = field(default_factory=list)           # what was skipped, and why

    def lines(self, width: int = 90) -> list[str]:
        found = ", ".join(self.singular_sets) if self.singular_sets else "none found"
        if not self.singular_sets and not self.candidates_searched:
            found += f" (searched by sampling only, {self.why_sampled_only})"
        lines = textwrap.wrap(f"Singular configurations (J loses rank): {found}", width,
                              subsequent_indent="  ")
        if self.singular_sets:
            lines.append(f"  found from the {self.method}")
        if self.worst_configuration:
            lines += textwrap.wrap(
                f"Worst conditioning of J in {self.samples} random configurations: sigma_min / "
                f"sigma_max = {self.worst_ratio:.3g} at {self.worst_configuration}", width,
                subsequent_indent="  ")
        if self.redundancy:
            lines += textwrap.wrap(self.redundancy, width, subsequent_indent="  ")
        for note in self.notes:
            lines += textwrap.wrap(note, width, subsequent_indent="  ")
        return lines


def _changes_sign(factor: sp.Expr, q: list[sp.Symbol], defaults: dict, rng) -> bool:
    """Whether a q-dependent factor takes both signs (so it vanishes somewhere in between).

    Factors that never vanish for real q, like cos(2 theta1 - 2 theta2) - 3, are dropped.
    """
    factor = factor.xreplace(defaults)
    if factor.free_symbols - set(q):
        return True  # it moves with time as well: keep it rather than sample t
    evaluate = sp.lambdify([q], factor, modules="math")
    signs = set()
    for _ in range(SAMPLES):
        value = finite_or_none(evaluate, [rng.uniform(-math.pi, math.pi) for _ in q])
        if value is not None and value != 0:
            signs.add(value > 0)
    return len(signs) == 2


def _symbolic_sets(jacobian: sp.Matrix, q: list[sp.Symbol], defaults: dict, rng) -> list[str]:
    """The q-dependent factors of det(J^T J) that change sign; with J rational (1 / q,
    tan q) the factors of its denominator too, where J is infinite.

    sin/cos/tan of each argument become symbols s, c (trig_polynomial.py), so that J^T J
    and its determinant are rational functions that factor without trigsimp (which took
    seconds on a 3-link chain); a factor that is constant on the circles s^2 + c^2 = 1
    (sin^2 + cos^2) is not a singular set.
    """
    polynomial_jacobian, pairs, back = circle_symbols(jacobian)
    gram = (polynomial_jacobian.T * polynomial_jacobian).applyfunc(sp.expand)
    numerator, denominator = sp.fraction(sp.factor(sp.cancel(gram.det(method="berkowitz"))))
    sets = []
    for part, where in ((numerator, ""), (denominator, " (J is infinite)")):
        for factor, _ in sp.factor_list(part)[1]:
            on_circles = reduce_on_circles(sp.Poly(factor), pairs).as_expr().xreplace(back)
            if on_circles.free_symbols & set(q):
                factor = factor.xreplace(back)
                if _changes_sign(factor, q, defaults, rng):
                    sets.append(f"{factor} = 0{where}")
    return sorted(set(sets))


def _symbolic_search(report: "SingularityReport", jacobian: sp.Matrix, q: list[sp.Symbol],
                     defaults: dict, rng) -> None:
    """Fills the report's singular sets from det(J^T J), or notes why it could not."""
    try:
        with Budget(SYMBOLIC_SECONDS).interrupting():
            report.singular_sets = _symbolic_sets(jacobian, q, defaults, rng)
        report.method = "factors of det(J^T J)"
    except BudgetSpent:
        report.notes.append(f"Symbolic search stopped at its time budget ({SYMBOLIC_SECONDS:g} "
                            "s CPU for det(J^T J) and its factors); searched by sampling")
    except (BasePolynomialError, NotImplementedError, ArithmeticError, ValueError,
            TypeError) as error:
        reason = str(error).splitlines()[0][:80] if str(error) else type(error).__name__
        report.notes.append("Symbolic search skipped: det(J^T J) could not be factored "
                            f"({reason}); searched by sampling")


def _candidate_sets(evaluate, q: list[sp.Symbol], jacobian: sp.Matrix, rng) -> list[str]:
    trig_arguments = {f.args[0] for f in jacobian.atoms(sp.sin, sp.cos)}
    sets = []
    for k, coordinate in enumerate(q):
        if coordinate not in trig_arguments:
            continue
        for function, zeros in (("sin", (0.0, math.pi)), ("cos", (math.pi / 2, -math.pi / 2))):
            lost_everywhere, evaluated = True, 0
            for sample in range(CANDIDATE_SAMPLES):
                values = [rng.uniform(-math.pi, math.pi) for _ in q]
                values[k] = zeros[sample % 2]
                matrix = finite_or_none(evaluate, values, rng.uniform(0.0, 10.0))
                if matrix is None:
                    continue  # J is not finite there (tan at a zero of cos): no evidence
                evaluated += 1
                ratio, _ = smallest_direction(matrix)
                if ratio > RANK_DROP:
                    lost_everywhere = False
                    break
            if lost_everywhere and evaluated:
                sets.append(f"{function}({coordinate}) = 0")
    return sets


def _sample_conditioning(report: SingularityReport, model: Model, evaluate, rng) -> None:
    """The worst sigma_min / sigma_max of J over random configurations where J is finite."""
    q = model.coordinates
    planned = max(MIN_SAMPLES, min(SAMPLES, SAMPLES * SAMPLED_FULLY_NQ**3 // len(q)**3))
    budget = Budget(SAMPLING_SECONDS)
    report.samples, skipped = 0, 0
    for sample in range(planned):
        if budget.spent():
            report.notes.append(f"Conditioning sampling stopped at its time budget "
                                f"({SAMPLING_SECONDS:g} s CPU) after {sample} of {planned} "
                                "configurations")
            break
        values = model.on_manifold([rng.uniform(-math.pi, math.pi) for _ in q])
        matrix = finite_or_none(evaluate, values, rng.uniform(0.0, 10.0))
        if matrix is None:
            skipped += 1
            continue
        ratio, _ = smallest_direction(matrix)
        if report.samples == 0 or ratio < report.worst_ratio:
            report.worst_ratio = ratio
            report.worst_configuration = ", ".join(
                f"{c.name} = {v:.4g}" for c, v in zip(q, values))
        report.samples += 1
    if skipped:
        report.notes.append(f"{skipped} of {planned} random configurations skipped: J is not "
                            "finite there (outside the domain of X, or at a pole)")


def analyse_singularities(model: Model, seed: int = 11,
                          kin: Kinematics | None = None) -> SingularityReport:
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    q = [c.symbol for c in model.coordinates]
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    evaluate = kin.numeric_jacobian()
    rng = random.Random(seed)
    report = SingularityReport()
    # unit quaternions have no singular set: a model with them is sampled only
    report.candidates_searched = len(q) <= SAMPLED_FULLY_NQ and not model.has_generalized_speeds
    if model.has_generalized_speeds:
        report.why_sampled_only = "unit quaternions have no singular set"
    if report.candidates_searched:  # the symbolic J only where it is small
        jacobian = sp.Matrix.vstack(*[kin.jacobian[p.name] for p in model.particles])
        if len(q) <= SYMBOLIC_MAX_NQ and sp.count_ops(jacobian) < 400:
            _symbolic_search(report, jacobian, q, defaults, rng)
        if not report.singular_sets:
            report.singular_sets = _candidate_sets(evaluate, q, jacobian, rng)
            report.method = "rank of J at the zeros of sin and cos of each angle"
    if len(q) <= CONDITIONING_MAX_NQ:
        _sample_conditioning(report, model, evaluate, rng)
    else:
        report.samples = 0
        report.notes.append(f"Conditioning of J not sampled: one sample costs about nq^3 = "
                            f"{len(q)**3:.2g} operations in Python (sampled up to nq = "
                            f"{CONDITIONING_MAX_NQ})")
    if model.has_generalized_speeds:  # q and -q are the same rotation: redundant by design
        report.notes.append("Redundancy not searched: q and -q of a unit quaternion are the "
                            "same rotation")
    else:
        report.redundancy = find_redundancy(model, kin, notes=report.notes)
    return report
