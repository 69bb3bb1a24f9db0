"""Uncertainty of the ISO 230-1:2012 straightness of a linear axis's trajectory: the straightness
about the least-squares line (``straightness``, µm), about the minimum zone
(``straightness_min_zone``, µm) and the least-squares line's slope (``slope``, µm/m).

ISO/TR 230-9:2005 gives the general form (GUM: uncorrelated inputs, sensitivity coefficients,
u_c the root sum of squares, U = k·u_c with k = 2); ISO 230-1:2012 §8.2 measures straightness
against a reference straight line, a straightedge read by an indicator or the optical
straightedge of a laser's straightness reflector read by its interferometer (the same
measurement: M.A.V. Chapman, "Calibration of machine squareness", Method 3: "the direct
analogy between a mechanical straightedge with an indicator and a straightness reflector with
an interferometer"). The model below is axiscal's reading of those documents; no public text gives
a worked straightness budget, so each choice is stated.

Both straightness figures are a *range of residuals* (ISO 230-1:2012 §3.4.9: the largest minus
the smallest deviation from the reference line), so both take the same contributors, each with
its own figure where the contributor scales with it:

- ``u_REF`` — the reference's own form: the straightedge's calibrated straightness (or the
  straightness optics' calibration), a standard uncertainty ``reference_u`` entering every
  reading along the travel: sensitivity 1 on each straightness figure (normal, from a
  certificate). A straightedge used with reversal cancels its form; then give its reversal's
  residual instead.
- ``u_GAIN,LS``, ``u_GAIN,MZ``, ``u_GAIN,SLOPE`` — the instrument's gain (scale) error,
  bounded by ±g (relative), rectangular: a figure F read with gain 1 + g is F(1 + g), so
  u = |F|·g/√3; the slope is a ratio of readings to travel and scales alike.
- ``u_RES`` — the instrument's resolution r, each reading uniform within ±r/2: a range is a
  difference of two readings, u = √2·r/√12.
- ``u_NOISE`` — the reading noise σ, **measured from the data** (:func:`reading_noise`): from
  the readings repeated at one position (pooled standard deviation, JCGM 100:2008 §4.2.4) when
  the file has repeats, else from each reading's departure from the chord of its two
  neighbours (the second difference, which a straight or uniformly curved trajectory leaves at
  a constant: its spread is the noise's). A range of two readings: u = √2·σ.
- ``u_EVE`` — the environmental variation over the test, E_VE (µm): the range of the reading
  with the instrument at rest over the test's duration (a drift check, ISO 230-2:2014 Annex
  A.5). For a laser it holds what air turbulence and temperature gradients across the beam do
  to the reading, which no model predicts (Hewlett-Packard, "5528A Laser Measurement System
  User's Guide", Section 10, Straightness measurements, Environmental errors: a straightness
  measurement "is especially susceptible to environmental effects", seen as the reading
  drifting with the optics at rest). Rectangular over ±E_VE/2: u = E_VE/(2√3) on
  each straightness figure, and u = E_VE/(2√3)/L on the slope over the travel L. Not given, it
  is 0 and a note says U leaves it out (as the squareness budgets do).

The slope ``slope`` (µm/m) of the least-squares line: ``u_FIT`` the line fit's standard
uncertainty from its residuals (:func:`~axiscal.standards.iso230_9_geometry.slope_uncertainty`,
ISO 230-1:2012 §3.4.8; GUM H.3), measured; ``u_GAIN,SLOPE``; ``u_EVE,SLOPE``; and
``u_REF,SLOPE``, the reference's own direction (``reference_slope_u``, µm/m): a single
trajectory's slope is read against the reference as it was set up, whose direction is not
calibrated, so it is 0 unless the slope is read against a calibrated direction (the straightness
optics' slope accuracy of :func:`~axiscal.standards.iso230_9_geometry.squareness_budget`). The
noise and the resolution are in the fit's residuals already.

Not included (the budget's notes say so): a correction of the range's bias by the noise (the
range of noisy readings exceeds the true range by about the noise's own range; it is not
subtracted), the set-up's misalignment (removed with the reference line), and the machine's own
thermal drift, which is the measurand's.

References
----------
ISO 230-1:2012, Test code for machine tools — Part 1: Geometric accuracy of machines operating
under no-load or quasi-static conditions, §3.4.8, §3.4.9, §8.2. ISO/TR 230-9:2005, Test code for
machine tools — Part 9: Estimation of measurement uncertainty for machine tool tests according
to series ISO 230, basic equations. ISO 230-2:2014 Annex A.5 (E_VE). JCGM 100:2008 (GUM) §4.2.4
(pooled standard deviation), §4.3.7 (rectangular distribution), §5.1.2 eq. 10.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from axiscal.errors import ConfigError
from axiscal.standards.iso230_9 import Contributor, UncertaintyBudget, combine
from axiscal.standards.iso230_9_inputs import BudgetInput

__all__ = ["STRAIGHTNESS_INPUTS", "ReadingNoise", "reading_noise", "straightness_budget",
           "straightness_input_table"]

#: key -> (label, unit, default, rule of the default). Defaults are assumptions, marked so on
#: every budget that takes them: set each from the reference's and the instrument's certificates.
STRAIGHTNESS_INPUTS = {
    "reference_u": ("standard uncertainty of the reference's form (straightedge or straightness "
                    "optics calibration)", "µm", 0.5,
                    "a calibration certificate's U = 1 µm with k = 2"),
    "gain": ("bound of the instrument's gain (scale) error", "%", 0.5,
             "a straightness interferometer's or an electronic indicator's typical "
             "scale specification; set it from yours"),
    "resolution": ("resolution of the instrument", "µm", 0.1,
                   "an electronic indicator's; a laser straightness interferometer "
                   "reads to 0.01 µm"),
    "e_ve": ("environmental variation over the test (air turbulence, temperature "
             "gradients, drift)", "µm", 0.0,
             "not given, taken as 0 so U leaves it out: measure the reading's range with the "
             "instrument at rest over the test's duration (ISO 230-2:2014 Annex A.5) or "
             "declare it"),
    "reference_slope_u": ("standard uncertainty of the reference's direction", "µm/m", 0.0,
                          "0: the slope is read against the reference as it was set up; give "
                          "the optics' slope accuracy when read against a calibrated direction"),
    "k": ("coverage factor", "", 2.0, "ISO/TR 230-9:2005: k = 2"),
}
#: How a user sets an input.
SET_WITH = "[straightness_uncertainty] {key} in the user configuration"
#: The figures of a straightness test (:func:`axiscal.store.kinds.evaluate_file`'s parameters).
FIGURES = ("straightness", "straightness_min_zone")
_CLAUSE = "ISO 230-1:2012 §8.2; ISO/TR 230-9:2005 (axiscal's reading for straightness)"
#: The subscript of each straightness figure in a contributor's name, and the figure in words.
_SHORT = {"straightness": "LS", "straightness_min_zone": "MZ"}
_WORDS = {"straightness": "least-squares straightness",
          "straightness_min_zone": "minimum-zone straightness"}


@dataclass(frozen=True)
class ReadingNoise:
    """The reading noise of a straightness file, measured from its readings.

    Attributes
    ----------
    sigma : float, m
        Standard deviation of one reading (0 when it could not be measured).
    how : str
        How it was measured, in words ("" when it was not).
    degrees_of_freedom : int
        Of the estimate (0 when it was not measured).
    """

    sigma: float
    how: str
    degrees_of_freedom: int

    @property
    def measured(self) -> bool:
        return self.degrees_of_freedom > 0


def reading_noise(positions, deviations) -> ReadingNoise:
    """The standard deviation σ of one reading of a straightness trajectory, from the data.

    Parameters
    ----------
    positions : array_like, m
    deviations : array_like, m

    Returns
    -------
    ReadingNoise
        σ in m, with how it was measured and its degrees of freedom; not measured (σ = 0,
        ``degrees_of_freedom`` 0) with fewer than 4 distinct positions and no repeats.

    Notes
    -----
    With readings repeated at the positions (two runs in one file: at least as many degrees of
    freedom as the second differences would give): the pooled standard deviation
    s_p² = Σ_j Σ_i (y_ij − ȳ_j)² / Σ_j (n_j − 1) (JCGM 100:2008 §4.2.4). Else, over the
    distinct positions (a few repeated ones by their mean, of variance σ²/n_j): at each inner
    position i (sorted), the departure from the chord of its neighbours,
    e_i = y_i − (a_i·y_{i−1} + b_i·y_{i+1}), a_i = (x_{i+1} − x_i)/(x_{i+1} − x_{i−1}),
    b_i = 1 − a_i (a second difference: a straight trajectory leaves 0, a uniformly curved one
    a constant), and σ² = Σ(e_i − ē)² / E₁, where E₁ = tr(C) − 1ᵀC1/m is the expectation of
    that sum for white noise of unit variance (C = AVAᵀ, A the banded matrix of the e_i's
    weights, V the readings' relative variances, m their number; computed in O(n)), so σ² is
    unbiased for white noise at any spacing. The machine's own form
    within three readings that is not a uniform curvature counts as noise: a conservative σ.

    Examples
    --------
    >>> n = reading_noise([0, .1, .2, .3, .4], [0, 1e-6, 0, 1e-6, 0])
    >>> round(n.sigma * 1e6, 6), n.degrees_of_freedom    # 2.6667 µm² / (4.5 − 1/3) = 0.64 µm²
    (0.8, 2)
    >>> round(reading_noise([0, 0, .1, .1], [0, 2e-6, 1e-6, 1e-6]).sigma * 1e6, 9)  # √(2/2)
    1.0
    """
    x, y = np.asarray(positions, float), np.asarray(deviations, float)
    keys = np.round(x, 9)                       # one position: equal to the nanometre
    uniq, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    means = np.bincount(inverse, weights=y) / counts
    pooled = int(np.sum(counts - 1))
    if pooled and pooled >= uniq.size - 3:      # repeated runs: as many degrees of freedom
        ss = float(np.sum((y - means[inverse]) ** 2))
        return ReadingNoise(math.sqrt(ss / pooled), f"pooled standard deviation of the "
                            f"readings repeated at {int(np.sum(counts > 1))} positions "
                            f"({pooled} degrees of freedom)", pooled)
    x, y, v = uniq, means, 1.0 / counts         # a mean of n readings: variance σ²/n
    m = x.size - 2
    if m < 2:
        return ReadingNoise(0.0, "", 0)
    a = (x[2:] - x[1:-1]) / (x[2:] - x[:-2])
    b = 1 - a
    e = y[1:-1] - (a * y[:-2] + b * y[2:])
    # E₁ = tr(AVAᵀ) − 1ᵀAVAᵀ1/m, A banded (row i: −a_i, 1, −b_i at columns i, i+1, i+2), V the
    # readings' variances (1, or 1/n for a mean of n): O(n), never an n × n matrix
    column = np.zeros(x.size)
    column[:m] -= a
    column[1:m + 1] += 1.0
    column[2:] -= b
    trace = float(np.sum(a**2 * v[:-2] + v[1:-1] + b**2 * v[2:]))
    expected = trace - float(np.sum(v * column**2)) / m
    sigma = math.sqrt(float(np.sum((e - e.mean()) ** 2)) / expected)
    return ReadingNoise(sigma, f"the spread of the {m} second differences of successive "
                        "readings (each reading's departure from the chord of its neighbours)",
                        m - 1)


def straightness_budget(positions, deviations,
                        table: Mapping[str, float] | None = None) -> UncertaintyBudget:
    """The uncertainty of a straightness test's figures (ISO 230-1:2012), with its inputs.

    Parameters
    ----------
    positions : array_like, m
    deviations : array_like, m
        The trajectory's readings (:class:`axiscal.io.straightness.StraightnessData`).
    table : mapping, optional
        The user configuration's ``[straightness_uncertainty]`` table (keys of
        :data:`STRAIGHTNESS_INPUTS`, each in its unit); absent inputs take the defaults,
        marked assumed.

    Returns
    -------
    UncertaintyBudget
        Parameters ``straightness`` and ``straightness_min_zone`` (µm) and ``slope`` (µm/m: its
        contributors' u too); ``inputs`` lists the table's inputs and the two measured ones
        (the reading noise σ, the slope fit's u; shown to three significant digits, U made
        with their full values).

    Raises
    ------
    ConfigError
        A key that is no input, or a value that is not a finite number ≥ 0 (k > 0).

    Notes
    -----
    u_c(F)² = u_REF² + (F·g/√3)² + (√2·r/√12)² + (√2·σ)² + (E_VE/(2√3))² for F each straightness;
    u_c(S)² = u_FIT² + (S·g/√3)² + u_REF,SLOPE² + (E_VE/(2√3)/L)² for the slope S; U = k·u_c
    (module docstring; ISO/TR 230-9:2005 basic equations, JCGM 100:2008 eq. 10).

    Examples
    --------
    >>> b = straightness_budget([0, .1, .2, .3, .4], [0, 1e-6, 0, 1e-6, 0])
    >>> round(b.U("straightness"), 3), round(b.U("straightness_min_zone"), 3), b.U("slope")
    (2.475, 2.475, 4.0)

    By hand (defaults): both straightness figures are 1 µm (the least-squares line is flat,
    and no tilt narrows the zone), the slope 0. u_REF = 0.5 µm; gain 1 µm × 0.5 % / √3 =
    0.00289; resolution √2 × 0.1 µm / √12 = 0.0408; σ = 0.8 µm (:func:`reading_noise`), so
    √2σ = 1.1314; E_VE 0: u_c = √(0.25 + 0.0000083 + 0.00167 + 1.28) = 1.2376, U = 2.475 µm.
    Slope: the fit's residuals −0.4, 0.6, −0.4, 0.6, −0.4 µm over Σ(x − x̄)² = 0.1 m² give
    u_FIT = √(1.2/3/0.1) = 2 µm/m, the other terms 0: U = 4 µm/m.
    """
    from axiscal.standards.iso230_1 import straightness
    from axiscal.standards.iso230_9_geometry import slope_uncertainty

    from axiscal.standards.iso230_9_entry import checked_table

    table = checked_table(table, STRAIGHTNESS_INPUTS, "[straightness_uncertainty]")
    v = {key: float(table.get(key, default)) for key, (_, _, default, _) in
         STRAIGHTNESS_INPUTS.items()}
    x, y = np.asarray(positions, float), np.asarray(deviations, float)
    ls = straightness(x, y, "least_squares")          # the figures of the stored record
    mz = straightness(x, y, "minimum_zone")
    figures = {"straightness": ls.deviation * 1e6, "straightness_min_zone": mz.deviation * 1e6}
    slope = ls.line.slope * 1e6
    travel = float(np.ptp(x))
    noise = reading_noise(x, y)
    fit = slope_uncertainty(x, y) if x.size >= 3 else None
    g = v["gain"] / 100.0
    c = [Contributor("u_REF", "form of the reference (straightedge or straightness optics)",
                     v["reference_u"], "normal", _CLAUSE,
                     f"{v['reference_u']:g} µm (calibration, k = 1)", FIGURES)]
    for n, F in figures.items():
        c.append(Contributor(f"u_GAIN,{_SHORT[n]}", f"instrument gain error on the {_WORDS[n]}",
                             abs(F) * g / _SQ3, "rectangular", _CLAUSE,
                             f"{F:.3g} µm × {v['gain']:g} % / √3", (n,)))
    c.append(Contributor("u_RES", "instrument resolution (two readings)",
                         math.sqrt(2) * v["resolution"] / math.sqrt(12), "rectangular", _CLAUSE,
                         f"√2 × {v['resolution']:g} µm / √12", FIGURES))
    sigma = noise.sigma * 1e6
    c.append(Contributor("u_NOISE", "reading noise (two readings), measured", math.sqrt(2) * sigma,
                         "normal", "JCGM 100:2008 §4.2 (Type A); ISO/TR 230-9:2005",
                         f"√2 × σ = √2 × {sigma:.3g} µm" if noise.measured
                         else "not measured: too few readings", FIGURES))
    c.append(Contributor("u_EVE", "environmental variation over the test",
                         v["e_ve"] / (2 * _SQ3), "rectangular",
                         "ISO 230-2:2014 Annex A.5; ISO/TR 230-9:2005",
                         f"E_VE = {v['e_ve']:g} µm", FIGURES))
    c.append(Contributor("u_FIT", "least-squares line fit of the slope (µm/m), measured",
                         fit or 0.0, "normal", "ISO 230-1:2012 §3.4.8; GUM H.3",
                         f"{fit:.3g} µm/m from the residuals" if fit is not None
                         else "not measured: 2 readings leave no residual", ("slope",)))
    c.append(Contributor("u_GAIN,SLOPE", "instrument gain error on the slope (µm/m)",
                         abs(slope) * g / _SQ3, "rectangular", _CLAUSE,
                         f"{slope:.3g} µm/m × {v['gain']:g} % / √3", ("slope",)))
    c.append(Contributor("u_REF,SLOPE", "direction of the reference (µm/m)",
                         v["reference_slope_u"], "normal", _CLAUSE,
                         f"{v['reference_slope_u']:g} µm/m", ("slope",)))
    c.append(Contributor("u_EVE,SLOPE", "environmental variation over the travel (µm/m)",
                         v["e_ve"] / (2 * _SQ3) / travel, "rectangular",
                         "ISO 230-2:2014 Annex A.5; ISO/TR 230-9:2005",
                         f"E_VE = {v['e_ve']:g} µm over {travel * 1e3:g} mm", ("slope",)))
    inputs = tuple(BudgetInput(key, label, v[key], unit, key not in table,
                               SET_WITH.format(key=key),
                               rule if key not in table else "")   # given: said by the "given" beside it
                   for key, (label, unit, _, rule) in STRAIGHTNESS_INPUTS.items())
    inputs += (
        BudgetInput("reading_noise", "reading noise σ of one reading",
                    float(f"{sigma:.3g}"), "µm", not noise.measured,
                    "the data file", f"measured: {noise.how}" if noise.measured else
                    "not measured: fewer than 4 readings at distinct positions and none "
                    "repeated; left out of U"),
        BudgetInput("slope_fit", "standard uncertainty of the least-squares slope",
                    float(f"{fit or 0.0:.3g}"), "µm/m", fit is None, "the data file",
                    "measured: the line fit's residuals (ISO 230-1:2012 §3.4.8)" if fit is not None
                    else "not measured: 2 readings leave no residual; left out of U"))
    notes = tuple(f"assumed: {i.label} {i.value:g} {i.unit} ({i.rule}); set with {i.set_with}"
                  .replace("  ", " ") for i in inputs
                  if i.assumed and i.name not in ("k", "reading_noise", "slope_fit"))
    notes += tuple(f"{i.label}: {i.rule}" for i in inputs
                   if i.assumed and i.name in ("reading_noise", "slope_fit"))
    notes += ("both straightness figures (least squares and minimum zone) are ranges of "
              "residuals and take the same contributors; the slope's U is in µm/m",
              "not included: a correction of the range's bias by the reading noise, and the "
              "set-up's misalignment (removed with the reference line)")
    return replace(combine(c, "um", v["k"], (*FIGURES, "slope"), notes), inputs=inputs,
                   method="ISO/TR 230-9:2005 general form as axiscal reads it for an ISO "
                   "230-1:2012 straightness; GUM eq. 10 (root sum of squares)")


def straightness_input_table() -> list[dict[str, str]]:
    """Every input of :func:`straightness_budget` as :func:`~axiscal.standards.iso230_9_inputs.
    input_table` lists the ISO 230-2 ones (budget ``straightness``), for the documentation.

    Examples
    --------
    >>> row = straightness_input_table()[0]
    >>> row["name"], row["unit"], row["default"], row["range"]
    ('reference_u', 'µm', '0.5', 'a finite number ≥ 0')
    """
    return [{"budget": "straightness", "name": key, "label": label, "unit": unit,
             "default": f"{default:g}",
             "range": "a finite number > 0" if key == "k" else "a finite number ≥ 0",
             "why": "", "rule": rule}
            for key, (label, unit, default, rule) in STRAIGHTNESS_INPUTS.items()]


_SQ3 = math.sqrt(3.0)
