"""Uncertainty budgets (ISO/TR 230-9 form) of squareness tests and five-DOF motion-error readings.

The same :class:`~axiscal.standards.iso230_9.UncertaintyBudget` as the positioning budgets, so the
ISO 14253-1 decision rules apply to any parameter here too.

Squareness (µm/m, one parameter ``squareness``), one budget per method of ISO 230-1:2012 §10.3 as
M.A.V. Chapman (Renishaw), "Calibration of machine squareness" describes them:

==================  ==========================================================================
method              contributors (sensitivity in brackets)
==================  ==========================================================================
``optics``          straightness optics accuracy on each slope [1 each], optical square error
                    [4.848 µm/m per arcsec], line-fit uncertainty of each slope [1], E_VE over
                    the shorter length [1/L]
``square``          granite/ceramic square error [1/L_sq], probe (indicator) accuracy over
                    each travel [√2/L], line-fit of each slope [1], E_VE [1/L]
``reversal``        as ``square`` without the square's error (it cancels in the reversal),
                    plus the repositioning of the square between the two set-ups [1/L_sq]
``ballbar``         transducer accuracy at 45° and 135° [√2/(2R)], ballbar calibration length
                    error (acts on both diagonals alike: only its thermal change during the
                    test, via E_VE [√2/(2R)])
``diagonal``        diagonal length errors D1, D2 (laser ppm over D0 and E_VE) [D0/(2XY) each],
                    diagonal length D0 [(D1 − D2)/(2XY)] (ISO 230-6:2002, squareness
                    = D0 (D1 − D2)/(2XY))
==================  ==========================================================================

Five-DOF motion errors (Optics Express 2018, "Method for simultaneous measurement of five DOF
motion errors of a rotary axis using a single-mode fiber-coupled laser", §3): per channel
(εz, εy, εx in arcsec; δy, δz in µm) the detector resolution (rectangular, r/(2√3)), the
detector calibration (relative scale error × the measured range, normal), the crosstalk the
set-up leaves after removing once per turn (a ± bound, rectangular) and the residual drift after
the common-path compensation (its standard deviation, normal).

Each contributor's ``clause`` names the document and clause it comes from.

:func:`squareness_budget_with_inputs` is the budget every front end shows: the user
configuration's ``[squareness_uncertainty]`` table under the values measured from the data, and
every input as a :class:`~axiscal.standards.iso230_9_inputs.BudgetInput` (measured, given, or
assumed with the rule of its default) with the assumed ones in plain words in ``notes``.
:func:`diagonal_budget` is that budget for a diagonal test (ISO 230-6:2002; ISO 230-1:2012
§10.3.2.6), the one ``axiscal squareness diagonal`` prints and the workbench page of a stored
diagonal test shows.
"""

from __future__ import annotations

import math
from typing import Mapping

from axiscal.errors import ConfigError, InputError
from axiscal.standards.iso230_9 import COVERAGE_FACTOR, Contributor, UncertaintyBudget, combine
from axiscal.standards.iso230_9_entry import OPTICS_SQUARE_ERROR, SQUARENESS_ENTRY, entered
from axiscal.standards.iso230_9_inputs import BudgetInput

__all__ = ["squareness_budget", "squareness_budget_with_inputs", "diagonal_budget",
           "five_dof_budget", "slope_uncertainty", "SQUARENESS_METHODS", "FIVE_DOF_CHANNELS",
           "squareness_input_table"]

SQUARENESS_METHODS = ("optics", "square", "reversal", "ballbar", "diagonal")
FIVE_DOF_CHANNELS = ("ez", "ey", "ex", "dy", "dz")
_SQ3 = math.sqrt(3.0)
_ARCSEC_UM_M = math.pi / 648000 * 1e6  # 1 arcsec in µm/m
_C = "M.A.V. Chapman, Calibration of machine squareness"
_P = ("squareness",)


def squareness_budget(
    method: str,
    *,
    length_x: float = 0.8,
    length_y: float = 0.8,
    optics_accuracy: float = 0.5,
    optics_k: float = 2.0,
    square_error: float = 0.5,
    square_length: float = 0.5,
    probe_accuracy: float = 0.5,
    slope_fit_x: float = 0.0,
    slope_fit_y: float = 0.0,
    e_ve: float = 0.0,
    reposition: float = 0.5,
    ballbar_radius: float = 0.15,
    transducer_accuracy: float = 0.5,
    laser_ppm: float = 0.5,
    diagonal_d1: float = 0.0,
    diagonal_d2: float = 0.0,
    diagonal_length_u: float = 10.0,
    k: float = COVERAGE_FACTOR,
) -> UncertaintyBudget:
    """Uncertainty of a squareness result by method (µm/m).

    Parameters
    ----------
    method : str
        One of :data:`SQUARENESS_METHODS`.
    length_x, length_y : float, m
        Travels measured (the test square's sides).
    optics_accuracy : float, µm/m
        Straightness optics slope accuracy (certificate, expanded with ``optics_k``); with
        ``optics`` the optical square's error is ``square_error``,
        in **arcsec** (certificate, k = 2).
    square_error : float
        ``square``: the mechanical square's error, µm over ``square_length`` (half-width);
        ``optics``: the optical square's error, arcsec (expanded, k = 2).
    square_length : float, m
    probe_accuracy : float, µm
        Indicator/probe accuracy (half-width).
    slope_fit_x, slope_fit_y : float, µm/m
        Standard uncertainty of each fitted slope (ISO 230-1 least-squares line).
    e_ve : float, µm
        Environmental variation error over the test (drift check), full range.
    reposition : float, µm
        ``reversal``: repeatability of placing the square again (half-width, over
        ``square_length``).
    ballbar_radius : float, m
    transducer_accuracy : float, µm
        Ballbar transducer accuracy (half-width).
    laser_ppm : float, ppm
        ``diagonal``: laser accuracy (expanded, k = 2).
    diagonal_d1, diagonal_d2 : float, µm
        ``diagonal``: measured length errors of the diagonals.
    diagonal_length_u : float, µm
        ``diagonal``: standard uncertainty of the diagonal length D0.
    k : float

    Returns
    -------
    UncertaintyBudget
        Unit ``um/m``, parameter ``squareness``.

    Examples
    --------
    >>> b = squareness_budget("diagonal", length_x=0.6, length_y=0.8, e_ve=0.0)
    >>> round(b.U("squareness"), 3)          # D0 = 1 m: 2 × √2 × 0.25 µm × 1/(0.96) µm/m
    0.737
    """
    if method not in SQUARENESS_METHODS:
        raise InputError(
            f"squareness method {method!r}: use one of {', '.join(SQUARENESS_METHODS)}"
        )
    for name, v in (("length_x", length_x), ("length_y", length_y),
                    ("square_length", square_length), ("ballbar_radius", ballbar_radius)):
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"squareness budget: {name} = {v!r} m must be > 0")
    L = min(length_x, length_y)
    eve, fits = _eve_and_fits(L, e_ve, slope_fit_x, slope_fit_y)
    make = {"optics": _optics, "square": _square, "reversal": _reversal, "ballbar": _ballbar,
            "diagonal": _diagonal}[method]
    c = make(**locals())
    return combine(c, "um/m", k, _P)


def _eve_and_fits(L, e_ve, slope_fit_x, slope_fit_y):
    """The contributors every squareness method shares: E_VE over the shorter length ``L`` (m)
    and the line fit of each slope (µm/m)."""
    eve = Contributor(
        "u_EVE",
        "environmental variation over the test",
        e_ve / (2 * _SQ3) / L,
        "rectangular",
        "ISO 230-2:2014 Annex A.5; ISO/TR 230-9",
        f"E_VE = {e_ve:g} µm over {L:g} m",
        _P,
    )
    fits = [
        Contributor(
            f"u_FIT,{a}",
            f"line fit of the {a} slope",
            u,
            "normal",
            "ISO 230-1:2012 §3.4.8 (least-squares reference line)",
            f"{u:g} µm/m",
            _P,
        )
        for a, u in (("X", slope_fit_x), ("Y", slope_fit_y))
    ]
    return eve, fits


def _optics(optics_accuracy, optics_k, square_error, fits, eve, **_):
    return [
        Contributor(
            f"u_OPTICS,{a}",
            f"straightness optics, {a} slope",
            optics_accuracy / optics_k,
            "normal",
            f"{_C}, method 1; ISO 230-1:2012 §10.3.2",
            f"± {optics_accuracy:g} µm/m (k = {optics_k:g})",
            _P,
        )
        for a in ("X", "Y")
    ] + [
        Contributor(
            "u_SQUARE",
            "optical square error",
            square_error / 2 * _ARCSEC_UM_M,
            "normal",
            f"{_C}, method 1 (optical square calibration)",
            f"± {square_error:g} arcsec (k = 2)",
            _P,
        ),
        *fits,
        eve,
    ]


def _square(square_error, square_length, probe_accuracy, length_x, length_y, fits, eve, **_):
    return [
        Contributor(
            "u_SQUARE",
            "mechanical square error",
            square_error / _SQ3 / square_length,
            "rectangular",
            f"{_C}, method 2; ISO 230-1:2012 §10.3.2",
            f"± {square_error:g} µm over {square_length:g} m",
            _P,
        ),
        _probe(probe_accuracy, length_x, length_y),
        *fits,
        eve,
    ]


def _reversal(reposition, square_length, probe_accuracy, length_x, length_y, fits, eve, **_):
    return [
        Contributor(
            "u_REPOSITION",
            "placing the square again for the reversal",
            reposition / _SQ3 / square_length,
            "rectangular",
            f"{_C}, method 3 (reversal: the square's own error cancels)",
            f"± {reposition:g} µm over {square_length:g} m",
            _P,
        ),
        _probe(probe_accuracy, length_x, length_y),
        *fits,
        eve,
    ]


def _probe(probe_accuracy, length_x, length_y):
    u = math.hypot(1 / length_x, 1 / length_y) * probe_accuracy / _SQ3
    return Contributor(
        "u_PROBE",
        "probe (indicator) accuracy on both slopes",
        u,
        "rectangular",
        "ISO 230-1:2012 §10.3.2; ISO/TR 230-9 §5",
        f"± {probe_accuracy:g} µm",
        _P,
    )


def _ballbar(transducer_accuracy, ballbar_radius, e_ve, **_):
    s = math.sqrt(2) / (2 * ballbar_radius)
    return [
        Contributor(
            "u_TRANSDUCER",
            "ballbar transducer at 45° and 135°",
            s * transducer_accuracy / _SQ3,
            "rectangular",
            f"{_C}, method 4; ISO 230-4:2005 (ballbar)",
            f"± {transducer_accuracy:g} µm, R = {ballbar_radius:g} m",
            _P,
        ),
        Contributor(
            "u_CALIBRATION",
            "ballbar calibration length change during the test",
            s * e_ve / (2 * _SQ3),
            "rectangular",
            f"{_C}, method 4 (a constant length error cancels)",
            f"E_VE = {e_ve:g} µm",
            _P,
        ),
    ]


def _diagonal(
    length_x, length_y, laser_ppm, e_ve, diagonal_d1, diagonal_d2, diagonal_length_u, **_
):
    d0 = math.hypot(length_x, length_y)
    s = d0 / (2 * length_x * length_y)  # ∂sq/∂D1 = −∂sq/∂D2, 1/m
    u_d = math.hypot(laser_ppm * d0 / 2, e_ve / (2 * _SQ3))  # µm per diagonal
    out = [
        Contributor(
            f"u_{n}",
            f"length error of diagonal {n}",
            s * u_d,
            "normal",
            "ISO 230-6:2002 §4 (squareness = D0 (D1 − D2)/(2XY))",
            f"laser ± {laser_ppm:g} ppm (k = 2) over {d0:g} m, E_VE {e_ve:g} µm",
            _P,
        )
        for n in ("D1", "D2")
    ]
    sd0 = abs(diagonal_d1 - diagonal_d2) / (2 * length_x * length_y) * 1e-6  # µm/m per µm
    out.append(
        Contributor(
            "u_D0",
            "diagonal length",
            sd0 * diagonal_length_u,
            "normal",
            "ISO 230-6:2002 §4",
            f"u(D0) = {diagonal_length_u:g} µm",
            _P,
        )
    )
    return out


#: How a user sets an input of a squareness budget.
SQUARENESS_SET_WITH = "[squareness_uncertainty] {key} in the user configuration (axiscal config)"
_OWN = "axiscal's default, no document fixes it: declare your instrument's"
_XL80 = "Renishaw XL-80 laser system specification, linear measurement accuracy"
#: Every input of :func:`squareness_budget`: label, unit and the rule of its default.
SQUARENESS_INPUTS = {
    "length_x": ("X travel", "m", _OWN), "length_y": ("Y travel", "m", _OWN),
    "optics_accuracy": ("straightness optics slope accuracy", "µm/m", _OWN),
    "optics_k": ("coverage factor of the optics accuracy", "", "a certificate's k = 2"),
    "square_error": ("error of the square", "µm", _OWN),
    "square_length": ("length of the square", "m", _OWN),
    "probe_accuracy": ("probe (indicator) accuracy, ± half-width", "µm", _OWN),
    "slope_fit_x": ("standard uncertainty of the X slope fit", "µm/m", "not fitted: 0"),
    "slope_fit_y": ("standard uncertainty of the Y slope fit", "µm/m", "not fitted: 0"),
    "e_ve": ("environmental variation error E_VE", "µm", "not given, taken as 0 so U leaves it "
             "out: measure it by a drift check over the test (ISO 230-2:2014 Annex A.5) or "
             "declare it"),
    "reposition": ("repeatability of placing the square again", "µm", _OWN),
    "ballbar_radius": ("ballbar radius", "m", _OWN),
    "transducer_accuracy": ("ballbar transducer accuracy, ± half-width", "µm", _OWN),
    "laser_ppm": ("laser accuracy (k = 2)", "ppm", _XL80),
    "diagonal_d1": ("length error of diagonal D1", "µm", "not measured: 0"),
    "diagonal_d2": ("length error of diagonal D2", "µm", "not measured: 0"),
    "diagonal_length_u": ("standard uncertainty of the diagonal length D0", "µm", _OWN),
    "k": ("coverage factor", "", "ISO/TR 230-9 and ISO 230-2:2014 Annex A: k = 2"),
}
#: The inputs each method's budget reads (the others do not move its U).
METHOD_INPUTS = {
    "optics": ("length_x", "length_y", "optics_accuracy", "optics_k", "square_error",
               "slope_fit_x", "slope_fit_y", "e_ve", "k"),
    "square": ("length_x", "length_y", "square_error", "square_length", "probe_accuracy",
               "slope_fit_x", "slope_fit_y", "e_ve", "k"),
    "reversal": ("length_x", "length_y", "reposition", "square_length", "probe_accuracy",
                 "slope_fit_x", "slope_fit_y", "e_ve", "k"),
    "ballbar": ("ballbar_radius", "transducer_accuracy", "e_ve", "k"),
    "diagonal": ("length_x", "length_y", "diagonal_d1", "diagonal_d2", "laser_ppm", "e_ve",
                 "diagonal_length_u", "k"),
}


def squareness_budget_with_inputs(
    method: str,
    table: Mapping[str, float] | None = None,
    *,
    set_with: str = SQUARENESS_SET_WITH,
    **measured: float,
) -> UncertaintyBudget:
    """:func:`squareness_budget` of ``method`` with every input it read, and where it came from.

    Parameters
    ----------
    method : str
        One of :data:`SQUARENESS_METHODS`.
    table : mapping, optional
        The user configuration's ``[squareness_uncertainty]`` table (keys of
        :func:`squareness_budget`): a number in its unit (the unit the output shows), or text
        with a unit (``"600 mm"``), each checked against its plausible range
        (:data:`axiscal.standards.iso230_9_entry.SQUARENESS_ENTRY`); inputs absent from it and
        from ``measured`` take the documented defaults and are marked assumed.
    set_with : str
        How a user sets an input, ``{key}`` replaced by its name.
    **measured : float
        Inputs measured from the data (travels, slopes' fit uncertainty, diagonal errors ...):
        they override ``table``.

    Returns
    -------
    UncertaintyBudget
        Unit ``um/m``, parameter ``squareness``, with ``inputs`` (the inputs of ``method``,
        :data:`METHOD_INPUTS`) and ``notes`` (each assumed input with its rule).

    Raises
    ------
    ConfigError
        A key of ``table`` that is no input, a value that is not a number (or a number with a
        unit of its kind), or one outside its plausible range.

    Examples
    --------
    >>> b = squareness_budget_with_inputs("diagonal", {"laser_ppm": 1.0}, length_x=0.6,
    ...                                   length_y=0.8)
    >>> round(b.U("squareness"), 3), [i.name for i in b.assumed][:2]
    (1.474, ['diagonal_d1', 'diagonal_d2'])
    """
    import inspect

    table = dict(table or {})
    defaults = {n: p.default for n, p in inspect.signature(squareness_budget).parameters.items()
                if n != "method"}
    for key, value in table.items():
        if key not in defaults:
            raise ConfigError(f"[squareness_uncertainty] {key}: no such input; use "
                              f"{', '.join(defaults)}")
        rule = OPTICS_SQUARE_ERROR if (key, method) == ("square_error", "optics") else \
            SQUARENESS_ENTRY[key]
        try:   # in the unit the output shows, or with its unit; refused outside its range
            table[key] = entered(key, value, rule, "[squareness_uncertainty]")
        except InputError as exc:
            raise ConfigError(str(exc)) from None
    b = squareness_budget(method, **{**table, **measured})
    records = tuple(_input_record(method, key, defaults[key], table, measured, set_with)
                    for key in METHOD_INPUTS[method])
    notes = tuple(f"assumed: {r.label} {r.value_text} ({r.rule}); set with {r.set_with}"
                  for r in records if r.assumed and r.name not in ("k", "optics_k"))
    from dataclasses import replace

    return replace(b, inputs=records, notes=notes)


def squareness_input_table() -> list[dict[str, str]]:
    """Every input of the squareness budgets as :func:`~axiscal.standards.iso230_9_inputs.
    input_table` lists the ISO 230-2 ones (budget ``squareness``; the methods that read it).

    Examples
    --------
    >>> row = next(r for r in squareness_input_table() if r["name"] == "length_x")
    >>> row["unit"], row["default"], row["range"]
    ('m', '0.8', '0.01 to 20 m')
    """
    import inspect

    defaults = {n: p.default for n, p in inspect.signature(squareness_budget).parameters.items()
                if n != "method"}
    rows = []
    for name, (label, unit, rule_text) in SQUARENESS_INPUTS.items():
        rule = SQUARENESS_ENTRY[name]
        methods = [m for m, names in METHOD_INPUTS.items() if name in names]
        extra = ("; with optics, the optical square's error in arcsec (k = 2)"
                 if name == "square_error" else "")
        rows.append({"budget": "squareness", "name": name,
                     "label": f"{label} ({', '.join(methods)}){extra}", "unit": rule.unit,
                     "default": f"{defaults[name]:g}", "range": rule.range_text,
                     "why": rule.why, "rule": rule_text})
    return rows


def _input_record(method, key, default, table, measured, set_with) -> BudgetInput:
    label, unit, rule = SQUARENESS_INPUTS[key]
    if key == "square_error" and method == "optics":
        label, unit = "optical square error (k = 2)", "arcsec"
    if key in measured:
        value, assumed, rule = measured[key], False, "measured from the data"
        set_with = "the data file"
    elif key in table:
        value, assumed, rule = table[key], False, ""    # given (by a job, the laboratory, a drift check)
    else:
        value, assumed = default, True
    return BudgetInput(key, label, float(value), unit, assumed,
                       set_with.format(key=key), rule)


def diagonal_budget(result, table: Mapping[str, float] | None = None, *,
                    set_with: str = SQUARENESS_SET_WITH) -> UncertaintyBudget:
    """The uncertainty of a diagonal test's squareness (µm/m), with its inputs.

    Parameters
    ----------
    result : axiscal.standards.iso230_6.DiagonalResult
        Supplies the travels X, Y (m) and the diagonals' length errors D1, D2 (m), measured.
    table : mapping, optional
        The user configuration's ``[squareness_uncertainty]`` table (laser accuracy, E_VE,
        uncertainty of D0, k); absent inputs take the documented defaults, marked assumed.
    set_with : str

    Returns
    -------
    UncertaintyBudget
        Contributors u_D1, u_D2 (laser ppm over D0 and E_VE, sensitivity D0/(2XY) each) and
        u_D0 (sensitivity (D1 − D2)/(2XY)); ``inputs`` and ``notes`` as
        :func:`squareness_budget_with_inputs`.

    Notes
    -----
    Squareness = D0 (D1 − D2)/(2XY) (ISO 230-6:2002 §4; ISO 230-1:2012 §10.3.2.6; M.A.V.
    Chapman, "Calibration of machine squareness", Method 5), its uncertainty by the law of
    propagation (ISO/TR 230-9:2005; GUM eq. 10), expanded with k = 2.

    Examples
    --------
    >>> from axiscal.standards.iso230_6 import diagonal_squareness
    >>> r = diagonal_squareness(0.6, 0.8, 6e-6, -3e-6)
    >>> b = diagonal_budget(r)
    >>> round(b.U("squareness"), 3), len(b.notes)   # 2·√2·0.25 µm/(0.96 m); u_D0 ≈ 1e-4
    (0.737, 3)
    """
    return squareness_budget_with_inputs(
        "diagonal", table, set_with=set_with, length_x=result.length_x,
        length_y=result.length_y, diagonal_d1=result.error_d1 * 1e6,
        diagonal_d2=result.error_d2 * 1e6)


def five_dof_budget(
    resolution: Mapping[str, float],
    ranges: Mapping[str, float],
    calibration: float = 0.01,
    crosstalk: Mapping[str, float] | None = None,
    drift: Mapping[str, float] | None = None,
    k: float = COVERAGE_FACTOR,
) -> dict[str, UncertaintyBudget]:
    """Uncertainty of each of the five measured motion errors.

    Parameters
    ----------
    resolution : mapping of channel to float, arcsec or µm
        Detector resolution per channel (``ez``, ``ey``, ``ex``, ``dy``, ``dz``), e.g. from
        :func:`axiscal.physics.five_dof.resolutions`.
    ranges : mapping of channel to float, arcsec or µm
        Peak-to-valley measured per channel (the calibration error scales with it).
    calibration : float
        Relative standard uncertainty of each detector's scale calibration (default 1 %).
    crosstalk : mapping of channel to float, optional
        Peak-to-valley left by the set-up's crosstalk after removing once per turn (as
        :class:`~axiscal.procedures.motion_errors.Crosstalk` ``residual`` quantifies it), a ± half.
    drift : mapping of channel to float, optional
        Standard deviation of the drift-compensated reading of a still set-up (§3.2).
    k : float

    Returns
    -------
    dict of channel to UncertaintyBudget
        Parameter name = channel; unit arcsec for angles, µm for displacements.

    Examples
    --------
    >>> b = five_dof_budget({"ez": 0.26}, {"ez": 10.0}, calibration=0.01)
    >>> round(b["ez"].U("ez"), 3)      # 2·√((0.26/(2√3))² + 0.1²)
    0.25
    """
    crosstalk, drift = dict(crosstalk or {}), dict(drift or {})
    if not (math.isfinite(calibration) and calibration >= 0):
        raise InputError(f"five-DOF calibration = {calibration!r} must be >= 0")
    out = {}
    for ch, res in resolution.items():
        if ch not in FIVE_DOF_CHANNELS:
            raise InputError(f"five-DOF channel {ch!r}: use one of {', '.join(FIVE_DOF_CHANNELS)}")
        unit = "arcsec" if ch.startswith("e") else "um"
        out[ch] = combine(_five_dof_contributors(ch, unit, res, ranges, calibration, crosstalk,
                                                 drift), unit, k, (ch,))
    return out


def _five_dof_contributors(ch, unit, res, ranges, calibration, crosstalk, drift) -> list:
    """Resolution, scale calibration and, where given, crosstalk and drift of channel ``ch``."""
    p = (ch,)
    sec = "Optics Express 2018 (five DOF of a rotary axis)"
    c = [
        Contributor(
            "u_RESOLUTION",
            "detector resolution",
            res / (2 * _SQ3),
            "rectangular",
            f"{sec}, §3 (eqs. 1-6)",
            f"{res:g} {unit}",
            p,
        ),
        Contributor(
            "u_CALIBRATION",
            "detector scale calibration",
            calibration * abs(ranges.get(ch, 0.0)),
            "normal",
            f"{sec}, §3; ISO/TR 230-9 §5",
            f"{calibration * 100:g} % of {ranges.get(ch, 0.0):g} {unit}",
            p,
        ),
    ]
    if ch in crosstalk:
        c.append(
            Contributor(
                "u_CROSSTALK",
                "crosstalk of the mounting errors",
                crosstalk[ch] / 2 / _SQ3,
                "rectangular",
                f"{sec}, mounting errors (as simulated)",
                f"± {crosstalk[ch] / 2:g} {unit}",
                p,
            )
        )
    if ch in drift:
        c.append(
            Contributor(
                "u_DRIFT",
                "residual drift after compensation",
                drift[ch],
                "normal",
                f"{sec}, §3.2 (eqs. 7-9)",
                f"σ = {drift[ch]:g} {unit}",
                p,
            )
        )
    return c


def slope_uncertainty(positions, deviations) -> float:
    """Standard uncertainty of a least-squares slope from its residuals, µm/m.

    Parameters
    ----------
    positions : array_like, m
    deviations : array_like, m

    Returns
    -------
    float, µm/m
        ``s_res / √Σ(x − x̄)²`` with ``s_res² = Σ r² / (n − 2)`` (ISO 230-1:2012 §3.4.8 least-
        squares reference line; the standard uncertainty of a regression slope, GUM H.3).

    Examples
    --------
    >>> round(slope_uncertainty([0, 0.1, 0.2, 0.3], [0, 1e-6, 0, 1e-6]), 3)  # √(0.8e-12/2/0.05)
    2.828
    """
    import numpy as np

    x, y = np.asarray(positions, float), np.asarray(deviations, float)
    if x.size < 3 or x.size != y.size:
        raise InputError(f"slope uncertainty: {x.size} points; a residual needs at least 3")
    sxx = float(np.sum((x - x.mean()) ** 2))
    if sxx <= 0:
        raise InputError("slope uncertainty: all positions are the same")
    slope, icpt = np.polyfit(x, y, 1)
    res = y - (slope * x + icpt)
    return float(math.sqrt(float(np.sum(res**2)) / (x.size - 2) / sxx) * 1e6)
