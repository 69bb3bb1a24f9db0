"""How quantities are shown to people: one label table and one decimal policy for every report.

A command's result is a dictionary with stable, code-like keys (``servo_mismatch_ms``,
``squareness.iso_um_per_m``, ``uncertainty[1].u_um_per_m``). A customer reads labels with units
instead: :func:`label` turns a key into "Servo mismatch [ms]", taking the unit from the key's
suffix (``_um``, ``_um_per_m``, ``_arcsec`` …) or from the table. :func:`fmt` writes a value with
the decimals of its unit (:data:`DECIMALS`); tables, the annotation boxes of plots and running text
all call it, so a figure and a table show the same digits. :func:`symbol_html` writes a symbol of a
standard (``u_E,MACHINE``, ``B_i``) with its subscript, as the standards print it.

Decimal policy (the resolution each unit is reported to; axiscal's rule, as no standard fixes the
decimals of a report: it keeps the digits the terminal and the plots already showed): µm to 0.01,
µm/m to 0.01, arcsec to 0.01, mm to 0.001, degrees to 0.001, seconds to 0.001, ms to 0.01, Hz to
0.1, percent to 0.1, a loop gain in 1/s to 0.1. A non-zero value that would round to zero keeps two
significant digits instead, down to a thousandth of the unit's resolution (an uncertainty of
0.00058 µm is not shown as 0.00: JCGM 100:2008 §7.2.6 gives an uncertainty to at most two
significant digits; a fit's 1e-17 µm stays 0.00).

Examples
--------
>>> label("servo_mismatch_ms")
'Servo mismatch [ms]'
>>> label("backlash_x_um", axes=("Y", "Z"))
'Backlash Y [µm]'
>>> fmt(43.8679, "µm"), fmt(105.703, "%"), fmt(0.00058, "µm")
('43.87', '105.7', '0.00058')
>>> symbol_html("u_E,MACHINE")
'u<sub>E,MACHINE</sub>'
"""

from __future__ import annotations

import html as _html
import math
import re
from typing import Any

from axiscal.standards.iso230_2 import PARAMETER_SYMBOLS

__all__ = ["DECIMALS", "QUANTITIES", "decimals", "fmt", "label", "name", "split_key",
           "symbol_html", "unit_text", "value_text"]

#: Key suffixes naming a unit, longest first (``slope_um_per_m`` is µm/m, not m).
SUFFIX_UNITS = (
    ("_um_per_m", "µm/m"), ("_m_per_s", "m/s"), ("_mm_per_min", "mm/min"), ("_percent", "%"),
    ("_arcsec", "arcsec"), ("_counts", "counts"), ("_mrad", "mrad"), ("_khz", "kHz"),
    ("_ppm", "ppm"), ("_deg", "°"), ("_um", "µm"), ("_mm", "mm"), ("_nm", "nm"), ("_hz", "Hz"),
    ("_ms", "ms"), ("_s", "s"), ("_c", "°C"),
)

#: Decimals shown for each unit (the module docstring gives the policy).
DECIMALS = {"µm": 2, "µm/m": 2, "arcsec": 2, "mm": 3, "°": 3, "s": 3, "ms": 2, "Hz": 1, "kHz": 2,
            "%": 1, "ppm": 2, "mrad": 2, "nm": 1, "m/s": 3, "mm/min": 0, "°C": 2, "counts": 1,
            "Pa": 0, "%RH": 1, "1/K": 8, "1/s": 1, "": 3}

#: Key (without its unit suffix) → (label, unit). ``None`` as unit: the suffix's or the result's
#: own ``unit``. ``{x}`` and ``{y}`` stand for the plane's first and second axis.
QUANTITIES: dict[str, tuple[str, str | None]] = {
    # positioning (ISO 230-2:2014 clause 3): the symbols of PARAMETER_SYMBOLS, with words
    **{k: (s, None) for k, s in PARAMETER_SYMBOLS.items()},
    "A": ("A, bidirectional accuracy", None), "E": ("E, bidirectional systematic error", None),
    "M": ("M, range of mean bidirectional error", None),
    "R": ("R, bidirectional repeatability", None), "B": ("B, reversal value", None),
    "B_mean": ("B̄, mean reversal value", None),
    "before": ("Before compensation", None), "after": ("After compensation", None),
    "truth_before": ("Simulation's truth before compensation", None),
    "truth_after": ("Simulation's truth after compensation", None),
    "reduction": ("Reduction of E", "%"), "budget_E": ("E the budget allows", None),
    "between_targets_E": ("E between the table's targets", None),
    "spacing_residual": ("Residual of the table spacing", None), "sigma": ("Noise σ", None),
    "n_points": ("Table points", ""), "spacing": ("Table spacing", "mm"), "seed": ("Seed", ""),
    "sign": ("Sign convention", ""), "controller": ("Controller", ""), "unit": ("Unit", ""),
    # ballbar and circular tests (ISO 230-4:2005; Chapman, Calibration of machine squareness)
    "servo_mismatch": ("Servo mismatch", "ms"), "servo_term": ("Servo term", "µm"),
    "scale_mismatch": ("Scale mismatch", "µm/m"), "squareness": ("Squareness", "µm/m"),
    "scale_x": ("Scale error {x}", "µm/m"), "scale_y": ("Scale error {y}", "µm/m"),
    "kv_x_per_s": ("Position-loop gain kv {x}", "1/s"),
    "kv_y_per_s": ("Position-loop gain kv {y}", "1/s"),
    "reversal_gap_x": ("Reversal gap {x}", "µm"), "reversal_gap_y": ("Reversal gap {y}", "µm"),
    "backlash_x": ("Backlash {x}", "µm"), "backlash_y": ("Backlash {y}", "µm"),
    "lateral_play_x": ("Lateral play {x}", "µm"), "lateral_play_y": ("Lateral play {y}", "µm"),
    "straightness_x": ("Straightness {x}", "µm"), "straightness_y": ("Straightness {y}", "µm"),
    "reversal_spike_x": ("Reversal spike {x}", "µm"),
    "reversal_spike_y": ("Reversal spike {y}", "µm"),
    "reversal_spike_x_decay": ("Reversal spike {x} decay length", "mm"),
    "reversal_spike_y_decay": ("Reversal spike {y} decay length", "mm"),
    "cyclic_x": ("Cyclic error {x}", "µm"), "cyclic_y": ("Cyclic error {y}", "µm"),
    "cyclic_x_pitch": ("Cyclic error {x} pitch", "mm"),
    "cyclic_y_pitch": ("Cyclic error {y} pitch", "mm"),
    "stick_slip": ("Stick-slip", "µm"), "vibration": ("Vibration", "µm"),
    "residual": ("Residual (not modelled)", "µm"), "residual_rms": ("Residual, rms", "µm"),
    "residual_ptp": ("Residual, peak-to-valley", "µm"), "feed": ("Feed", "mm/min"),
    "G_ccw": ("G, circular deviation CCW", None), "G_cw": ("G, circular deviation CW", None),
    "G_lsc_ccw": ("G about the least-squares centre, CCW", None),
    "G_lsc_cw": ("G about the least-squares centre, CW", None),
    "H": ("H, circular hysteresis", None), "F_max": ("F max, radial deviation", None),
    "F_min": ("F min, radial deviation", None), "fit_rms": ("Fit residual, rms", None),
    "radius": ("Radius", None), "arc": ("Arc", None),
    # squareness (ISO 230-1:2012 §10.3; Chapman, Calibration of machine squareness)
    "iso": ("Squareness by ISO 230-1 (referred axis)", None), "iso_datum": ("ISO datum axis", ""),
    "iso_referred": ("ISO referred axis", ""), "angle_note": ("Angle", ""),
    "convention": ("Sign convention", ""), "axes": ("Axes", ""),
    "truth": ("Simulation's truth", None),
    "U": ("U (k = 2), expanded uncertainty", None), "u": ("Standard uncertainty u", None),
    "correction": ("Correction", None), "prism_error": ("Prism error", None),
    "slope_first": ("Slope of the first run", None),
    "slope_second": ("Slope of the second run", None),
    "straightness_first": ("Straightness of the first run", None),
    "straightness_second": ("Straightness of the second run", None),
    "slope_d1": ("Slope of diagonal D1", None), "slope_d2": ("Slope of diagonal D2", None),
    "error_d1": ("Length error of diagonal D1", None),
    "error_d2": ("Length error of diagonal D2", None),
    "length_x": ("Length along the first axis", None),
    "length_y": ("Length along the second axis", None),
    "nominal": ("Nominal length", None), "labels": ("Diagonals", ""), "D1": ("D1", ""),
    "D2": ("D2", ""), "config": ("Configuration", ""), "orientation": ("Orientation", "°"),
    "measurements": ("Measurements", ""), "uncertainty": ("Uncertainty contributions", None),
    "name": ("Name", ""), "uncertainty.name": ("Contribution", ""), "events.name": ("Event", ""),
    "parameters.name": ("Parameter", ""), "clause": ("Source", ""),
    "folded": ("Errors the ISO 230-4 fit folds in", None), "quantity": ("Quantity", ""),
    "iso230_4": ("By the ISO 230-4 fit", None), "diagnosis": ("By the full diagnosis", None),
    "material": ("Material", ""), "statement": ("Statement", ""),
    "um_per_m": ("Squareness", "µm/m"), "arcsec": ("Squareness", "arcsec"),
    "results": ("Results per test", None),
    "averages": ("Averages", None), "method": ("Method", ""), "group": ("Group", ""),
    "centre": ("Centre", None), "size": ("Size", None), "machine": ("Machine", ""),
    "scope": ("Scope", ""), "readings": ("Readings", ""), "file": ("File", ""),
    # straightness (ISO 230-1:2012 §8.2)
    "straightness": ("Straightness", None), "slope": ("Slope", None),
    "straightness_min_zone": ("Straightness, minimum-zone line", None),
    "vibration_hz": ("Vibration frequency", "Hz"),
    "intercept": ("Intercept", None),
    "reference": ("Reference line", ""), "methods": ("By each reference line", None),
    "end_point": ("End-point line", ""), "least_squares": ("Least-squares line", ""),
    "minimum_zone": ("Minimum-zone line", ""),
    # rotary budget (Renishaw, Interferometric calibration of rotary axes, eq. 1, Figure 22)
    "alpha": ("α, misalignment", None), "beta": ("β, misalignment", None),
    "omega": ("ω, misalignment", None), "max_alpha": ("Largest α for the accuracy", None),
    "base": ("Base accuracy of the calibrator", None), "accuracy": ("Required accuracy", None),
    "accuracy_source": ("Accuracy taken from", ""), "peak": ("Peak of eq. 1", None),
    "datum_relative": ("Relative to the datum", None), "half_range": ("Half range", None),
    "equation1_accuracy": ("Expected accuracy by eq. 1", None),
    "expected_accuracy": ("Expected accuracy", None),
    "figure22_model": ("Figure 22 model", None), "terms": ("Terms of eq. 1", None),
    "alpha_beta": ("α·β term", None), "alpha_omega": ("α·ω term", None),
    "quadratic": ("Quadratic term", None), "applied": ("Applied", ""),
    # capture and raw readings (ISO 230-2:2014 §4.3, §5.3.3)
    "out": ("Data written to", ""), "stops": ("Stops found", ""), "dwell": ("Dwell", None),
    "sample_rate": ("Sample rate", None), "settling": ("Settling time", "s"),
    "median": ("Median", None), "max": ("Largest", None), "window": ("Window", None),
    "amplitude": ("Amplitude", None), "peak_hz": ("Peak frequency", "Hz"),
    "overruns": ("Overruns", ""), "target_unit": ("Target unit", ""), "targets": ("Targets", None),
    "n": ("Readings", ""), "axis": ("Axis", ""), "direction": ("Direction", ""),
    "offset": ("Offset", "counts"), "air_temperature": ("Air temperature", "°C"),
    "material_temperature": ("Material temperature", "°C"), "bounds": ("Bounds", ""),
    "difference": ("Difference", None),
    # laser scale referencing (Renishaw, Laser scale axis referencing)
    "compensation": ("Compensation factor", None), "laser_count_rate": ("Laser count rate", None),
    "controller_max_speed": ("Controller's largest speed", None),
    "count_size": ("Count size", None),
    "counts_per_period": ("Counts per period", ""), "events": ("Events", None),
    "controller_count": ("Controller count", "counts"), "counts_beyond_switch":
    ("Beyond the switch", "counts"), "nominal_counts": ("Nominal", "counts"),
    "position": ("Position", None), "time": ("Time", None), "uncertainty_counts":
    ("Uncertainty", "counts"), "home_position": ("Home position", None),
    "peak_input_frequency": ("Peak input frequency", None), "period": ("Scale period", None),
    "power_up_phase": ("Phase at power-up", "counts"), "rephase_periods": ("Rephasing", "periods"),
    "switch_trip": ("Switch trips at", None), "virtual_counts": ("Virtual counts", "counts"),
    "homed": ("Homed", ""), "tracking": ("Tracking after homing", None),
    "count_uncertainty": ("One laser count", "counts"),
    "end_controller": ("Controller at the end", None),
    "end_part": ("Part at the end", None), "end_true": ("True position at the end", None),
    "end_uncompensated": ("Uncompensated scale at the end", None),
    "max_count_error": ("Largest count error", "counts"),
    "max_part_error": ("Largest part error", None),
    "max_pulse_error": ("Largest pulse error", "counts"),
    "alarm": ("Alarm", ""), "alarms": ("Alarms", ""), "deskew_move": ("Deskew move", "counts"),
    "homing_skew_bound": ("Homing skew bound", None),
    "homing_skew_max": ("Largest homing skew", "counts"),
    "homing_skew_min": ("Smallest homing skew", "counts"),
    "required_skew_limit": ("Skew limit needed", "counts"), "skew_limit": ("Skew limit", "counts"),
    "skew_after_sync": ("Skew after synchronisation", "counts"),
    "skew_before_sync": ("Skew before synchronisation", "counts"),
    "switch_sigma": ("Switch repeatability σ", None), "virtual_1": ("Virtual count X1", "counts"),
    "virtual_2": ("Virtual count X2", "counts"), "worst_case": ("Worst cases", None),
    # volumetric accuracy (ISO/TR 16907:2015; body diagonals, ISO 230-6:2002)
    "largest": ("Largest volumetric error |E|", "µm"),
    "range_X": ("Range of the volumetric error along X", "µm"),
    "range_Y": ("Range of the volumetric error along Y", "µm"),
    "range_Z": ("Range of the volumetric error along Z", "µm"),
    **{f"diagonal_{d}": (f"Body diagonal {d}, range", "µm") for d in ("PPP", "NPP", "PNP",
                                                                      "PPN")},
    # history comparisons and trends
    "first": ("First test", ""), "second": ("Second test", ""), "parameters": ("Parameters", None),
    "change": ("Change", None), "warnings": ("Warnings", ""),
}

#: Code-like values → words (a result's ``reference = "least_squares"``).
VALUES = {"least_squares": "least squares", "minimum_zone": "minimum zone",
          "end_point": "end point", "figure22_model": "Figure 22 model (Renishaw, Interferometric "
          "calibration of rotary axes)", "um": "µm", "deg": "°"}

_CODE_VALUE = re.compile(r"^[a-z0-9]+(_[a-z0-9]+)+$")


def split_key(key: str) -> tuple[str, str | None]:
    """A key and the unit its suffix names: ``("backlash_x", "µm")`` for ``backlash_x_um``."""
    for suffix, unit in SUFFIX_UNITS:
        if key.endswith(suffix) and len(key) > len(suffix):
            return key[: -len(suffix)], unit
    return key, None


def quantity(key: str, unit: str | None = None, axes=("X", "Y")) -> tuple[str, str]:
    """(label, unit) of a result key; ``unit`` is the result's own unit for keys without one.

    A dotted key (``uncertainty.name``) is looked up whole, then by its last part. A key the table
    does not know is written in words (underscores to spaces) rather than shown as code.
    """
    if key in QUANTITIES:
        name, table_unit = QUANTITIES[key]
        return name.format(x=axes[0], y=axes[1]), table_unit or unit_text(unit or "")
    key = key.rsplit(".", 1)[-1]
    base, suffixed = split_key(key)
    name, table_unit = QUANTITIES.get(key, QUANTITIES.get(base, (None, None)))
    if name is None:
        name = base.replace("_", " ")
        name = name[:1].upper() + name[1:]
    u = suffixed if suffixed is not None else table_unit
    if u is None:
        u = unit_text(unit) if unit else ""
    return name.format(x=axes[0], y=axes[1]), u


def name(key: str, axes=("X", "Y")) -> str:
    """What the interface calls a stored parameter ``key`` (the key itself is the API's and
    ``history trend --parameter``'s name): the symbol of ISO 230-2:2014 clause 3 (``R↑`` for
    ``R_up``, :data:`~axiscal.standards.iso230_2.PARAMETER_SYMBOLS`), else the label of
    :data:`QUANTITIES` (``Reversal spike X decay length``); a key of another standard
    (``jis-b6192:R``) as its symbol and the standard's name (``R (JIS B 6192 / B 0182)``).

    >>> name("R_up"), name("B_mean"), name("reversal_spike_x_decay"), name("jis-b6192:R")
    ('R↑', 'B̄', 'Reversal spike X decay length', 'R (JIS B 6192 / B 0182)')
    >>> name("iso230-2:1988:R_up")
    'R↑ (ISO 230-2:1988)'
    """
    if key in PARAMETER_SYMBOLS:
        return PARAMETER_SYMBOLS[key]
    if ":" in key:
        std, _, rest = key.rpartition(":")
        words = name(rest, axes) if std.startswith("iso230-4") else \
            PARAMETER_SYMBOLS.get(rest, rest.replace("_", " "))   # another standard's symbol
        from axiscal.standards.positioning_standards import STANDARDS

        return f"{words} ({STANDARDS[std].title if std in STANDARDS else std})"
    for fig in ("_total", "_synchronous", "_asynchronous"):   # ISO 230-7:2015 §3 motions
        if key.endswith(fig) and key not in QUANTITIES:
            base = key[:-len(fig)].replace("_", " ")
            return f"{base[:1].upper()}{base[1:]} error motion, {fig[1:]}"
    return quantity(key, None, _axes(axes))[0]


def _axes(axes) -> tuple[str, str]:
    """A plane's two axis names from ``("X", "Y")`` or a stored axis name ``"XY"``."""
    if isinstance(axes, str):
        return (axes[0], axes[1]) if len(axes) == 2 else ("X", "Y")
    return tuple(axes)


def label(key: str, unit: str | None = None, axes=("X", "Y")) -> str:
    """The label of a result key with its unit in brackets: ``Servo mismatch [ms]``."""
    name, u = quantity(key, unit, axes)
    return f"{name} [{u}]" if u else name


def unit_text(unit: str) -> str:
    """A unit as people write it: µm for um, ° for deg, otherwise as it is."""
    return {"um": "µm", "deg": "°", "um/m": "µm/m", "percent": "%"}.get(unit, unit)


def decimals(unit: str) -> int:
    """Decimals shown for a value in ``unit`` (:data:`DECIMALS`; three for an unknown unit)."""
    return DECIMALS.get(unit_text(unit or ""), 3)


def fmt(value: Any, unit: str = "", sign: bool = False) -> str:
    """A value with its unit's decimals (:func:`decimals`); a non-zero value that would print as
    zero keeps two significant digits; None and NaN as a dash, integers as they are; ``sign``
    writes ``+`` before a positive number."""
    text = _fmt(value, unit)
    return "+" + text if sign and text[:1].isdigit() and text.strip("0.") else text


def _fmt(value: Any, unit: str) -> str:
    if isinstance(value, str):
        return value_text(value)
    text = fixed(value, decimals(unit))
    v = float(value) if isinstance(value, float) or hasattr(value, "dtype") else None
    if v is None or not math.isfinite(v) or float(text) != 0:
        return text
    d = decimals(unit)
    if v != 0 and abs(v) >= 10.0 ** -(d + 3):
        text = f"{v:.{1 - math.floor(math.log10(abs(v)))}f}"
    return text.lstrip("-") if float(text) == 0 else text


def fixed(value: Any, digits: int) -> str:
    """A number to ``digits`` decimals: None and NaN as a dash, flags as yes/no, integers as
    they are (the cells of every report table); a value that rounds to zero has no sign.

    >>> fixed(-0.0001, 3), fixed(-0.0, 3), fixed(-0.0006, 3)
    ('0.000', '0.000', '-0.001')
    """
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    v = float(value)
    if math.isnan(v):
        return "—"
    text = f"{v:.{digits}f}"
    return text.lstrip("-") if text.startswith("-") and float(text) == 0 else text


def value_text(value: str) -> str:
    """A text value in words: a code-like value (``least_squares``) through :data:`VALUES`."""
    if value in VALUES:
        return VALUES[value]
    return value.replace("_", " ") if _CODE_VALUE.match(value) else value


#: A symbol ``X_sub``; a configuration's name (``[motion_uncertainty] resolution_dy``: a word
#: of four or more lowercase letters before the ``_``) is not one.
_SYMBOL = re.compile(r"(?<![\w/.])(?![a-z]{4,}_[a-z])([0-9]*[A-Za-zα-ωΔδεθ][\w̄↑↓]*?)_"
                     r"(\{[^}]*\}|[A-Za-z0-9↑↓]+(?:,[A-Za-z0-9↑↓]+)*)"
                     r"(?!\w|/[A-Za-z_.]|\.\w)")


def symbol_html(text: str) -> str:
    """Escape ``text`` and write every symbol ``X_sub`` (``u_E,MACHINE``, ``B_i``, ``R↑_i``) as
    ``X<sub>sub</sub>``, as the standards print them; file names are left alone.

    >>> symbol_html("B_i = x̄↑ − x̄↓; see run_1.csv")
    'B<sub>i</sub> = x̄↑ − x̄↓; see run_1.csv'
    >>> symbol_html("u_RES,dy; set with [motion_uncertainty] resolution_dy")
    'u<sub>RES,dy</sub>; set with [motion_uncertainty] resolution_dy'

    A configuration's table and key (``[straightness_uncertainty] reference_u``) are names to
    type, left as written:

    >>> symbol_html("E_VE; set with [straightness_uncertainty] e_ve in the user configuration")
    'E<sub>VE</sub>; set with [straightness_uncertainty] e_ve in the user configuration'
    >>> symbol_html("min[x_i]")
    'min\u2009[x<sub>i</sub>]'
    >>> symbol_html("u_E,MACHINE; [squareness_uncertainty] laser_ppm")
    'u<sub>E,MACHINE</sub>; [squareness_uncertainty] laser_ppm'
    """
    parts = _CONFIG_KEY.split(text)
    return "".join(_html.escape(p, quote=False) if n % 2 else _symbols(p)
                   for n, p in enumerate(parts))


#: ``[table] key`` of a configuration (table names and keys in lower case with underscores).
_CONFIG_KEY = re.compile(r"(\[[a-z]{3,}[a-z0-9_.]*\](?: [a-z][a-z0-9_]*\b)?)")


def _symbols(text: str) -> str:
    escaped = re.sub(r"\b(max|min)\[", "\\1\u2009[", _html.escape(text, quote=False))
    return _SYMBOL.sub(_subscript, escaped)


#: A word joined to a word by underscores (``squareness_uncertainty``, ``laser_ppm``): a key of
#: code, not a symbol; left as written (issue 40: printed "squareness<sub>uncertainty</sub>").
_CODE_WORDS = re.compile(r"[a-z][a-z_]{2,}")


def _subscript(m) -> str:
    base, sub = m.group(1), m.group(2).strip("{}")
    if _CODE_WORDS.fullmatch(base) and re.fullmatch(r"[a-z]{2,}", sub):
        return m.group(0)
    return f"{base}<sub>{sub}</sub>"
