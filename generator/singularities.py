"""Where the parameterization loses rank: gimbal lock, the poles of spherical coordinates.

J = dX/dq losing rank at a configuration means some direction of q moves no particle there;
Mt = J^T M J is singular and the accelerations are undefined. Two complementary analyses:

- symbolic: for small models, det(J^T J) is factored and each factor that depends on q is a
  singular set (`sin(theta) = 0` for spherical coordinates);
- candidates: for each coordinate inside sin/cos, J is evaluated with that coordinate at the
  zeros of sin (0, pi) and of cos (+-pi/2) and the others random; a rank drop at every sample
  is reported as `sin(q) = 0` or `cos(q) = 0` (finds Z-Y-X Euler angles' pitch singularity
  without a 6 x 6 symbolic determinant);
- sampling: the smallest singular value of J relative to its largest over many random
  configurations, with the worst configuration found;
- redundancy (redundancy.py): distinct configurations with the same particle positions.
The report goes to the generate output and into the generated header's doc comment.
"""

from __future__ import annotations

import math
import textwrap
import random
from dataclasses import dataclass, field

import sympy as sp

from .derive import Kinematics
from .model import Model
from .conditioning import smallest_direction
from .redundancy import find_redundancy

SYMBOLIC_MAX_NQ = 3        # det(J^T J) symbolically only up to this many coordinates
SAMPLES = 200
CANDIDATE_SAMPLES = 12
# Each sample costs about nq^3 operations: beyond SAMPLED_FULLY_NQ coordinates the number of
# samples shrinks to keep the analysis as cheap as for that size (at least MIN_SAMPLES), and
# the per-coordinate candidate search (2 nq samples at least) is skipped.
SAMPLED_FULLY_NQ = 6
MIN_SAMPLES = 8
RANK_DROP = 1e-6           # sigma_min / sigma_max below this counts as rank lost (J^T J is
                           # diagonalized, so round-off alone leaves about sqrt(eps) = 1e-8)


@dataclass
class SingularityReport:
    singular_sets: list[str] = field(default_factory=list)   # e.g. "sin(theta) = 0"
    method: str = ""                                          # how they were found
    worst_ratio: float = 1.0                                  # sigma_min / sigma_max sampled
    worst_configuration: str = ""
    redundancy: str | None = None                             # redundancy.find_redundancy
    samples: int = SAMPLES
    candidates_searched: bool = True

    def lines(self, width: int = 90) -> list[str]:
        found = ", ".join(self.singular_sets) if self.singular_sets else "none found"
        if not self.singular_sets and not self.candidates_searched:
            found += f" (searched by sampling only, nq > {SAMPLED_FULLY_NQ})"
        lines = textwrap.wrap(f"Singular configurations (J loses rank): {found}", width,
                              subsequent_indent="  ")
        if self.singular_sets:
            lines.append(f"  found from the {self.method}")
        lines += textwrap.wrap(
            f"Worst conditioning of J in {self.samples} random configurations: sigma_min / "
            f"sigma_max = {self.worst_ratio:.3g} at {self.worst_configuration}", width,
            subsequent_indent="  ")
        if self.redundancy:
            lines += textwrap.wrap(self.redundancy, width, subsequent_indent="  ")
        return lines


def _changes_sign(factor: sp.Expr, q: list[sp.Symbol], defaults: dict, rng) -> bool:
    """Whether a q-dependent factor takes both signs (so it vanishes somewhere in between).

    Factors that never vanish for real q, like cos(2 theta1 - 2 theta2) - 3, are dropped.
    """
    evaluate = sp.lambdify([q], factor.xreplace(defaults), modules="math")
    signs = set()
    for _ in range(SAMPLES):
        value = evaluate([rng.uniform(-math.pi, math.pi) for _ in q])
        if value != 0:
            signs.add(value > 0)
    return len(signs) == 2


def _symbolic_sets(jacobian: sp.Matrix, q: list[sp.Symbol], defaults: dict, rng) -> list[str]:
    gram = (jacobian.T * jacobian).applyfunc(sp.trigsimp)
    determinant = sp.factor(sp.trigsimp(gram.det(method="berkowitz")))
    sets = []
    for factor, _ in sp.factor_list(determinant)[1]:
        if factor.free_symbols & set(q) and _changes_sign(factor, q, defaults, rng):
            sets.append(f"{factor} = 0")
    return sorted(set(sets))


def _candidate_sets(evaluate, q: list[sp.Symbol], jacobian: sp.Matrix, rng) -> list[str]:
    trig_arguments = {f.args[0] for f in jacobian.atoms(sp.sin, sp.cos)}
    sets = []
    for k, coordinate in enumerate(q):
        if coordinate not in trig_arguments:
            continue
        for function, zeros in (("sin", (0.0, math.pi)), ("cos", (math.pi / 2, -math.pi / 2))):
            lost_everywhere = True
            for sample in range(CANDIDATE_SAMPLES):
                values = [rng.uniform(-math.pi, math.pi) for _ in q]
                values[k] = zeros[sample % 2]
                ratio, _ = smallest_direction(evaluate(values, rng.uniform(0.0, 10.0)))
                if ratio > RANK_DROP:
                    lost_everywhere = False
                    break
            if lost_everywhere:
                sets.append(f"{function}({coordinate}) = 0")
    return sets


def analyse_singularities(model: Model, seed: int = 11,
                          kin: Kinematics | None = None) -> SingularityReport:
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    q = [c.symbol for c in model.coordinates]
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    jacobian = sp.Matrix.vstack(*[kin.jacobian[p.name] for p in model.particles])
    evaluate = kin.numeric_jacobian()
    rng = random.Random(seed)
    report = SingularityReport()
    if len(q) <= SYMBOLIC_MAX_NQ and sp.count_ops(jacobian) < 400:
        report.singular_sets = _symbolic_sets(jacobian, q, defaults, rng)
        report.method = "factors of det(J^T J)"
    report.candidates_searched = len(q) <= SAMPLED_FULLY_NQ
    if not report.singular_sets and report.candidates_searched:
        report.singular_sets = _candidate_sets(evaluate, q, jacobian, rng)
        report.method = "rank of J at the zeros of sin and cos of each angle"
    report.samples = max(MIN_SAMPLES, min(SAMPLES, SAMPLES * SAMPLED_FULLY_NQ**3 // len(q)**3))
    for sample in range(report.samples):
        values = [rng.uniform(-math.pi, math.pi) for _ in q]
        t = rng.uniform(0.0, 10.0)
        ratio, _ = smallest_direction(evaluate(values, t))
        if sample == 0 or ratio < report.worst_ratio:
            report.worst_ratio = ratio
            report.worst_configuration = ", ".join(
                f"{c.name} = {v:.4g}" for c, v in zip(model.coordinates, values))
    report.redundancy = find_redundancy(model, kin)
    return report
