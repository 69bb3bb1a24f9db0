"""Thermal effects on machine tools by ISO 230-3:2020: the figures of its tests.

ISO 230-3:2020, *Test code for machine tools — Part 3: Determination of thermal effects*, defines
four tests (its public scope): the environmental temperature variation error (ETVE) test, the
thermal distortion caused by rotating spindles, the thermal distortion caused by moving linear
axes (Clause 7: NC machines only; axes up to 2 000 mm, a representative 2 000 mm of a longer
axis) and the thermal distortion caused by rotary motion of components. They correspond to the
drift test of ISO/TR 16015:2003, A.4.2.

This module evaluates a :class:`~axiscal.standards.iso230_3_data.ThermalLog`; pure: no I/O, no
clock, no randomness. Every figure is a :class:`ThermalFigure` holding its value, a bound U of
its measurement uncertainty, its unit and its clause.

What the figures are (axiscal's reading; the clause text was not available to the project, so
the figure names follow the quantities the public scope and the test names state):

* ETVE (Clause 5): per logged direction X, Y, Z the range (max − min) of the relative
  displacement of tool and table over the log, and each temperature's range.
* Spindle (Clause 6): five sensors on a test mandrel: X1, Y1 near the spindle nose, X2, Y2 a
  distance l further along the mandrel, Z on its end. Drift relative to the first reading::

      δX = X1,  δY = Y1,  δZ = Z,  A = (Y2 − Y1)/l (tilt about X),  B = (X1 − X2)/l (about Y)

  (right-hand rotations; sensor 2 lies at −l along Z from sensor 1, so a rotation B moves it by
  −l·B in X and a rotation A by +l·A in Y). For each: the largest drift while running (signed),
  the drift at the end of the run, and after the stop the drift at the end and its change
  during the stop.
* Linear axis (Clause 7): the positioning error at P1 and P2 near both ends, measured again and
  again while the axis cycles; its drift at each target relative to the first measurement (the
  largest while running, signed, and at the end of the run), and the axis's growth between them
  ``G = δ(P2) − δ(P1)`` (largest, and per metre of P2 − P1).
* Rotary motion of components (Clause 8): a rotary table turning (its speed a fraction of its
  maximum, constant or a programme) is the load; five sensors on an artefact on the table (a
  test mandrel or cylinder on its axis): X1, Y1 at its reference point, X2, Y2 a distance l
  further along it, Z on its end, read against the spindle side. The drift of the table's
  artefact relative to the tool in X, Y, Z and its two tilts, by the same equations and figures
  as the spindle test (axiscal's reading: the public scope names the test, not its layout).

Uncertainty: the reading noise σ of each channel is estimated from its sample-to-sample steps
(:func:`~axiscal.standards.iso230_3_data.noise_sigma`). A drift is a difference of two readings,
u = √2·σ, reported with k = 2; the largest of n noisy drifts may exceed the true one by up to
about σ·√(2 ln n) more (the expected maximum of n normal deviates), which U of an extreme adds.
Tilts divide by l. Sensor calibration and set-up errors are not in U (a stated gap).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError, one_line
from axiscal.standards.iso230_3_data import TESTS, ThermalLog, check_log, noise_sigma

__all__ = ["ThermalFigure", "ThermalResult", "evaluate_thermal", "evaluate_etve", "drift_series",
           "evaluate_spindle", "evaluate_linear", "evaluate_rotary", "signed_extreme",
           "e_ve_from_etve"]

_UNITS = {"length": ("µm", 1e6), "angle": ("µrad", 1e6), "temperature": ("K", 1.0),
          "ratio": ("µm/m", 1e6), "time": ("h", 1 / 3600)}


@dataclass(frozen=True)
class ThermalFigure:
    """One figure of an ISO 230-3 test.

    Attributes
    ----------
    name : str
        Key (``delta_X_max_run``).
    label : str
        What it is, in words.
    value : float
        SI: m, rad, K, 1 (growth per length) or s.
    uncertainty : float or None
        Bound U of the value's measurement uncertainty, same unit (None where not estimated).
    kind : {"length", "angle", "temperature", "ratio", "time"}
    clause : str
    """

    name: str
    label: str
    value: float
    uncertainty: float | None
    kind: str
    clause: str

    @property
    def unit(self) -> str:
        """The display unit (µm, µrad, K, µm/m, h)."""
        return _UNITS[self.kind][0]

    def shown(self) -> tuple[float, float | None]:
        """(value, U) in the display unit."""
        k = _UNITS[self.kind][1]
        return self.value * k, None if self.uncertainty is None else self.uncertainty * k

    def __str__(self) -> str:
        v, u = self.shown()
        tail = f" ± {u:.3g}" if u is not None else ""
        return f"{self.label}: {v:.4g}{tail} {self.unit}"


@dataclass(frozen=True)
class ThermalResult:
    """The figures of one ISO 230-3 test.

    Attributes
    ----------
    test : str
    clause : str
    figures : tuple of ThermalFigure
    duration : float, s
    run_end : float or None, s
    notes : tuple of str
    """

    test: str
    clause: str
    figures: tuple[ThermalFigure, ...]
    duration: float
    run_end: float | None
    notes: tuple[str, ...] = ()

    def __getitem__(self, name: str) -> ThermalFigure:
        for f in self.figures:
            if f.name == name:
                return f
        raise KeyError(name)

    def to_dict(self) -> dict:
        """The documented JSON object of ``axiscal thermal evaluate --json``."""
        figs = []
        for f in self.figures:
            v, u = f.shown()
            figs.append({"name": f.name, "label": f.label, "value": round(v, 6),
                         "U": None if u is None else round(u, 6), "unit": f.unit,
                         "clause": f.clause})
        return {"test": self.test, "clause": self.clause, "duration_h": round(self.duration / 3600, 6),
                "run_end_h": None if self.run_end is None else round(self.run_end / 3600, 6),
                "figures": figs, "notes": list(self.notes)}

    def __str__(self) -> str:
        lines = [f"{self.clause} ({self.test} test), {self.duration / 3600:.3g} h"]
        lines += [f"  {f}" for f in self.figures]
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)


def signed_extreme(values) -> float:
    """The value of largest magnitude, with its sign (the first one on a tie).

    Examples
    --------
    >>> signed_extreme([0.0, 1.0, -3.0, 2.0])
    -3.0
    """
    v = np.asarray(values, dtype=float)
    return float(v[int(np.argmax(np.abs(v)))])


def evaluate_thermal(log: ThermalLog) -> ThermalResult:
    """Evaluate a thermal log by its test (see the module docstring)."""
    check_log(log)
    return {"etve": evaluate_etve, "spindle": evaluate_spindle, "linear": evaluate_linear,
            "rotary": evaluate_rotary}[log.test](log)


def evaluate_etve(log: ThermalLog) -> ThermalResult:
    """ETVE (ISO 230-3:2020 Clause 5): the range of each displacement and temperature.

    Examples
    --------
    >>> t = np.arange(0, 13 * 3600 + 1, 300.0)
    >>> x = 2e-6 * np.sin(2 * np.pi * t / 86400) + 1e-8 * (np.arange(t.size) % 3)
    >>> tr = 20 + 0.5 * np.sin(2 * np.pi * t / 86400) + 0.001 * (np.arange(t.size) % 3)
    >>> r = evaluate_etve(ThermalLog("etve", t, {"T_room": tr}, {"X": x}))
    >>> round(r["ETVE_X"].shown()[0], 2)   # 2 µm × (1 + sin 15°) + 0.02 µm
    2.54
    """
    _is(log, "etve")
    clause = TESTS["etve"]
    figs = []
    n = log.time.size
    for name, v in sorted(log.displacements.items()):
        s = noise_sigma(v)
        figs.append(ThermalFigure(f"ETVE_{name}", f"ETVE in {name}: range of the displacement",
                                  float(np.ptp(v)), _extreme_u(s, n, range_=True), "length", clause))
    figs += _temperature_ranges(log, clause)
    figs.append(ThermalFigure("duration", "duration of the log", log.duration, None, "time",
                              clause))
    return ThermalResult("etve", clause, tuple(figs), log.duration, log.run_end)


def evaluate_spindle(log: ThermalLog) -> ThermalResult:
    """Thermal distortion caused by a rotating spindle (ISO 230-3:2020 Clause 6).

    Drift in X, Y, Z and the tilts A, B from the five sensors (module docstring), while running
    and after the stop.
    """
    _is(log, "spindle")
    return _five_sensors(log, "mandrel", "the sensors nearest the spindle nose")


def evaluate_rotary(log: ThermalLog) -> ThermalResult:
    """Thermal distortion caused by rotary motion of components (ISO 230-3:2020 Clause 8): a
    rotary table turning.

    Drift in X, Y, Z and the tilts A, B of the artefact on the table, from its five sensors
    (module docstring), while turning and after the stop: the spindle test's figures.
    """
    _is(log, "rotary")
    return _five_sensors(log, "artefact on the table", "the sensors at the artefact's reference "
                         "point")


def _five_sensors(log: ThermalLog, what: str, near: str) -> ThermalResult:
    """The figures of a five-sensor test (spindle, Clause 6; rotary table, Clause 8)."""
    d = log.displacements
    l = float(log.sensor_spacing)
    series = drift_series(log)
    sig = {k: noise_sigma(d[k]) for k in d}
    sigma = {"X": sig["X1"], "Y": sig["Y1"], "Z": sig["Z"],
             "A": math.hypot(sig["Y1"], sig["Y2"]) / l, "B": math.hypot(sig["X1"], sig["X2"]) / l}
    words = {"X": "drift in X", "Y": "drift in Y", "Z": "drift in Z",
             "A": "tilt about X (YZ plane)", "B": "tilt about Y (ZX plane)"}
    clause = TESTS[log.test]
    figs = _drift_figures(log, series, sigma, words, clause)
    figs += _temperature_rises(log, clause)
    notes = (f"X and Y at {near}; tilts from the sensor pairs {l * 1e3:g} mm apart along the "
             f"{what}",)
    return ThermalResult(log.test, clause, tuple(figs), log.duration, log.run_end, notes)


def evaluate_linear(log: ThermalLog) -> ThermalResult:
    """Thermal distortion caused by moving a linear axis (ISO 230-3:2020 Clause 7).

    Drift of the positioning error at P1 and P2 and the growth G = δ(P2) − δ(P1) between them.
    """
    _is(log, "linear")
    p1, p2 = log.targets
    d = log.displacements
    s1, s2 = noise_sigma(d["P1"]), noise_sigma(d["P2"])
    series = drift_series(log)
    sigma = {"P1": s1, "P2": s2, "G": math.hypot(s1, s2)}
    words = {"P1": f"drift at P1 = {p1 * 1e3:g} mm", "P2": f"drift at P2 = {p2 * 1e3:g} mm",
             "G": "growth between P1 and P2"}
    clause = TESTS["linear"]
    figs = _drift_figures(log, series, sigma, words, clause)
    g = next(f for f in figs if f.name == "delta_G_max_run")
    span = abs(p2 - p1)
    figs.append(ThermalFigure("growth_per_length_max_run", "largest growth per metre of P2 − P1",
                              g.value / span, g.uncertainty / span, "ratio", clause))
    figs += _temperature_rises(log, clause)
    notes = [f"axis {log.axis or '?'}: P1 = {p1 * 1e3:g} mm, P2 = {p2 * 1e3:g} mm"]
    if span > 2.0 + 1e-9:
        notes.append("P2 − P1 exceeds 2 000 mm; Clause 7 takes a representative 2 000 mm of a "
                     "longer axis")
    return ThermalResult("linear", clause, tuple(figs), log.duration, log.run_end, tuple(notes))


def drift_series(log: ThermalLog) -> dict[str, np.ndarray]:
    """The quantities whose drift a test reports, over time (m or rad; not yet relative to the
    start): ETVE ``X``, ``Y``, ``Z`` as logged; spindle ``X, Y, Z, A, B`` from the five sensors
    (module docstring), the rotary test's alike; linear ``P1``, ``P2`` and the growth
    ``G = P2 − P1``. The one place these
    are derived: the evaluations and the thermal model (``compensation/thermal_model.py``) use it.
    """
    d = log.displacements
    if log.test in ("spindle", "rotary"):
        l = float(log.sensor_spacing)
        return {"X": d["X1"], "Y": d["Y1"], "Z": d["Z"],
                "A": (d["Y2"] - d["Y1"]) / l, "B": (d["X1"] - d["X2"]) / l}
    if log.test == "linear":
        return {"P1": d["P1"], "P2": d["P2"], "G": d["P2"] - d["P1"]}
    return dict(sorted(d.items()))


def e_ve_from_etve(log: ThermalLog, channel: str, start: float, duration: float) -> float:
    """E_VE (ISO 230-2:2014 Annex A.5) taken from an ETVE record, m.

    The range of one displacement channel over the window ``[start, start + duration]`` (the
    positioning test's duration). What it is and is not: the machine's response to the room in
    that direction at the ETVE set-up's place, over that time; it holds neither the drift of the
    positioning test's own instrument (laser, air compensation) nor the response elsewhere in the
    travel. A drift check (:mod:`axiscal.procedures.thermal`) measures the set-up itself.

    Parameters
    ----------
    log : ThermalLog, an ETVE test
    channel : str, ``"X"``, ``"Y"`` or ``"Z"``
    start, duration : float, s

    Examples
    --------
    >>> t = np.arange(0, 13 * 3600 + 1, 60.0)
    >>> log = ThermalLog("etve", t, {"T": 20 + 1e-3 * t / 3600}, {"X": 1e-6 * t / 3600})
    >>> round(e_ve_from_etve(log, "X", 3600.0, 7200.0) * 1e6, 6)
    2.0
    """
    _is(log, "etve")
    if channel not in log.displacements:
        raise InputError(f"E_VE from ETVE: no channel {one_line(repr(channel), 60)}; the log has "
                         f"{', '.join(sorted(log.displacements))}")
    if not duration > 0:
        raise InputError(f"E_VE from ETVE: duration {duration:g} s must be > 0")
    if start < log.time[0] - 1e-9 or start + duration > log.time[-1] + 1e-9:
        raise InputError(f"E_VE from ETVE: the window {start / 3600:g} h + {duration / 3600:g} h "
                         f"lies outside the log's {log.time[0] / 3600:g} to "
                         f"{log.time[-1] / 3600:g} h")
    m = (log.time >= start - 1e-9) & (log.time <= start + duration + 1e-9)
    if m.sum() < 2:
        raise InputError("E_VE from ETVE: fewer than 2 samples in the window")
    return float(np.ptp(log.displacements[channel][m]))


def _is(log: ThermalLog, test: str) -> None:
    if log.test != test:
        raise InputError(f"a {log.test} log given to the {test} evaluation")


def _extreme_u(sigma: float, n: int, range_: bool = False) -> float:
    """U of an extreme (or a range) of n readings with noise σ (module docstring)."""
    bias = sigma * math.sqrt(2 * math.log(max(n, 2)))
    return 2 * math.sqrt(2) * sigma + (2 * bias if range_ else bias)


def _drift_figures(log, series, sigma, words, clause) -> list[ThermalFigure]:
    run = log.running
    n = int(run.sum())
    figs = []
    for k, v in series.items():
        kind = "angle" if k in ("A", "B") else "length"
        d = v - v[0]
        s = sigma[k]
        figs.append(ThermalFigure(f"delta_{k}_max_run", f"largest {words[k]} while running",
                                  signed_extreme(d[run]), _extreme_u(s, n), kind, clause))
        end = int(np.flatnonzero(run)[-1])
        figs.append(ThermalFigure(f"delta_{k}_end_run", f"{words[k]} at the end of the run",
                                  float(d[end]), 2 * math.sqrt(2) * s, kind, clause))
        if end < v.size - 1:
            figs.append(ThermalFigure(f"delta_{k}_end_stop", f"{words[k]} at the end of the stop",
                                      float(d[-1]), 2 * math.sqrt(2) * s, kind, clause))
            figs.append(ThermalFigure(f"delta_{k}_recovery", f"change of the {words[k]} during "
                                      "the stop", float(d[-1] - d[end]), 2 * math.sqrt(2) * s,
                                      kind, clause))
    return figs


def _temperature_ranges(log, clause) -> list[ThermalFigure]:
    return [ThermalFigure(f"range_{name}", f"range of {name}", float(np.ptp(v)),
                          _extreme_u(noise_sigma(v), v.size, range_=True), "temperature", clause)
            for name, v in sorted(log.temperatures.items())]


def _temperature_rises(log, clause) -> list[ThermalFigure]:
    end = int(np.flatnonzero(log.running)[-1])
    return [ThermalFigure(f"rise_{name}", f"rise of {name} by the end of the run",
                          float(v[end] - v[0]), 2 * math.sqrt(2) * noise_sigma(v), "temperature",
                          clause)
            for name, v in sorted(log.temperatures.items())]
