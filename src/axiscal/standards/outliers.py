"""Readings that stand apart from their run-mates: Grubbs' test on the runs of one target.

ISO 230-2:2014 evaluates every reading; it has no rule for outliers, and axiscal never removes
one. But a single reading far from the other runs at its target (a first run taken before the
machine was warm, a laser beam cut for a moment) can alone set the axis's repeatability R and
accuracy A, and a reader must be told. Each target's readings in one direction are tested by
Grubbs' test (two-sided), at a significance of 5 % for the whole test: with m targets and
directions tested, each at 5 %/m (Bonferroni), so that a test of normal readings raises a false
alarm once in twenty tests, not once in twenty targets. A reading found is said beside the
parameters it sets; it stays in the evaluation.

References
----------
.. [1] F. E. Grubbs, "Procedures for detecting outlying observations in samples",
   Technometrics 11 (1969) 1-21.
.. [2] ASTM E178-16a, Standard Practice for Dealing With Outlying Observations, §6.1 (the
   statistic T = |x - x̄| / s) and Table 1 (its critical values).
.. [3] ISO 5725-2:1994, §7.3.4 (Grubbs' test for one outlying observation).
.. [4] M. Abramowitz, I. A. Stegun, Handbook of Mathematical Functions (1964), 26.7.3 and 26.7.4
   (Student's t distribution for a whole number of degrees of freedom).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["ALPHA", "Outlier", "grubbs_critical", "grubbs_p_value", "positioning_outliers",
           "with_outliers"]

#: Significance of Grubbs' test (two-sided) over a whole test, as ISO 5725-2:1994 §7.3.4 takes
#: for an outlier; each of the m target-direction groups is tested at ALPHA/m (Bonferroni).
ALPHA = 0.05


@dataclass(frozen=True)
class Outlier:
    """One reading that Grubbs' test finds apart from the other runs at its target.

    Attributes
    ----------
    target : float, target unit
    direction : {"up", "down"}
    run : int
        The run, counted from 1.
    value : float, deviation unit
        The reading.
    mean, s : float, deviation unit
        Mean and standard deviation of the readings at the target in that direction, with it.
    G, G_critical : float
        Grubbs' statistic ``|x - x̄| / s`` and its critical value for ``n`` readings at
        :data:`ALPHA` / ``groups``.
    groups : int
        Target-direction groups of the test (the Bonferroni divisor).
    n : int
        Readings at the target in that direction.
    sets : tuple of str
        The axis parameters (ISO 230-2:2014 symbols) whose value this target decides: R↑ when
        its R_i↑ is the largest, A↑ when its x̄ ± 2s is the extreme, and A, R of both directions
        likewise.
    unit, target_unit : str
    """

    target: float
    direction: str
    run: int
    value: float
    mean: float
    s: float
    G: float
    G_critical: float
    n: int
    sets: tuple[str, ...]
    unit: str
    target_unit: str
    groups: int = 1

    def __str__(self) -> str:
        from axiscal import units

        u, tu = units.display(self.unit), units.display(self.target_unit)
        arrow = "↑" if self.direction == "up" else "↓"
        sets = (f"; it sets {', '.join(self.sets)}" if self.sets else "")
        return (f"run {self.run} {arrow} at target {self.target:g} {tu}: reading {self.value:+.2f}"
                f" {u} lies {self.G:.3f} s from the mean {self.mean:+.2f} {u} of its {self.n} "
                f"runs (Grubbs' test, 5 % over the test's {self.groups} target-direction groups: "
                f"critical {self.G_critical:.3f}){sets}; kept, as ISO "
                f"230-2:2014 evaluates every reading")

    def as_dict(self) -> dict:
        """The ``outliers`` objects of ``--json``."""
        return {"target": self.target, "direction": self.direction, "run": self.run,
                "value": self.value, "mean": self.mean, "s": self.s, "G": self.G,
                "G_critical": self.G_critical, "n": self.n, "sets": list(self.sets),
                "groups": self.groups,
                "rule": "Grubbs two-sided, alpha 0.05 over the test, Bonferroni over the "
                        "target-direction groups (ISO 5725-2:1994 7.3.4)",
                "text": str(self)}


def grubbs_p_value(G: float, n: int) -> float:
    """The two-sided p-value of Grubbs' statistic ``G`` for ``n`` readings.

    Notes
    -----
    G is turned into Student's t with ν = n - 2 degrees of freedom (Grubbs 1969, ASTM E178-16a
    §6.1.2): t² = n(n-2)G² / ((n-1)² - nG²), and p = 2n·P(T > t), the Bonferroni bound that the
    tabulated critical values use. P(T > t) for a whole ν from Abramowitz and Stegun 26.7.3 and
    26.7.4, in closed form (no scipy on the evaluation's path).
    """
    if n < 3:
        return 1.0
    top = (n - 1) ** 2 - n * G * G
    if top <= 0:
        return 0.0
    t = math.sqrt(n * (n - 2) * G * G / top)
    return min(1.0, n * (1.0 - _t_within(t, n - 2)))


def grubbs_critical(n: int, alpha: float = ALPHA) -> float:
    """The critical value of Grubbs' statistic for ``n`` readings (two-sided, ``alpha``).

    Examples
    --------
    ASTM E178-16a Table 1 (n = 5 and 10, upper 2.5 %, i.e. 5 % two-sided):

    >>> round(grubbs_critical(5), 3), round(grubbs_critical(10), 3)
    (1.715, 2.29)
    """
    lo, hi = 0.0, (n - 1) / math.sqrt(n)
    for _ in range(60):               # p falls as G grows: bisect p(G) = alpha
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if grubbs_p_value(mid, n) > alpha else (lo, mid)
    return 0.5 * (lo + hi)


def positioning_outliers(targets, up, down, result, alpha: float = ALPHA) -> tuple[Outlier, ...]:
    """The readings of a positioning test that Grubbs' test finds apart from their run-mates.

    Parameters
    ----------
    targets : ndarray (m,), target unit
    up, down : ndarray (m, n), deviation unit
        The readings per target and run in each direction (NaN missing), as evaluated.
    result : Iso230_2Result
        The evaluation of those readings (for which targets set A and R).
    alpha : float
        Significance over the whole test, two-sided; each of the m target-direction groups
        with 3 readings or more is tested at ``alpha / m`` (Bonferroni).

    Returns
    -------
    tuple of Outlier
        At most one per target and direction (the farthest reading), in target order.
    """
    candidates = []
    for direction, arr in (("up", up), ("down", down)):
        for i, row in enumerate(np.asarray(arr, dtype=float)):
            ok = np.isfinite(row)
            n = int(ok.sum())
            if n < 3:
                continue
            vals = row[ok]
            mean, s = float(vals.mean()), float(vals.std(ddof=1))
            if not s > 0:
                candidates.append(None)          # a group tested, nothing apart
                continue
            j = int(np.argmax(np.abs(row - mean) * ok))
            G = abs(float(row[j]) - mean) / s
            candidates.append((direction, i, j, row[j], mean, s, G, n))
    m = max(len(candidates), 1)
    found = [Outlier(float(targets[i]), d, j + 1, float(x), mean, s, G,
                     grubbs_critical(n, alpha / m), n, _sets(result, i, d),
                     result.deviation_unit, result.target_unit, m)
             for d, i, j, x, mean, s, G, n in filter(None, candidates)
             if grubbs_p_value(G, n) < alpha / m]
    return tuple(sorted(found, key=lambda o: (o.target, o.direction)))


def with_outliers(result, targets, up, down):
    """``result`` (an Iso230_2Result) with the readings that stand apart named in ``outliers``;
    those that set a parameter are warned of, the others counted. They stay in the evaluation:
    ISO 230-2:2014 has no rule to drop one."""
    from dataclasses import replace

    found = positioning_outliers(targets, up, down, result)
    warn = [f"a reading apart from its run-mates: {o}" for o in found if o.sets]
    if len(found) > len(warn):
        warn.append(f"{len(found) - len(warn)} more reading(s) apart from their run-mates "
                    "(Grubbs' test, 5 % over the test) set no parameter: see outliers")
    return replace(result, outliers=found, warnings=result.warnings + tuple(warn))


def _sets(result, i: int, direction: str) -> tuple[str, ...]:
    """The parameters target ``i`` decides in ``direction`` (ISO 230-2:2014 §3.3 symbols): its
    R_i↑ (R_i↓) the largest; its R_i (eq. 12) equal to R; its x̄ ± 2s the extreme of A↑ (A↓) and
    of A (eq. 13-15)."""
    arrow = "↑" if direction == "up" else "↓"
    up = direction == "up"
    mean, s = (result.mean_up, result.s_up) if up else (result.mean_down, result.s_down)
    r_i = result.R_up_i if up else result.R_down_i
    out = []
    with np.errstate(invalid="ignore"):
        if np.nanargmax(r_i) == i:
            out.append(f"R{arrow}")
        if result.R is not None and (math.isclose(r_i[i], result.R)
                                     or math.isclose(result.R_i[i], result.R)):
            out.append("R")
        hi, lo = mean + 2 * s, mean - 2 * s
        if np.nanargmax(hi) == i or np.nanargmin(lo) == i:
            out.append(f"A{arrow}")
        if result.A is not None:
            both_hi = np.fmax(result.mean_up + 2 * result.s_up, result.mean_down + 2 * result.s_down)
            both_lo = np.fmin(result.mean_up - 2 * result.s_up, result.mean_down - 2 * result.s_down)
            if math.isclose(hi[i], np.nanmax(both_hi)) or math.isclose(lo[i], np.nanmin(both_lo)):
                out.append("A")
    return tuple(out)


def _t_within(t: float, nu: int) -> float:
    """P(|T| < t) for Student's t with a whole ``nu`` degrees of freedom (A&S 26.7.3, 26.7.4)."""
    theta = math.atan(t / math.sqrt(nu))
    c2, s = math.cos(theta) ** 2, math.sin(theta)
    if nu % 2 == 0:                   # 26.7.4: sin θ (1 + 1/2 cos² θ + 1·3/(2·4) cos⁴ θ + ...)
        term, total = 1.0, 1.0
        for k in range(1, nu // 2):
            term *= c2 * (2 * k - 1) / (2 * k)
            total += term
        return s * total
    if nu == 1:
        return 2 * theta / math.pi
    term, total = 1.0, 1.0            # 26.7.3: 2/π (θ + sin θ cos θ (1 + 2/3 cos² θ + ...))
    for k in range(1, (nu - 1) // 2):
        term *= c2 * (2 * k) / (2 * k + 1)
        total += term
    return 2 / math.pi * (theta + s * math.cos(theta) * total)
