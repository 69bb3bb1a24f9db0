"""The sampling uncertainty of R and B: how well 5 runs know a standard deviation and a mean.

ISO 230-2:2014 Annex A gives U of the repeatability R and the reversal B from the reading's
resolution and E_VE only (the *narrow* U): the uncertainty of the measuring chain at one target.
A statement that R conforms to a tolerance is, however, a statement about the machine's
scatter, which n runs only estimate. The standard uncertainty of an experimental standard
deviation s from n readings is s/√(2(n − 1)) (JCGM 100:2008 Annex E.4.3, Table E.1: 35 % of s
for n = 5), and that of a mean s/√n (JCGM 100:2008 §4.2.3). :func:`sampling_contributors` turns
them into one contributor per parameter, at the target that gives the parameter its value
(the *wider* U); :func:`~axiscal.standards.iso230_9.positioning_budget` adds them, states both
and prints the wider one, which a conformity statement about R or B needs.

Models (ISO 230-2:2014 clause 3, equations (6), (10)-(15); sensitivity coefficients of each
equation, uncorrelated runs):

=========  ========================================  =============================================
parameter  value at the governing target i           sampling standard uncertainty
=========  ========================================  =============================================
R↑, R↓     4 s_i                                      4 s_i/√(2(n_i − 1))
R          2 s_i↑ + 2 s_i↓ + |B_i| (or R_i↑, R_i↓)   √(4u(s↑)² + 4u(s↓)² + u(B_i)²) (or as R↑)
B          |B_i| = |x̄_i↑ − x̄_i↓|                     u(B_i) = √(s_i↑²/n_i↑ + s_i↓²/n_i↓)
B̄          mean of B_i over m targets                 √(Σ u(B_i)²)/m
=========  ========================================  =============================================

The maximum over targets is taken at the target that gives it; the selection of a maximum among
m estimates is not modelled (it makes the value, if anything, larger than the machine's).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["sampling_contributors", "relative_u_of_s"]

_CLAUSE = "JCGM 100:2008 Annex E.4.3 (s from n runs), §4.2.3 (means)"


def relative_u_of_s(n: int) -> float:
    """u(s)/s = 1/√(2(n − 1)) (JCGM 100:2008 Annex E.4.3); NaN for n < 2.

    Examples
    --------
    >>> round(relative_u_of_s(5), 4)
    0.3536
    """
    return 1.0 / math.sqrt(2.0 * (n - 1)) if n >= 2 else math.nan


def sampling_contributors(result) -> list[dict]:
    """One contributor per scatter parameter (R, R↑, R↓, B, B̄) of ``result``: the sampling
    uncertainty of the standard deviations and means it is formed from, in the result's
    deviation unit, at the target that gives the parameter its value.

    Parameters
    ----------
    result : Iso230_2Result

    Returns
    -------
    list of dict
        The fields of :class:`~axiscal.standards.iso230_9.Contributor` (``name``, ``quantity``,
        ``u``, ``distribution``, ``clause``, ``basis``, ``applies_to``): ``u_SAMPLING (R)`` …
        each acting on its one parameter; none for a parameter that does not apply or whose
        target has fewer than 2 readings in a direction.
    """
    t = result.targets
    u_unit = {"um": "µm"}.get(result.deviation_unit, result.deviation_unit)
    up = _direction(result.s_up, result.n_up)
    down = _direction(result.s_down, result.n_down)
    out = []
    for name, sym, s_u, r_i in (("R_up", "R↑", up, result.R_up_i),
                                ("R_down", "R↓", down, result.R_down_i)):
        if getattr(result, name) is None or not np.any(np.isfinite(r_i)):
            continue
        i = int(np.nanargmax(r_i))
        s, us, n = s_u[i]
        if math.isfinite(us):
            out.append(_c(name, sym, 4 * us, f"at target {t[i]:g}: {sym} = 4 s = "
                          f"{4 * s:.4g} {u_unit} from {n} runs, u(s) = s/√(2(n − 1)) = "
                          f"{us:.3g} {u_unit}"))
    if result.R is not None and np.any(np.isfinite(result.R_i)):
        i = int(np.nanargmax(result.R_i))
        if result.R_i[i] == result.R_up_i[i] or result.R_i[i] == result.R_down_i[i]:
            s, us, n = (up if result.R_i[i] == result.R_up_i[i] else down)[i]
            u = 4 * us
            how = f"R_i = 4 s = {4 * s:.4g} {u_unit} from {n} runs"
        else:
            u = math.sqrt(4 * up[i][1] ** 2 + 4 * down[i][1] ** 2 + _u_b(up, down, i) ** 2)
            how = (f"R_i = 2s↑ + 2s↓ + |B_i| = {result.R_i[i]:.4g} {u_unit}: "
                   "√(4u(s↑)² + 4u(s↓)² + u(B_i)²)")
        if math.isfinite(u):
            out.append(_c("R", "R", u, f"at target {t[i]:g}: {how}"))
    if result.B is not None:
        i = int(np.nanargmax(np.abs(result.reversal)))
        u = _u_b(up, down, i)
        if math.isfinite(u):
            out.append(_c("B", "B", u, f"at target {t[i]:g}: u(B_i) = √(s↑²/n↑ + s↓²/n↓)"))
        all_u = [_u_b(up, down, j) for j in range(t.size)]
        if all(math.isfinite(x) for x in all_u):
            out.append(_c("B_mean", "B̄", math.sqrt(sum(x * x for x in all_u)) / t.size,
                          f"√(Σ u(B_i)²)/m over {t.size} targets"))
    return out


def _direction(s, n) -> list[tuple[float, float, int]]:
    """(s, u(s), n) per target of one direction (u NaN below 2 readings)."""
    return [(float(si), float(si) * relative_u_of_s(int(ni)), int(ni)) for si, ni in zip(s, n)]


def _u_b(up, down, i: int) -> float:
    (su, _, nu), (sd, _, nd) = up[i], down[i]
    if nu < 2 or nd < 2:
        return math.nan
    return math.sqrt(su * su / nu + sd * sd / nd)


def _c(name: str, sym: str, u: float, basis: str) -> dict:
    return {"name": f"u_SAMPLING ({sym})", "quantity": f"sampling of the runs behind {sym}",
            "u": u, "distribution": "normal", "clause": _CLAUSE, "basis": basis,
            "applies_to": (name,)}
