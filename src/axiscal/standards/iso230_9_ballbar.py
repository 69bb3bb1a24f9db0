"""Uncertainty of the ISO 230-4:2005 circular test figures measured with a ballbar: the circular
deviation G of each direction and the circular hysteresis H.

ISO/TR 230-9:2005 gives the general form (GUM: uncorrelated inputs, sensitivity coefficients,
u_c the root sum of squares, U = k·u_c with k = 2) but no worked ballbar budget; the model
below is axiscal's reading of it for a telescoping ballbar, with each input's effect on a
figure that is a *difference* of readings of one set-up (G: the largest minus the smallest
radial deviation from the least-squares circle of one run, ISO 230-4:2005 §3.2; H: the largest
radial difference between the two directions' paths, §3.3):

- ``u_CAL`` — the calibrated length of the bar (calibrator certificate): it shifts every
  reading of the set-up by the same amount, so it enters the mean radius only. Sensitivity 0
  for G and H; listed so the reader sees it was considered.
- ``u_GAIN`` — the transducer's gain (scale) error, bounded by ±g (relative), rectangular: a
  figure F read with gain 1 + g is F(1 + g), so u = F·g/√3.
- ``u_RES`` — the transducer's resolution r, each reading uniform within ±r/2: a difference
  of two readings has u = √2·r/√12.
- ``u_THERMAL`` — the bar's length changing by α·L·ΔT during the test (α its expansion
  coefficient, L the radius, ΔT the change of its temperature over the test): in the worst case
  the whole change falls between the two readings of a figure; rectangular, u = α·L·ΔT/√3.
- ``u_CENTRE`` — the set-up's centring offset e from the circle's centre: the least-squares
  fit removes it to first order, the second-order radial term spans e²/(2R) (R the radius);
  rectangular, u = e²/(2R)/√3; the same for both directions, so it does not act on H.

Not included (a note of the budget says so): the roundness of the balls and the form of the
magnetic cups, and the machine's own thermal drift, which is the measurand's.

References
----------
ISO 230-4:2005, Test code for machine tools — Part 4: Circular tests for numerically
controlled machine tools, §3.2, §3.3. ISO/TR 230-9:2005, Test code for machine tools — Part 9:
Estimation of measurement uncertainty for machine tool tests according to series ISO 230, basic
equations. JCGM 100:2008 (GUM) §5.1.2 eq. 10, §4.3.7 (rectangular distribution).
"""

from __future__ import annotations

import math
from typing import Mapping

from axiscal.errors import ConfigError, InputError
from axiscal.standards.iso230_9 import Contributor, combine
from axiscal.standards.iso230_9_entry import EntryRule, entered
from axiscal.standards.iso230_9_inputs import BudgetInput

__all__ = ["BALLBAR_INPUTS", "BALLBAR_ENTRY", "ballbar_budget"]

#: key -> (label, unit, default, rule of the default). Defaults are assumptions, marked so on
#: every budget that takes them: set each from the ballbar's and the calibrator's certificates.
BALLBAR_INPUTS = {
    "calibration_u": ("standard uncertainty of the ballbar's calibrated length", "µm", 0.5,
                      "assumed: a calibrator certificate's U = 1 µm with k = 2"),
    "gain": ("bound of the transducer's gain error", "%", 0.3,
             "assumed: a typical telescoping ballbar's specification; set it from yours"),
    "resolution": ("resolution of the transducer", "µm", 0.1,
                   "assumed: a typical telescoping ballbar's"),
    "alpha": ("thermal expansion coefficient of the bar", "µm/(m·K)", 11.5,
              "assumed: steel"),
    "delta_t": ("change of the bar's temperature during the test", "K", 0.5,
                "assumed: a workshop held within ±0.25 K over the test"),
    "centring": ("centring offset of the set-up", "mm", 0.1,
                 "assumed: the set-up centred with the centring ball within 0.1 mm"),
    "k": ("coverage factor", "", 2.0, "ISO/TR 230-9:2005: k = 2"),
}
#: How each input is typed (:mod:`axiscal.standards.iso230_9_entry`): in the unit shown
#: beside it (α 11.5, as every report prints it, not 1.15e-05), or as text with its unit
#: (``"1.15e-5 1/K"``), and within a plausible range, so a value typed in another unit is
#: refused instead of making U wrong by orders of magnitude.
BALLBAR_ENTRY = {
    "calibration_u": EntryRule("µm", "um", 0.0, 100.0, "0.5 um",
                               "a ballbar calibrator's standard uncertainty"),
    "gain": EntryRule("%", "percent", 0.0, 10.0, "0.3 %", "a transducer's gain error"),
    "resolution": EntryRule("µm", "um", 0.0, 100.0, "0.1 um", "a transducer's resolution"),
    "alpha": EntryRule("µm/(m·K)", "um/(m*K)", 0.001, 100.0, "11.5 um/(m K)",
                       "steel 11.5, aluminium 23, Invar 1.2, carbon fibre about 0", zero=True),
    "delta_t": EntryRule("K", "K", 0.0, 20.0, "0.5 K", "a bar's temperature change over a test",
                         difference=True),
    "centring": EntryRule("mm", "mm", 0.0, 10.0, "0.1 mm", "a set-up's centring offset"),
    "k": EntryRule("", "", 1.0, 10.0, "2", "a coverage factor, usually 2"),
}
#: How a user sets an input.
SET_WITH = "[ballbar_uncertainty] {key} in the user configuration"


def ballbar_budget(result, radius: float, table: Mapping[str, float] | None = None):
    """The uncertainty of G (each direction measured) and H of a ballbar test, with its inputs.

    Parameters
    ----------
    result : BallbarDiagnosis or CircularResult
        :func:`axiscal.store.kinds.evaluate_ballbar`'s result: supplies G_ccw, G_cw and H (m).
    radius : float, m
        The bar's length (the circle's radius).
    table : mapping, optional
        The user configuration's ``[ballbar_uncertainty]`` table (keys of
        :data:`BALLBAR_INPUTS`, each in its unit); absent inputs take the defaults, marked
        assumed.

    Returns
    -------
    UncertaintyBudget
        Unit ``um``; parameters ``G_ccw``, ``G_cw`` (those measured) and ``H`` (both
        directions measured), as :func:`axiscal.store.kinds.ballbar_parameters` names them.

    Raises
    ------
    ConfigError
        A key that is no input, or a value that is not a finite number ≥ 0 (k > 0).

    Notes
    -----
    u_c(F)² = (F·g/√3)² + (√2·r/√12)² + (α·L·ΔT/√3)² [+ (e²/(2R)/√3)² for G], U = k·u_c
    (module docstring; ISO/TR 230-9:2005 basic equations, JCGM 100:2008 eq. 10).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> r = SimpleNamespace(G_ccw=10e-6, G_cw=12e-6, H=3e-6)
    >>> b = ballbar_budget(r, 0.1)
    >>> round(b.U("G_ccw"), 3), round(b.U("H"), 3)
    (0.672, 0.669)

    By hand (defaults; G = 10 µm): gain 10·0.003/√3 = 0.0173, resolution √2·0.1/√12 = 0.0408,
    thermal 11.5 µm/(m·K)·100 mm·0.5 K/√3 = 0.3320, centring (0.1 mm)²/(200 mm)/√3 = 0.0289 µm:
    u_c = 0.3362, U = 0.672 µm; H = 3 µm (no centring term): u_c = 0.3345, U = 0.669 µm.
    """
    table = dict(table or {})
    for key in table:
        if key not in BALLBAR_INPUTS:
            raise ConfigError(f"[ballbar_uncertainty] {key}: no such input; use "
                              f"{', '.join(BALLBAR_INPUTS)}")
    try:
        typed = {key: entered(key, value, BALLBAR_ENTRY[key], "[ballbar_uncertainty]")
                 for key, value in table.items()}
    except InputError as e:
        raise ConfigError(str(e)) from None
    v = {key: float(typed.get(key, default)) for key, (_, _, default, _) in
         BALLBAR_INPUTS.items()}
    circ = getattr(result, "circular", result)
    figures = {n: getattr(circ, n) * 1e6 for n in ("G_ccw", "G_cw", "H")
               if getattr(circ, n, None) is not None and math.isfinite(getattr(circ, n))}
    g = v["gain"] / 100.0
    clause = "ISO/TR 230-9:2005 (axiscal's reading for a ballbar)"
    c = [Contributor("u_CAL", "calibrated length of the bar", v["calibration_u"], "normal",
                     clause, f"{v['calibration_u']:g} µm; a common shift of every reading: "
                     "sensitivity 0 for G and H", ())]
    for n, F in figures.items():
        c.append(Contributor(f"u_GAIN,{n}", f"transducer gain error on {n}", F * g / math.sqrt(3),
                             "rectangular", clause, f"{F:.3g} µm × {v['gain']:g} % / √3", (n,)))
    c.append(Contributor("u_RES", "transducer resolution (two readings)",
                         math.sqrt(2) * v["resolution"] / math.sqrt(12), "rectangular", clause,
                         f"√2 × {v['resolution']:g} µm / √12", tuple(figures)))
    thermal = v["alpha"] * 1e-6 * radius * v["delta_t"] * 1e6      # α typed in µm/(m·K)
    c.append(Contributor("u_THERMAL", "bar length change during the test",
                         thermal / math.sqrt(3), "rectangular", clause,
                         f"{v['alpha']:g} µm/(m·K) × {radius * 1e3:g} mm × {v['delta_t']:g} K / √3",
                         tuple(figures)))
    e = v["centring"] * 1e-3
    c.append(Contributor("u_CENTRE", "second-order effect of the centring offset",
                         e * e / (2 * radius) * 1e6 / math.sqrt(3), "rectangular", clause,
                         f"({v['centring']:g} mm)² / (2 × {radius * 1e3:g} mm) / √3",
                         tuple(n for n in figures if n.startswith("G"))))
    inputs = tuple(BudgetInput(key, label, v[key], unit, key not in table,
                               SET_WITH.format(key=key),
                               rule if key not in table else "")   # given: said by the "given" beside it
                   for key, (label, unit, _, rule) in BALLBAR_INPUTS.items())
    notes = tuple(f"assumed: {i.label} {i.value:g} {i.unit} ({i.rule}); set with {i.set_with}"
                  .replace("  ", " ") for i in inputs if i.assumed and i.name != "k") + (
        "not included: the roundness of the balls and the form of the magnetic cups",)
    from dataclasses import replace

    return replace(combine(c, "um", v["k"], tuple(figures), notes), inputs=inputs,
                   method="ISO/TR 230-9:2005 general form as axiscal reads it for a ballbar; "
                   "GUM eq. 10 (root sum of squares)")
