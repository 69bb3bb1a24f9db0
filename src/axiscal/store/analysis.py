"""Comparing two stored tests and trending a parameter over time.

Trend model
-----------
A straight line ``y(t) = a + b (t − t̄)`` (t in years) is fitted by ordinary least squares to
the parameter's values, the uncertainty of each value taken as unknown and equal, so estimated
from the residuals with ``n − 2`` degrees of freedom: ISO/TS 28037:2010, *Determination and use
of straight-line calibration functions*, clause 6 (uncertainties associated with the y values
only; here unknown and estimated). The drift is ``b`` with its standard uncertainty ``u(b)``.

The date at which the line reaches a tolerance ``T`` is ``t* = t̄ + (T − a)/b``; its standard
uncertainty follows from the law of propagation of uncertainty (JCGM 100:2008, GUM, eq. 13) with
the covariance of ``a`` and ``b`` (zero after centring t, so
``u²(t*) = u²(a)/b² + (T − a)² u²(b)/b⁴``). A recalibration interval a user can defend is the
earlier end of ``t* ± k u(t*)`` with k = 2 (ILAC-G24:2007 / OIML D 10, "Guidelines for the
determination of calibration intervals of measuring instruments": intervals from the
instrument's drift history). With fewer than three tests there is no residual to estimate the
scatter from, and no prediction is made.

A test whose file gave no date carries the day it was stored, not the day it was measured: it is
shown, marked, but left out of the fit (a date the drift would be read against that nobody
measured at).
"""

from __future__ import annotations

import datetime as dt
import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["Trend", "fit_trend", "Comparison", "compare_tests"]

_YEAR = 365.25 * 86400.0


@dataclass(frozen=True)
class Trend:
    """A parameter over time with its fitted drift (module docstring).

    Attributes
    ----------
    dates : tuple of datetime
    values : numpy.ndarray
    unit : str
    drift : float or None
        ``b``, unit per year.
    u_drift : float or None
        Standard uncertainty of the drift.
    level : float or None
        Fitted value at the last test.
    tolerance : float or None
    crossing : datetime or None
        When the line reaches the tolerance (None if it moves away or never gets there).
    u_crossing_days : float or None
        Standard uncertainty of ``crossing``, days.
    recalibrate_by : datetime or None
        ``crossing − 2 u``: the cautious recalibration date.
    dated : tuple of bool
        Per point: whether its file gave the date (False: the day it was stored; left out of
        the fit). Empty: every point dated.
    """

    parameter: str
    dates: tuple
    values: np.ndarray
    unit: str
    drift: float | None
    u_drift: float | None
    level: float | None
    tolerance: float | None
    crossing: dt.datetime | None
    u_crossing_days: float | None
    recalibrate_by: dt.datetime | None
    test_ids: tuple = ()
    dated: tuple = ()

    def is_dated(self, i: int) -> bool:
        """Whether point ``i`` has the date its file gave (so is in the fit)."""
        return not self.dated or bool(self.dated[i])

    @property
    def undated(self) -> int:
        """How many points have no date of their own (left out of the fit)."""
        return sum(not d for d in self.dated)

    def drift_text(self) -> str:
        """The drift with its standard uncertainty, rounded as a certificate rounds a value
        and its uncertainty (:func:`~axiscal.standards.uncertainty_reporting.format_value`,
        ILAC-P14:09/2020 §5.3: U to two significant digits, the value to the same last digit):
        ``+3.1 ± 1.4 µm/year``; empty without a drift."""
        from axiscal.report.labels import unit_text
        from axiscal.standards.uncertainty_reporting import format_uncertainty, format_value

        if self.drift is None:
            return ""
        value = format_value(self.drift, self.u_drift)
        sign = "+" if not value.startswith("-") else ""
        return (f"{sign}{value} ± {format_uncertainty(self.u_drift)} "
                f"{unit_text(self.unit)}/year")

    def as_dict(self) -> dict:
        iso = (lambda d: d.isoformat() if d else None)
        return {"parameter": self.parameter, "unit": self.unit,
                "points": [{"date": d.isoformat(), "value": float(v), "test": i,
                            "dated": self.is_dated(k)}
                           for k, (d, v, i) in enumerate(zip(self.dates, self.values,
                                                             self.test_ids))],
                "model": "least-squares straight line, ISO/TS 28037:2010 clause 6",
                "drift_per_year": self.drift, "u_drift_per_year": self.u_drift,
                "level": self.level, "tolerance": self.tolerance,
                "crossing": iso(self.crossing), "u_crossing_days": self.u_crossing_days,
                "recalibrate_by": iso(self.recalibrate_by)}

    def __str__(self) -> str:
        from axiscal.report.labels import unit_text

        unit = unit_text(self.unit)   # µm, as every report writes it
        lines = [f"{self.parameter} over {len(self.values)} tests "
                 f"({self.dates[0]:%Y-%m-%d} … {self.dates[-1]:%Y-%m-%d})"
                 if self.dates else f"{self.parameter}: no tests"]
        if self.undated:
            lines.append(f"  {self.undated} test(s) without a date in the file (the day stored "
                         "shown instead) left out of the drift fit")
        if self.drift is not None:
            lines.append(f"  drift {self.drift_text()} (standard uncertainty), level now "
                         f"{self.level:.4g} {unit}")
        elif len(self.values) - self.undated < 3:
            lines.append("  no drift estimate: three tests at least are needed")
        else:
            lines.append("  no drift estimate: the tests were all taken on one date; a "
                         "drift needs tests on different dates")
        if self.tolerance is not None and self.drift is not None:
            if self.crossing is not None:
                lines.append(f"  reaches the tolerance {self.tolerance:g} {unit} on "
                             f"{self.crossing:%Y-%m-%d} ± {self.u_crossing_days:.0f} days; "
                             f"recalibrate by {self.recalibrate_by:%Y-%m-%d} (k = 2)")
            else:
                lines.append(f"  the fitted line does not reach {self.tolerance:g} {unit}")
        return "\n".join(lines)


def fit_trend(parameter: str, dates, values, unit: str, tolerance: float | None = None,
              test_ids=(), dated=()) -> Trend:
    """Fit the drift of ``values`` (at ``dates``) and predict when it reaches ``tolerance``.

    ``dated``: per point, whether its date is the one its file gave; a point without
    (False) is kept in the trend, marked, and left out of the fit (module docstring).

    Examples
    --------
    Four yearly tests rising 1 µm a year from 5 µm, with ±0.1 µm scatter, against 10 µm:

    >>> d = [dt.datetime(2020 + k, 1, 1) for k in range(4)]
    >>> t = fit_trend("E", d, [5.0, 6.1, 6.9, 8.0], "um", tolerance=10)
    >>> round(t.drift, 2), t.crossing.year
    (0.98, 2025)
    """
    v = np.asarray(values, dtype=float)
    dates = tuple(dates)
    if len(dates) != v.size:
        raise InputError("as many dates as values are needed")
    if tolerance is not None and not (math.isfinite(tolerance) and 0 < tolerance <= 1e100):
        # a tolerance is the permissible size of a parameter, so positive: the parameters of
        # ISO 230-2:2014 (E, A, R, B, M) are ranges and spans; 1e100 is _parse.MAX_MAGNITUDE
        raise InputError(f"tolerance = {tolerance!r}: a positive finite number (up to 1e100) "
                         "in the parameter's unit")
    dated = tuple(bool(d) for d in dated)
    if dated and len(dated) != v.size:
        raise InputError("as many dated flags as values are needed")
    base = dict(parameter=parameter, dates=dates, values=v, unit=unit, tolerance=tolerance,
                test_ids=tuple(test_ids), dated=dated if not all(dated) else ())
    if dated:                                   # the fit: the tests with a date of their own
        dates = tuple(d for d, k in zip(dates, dated) if k)
        v = v[np.asarray(dated, dtype=bool)]
    if v.size < 3:
        return Trend(drift=None, u_drift=None, level=None, crossing=None,
                     u_crossing_days=None, recalibrate_by=None, **base)
    t0 = dates[0]
    # a test's date is a day: tests stored minutes apart on one day (no date in their files)
    # are one date, not a drift of millions of µm a year
    t = np.array([(d.toordinal() - t0.toordinal()) * 86400.0 / _YEAR for d in dates])
    tm = t.mean()
    x = t - tm
    sxx = float((x ** 2).sum())
    if sxx == 0:
        return Trend(drift=None, u_drift=None, level=None, crossing=None,
                     u_crossing_days=None, recalibrate_by=None, **base)
    a = float(v.mean())
    b = float((x * (v - a)).sum() / sxx)
    res = v - (a + b * x)
    s2 = float((res ** 2).sum() / (v.size - 2))
    ua, ub = math.sqrt(s2 / v.size), math.sqrt(s2 / sxx)
    level = a + b * x[-1]
    crossing = u_days = cautious = None
    if tolerance is not None and b != 0 and (tolerance - level) / b > 0:
        tc = tm + (tolerance - a) / b                 # years after t0
        if tc < 1000:
            # the same law of propagation, written so that no square overflows
            u_tc = math.hypot(ua / b, (tolerance - a) / b * ub / b)
            crossing = t0 + dt.timedelta(days=tc * 365.25)
            u_days = u_tc * 365.25
            cautious = t0 + dt.timedelta(days=max(t[-1], tc - 2 * u_tc) * 365.25)
    return Trend(drift=b, u_drift=ub, level=level, crossing=crossing, u_crossing_days=u_days,
                 recalibrate_by=cautious, **base)


@dataclass(frozen=True)
class Comparison:
    """Two tests of one axis side by side: every parameter and the per-target difference."""

    first: int
    second: int
    rows: tuple                   # (name, first, second, change, unit)
    targets: np.ndarray | None    # common targets (ISO 230-2)
    difference: np.ndarray | None  # second − first mean bidirectional deviation at them
    target_unit: str = ""
    unit: str = ""

    def as_dict(self) -> dict:
        return {"first": self.first, "second": self.second,
                "parameters": [{"name": n, "first": a, "second": b, "change": c, "unit": u}
                               for n, a, b, c, u in self.rows],
                "targets": None if self.targets is None else self.targets.tolist(),
                "difference": None if self.difference is None else self.difference.tolist(),
                "target_unit": self.target_unit, "unit": self.unit}

    def __str__(self) -> str:
        from axiscal.report.labels import unit_text

        w = max([16, *(len(n) + 2 for n, *_ in self.rows)])   # "iso230-2:2006:R_down" too
        lines = [f"{'parameter':<{w}}{'test ' + str(self.first):>14}"
                 f"{'test ' + str(self.second):>14}{'change':>12}"]
        for n, a, b, c, u in self.rows:
            f = (lambda v: "—" if v is None else f"{v:.3f}")
            lines.append(f"{n:<{w}}{f(a):>14}{f(b):>14}{f(c):>12} {unit_text(u)}")
        return "\n".join(lines)


def compare_tests(first, second) -> Comparison:
    """Compare two :class:`~axiscal.store.history.StoredTest` of the same kind and axis."""
    s1, s2 = first.summary, second.summary
    if s1.id == s2.id:
        raise InputError(f"test {s1.id} compared with itself: choose two different tests")
    for s in (s1, s2):        # a withdrawn test leaves compares (axiscal.store.corrections)
        if getattr(s, "withdrawn", ""):
            raise InputError(f"test {s.id} is withdrawn ({s.withdrawn}); reinstate it to "
                             "compare it")
    if s1.kind != s2.kind:
        raise InputError(f"test {s1.id} is {s1.kind}, test {s2.id} is {s2.kind}: compare tests "
                         "of one kind")
    if (s1.machine, s1.axis) != (s2.machine, s2.axis):
        raise InputError(f"test {s1.id} is {s1.machine} {s1.axis}, test {s2.id} is "
                         f"{s2.machine} {s2.axis}: compare two tests of one axis")
    names = list(dict.fromkeys([*s1.parameters, *s2.parameters]))
    rows = []
    for n in names:
        a = s1.parameters.get(n, (None, ""))
        b = s2.parameters.get(n, (None, ""))
        change = None if a[0] is None or b[0] is None else b[0] - a[0]
        rows.append((n, a[0], b[0], change, a[1] or b[1]))
    targets = diff = None
    tu = unit = ""
    if s1.kind == "iso230-2":
        t1, t2 = np.asarray(first.result["targets"]), np.asarray(second.result["targets"])
        m1 = np.asarray(first.result["mean_bi"], dtype=float)
        m2 = np.asarray(second.result["mean_bi"], dtype=float)
        common, i1, i2 = np.intersect1d(np.round(t1, 9), np.round(t2, 9), return_indices=True)
        if common.size:
            targets, diff = common, m2[i2] - m1[i1]
        tu, unit = first.result.get("target_unit", ""), first.result.get("deviation_unit", "")
    return Comparison(s1.id, s2.id, tuple(rows), targets, diff, tu, unit)
