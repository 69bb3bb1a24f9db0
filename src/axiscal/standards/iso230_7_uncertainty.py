"""Uncertainty of the ISO 230-7:2015 error motion values measured with the five-DOF optical
sensor of "Method for simultaneous measurement of five DOF motion errors of a rotary axis using a
single-mode fiber-coupled laser" (Optics Express, 2018; below "the five-DOF method").

The figures (:mod:`axiscal.store.kinds` stores them as ``<motion>_total``,
``<motion>_synchronous``, ``<motion>_asynchronous``; ``<motion>`` is ``radial_Y``, ``radial_X``,
``axial``, ``tilt_X`` or ``tilt_Y``) are all *ranges* of readings of one channel
(:mod:`axiscal.standards.iso230_7`, ISO 230-7:2015 §3 and §5.4):

- total error motion value: the peak-to-valley of every run about the polar-chart centre (the
  least-squares centre: the once-per-turn fundamental removed for radial and tilt motion);
- synchronous value: the peak-to-valley of the mean over the R runs at each angle;
- asynchronous value: the largest spread across the runs at one angle.

The evaluation is linear in the readings before the range is taken (the mean, the fitted
fundamental and the centre are least-squares projections), so each contributor of a channel acts
on a figure as follows (ISO/TR 230-9:2005 general form: uncorrelated inputs, sensitivity 1 in the
figure's unit, u_c the root sum of squares, U = k·u_c; JCGM 100:2008 eq. 10):

- ``u_RES`` — the detector's resolution r (the five-DOF method §3, "Measurement resolution":
  εy = ΔZ_PSD1/(2 f1) eq. 2, εx = (ΔZ_QD1 − ΔZ_QD2)/(2h) eq. 6, δ = ΔQD/2 eqs. 4-5): each
  reading uniform within ±r/2 (JCGM 100:2008 §4.3.7), a range is the difference of two readings:
  u = √2·r/√12, on every figure. Removing the least-squares fundamental and centre is a
  projection, which does not increase the variance of a difference of two values (sensitivity
  ≤ 1; 1 is taken).
- ``u_CAL`` — the scale calibration of the channel, a relative standard uncertainty c: a figure F
  read with gain 1 + g is F(1 + g) (the projections commute with a gain), u = c·F, each figure
  with its own F.
- ``u_DRIFT`` — the reading noise and drift of a still set-up, σ per reading (the five-DOF method
  §3.2, the 60 min stability experiment after the common-path compensation of eqs. 7-9): a
  difference of two readings, u = √2·σ, on the total and asynchronous values, and on the
  synchronous value of a single run.
- ``u_REPEAT`` (measured, R ≥ 2 runs) — the synchronous value is the mean of R runs (ISO
  230-7:2015 §3): its random part is the run-to-run scatter s (pooled standard deviation across
  the runs at each angle, Type A, JCGM 100:2008 §4.2) averaged over R, a difference of two means:
  u = √2·s/√R. s holds the instrument's noise and drift as they vary from run to run, so u_DRIFT
  is not added to the synchronous value again.
- ``u_XTALK`` — the crosstalk pattern the mounting leaves in the channel (the five-DOF method
  §3.3, "Analysis of the results": the comparison with an autocollimator differed by up to
  3.9 arcsec, ascribed to crosstalk), given as its peak-to-valley X after the fundamental is
  removed (``axiscal motion simulate`` quantifies it for a set-up): a pattern added to every run
  changes a range by at most ±X (range(a + b) lies within range(a) ± range(b)), rectangular,
  u = X/√3 on the total and synchronous values; it repeats in every run, so it cancels in the
  asynchronous value (sensitivity 0).
- ``u_REF`` — the error motion of the reference rotary axis that carries the two retro-reflectors
  (the five-DOF method §2.1: it counter-rotates on the target axis, so its own motion adds to
  the measured one), given as its total error motion value T: ±T on every figure, rectangular,
  u = T/√3.

An artefact: ISO 230-7 radial and axial error motion measured with displacement sensors against
a precision sphere or cylinder contains the artefact's roundness (form) error unless it is
separated by a reversal or multi-probe technique, so the standard asks for an artefact whose
form error is small against the motion measured, or its separation. The five-DOF method has no
round artefact: the target is a pair of corner cubes on the reference axis, whose beam deviation
(3 arcsec, §3) is constant over the turn and does not enter a range; the role of the artefact's
form error is taken by the reference axis's error motion (``u_REF``).

Not included (notes of the budget say so): the detectors' non-linearity over their range (the
five-DOF method §3.1: linear fits against a grating ruler and an autocollimator left σ 0.76 µm
over ±80 µm and 0.58 arcsec over ±120 arcsec; a figure measured near the detector's centre sees
less), and the upward bias noise gives a peak-to-valley of many readings (a figure is the range
of what was read, noise included).

References
----------
ISO 230-7:2015, Test code for machine tools — Part 7: Geometric accuracy of axes of rotation,
§3 (total, synchronous, asynchronous error motion; fundamental), §5.4 (polar plot, PC centre).
ISO/TR 230-9:2005, Test code for machine tools — Part 9: Estimation of measurement uncertainty
for machine tool tests according to series ISO 230, basic equations. JCGM 100:2008 (GUM) §4.2,
§4.3.7, §5.1.2 eq. 10. "Method for simultaneous measurement of five DOF motion errors of a
rotary axis using a single-mode fiber-coupled laser", Optics Express (2018), §2, §3, §3.1-§3.3.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Mapping

import numpy as np

from axiscal.errors import ConfigError
from axiscal.physics.five_dof import resolutions
from axiscal.standards.iso230_9 import Contributor, combine
from axiscal.standards.iso230_9_inputs import BudgetInput
from axiscal.units import ARCSEC, UM

__all__ = ["MOTION_INPUTS", "MOTION_CHANNEL", "STABILITY_SIGMA", "motion_budget",
           "motion_parameters"]

#: The ISO 230-7 error motion of each channel of the five-DOF method (δ in µm, ε in arcsec).
MOTION_CHANNEL = {"radial Y": "dy", "radial X": "dx", "axial": "dz", "tilt X": "ex",
                  "tilt Y": "ey"}
#: The five-DOF method §3.2: standard deviation of each reading of the 60 min stability
#: experiment after the drift compensation (arcsec, µm); δx is not measured there.
STABILITY_SIGMA = {"ez": 0.05, "ey": 0.06, "ex": 0.19, "dy": 0.04, "dz": 0.03}

_DESIGN = resolutions(0.2, 0.03, 0.5e-6, 0.08e-6)       # the five-DOF method §3: f1, h, PSD, QD
_RES = {"dx": _DESIGN.displacement / UM, "dy": _DESIGN.displacement / UM,
        "dz": _DESIGN.displacement / UM, "ex": _DESIGN.tilt_x / ARCSEC,
        "ey": _DESIGN.angular / ARCSEC}
_WHAT = {"dx": "δx (radial X)", "dy": "δy (radial Y)", "dz": "δz (axial)",
         "ex": "εx (tilt about X)", "ey": "εy (tilt about Y)"}
_DESIGN_RULE = ("the five-DOF method's sensor design (Optics Express 2018 §3: f1 = "
                "200 mm, h = 30 mm, PSD 0.5 µm, QD 0.08 µm); the data file does not state it")


def _unit(ch: str) -> str:
    return "arcsec" if ch.startswith("e") else "µm"


def _inputs() -> dict:
    out = {}
    for ch, r in _RES.items():
        out[f"resolution_{ch}"] = (f"resolution of {_WHAT[ch]}", _unit(ch), round(r, 4),
                                   _DESIGN_RULE)
    out["calibration"] = ("relative standard uncertainty of each detector's scale calibration",
                          "%", 1.0, "1 % of the figure (the source's calibration, "
                          "§3.1, states fits, not a scale uncertainty)")
    for ch in _RES:
        sigma = STABILITY_SIGMA.get(ch, STABILITY_SIGMA["dy"])
        src = ("as δy, the same quadrant detector; the source measures no δx" if ch == "dx"
               else "the five-DOF method §3.2, 60 min stability σ")
        out[f"drift_{ch}"] = (f"reading noise and drift σ of {_WHAT[ch]}, still set-up",
                              _unit(ch), sigma, f"{src}; the data file holds no "
                              "still-set-up record")
    for ch in _RES:
        out[f"crosstalk_{ch}"] = (f"crosstalk left in {_WHAT[ch]} (peak-to-valley)", _unit(ch),
                                  0.0, "0, not evaluated: axiscal motion simulate "
                                  "quantifies a set-up's crosstalk residual")
    for group, unit in (("radial", "µm"), ("axial", "µm"), ("tilt", "arcsec")):
        out[f"reference_{group}"] = (f"{group} total error motion of the reference rotary axis",
                                     unit, 0.0, "0, not stated by the source: take it "
                                     "from the reference axis's own ISO 230-7 test")
    out["k"] = ("coverage factor", "", 2.0, "ISO/TR 230-9:2005: k = 2")
    return out


#: key -> (label, unit, default, rule of the default). Every default is an assumption, marked so
#: on every budget that takes it: set each in the user configuration's ``[motion_uncertainty]``.
MOTION_INPUTS = _inputs()
#: How a user sets an input.
SET_WITH = "[motion_uncertainty] {key} in the user configuration"
_REF_GROUP = {"dx": "radial", "dy": "radial", "dz": "axial", "ex": "tilt", "ey": "tilt"}


def motion_parameters(result) -> dict:
    """The stored figures of an ISO 230-7 result, name -> (value, unit): for each error motion
    its total, synchronous and (R ≥ 2 runs) asynchronous value in µm or arcsec, as ``axiscal
    motion analyze --json`` writes them (:func:`axiscal.io.simulation_results.iso230_7_json`)."""
    out = {}
    for m in result.motions:
        scale, unit = (UM, "um") if m.kind == "length" else (ARCSEC, "arcsec")
        key = m.name.replace(" ", "_")
        for fig in ("total", "synchronous", "asynchronous"):
            v = getattr(m, fig)
            if math.isfinite(v):
                out[f"{key}_{fig}"] = (v / scale, unit)
    return out


def motion_budget(result, table: Mapping[str, float] | None = None):
    """The uncertainty of every ISO 230-7 error motion value of a five-DOF measurement.

    Parameters
    ----------
    result : Iso230_7Result
        :func:`axiscal.standards.iso230_7.evaluate`'s result (SI).
    table : mapping, optional
        The user configuration's ``[motion_uncertainty]`` table (keys of :data:`MOTION_INPUTS`,
        each in its unit); absent inputs take the defaults, marked assumed.

    Returns
    -------
    UncertaintyBudget
        Parameters as :func:`motion_parameters` names them; each contributor's u in the unit
        of the figures it acts on (µm for radial and axial, arcsec for tilt motion).

    Raises
    ------
    ConfigError
        A key that is no input, or a value that is not a finite number ≥ 0 (k > 0).

    Notes
    -----
    For a figure F of channel c (module docstring; ISO 230-7:2015 §3, ISO/TR 230-9:2005, JCGM
    100:2008 eq. 10):

    u_c(total)² = (√2·r/√12)² + (c·F)² + (√2·σ)² + (X/√3)² + (T/√3)²,
    u_c(synchronous)² = (√2·r/√12)² + (c·F)² + (√2·s/√R)² + (X/√3)² + (T/√3)²
    (√2·σ in place of √2·s/√R for one run), u_c(asynchronous)² = (√2·r/√12)² + (c·F)² +
    (√2·σ)² + (T/√3)²; U = k·u_c.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> runs = np.array([[0.0, 1.0, 0.0, -1.0], [0.2, 1.0, -0.2, -1.0]]) * 1e-6
    >>> m = SimpleNamespace(name="radial Y", kind="length", total=2.0e-6, synchronous=2.0e-6,
    ...                     asynchronous=0.2e-6, runs=runs)
    >>> b = motion_budget(SimpleNamespace(motions=(m,), n_runs=2))
    >>> [round(b.U(f"radial_Y_{f}"), 4) for f in ("total", "synchronous", "asynchronous")]
    [0.1244, 0.2066, 0.1178]

    By hand (defaults: r = 0.04 µm, c = 1 %, σ = 0.04 µm): u_RES = √2·0.04/√12 = 0.01633 µm
    on all three. Total F = 2 µm: u_CAL = 0.02, u_DRIFT = √2·0.04 = 0.05657, u_c = √(0.01633² +
    0.02² + 0.05657²) = 0.06218, U = 0.1244 µm. Synchronous (two runs): the variances across
    the runs at the four angles are 0.02, 0, 0.02, 0 µm², s = √0.01 = 0.1 µm, u_REPEAT =
    √2·0.1/√2 = 0.1, u_c = √(0.01633² + 0.02² + 0.1²) = 0.10328, U = 0.2066 µm. Asynchronous
    F = 0.2 µm: u_CAL = 0.002, u_c = √(0.01633² + 0.002² + 0.05657²) = 0.05891, U = 0.1178 µm.
    """
    table = _checked(table)
    v = {key: float(table.get(key, spec[2])) for key, spec in MOTION_INPUTS.items()}
    clause = "ISO 230-7:2015 §3; ISO/TR 230-9:2005"
    src = "Optics Express 2018 (five-DOF method)"
    c, params, used = [], [], set()
    cal = v["calibration"] / 100.0
    for m in result.motions:
        ch, key = MOTION_CHANNEL[m.name], m.name.replace(" ", "_")
        scale = UM if m.kind == "length" else ARCSEC
        unit = _unit(ch)
        figs = {f: getattr(m, f) / scale for f in ("total", "synchronous", "asynchronous")
                if math.isfinite(getattr(m, f))}
        names = {f: f"{key}_{f}" for f in figs}
        params += list(names.values())
        runs = np.asarray(m.runs, float) / scale
        n = runs.shape[0]
        r, sigma = v[f"resolution_{ch}"], v[f"drift_{ch}"]
        xt, ref = v[f"crosstalk_{ch}"], v[f"reference_{_REF_GROUP[ch]}"]
        used |= {f"resolution_{ch}", f"drift_{ch}", f"crosstalk_{ch}",
                 f"reference_{_REF_GROUP[ch]}"}
        c.append(Contributor(f"u_RES,{ch}", f"resolution of {_WHAT[ch]}, two readings",
                             math.sqrt(2) * r / math.sqrt(12), "rectangular",
                             f"{src} §3; {clause}", f"√2 × {r:g} {unit} / √12",
                             tuple(names.values())))
        for f, F in figs.items():
            c.append(Contributor(f"u_CAL,{names[f]}", f"scale calibration of {_WHAT[ch]} on "
                                 f"the {f} value", cal * abs(F), "normal", f"{src} §3.1; {clause}",
                                 f"{v['calibration']:g} % × {abs(F):.4g} {unit}", (names[f],)))
        drift_on = [names[f] for f in figs if f != "synchronous" or n < 2]
        c.append(Contributor(f"u_DRIFT,{ch}", f"reading noise and drift of {_WHAT[ch]}, two "
                             "readings", math.sqrt(2) * sigma, "normal", f"{src} §3.2; {clause}",
                             f"√2 × σ {sigma:g} {unit}", tuple(drift_on)))
        if n >= 2:
            s = _pooled_sd(runs)
            c.append(Contributor(f"u_REPEAT,{ch}", f"run-to-run scatter of {_WHAT[ch]} in the "
                                 f"mean of {n} runs (measured)", math.sqrt(2) * s / math.sqrt(n),
                                 "normal", f"ISO 230-7:2015 §3 (synchronous: the mean); JCGM "
                                 f"100:2008 §4.2", f"√2 × s {s:.4g} {unit} / √{n}",
                                 (names["synchronous"],)))
        if xt > 0:
            c.append(Contributor(f"u_XTALK,{ch}", f"crosstalk left in {_WHAT[ch]}",
                                 xt / math.sqrt(3), "rectangular", f"{src} §3.3; {clause}",
                                 f"± {xt:g} {unit} / √3", tuple(names[f] for f in figs
                                                              if f != "asynchronous")))
        if ref > 0:
            c.append(Contributor(f"u_REF,{ch}", "error motion of the reference rotary axis",
                                 ref / math.sqrt(3), "rectangular", f"{src} §2.1; {clause}",
                                 f"± {ref:g} {unit} / √3", tuple(names.values())))
    inputs = tuple(BudgetInput(key, label, v[key], unit, key not in table,
                               SET_WITH.format(key=key),
                               rule if key not in table else "")   # given: said by the "given" beside it
                   for key, (label, unit, _, rule) in MOTION_INPUTS.items()
                   if key in used or key in ("calibration", "k"))
    inputs += tuple(_measured(result))
    notes = _notes(inputs) + (
        "not included: the detectors' non-linearity over their range (Optics Express 2018 "
        "§3.1: σ 0.76 µm over ±80 µm, 0.58 arcsec over ±120 arcsec), the upward bias noise "
        "gives a peak-to-valley of many readings, and the sampling of R runs (more runs can "
        "only widen a total or asynchronous value)",
        "εz (angular positioning) is not an error motion value of ISO 230-7 and has no U here")
    return replace(combine(c, "µm or arcsec (the figure's)", v["k"], tuple(params), notes),
                   inputs=inputs, method="ISO/TR 230-9:2005 general form as axiscal reads it "
                   "for the five-DOF method; GUM eq. 10 (root sum of squares)")


#: The assumed inputs in groups, each said once (prefix of the keys, what the default is).
_GROUPS = (("resolution_", "assumed from the five-DOF method's sensor design (Optics Express "
            "2018 §3), the data file not stating it"),
           ("drift_", "assumed from the five-DOF method's 60 min stability experiment (Optics "
            "Express 2018 §3.2), the data file holding no still-set-up record"),
           ("calibration", "assumed"),
           ("crosstalk_", "assumed 0, so not included until given"),
           ("reference_", "assumed 0, so not included until given"))


def _notes(inputs) -> tuple:
    """The assumed inputs in plain words, a note per group with its values and keys."""
    out = []
    for prefix, why in _GROUPS:
        group = [i for i in inputs if i.assumed and i.name.startswith(prefix)]
        if group:
            values = "; ".join(f"{i.label} {i.value_text}" for i in group)
            keys = ", ".join(i.name for i in group)
            out.append(f"{why}: {values}; set with {keys} in [motion_uncertainty] of the user "
                       "configuration")
    return tuple(out)


def _checked(table) -> dict:
    """The ``[motion_uncertainty]`` table by the budgets' one rule
    (:func:`~axiscal.standards.iso230_9_entry.checked_table`)."""
    from axiscal.standards.iso230_9_entry import checked_table

    return checked_table(table, MOTION_INPUTS, "[motion_uncertainty]")


def _pooled_sd(runs) -> float:
    """s: the square root of the mean over the angles of the variance across the runs (n − 1)."""
    return float(np.sqrt(np.mean(np.var(runs, axis=0, ddof=1))))


def _measured(result):
    """The run-to-run scatter s of each channel, as a measured input (R ≥ 2)."""
    for m in result.motions:
        runs = np.asarray(m.runs, float)
        if runs.shape[0] < 2:
            continue
        ch = MOTION_CHANNEL[m.name]
        scale = UM if m.kind == "length" else ARCSEC
        yield BudgetInput(f"scatter_{ch}", f"run-to-run scatter s of {_WHAT[ch]}",
                          float(f"{_pooled_sd(runs / scale):.4g}"), _unit(ch), False,
                          "nothing: measured from the file's runs",
                          f"measured: pooled over {runs.shape[1]} angles of {runs.shape[0]} runs")
