"""How each input of an ISO 230-2 Annex A budget is typed: its unit and its plausible range.

A number a user types for an input of the ``[uncertainty]`` table (a job or configuration file,
``--uncertainty NAME=VALUE``, the ``uncertainty=`` mapping of :func:`axiscal.evaluate`) is in
the unit the output shows beside it: the expansion coefficient α is typed as 11.5 (µm/(m·K)),
as every report prints it, and becomes 11.5e-6 /K inside. A value may also carry its own unit
as text, read by pint (``"11.5 um/(m K)"``, ``"20.5 degC"``, ``"293.15 K"``, ``"0.05 mm"``).

A value outside its plausible range is refused with the range: the usual slip is a value in
another unit (α in 1/K typed where µm/(m·K) is meant, a material temperature in K typed where
°C is meant), and a budget from it would be wrong by orders of magnitude (α = 11.5 read as 1/K
gave U(A) = 210,000 µm). The ranges are wide on purpose (axiscal's rule: every machine scale,
instrument and shop the sources of the defaults describe, with a margin); a range with
``zero`` also takes exactly 0 (an exactly known value, α of a Zerodur scale).

:func:`axiscal.standards.iso230_9_inputs.input_table` lists every input with its unit, default,
range and rule; the documentation's page "Uncertainty inputs" is generated from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from axiscal.errors import InputError

__all__ = ["EntryRule", "MAX_INPUT", "checked_table", "LINEAR_ENTRY", "ROTARY_ENTRY",
           "SQUARENESS_ENTRY", "OPTICS_SQUARE_ERROR", "entered", "entered_table"]


@dataclass(frozen=True)
class EntryRule:
    """The unit a number of one input is typed in, and the range it must lie in.

    Attributes
    ----------
    unit : str
        The unit of a plain number, as the output shows it (``µm/(m·K)``).
    pint : str
        The same unit as pint writes it (``um/(m*K)``), for a value given with its unit.
    scale : float
        The input's value inside (the field of :class:`~axiscal.standards.iso230_9.LinearInputs`
        or :class:`~axiscal.standards.iso230_9.RotaryInputs`) = typed value × ``scale``.
    low, high : float
        The plausible range, in ``unit``.
    zero : bool
        Exactly 0 is plausible too, below ``low``.
    difference : bool
        A difference of temperature (K): ``"0.1 degC"`` means 0.1 K.
    example : str
        A plausible value with its unit, shown in the error message.
    why : str
        What the range holds, shown in the error message.
    """

    unit: str
    pint: str
    low: float
    high: float
    example: str
    why: str
    scale: float = 1.0
    zero: bool = False
    difference: bool = False

    @property
    def range_text(self) -> str:
        """``0.001 to 100 µm/(m·K)`` (``0, or ...`` when 0 is plausible)."""
        unit = f" {self.unit}" if self.unit else ""
        text = f"{self.low:g} to {self.high:g}{unit}"
        return f"0, or {text}" if self.zero and self.low > 0 else text


#: Largest magnitude of any uncertainty input, in its own unit (the bound of every measured value,
#: :data:`axiscal._parse.MAX_MAGNITUDE`): the budget squares and sums them (GUM eq. 10), and an
#: input of 1e150 or more overflowed there with a traceback (issue 39).
MAX_INPUT = 1e100

_ALPHA_WHY = "steel 11.5, glass scale about 8, aluminium 23, Invar 1.2, Zerodur about 0"
_T_WHY = "a machine in a workshop"

#: How each number of a linear budget is typed (text inputs, reference and e_ve_source, have
#: no rule).
LINEAR_ENTRY: dict[str, EntryRule] = {
    "laser_accuracy_ppm": EntryRule("ppm", "ppm", 0.01, 100.0, "0.5 ppm",
                                    "laser interferometers are certified to about 0.1-5 ppm"),
    "laser_accuracy_k": EntryRule("", "", 1.0, 10.0, "2", "a coverage factor, usually 2"),
    "encoder_accuracy": EntryRule("µm/m", "um/m", 0.01, 1000.0, "5 um/m",
                                  "scales are accurate to about ±1 to ±100 µm/m"),
    "resolution": EntryRule("µm", "um", 1e-6, 100.0, "1 nm",
                            "from 0.001 nm to 0.1 mm", zero=True),
    "beam_offset": EntryRule("mm", "mm", 0.0, 25.0, "0.125 mm",
                             "an offset larger than a retroreflector's aperture loses the beam"),
    "expansion_coefficient": EntryRule("µm/(m·K)", "um/(m*K)", 0.001, 100.0, "11.5 um/(m K)",
                                       _ALPHA_WHY, scale=1e-6, zero=True),
    "expansion_coefficient_halfwidth": EntryRule(
        "µm/(m·K)", "um/(m*K)", 0.001, 50.0, "1.15 um/(m K)",
        "a half-width of α, 10 % of α for a handbook value", scale=1e-6, zero=True),
    "material_temperature": EntryRule("°C", "degC", 0.0, 50.0, "293.15 K", _T_WHY),
    "shop_temperature_min": EntryRule("°C", "degC", 0.0, 50.0, "290.15 K", _T_WHY),
    "shop_temperature_max": EntryRule("°C", "degC", 0.0, 50.0, "296.15 K", _T_WHY),
    "temperature_halfwidth": EntryRule("K", "K", 0.0, 10.0, "0.1 K",
                                       "a temperature sensor's accuracy", difference=True),
    "sensor_position_halfwidth": EntryRule("K", "K", 0.0, 10.0, "0.2 K",
                                           "a temperature difference along a scale",
                                           difference=True),
    "e_ve": EntryRule("µm", "um", 0.0, 1000.0, "0.3 um", "a drift check's range"),
}
#: How each number of a rotary budget is typed.
ROTARY_ENTRY: dict[str, EntryRule] = {
    "calibrator_accuracy": EntryRule("arcsec", "arcsec", 0.001, 100.0, "1 arcsec",
                                     "rotary calibrators are certified to about 0.1-5 arcsec"),
    "calibrator_k": EntryRule("", "", 1.0, 10.0, "2", "a coverage factor, usually 2"),
    "resolution": EntryRule("arcsec", "arcsec", 1e-4, 100.0, "0.1 arcsec",
                            "a reading's last digit", zero=True),
    "alpha": EntryRule("mrad", "mrad", 0.0, 100.0, "0.5 mrad", "a set-up misalignment"),
    "beta": EntryRule("mrad", "mrad", 0.0, 100.0, "1 mrad", "a set-up misalignment"),
    "omega": EntryRule("mrad", "mrad", 0.0, 100.0, "2.5 mrad", "a set-up misalignment"),
    "e_ve": EntryRule("arcsec", "arcsec", 0.0, 100.0, "0.5 arcsec", "a drift check's range"),
}


_SQ_WHY = "a squareness set-up"
#: How each number of a squareness budget's ``[squareness_uncertainty]`` table is typed (keys of
#: :func:`axiscal.standards.iso230_9_geometry.squareness_budget`; ``square_error`` of the
#: ``optics`` method is :data:`OPTICS_SQUARE_ERROR`).
SQUARENESS_ENTRY: dict[str, EntryRule] = {
    "length_x": EntryRule("m", "m", 0.01, 20.0, "0.8 m", "an axis travel; mm need their unit"),
    "length_y": EntryRule("m", "m", 0.01, 20.0, "0.8 m", "an axis travel; mm need their unit"),
    "optics_accuracy": EntryRule("µm/m", "um/m", 0.0, 100.0, "0.5 um/m",
                                 "straightness optics' slope accuracy"),
    "optics_k": EntryRule("", "", 1.0, 10.0, "2", "a coverage factor, usually 2"),
    "square_error": EntryRule("µm", "um", 0.0, 100.0, "0.5 um", "a square's certified error"),
    "square_length": EntryRule("m", "m", 0.01, 5.0, "0.5 m",
                               "a granite or steel square; mm need their unit"),
    "probe_accuracy": EntryRule("µm", "um", 0.0, 100.0, "0.5 um", "an indicator's accuracy"),
    "slope_fit_x": EntryRule("µm/m", "um/m", 0.0, 1000.0, "0.2 um/m", "a fitted slope's u"),
    "slope_fit_y": EntryRule("µm/m", "um/m", 0.0, 1000.0, "0.2 um/m", "a fitted slope's u"),
    "e_ve": EntryRule("µm", "um", 0.0, 1000.0, "0.3 um", "a drift check's range"),
    "reposition": EntryRule("µm", "um", 0.0, 100.0, "0.5 um", _SQ_WHY),
    "ballbar_radius": EntryRule("m", "m", 0.01, 2.0, "0.15 m",
                                "a ballbar's length; mm need their unit"),
    "transducer_accuracy": EntryRule("µm", "um", 0.0, 100.0, "0.5 um",
                                     "a ballbar transducer's accuracy"),
    "laser_ppm": EntryRule("ppm", "ppm", 0.01, 100.0, "0.5 ppm",
                           "laser interferometers are certified to about 0.1-5 ppm"),
    "diagonal_d1": EntryRule("µm", "um", -1000.0, 1000.0, "5 um", "a diagonal's length error"),
    "diagonal_d2": EntryRule("µm", "um", -1000.0, 1000.0, "5 um", "a diagonal's length error"),
    "diagonal_length_u": EntryRule("µm", "um", 0.0, 1000.0, "10 um", _SQ_WHY),
    "k": EntryRule("", "", 1.0, 10.0, "2", "a coverage factor, usually 2"),
}
#: ``square_error`` of the ``optics`` method: the optical square's error, arcsec (k = 2).
OPTICS_SQUARE_ERROR = EntryRule("arcsec", "arcsec", 0.0, 100.0, "1 arcsec",
                                "an optical square's certified error")


def entered(name: str, value: Any, rule: EntryRule, where: str = "uncertainty") -> float:
    """One typed value of an input, checked and in the unit the budget uses inside.

    Parameters
    ----------
    name : str
        The input's key (named in the error).
    value : float or str
        A number in ``rule.unit``, or text: a number alone, or a number and its unit.
    rule : EntryRule
    where : str
        What the error names before the key (``uncertainty``, ``[squareness_uncertainty]``).

    Returns
    -------
    float
        ``value`` in ``rule.unit`` × ``rule.scale``.

    Raises
    ------
    InputError
        Not a number, a unit of another kind, or a value outside the plausible range (named).

    Examples
    --------
    >>> entered("expansion_coefficient", 11.5, LINEAR_ENTRY["expansion_coefficient"])
    1.15e-05
    >>> entered("material_temperature", "293.15 K", LINEAR_ENTRY["material_temperature"])
    20.0
    >>> entered("material_temperature", 293.15, LINEAR_ENTRY["material_temperature"])
    Traceback (most recent call last):
    ...
    axiscal.errors.InputError: uncertainty material_temperature = 293.15 °C is implausible: ...
    """
    unit = f" {rule.unit}" if rule.unit else ""
    if isinstance(value, str):
        from axiscal.units import quantity

        try:
            typed = quantity(value, rule.pint or "dimensionless", difference=rule.difference)
        except InputError as e:
            raise InputError(f"{where} {name} = {e}; e.g. {rule.example!r}") from None
        typed = float(f"{typed:.12g}")   # 68 °F is 20 °C, not 20.000000000000057
    elif isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{where} {name} = {value!r}: give a number in{unit or ' 1'} "
                         f"or text with its unit, e.g. {rule.example!r}")
    else:
        typed = float(value)
    if not math.isfinite(typed):
        raise InputError(f"{where} {name} = {typed!r} must be a finite number")
    if not (rule.low <= typed <= rule.high or (rule.zero and typed == 0.0)):
        raise InputError(
            f"{where} {name} = {typed:g}{unit} is implausible: give {rule.range_text} "
            f"({rule.why}); a value in another unit needs its unit, e.g. {rule.example!r}")
    return typed * rule.scale


def entered_table(table: Mapping[str, Any], rules: Mapping[str, EntryRule]) -> dict[str, Any]:
    """Every value of an ``[uncertainty]`` table with a rule, :func:`entered`; others as given
    (the text inputs, and unknown keys left for the caller to refuse by name)."""
    return {k: entered(k, v, rules[k]) if k in rules and v is not None else v
            for k, v in table.items()}


def checked_table(table: Mapping[str, Any] | None, inputs: Mapping[str, tuple], where: str,
                  extra: tuple[str, ...] = ()) -> dict[str, Any]:
    """A budget's configuration table (``[straightness_uncertainty]``, ``[motion_uncertainty]``,
    ``[volumetric_uncertainty]``) checked by one rule: every key one of ``inputs`` (or of
    ``extra``, text keys returned as given), every value a finite number ≥ 0 and at most
    :data:`MAX_INPUT` (squared in the budget: GUM eq. 10;
    issue 39) in the input's unit, or text with its unit read by pint (``"0.5 um"``); the
    coverage factor ``k`` > 0.

    Parameters
    ----------
    table : mapping or None
    inputs : mapping of key to (label, unit, default, rule)
        The budget's inputs, each unit as the output shows it (``µm``, ``%``, ``µrad``).
    where : str
        The table's name as the user types it (``[motion_uncertainty]``), named in the error.
    extra : tuple of str
        Keys of text values the caller checks itself (``correlation``).

    Returns
    -------
    dict
        Each number in its input's unit, as float.

    Raises
    ------
    ConfigError
        An unknown key, or a value out of the rule (one line naming the key and the unit).

    Examples
    --------
    >>> inputs = {"resolution": ("resolution", "µm", 0.1, ""), "k": ("k", "", 2.0, "")}
    >>> checked_table({"resolution": "100 nm"}, inputs, "[straightness_uncertainty]")
    {'resolution': 0.1}
    >>> checked_table({"resolution": -1}, inputs, "[straightness_uncertainty]")
    Traceback (most recent call last):
    ...
    axiscal.errors.ConfigError: [straightness_uncertainty] resolution = -1: a finite number ≥ 0 (at most 1e+100) in µm
    """
    from axiscal.errors import ConfigError

    known = [*inputs, *extra]
    out: dict[str, Any] = {}
    for key, value in dict(table or {}).items():
        if key not in known:
            raise ConfigError(f"{where} {key}: no such input; use {', '.join(known)}")
        if key in extra:
            out[key] = value
            continue
        unit = inputs[key][1]
        typed = value
        if isinstance(value, str):
            from axiscal.units import quantity

            try:
                typed = quantity(value, unit or "dimensionless")
            except InputError as e:
                raise ConfigError(f"{where} {key} = {e}") from None
        if isinstance(typed, bool) or not isinstance(typed, (int, float)) \
                or not math.isfinite(typed) or not 0 <= typed <= MAX_INPUT \
                or (key == "k" and typed <= 0):
            raise ConfigError(f"{where} {key} = {value!r:.40}: a finite number ≥ 0 (at most "
                              f"{MAX_INPUT:g}) in {unit or 'no unit'}")
        out[key] = float(typed)
    return out
