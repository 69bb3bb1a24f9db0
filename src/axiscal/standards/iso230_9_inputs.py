"""Inputs of the ISO 230-2 Annex A uncertainty budgets, and the documented rule behind every default.

A budget is only as good as its inputs, and most users never declare them: the laser's accuracy,
how well the beam was aligned, the shop's temperature, the environmental variation error E_VE.
Each input of :class:`LinearInputs` and :class:`RotaryInputs` therefore comes with a
:class:`BudgetInput` record saying where its value came from: declared by the user (a job or
configuration file's ``[uncertainty]`` table, or a command's option), taken from the data file
(material temperature, expansion coefficient, the reference instrument's kind), or **assumed**
by a documented rule. The records travel with the budget
(:attr:`~axiscal.standards.iso230_9.UncertaintyBudget.inputs`) so every front end and report
shows them beside U.

Rules of the defaults
---------------------
beam offset (laser)
    d = 0.125 mm over any travel: the operator aligns until the two return dots no longer move
    apart, and the smallest motion of the dots an operator perceives is about S = 0.25 mm
    (Hewlett-Packard, "5528A Laser Measurement System User's Guide", Section 6, Distance
    measurements, cosine error: E = S²/(8D²)). A retroreflector returns the beam displaced by
    twice its lateral offset, so d = S/2 and the cosine error e = L·θ²/2 = d²/(2L) = S²/(8L). A
    short travel therefore has the larger cosine error (the same guide recommends the maximum-
    reading technique there): declare the offset you achieved.
reference instrument
    A laser interferometer, unless the data file names another: an EPICS ecmc reference PV
    ``…-Enc<NN>-PosAct`` (ecmc's name for an encoder's actual position) is an encoder, a name
    with "laser" or "interferometer" a laser. An encoder's device contributor is its scale
    accuracy (±5 µm/m: Renishaw RTLC20 tape scale, "TONiC FS incremental encoder system with
    RTLC20 linear scale") as a rectangular ± bound; it has no beam, so no beam misalignment.
laser accuracy
    ±0.5 ppm (k = 2): Renishaw XL-80 laser system specification, linear measurement accuracy.
material temperature
    When the data file and the user do not state it, the shop's temperature range is used
    (default 20 ± 3 °C, 17-23 °C: no standard fixes a shop's range, so it is shown as assumed);
    the uncertainty of α then acts over the largest |T − 20 °C| of that range.
resolution of the reading
    Where the data shows it: the readings at one target differ by whole multiples of one step
    (an encoder's increment, 0.2037 µm in an ESS ecmc file), so that step is the resolution,
    taken from the data (:func:`reading_step`); else the default (1 nm for a laser or an
    encoder, 0.1 arcsec for a rotary calibrator). A declared value always wins.
one laboratory configuration for every kind
    The ``[uncertainty]`` table serves linear and rotary tests: keys of the other kind's budget
    are ignored and named in the budget's notes (:func:`split_table`); ``[uncertainty.linear]``
    and ``[uncertainty.rotary]`` hold values for one kind only (over the common ones), and each
    holds the laboratory's CMC per parameter (``cmc = {E = 1.0, R = 0.6}``, µm or arcsec).
E_VE
    Never assumed: measure it with a drift check (:func:`environmental_variation`, ISO 230-2:2014
    Annex A.5) or declare it. A budget without it leaves E_VE out of U, lists it in
    ``missing_inputs`` and says so.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, fields
from typing import Any, Mapping

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.iso230_9_entry import (LINEAR_ENTRY, MAX_INPUT, ROTARY_ENTRY,  # noqa: F401
                                              entered_table)

__all__ = [
    "BudgetInput",
    "LinearInputs",
    "RotaryInputs",
    "reference_kind",
    "resolve_linear",
    "resolve_rotary",
    "environmental_variation",
    "runs_statement",
    "REFERENCE_KINDS",
    "input_table",
    "reading_step",
    "split_table",
    "KIND_TABLES",
]

#: Sub-tables of ``[uncertainty]`` holding one axis kind's values and CMC.
KIND_TABLES = ("linear", "rotary")

#: Reference instruments a linear budget knows (a rotary budget's reference is a calibrator).
REFERENCE_KINDS = ("laser", "encoder")
_TEXT_KEYS = ("reference", "e_ve_source")
_E_VE_SOURCES = ("drift check", "declared")

_HP = ("Hewlett-Packard, 5528A Laser Measurement System User's Guide, Section 6, cosine error "
       "(smallest perceptible motion of the return dots S = 0.25 mm; d = S/2)")
_EVE_RULE = ("not given, so U leaves it out: measure it by a drift check over the test's duration "
             "(ISO 230-2:2014 Annex A.5) or declare it")


@dataclass(frozen=True)
class BudgetInput:
    """One input of an uncertainty budget as a reader must see it beside U.

    Attributes
    ----------
    name : str
        Key in the ``[uncertainty]`` table (``beam_offset`` ...).
    label : str
        What it is, in words.
    value : float, str or None
        None when the input is missing (E_VE not given).
    unit : str
    assumed : bool
        True when neither the user nor the data file gave it (or it is missing).
    set_with : str
        The option or job key that sets it.
    rule : str
        The documented rule of an assumed value, or where a given value came from.
    """

    name: str
    label: str
    value: Any
    unit: str
    assumed: bool
    set_with: str
    rule: str

    def to_json(self) -> dict[str, Any]:
        """``{"value", "unit", "assumed", "set_with", "rule", "label"}``."""
        return {"value": self.value, "unit": self.unit, "assumed": self.assumed,
                "set_with": self.set_with, "rule": self.rule, "label": self.label}

    @property
    def value_text(self) -> str:
        """The value with its unit (``0.125 mm``; ``not given``)."""
        if self.value is None:
            return "not given"
        if self.unit == "1/K":   # as α is written: 11.5 µm/(m·K), not 1.15e-05 1/K
            return f"{self.value * 1e6:.4g} µm/(m·K)"
        v = f"{self.value:g}" if isinstance(self.value, (int, float)) else str(self.value)
        return f"{v} {self.unit}".strip()

    def __str__(self) -> str:
        how = "assumed" if self.assumed else "given"
        return f"{self.label} {self.value_text} ({how}: {self.rule}; set with {self.set_with})"




def _check_inputs(inputs, signed: tuple, k: str) -> None:
    """Every number finite and >= 0 (``signed`` ones may be negative), text keys from their
    lists, and the coverage factor ``k`` positive."""
    for f in fields(inputs):
        v = getattr(inputs, f.name)
        if f.name == "e_ve_source":
            if v not in _E_VE_SOURCES:
                raise InputError(
                    f"uncertainty e_ve_source = {v!r}: use 'drift check' or 'declared'")
        elif f.name == "reference":
            if v not in REFERENCE_KINDS:
                raise InputError(f"uncertainty reference = {v!r}: use laser or encoder")
        elif v is not None and (isinstance(v, bool) or not isinstance(v, (int, float))
                                or not math.isfinite(v) or (v < 0 and f.name not in signed)):
            raise InputError(f"uncertainty {f.name} = {v!r} must be a finite number >= 0")
        elif v is not None and abs(v) > MAX_INPUT:   # squared in the budget: 1e200² overflows
            raise InputError(f"uncertainty {f.name} = {v:g} is out of range (at most "
                             f"{MAX_INPUT:g} in magnitude; no calibration input is so large)")
    if getattr(inputs, k) <= 0:
        raise InputError(f"uncertainty {k} must be > 0")


def _known_keys(cls, d: Mapping[str, Any], rules) -> dict:
    """``d`` as keyword arguments of ``cls``, an unknown key refused by name, each number read
    in the unit the output shows and checked against its plausible range
    (:mod:`axiscal.standards.iso230_9_entry`)."""
    known = {f.name for f in fields(cls)}
    if any(k not in known for k in d):   # the schema's refusal (and its import) for a stray key
        from axiscal._schema import refuse_unknown

        refuse_unknown(dict(d) if not isinstance(d, dict) else d, known, "[uncertainty]")
    return entered_table(d, rules)


@dataclass(frozen=True)
class LinearInputs:
    """What a linear ISO 230-2 budget needs; each field settable in ``[uncertainty]``.

    The fields hold the budget's own units (α in 1/K); a value typed in ``[uncertainty]`` or
    with ``--uncertainty`` is in the unit the output shows (α in µm/(m·K)) or carries its unit,
    and is checked against a plausible range (:mod:`axiscal.standards.iso230_9_entry`).

    Attributes
    ----------
    reference : str
        ``laser`` (interferometer) or ``encoder`` (a linear scale as reference).
    laser_accuracy_ppm : float, ppm
        Laser accuracy from its calibration certificate, expanded with ``laser_accuracy_k``.
    laser_accuracy_k : float
    encoder_accuracy : float, µm/m
        Encoder reference: scale accuracy, a ± bound (rectangular).
    resolution : float, deviation unit (µm)
        Resolution of the reading.
    beam_offset : float, mm
        Laser: lateral offset of the beam over the travel as aligned.
    expansion_coefficient : float, 1/K
        α of the machine's scale (the dataset's value when it has one).
    expansion_coefficient_halfwidth : float or None, 1/K
        Half-width of the rectangular distribution of α (None: 10 % of α).
    material_temperature : float or None, °C
        Mean temperature of the machine (None: not stated; the shop range applies).
    shop_temperature_min, shop_temperature_max : float, °C
        Range the shop's temperature stays in, used when the material temperature is not stated.
    temperature_halfwidth : float, K
        Accuracy of the material temperature sensor (half-width).
    sensor_position_halfwidth : float, K
        Largest difference between the sensor's place and the scale's mean temperature.
    e_ve : float or None, deviation unit (µm)
        Environmental variation error: range of a drift check over the test's duration
        (None: not given, left out of U).
    e_ve_source : str
        ``drift check`` or ``declared``.
    """

    reference: str = "laser"
    laser_accuracy_ppm: float = 0.5
    laser_accuracy_k: float = 2.0
    encoder_accuracy: float = 5.0
    resolution: float = 0.001
    beam_offset: float = 0.125
    expansion_coefficient: float = 11.5e-6
    expansion_coefficient_halfwidth: float | None = None
    material_temperature: float | None = None
    shop_temperature_min: float = 17.0
    shop_temperature_max: float = 23.0
    temperature_halfwidth: float = 0.1
    sensor_position_halfwidth: float = 0.2
    e_ve: float | None = None
    e_ve_source: str = "declared"

    def __post_init__(self) -> None:
        _check_inputs(self, ("material_temperature", "shop_temperature_min",
                             "shop_temperature_max"), "laser_accuracy_k")
        if self.shop_temperature_min > self.shop_temperature_max:
            raise InputError(f"uncertainty shop_temperature_min = {self.shop_temperature_min:g} "
                             f"°C is above shop_temperature_max = {self.shop_temperature_max:g} °C")

    @property
    def alpha_halfwidth(self) -> float:
        """Half-width a_α of α's rectangular distribution, 1/K (10 % of α unless declared)."""
        if self.expansion_coefficient_halfwidth is None:
            return 0.1 * self.expansion_coefficient
        return self.expansion_coefficient_halfwidth

    @property
    def temperature_deviation(self) -> float:
        """|T − 20 °C| in K: of the stated material temperature, else the largest of the shop
        range (ISO/TR 16015:2003 case b: the uncertainty of α acts over T − 20 °C)."""
        if self.material_temperature is not None:
            return abs(self.material_temperature - 20.0)
        return max(abs(self.shop_temperature_min - 20.0), abs(self.shop_temperature_max - 20.0))

    @classmethod
    def from_mapping(cls, d: Mapping[str, Any], dataset=None) -> "LinearInputs":
        """From a config table (``[uncertainty]``), filling α, T and the reference from the
        dataset where the table does not give them."""
        return resolve_linear(d, dataset)[0]


@dataclass(frozen=True)
class RotaryInputs:
    """What a rotary ISO 230-2 budget needs (angles in arcsec, misalignments in mrad).

    A value typed in ``[uncertainty]`` is read and checked as for :class:`LinearInputs`.

    Attributes
    ----------
    calibrator_accuracy : float, arcsec
        Accuracy of the rotary calibrator from its certificate, expanded with ``calibrator_k``.
    calibrator_k : float
    resolution : float, arcsec
    alpha, beta, omega : float, mrad
        Misalignments of Renishaw, "Interferometric calibration of rotary axes", eq. 1: axes (α),
        laser line of sight (β), reflector twist (ω).
    e_ve : float or None, arcsec
        None: not given, left out of U.
    e_ve_source : str
    """

    calibrator_accuracy: float = 1.0
    calibrator_k: float = 2.0
    resolution: float = 0.1
    alpha: float = 0.5
    beta: float = 1.0
    omega: float = 2.5
    e_ve: float | None = None
    e_ve_source: str = "declared"

    def __post_init__(self) -> None:
        _check_inputs(self, signed=(), k="calibrator_k")

    @classmethod
    def from_mapping(cls, d: Mapping[str, Any]) -> "RotaryInputs":
        """From a config table (``[uncertainty]``)."""
        return resolve_rotary(d)[0]


#: (label, unit, rule of the default) of every linear input.
_LINEAR = {
    "reference": ("reference instrument", "", "a laser interferometer unless the data file "
                  "names another reference (ISO 230-2:2014 Annex A.2)"),
    "laser_accuracy_ppm": ("laser measurement accuracy (expanded)", "ppm",
                           "Renishaw XL-80 laser system specification, linear measurement "
                           "accuracy ±0.5 ppm; use your laser's calibration certificate"),
    "laser_accuracy_k": ("coverage factor of the laser accuracy", "",
                         "k = 2, as calibration certificates state it (JCGM 100:2008 §6.3)"),
    "encoder_accuracy": ("encoder scale accuracy (± bound)", "µm/m",
                         "Renishaw, TONiC FS encoder system with RTLC20 linear scale: accurate "
                         "to ±5 µm/m; use your encoder's data sheet or calibration"),
    "resolution": ("resolution of the reading", "µm",
                   "1 nm, the last digit of a laser interferometer's or an encoder's reading "
                   "(axiscal's rule; ISO 230-2:2014 Annex A.2 names the effect)"),
    "beam_offset": ("beam offset over the travel", "mm", _HP),
    "expansion_coefficient": ("expansion coefficient α of the machine's scale", "1/K",
                              "steel, 11.5 µm/(m·K) (ISO/TR 16015:2003, table of materials)"),
    "expansion_coefficient_halfwidth": ("uncertainty of α (half-width)", "1/K",
                                        "±10 % of α for a handbook value (axiscal's rule)"),
    "material_temperature": ("material temperature", "°C", "not stated: the shop range "
                             "applies"),
    "shop_temperature_min": ("lowest shop temperature", "°C", "20 ± 3 °C, a shop without a "
                             "stated climate (axiscal's rule; no standard fixes it)"),
    "shop_temperature_max": ("highest shop temperature", "°C", "20 ± 3 °C, a shop without a "
                             "stated climate (axiscal's rule; no standard fixes it)"),
    "temperature_halfwidth": ("material temperature sensor accuracy (half-width)", "K",
                              "±0.1 K, a laser compensator's material sensor (Renishaw XC-80)"),
    "sensor_position_halfwidth": ("sensor place vs the scale's mean temperature (half-width)",
                                  "K", "±0.2 K for one sensor on the scale (axiscal's rule; "
                                  "ISO 230-2:2014 Annex A.4 names the effect, not a value)"),
    "e_ve": ("environmental variation error E_VE", "µm", _EVE_RULE),
    "e_ve_source": ("how E_VE was found", "", "declared unless a drift check is named"),
}
_ROTARY = {
    "calibrator_accuracy": ("rotary calibrator accuracy (expanded)", "arcsec",
                            "±1 arcsec (k = 2), a reference calibrator's specification (Renishaw "
                            "XR20 class); use its calibration certificate"),
    "calibrator_k": ("coverage factor of the calibrator accuracy", "",
                     "k = 2, as calibration certificates state it (JCGM 100:2008 §6.3)"),
    "resolution": ("resolution of the reading", "arcsec", "0.1 arcsec display resolution"),
    "alpha": ("axes misalignment α", "mrad", "set-up tolerance of Renishaw, \"Interferometric "
              "calibration of rotary axes\", eq. 1 (axiscal's rule: 0.5 mrad)"),
    "beta": ("line-of-sight misalignment β", "mrad", "Renishaw, \"Interferometric calibration "
             "of rotary axes\", eq. 1 (axiscal's rule: 1 mrad)"),
    "omega": ("reflector twist ω", "mrad", "Renishaw, \"Interferometric calibration of rotary "
              "axes\", eq. 1 (axiscal's rule: 2.5 mrad)"),
    "e_ve": ("environmental variation error E_VE", "arcsec", _EVE_RULE),
    "e_ve_source": ("how E_VE was found", "", "declared unless a drift check is named"),
}


def input_table() -> list[dict[str, str]]:
    """Every input of the ISO 230-2 Annex A budgets: budget, name, label (what it is), unit,
    default, plausible range and what it holds (why), and the rule of its default (the
    documentation's table).

    Examples
    --------
    >>> row = next(r for r in input_table() if r["name"] == "expansion_coefficient")
    >>> row["unit"], row["default"], row["range"]
    ('µm/(m·K)', '11.5', '0, or 0.001 to 100 µm/(m·K)')
    """
    rows = []
    for budget, cls, spec, rules in (("linear", LinearInputs, _LINEAR, LINEAR_ENTRY),
                                     ("rotary", RotaryInputs, _ROTARY, ROTARY_ENTRY)):
        defaults = {f.name: f.default for f in fields(cls)}
        for name, (label, unit, rule_text) in spec.items():
            rule = rules.get(name)
            default = defaults[name]
            if default is not None and rule is not None:
                default = f"{default / rule.scale:.6g}"
            elif default is None:
                default = {"expansion_coefficient_halfwidth": "10 % of α",
                           "material_temperature": "the data file's, else not stated",
                           }.get(name, "not given")
            rows.append({
                "budget": budget, "name": name, "label": label,
                "unit": rule.unit if rule else unit, "default": str(default),
                "range": rule.range_text if rule else {
                    "reference": "laser or encoder",
                    "e_ve_source": "drift check or declared"}[name],
                "why": rule.why if rule else "", "rule": rule_text,
            })
    return rows


def reference_kind(instrument: str) -> tuple[str, str] | None:
    """The reference instrument's kind as a data file names it, with the reason.

    Parameters
    ----------
    instrument : str
        The dataset's ``metadata.instrument`` (an ecmc file's ``REF_PV``, a CSV's instrument).

    Returns
    -------
    (kind, why) or None
        ``("encoder", ...)`` for an EPICS ecmc PV ``…-Enc<NN>-PosAct`` or a name with "encoder"
        or "scale"; ``("laser", ...)`` for "laser" or "interferometer"; None when it says
        neither.

    Examples
    --------
    >>> reference_kind("IOC_TEST:m0s005-Enc01-PosAct")[0]
    'encoder'
    >>> reference_kind("simulated laser interferometer, linear optics")[0]
    'laser'
    >>> reference_kind("") is None
    True
    """
    text = instrument or ""
    if re.search(r"-Enc\d*-PosAct\b", text, re.IGNORECASE):
        return "encoder", (f"the data file's reference {text!r} is an ecmc encoder's actual "
                           "position (…-Enc<NN>-PosAct)")
    if re.search(r"\b(encoder|linear scale|glass scale)\b", text, re.IGNORECASE):
        return "encoder", f"the data file names the reference {text!r}"
    if re.search(r"laser|interferometer", text, re.IGNORECASE):
        return "laser", f"the data file names the reference {text!r}"
    return None


def resolve_linear(table: Mapping[str, Any] | None, dataset=None,
                   set_with: str = "[uncertainty] {key}"):
    """The inputs of a linear budget and where each came from.

    Parameters
    ----------
    table : mapping or None
        The ``[uncertainty]`` table (job, configuration, options): declared values.
    dataset : PositioningDataset, optional
        Supplies α, the material temperature and the reference's kind where ``table`` does not.
    set_with : str
        How a user sets an input, ``{key}`` replaced by its name (a front end names its option).

    Returns
    -------
    (LinearInputs, tuple of BudgetInput, tuple of str)
        The inputs, their records (assumed ones marked), and the names of missing inputs.
    """
    kw = _known_keys(LinearInputs, table or {}, LINEAR_ENTRY)
    given = {k: "declared by the user (job or configuration file, or the --uncertainty option)"
             for k in kw}
    if dataset is not None:
        env = dataset.metadata.environment
        if "expansion_coefficient" not in kw and env.expansion_coefficient is not None:
            kw["expansion_coefficient"] = env.expansion_coefficient
            given["expansion_coefficient"] = "taken from the data file"
        if "material_temperature" not in kw and env.material_temperature:
            kw["material_temperature"] = float(np.mean(env.material_temperature))
            given["material_temperature"] = "taken from the data file (mean of its sensors)"
        found = reference_kind(dataset.metadata.instrument)
        if "reference" not in kw and found is not None:
            kw["reference"], why = found
            given["reference"] = f"taken from the data file: {why}"
        _step_from_data(kw, given, dataset, "um", LinearInputs.resolution, "µm")
    inputs = LinearInputs(**kw)
    skip = {"laser": {"encoder_accuracy"},
            "encoder": {"laser_accuracy_ppm", "laser_accuracy_k", "beam_offset"}}[inputs.reference]
    if inputs.material_temperature is not None:
        skip |= {"shop_temperature_min", "shop_temperature_max"}
    if inputs.e_ve is None:
        skip.add("e_ve_source")
    rows = _records(inputs, _LINEAR, given, skip, set_with)
    return inputs, rows, ("e_ve",) if inputs.e_ve is None else ()


def resolve_rotary(table: Mapping[str, Any] | None, set_with: str = "[uncertainty] {key}",
                   dataset=None):
    """As :func:`resolve_linear` for a rotary budget (a rotary calibrator as reference); the
    dataset supplies the resolution where its readings show a step."""
    kw = _known_keys(RotaryInputs, table or {}, ROTARY_ENTRY)
    given = {k: "declared by the user (job or configuration file, or the --uncertainty option)"
             for k in kw}
    if dataset is not None:
        _step_from_data(kw, given, dataset, "arcsec", RotaryInputs.resolution, "arcsec")
    inputs = RotaryInputs(**kw)
    skip = {"e_ve_source"} if inputs.e_ve is None else set()
    rows = _records(inputs, _ROTARY, given, skip, set_with)
    return inputs, rows, ("e_ve",) if inputs.e_ve is None else ()


def _records(inputs, spec, given: dict, skip: set, set_with: str) -> tuple[BudgetInput, ...]:
    if "e_ve" in given and inputs.e_ve_source == "drift check":
        given = {**given, "e_ve": "measured by a drift check: the range of its readings "
                                  "(ISO 230-2:2014 Annex A.5)"}
    out = []
    for name, (label, unit, rule) in spec.items():
        if name in skip:
            continue
        value = getattr(inputs, name)
        if name == "expansion_coefficient_halfwidth" and value is None:
            value = inputs.alpha_halfwidth
        assumed = name not in given or value is None
        if name == "material_temperature" and value is None:
            assumed = True
        out.append(BudgetInput(name, label, value, unit, assumed, set_with.format(key=name),
                               rule if assumed else given[name]))
    return tuple(out)


def environmental_variation(readings) -> float:
    """E_VE from a drift check: the range of the readings of a still set-up over the test's time.

    Parameters
    ----------
    readings : array_like, deviation unit
        Laser readings with the machine at rest (target and reflector fixed), taken over at least
        the duration of the positioning test.

    Returns
    -------
    float, deviation unit
        max − min (ISO 230-2:2014 Annex A, environmental variation error E_VE).

    Examples
    --------
    >>> environmental_variation([0.1, 0.4, -0.2, 0.3])
    0.6
    """
    r = np.asarray(readings, dtype=float).ravel()
    if r.size < 2 or not np.all(np.isfinite(r)):
        raise InputError(f"drift check: {r.size} readings; E_VE needs at least 2 finite readings")
    return round(float(r.max() - r.min()), 12)


def runs_statement(n_runs: int) -> str:
    """What the number of runs means for R and B, in words.

    Notes
    -----
    R and B are formed from the standard deviations s↑, s↓ and means of n runs per direction
    (ISO 230-2:2014 clause 3). The relative standard uncertainty of an experimental standard
    deviation from n readings is 1/√(2(n − 1)) (JCGM 100:2008 Annex E.4.3, Table E.1): 35 % for
    n = 5. ISO 230-2:2014 Annex A does not include it in U of R and B; axiscal adds it
    (:mod:`axiscal.standards.iso230_9_sampling`) and the statement says so.

    Examples
    --------
    >>> runs_statement(5)[:45]
    'R and B rest on 5 runs per direction: the sta'
    """
    n = int(n_runs)
    if n < 2:
        return (f"R and B rest on {n} run per direction: no standard deviation can be formed "
                "(ISO 230-2:2014 needs at least 2 runs, 5 recommended)")
    rel = 100.0 / math.sqrt(2 * (n - 1))
    return (f"R and B rest on {n} runs per direction: the standard uncertainty of each standard "
            f"deviation s from {n} runs is s/√(2(n − 1)) = {rel:.0f} % of s (JCGM 100:2008 "
            "Annex E.4.3); ISO 230-2:2014 Annex A does not include it in U of R and B, "
            "axiscal adds it to their U")


def reading_step(dataset) -> float | None:
    """The step of the reference's readings where the data shows one, in the deviation unit.

    Parameters
    ----------
    dataset : PositioningDataset

    Returns
    -------
    float or None
        q such that the readings at each target differ from each other by whole multiples of
        q (within 1 % of q), found from the smallest difference (or a half, third or quarter of
        it); None when fewer than 4 differences exist or they are not multiples of one step (a
        laser's readings, or a simulation's, vary continuously).

    Notes
    -----
    ISO 230-2:2014 Annex A.2 names the resolution of the reading as a contributor; an encoder
    read as the reference (an EPICS ecmc ``…-Enc01-PosAct``) moves in increments, which the
    readings at one target show: the ESS file ``mcu1025_fat_sat_ISO230.dat`` steps by
    0.20365 µm, where the default would assume 1 nm.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays("linear", [0, 10], [[0.0, 0.4, 0.6], [1.0, 1.2, 1.8]],
    ...                                     [[0.2, 0.2, 0.4], [1.4, 1.2, 1.0]], "mm", "um")
    >>> round(reading_step(ds), 6)
    0.2
    """
    diffs = []
    for i in range(dataset.targets.size):
        v = np.concatenate([dataset.up[i], dataset.down[i]])
        v = v[np.isfinite(v)]
        d = np.abs(v[:, None] - v[None, :])[np.triu_indices(v.size, 1)]
        eps = 1e-9 * (1.0 + float(np.max(np.abs(v)))) if v.size else 0.0
        diffs.extend(d[d > eps])
    if len(diffs) < 4:
        return None
    d = np.asarray(diffs)
    smallest = float(d.min())
    for parts in (1, 2, 3, 4):
        q = smallest / parts
        r = np.round(d / q)
        if np.all(np.abs(d / q - r) < 0.01):
            return float(d.sum() / r.sum())
    return None


def _step_from_data(kw: dict, given: dict, dataset, unit: str, default: float,
                    shown: str) -> None:
    """``resolution`` from the data's step (:func:`reading_step`) when none was declared and
    the step is coarser than the default."""
    if "resolution" in kw:
        return
    from axiscal.units import convert

    q = reading_step(dataset)
    if q is None:
        return
    q = float(convert(q, dataset.deviation_unit, unit))
    if q > default * 1.0001:
        kw["resolution"] = q
        given["resolution"] = (f"taken from the data: the readings at one target differ by "
                               f"whole multiples of {q:.4g} {shown}, the reference's step")


def split_table(table: Mapping[str, Any] | None, kind: str
                ) -> tuple[dict, dict[str, float], tuple[str, ...]]:
    """One laboratory configuration for every kind of test: the ``[uncertainty]`` inputs of
    ``kind``'s budget, its CMC per parameter and the keys ignored as the other kind's.

    Parameters
    ----------
    table : mapping or None
        The ``[uncertainty]`` table: common keys, and the sub-tables ``linear`` and ``rotary``
        (values for that kind only, over the common ones, and ``cmc``: parameter -> the
        laboratory's calibration and measurement capability as an expanded uncertainty, µm
        for a linear axis, arcsec for a rotary one).
    kind : str
        ``linear`` or ``rotary``.

    Returns
    -------
    (inputs, cmc, ignored)
        ``inputs`` for :func:`resolve_linear` or :func:`resolve_rotary` (a key of neither kind
        stays, to be refused by name), ``cmc`` in µm or arcsec, ``ignored`` the common keys
        that only the other kind's budget has (said in the budget's notes, not refused).

    Raises
    ------
    InputError
        ``cmc`` outside a kind's sub-table, a sub-table that is not a table, a CMC that names
        no ISO 230-2 parameter or is not a number > 0.
    """
    from axiscal.standards.iso230_2 import PARAMETER_NAMES

    table = dict(table or {})
    if "cmc" in table:
        raise InputError("[uncertainty] cmc: give the CMC per kind of axis, [uncertainty.linear] "
                         "cmc (µm) or [uncertainty.rotary] cmc (arcsec)")
    subs = {k: table.pop(k, None) or {} for k in KIND_TABLES}
    for k, sub in subs.items():
        if not isinstance(sub, Mapping):
            raise InputError(f"[uncertainty.{k}] must be a table")
    own = dict(subs[kind])
    cmc = own.pop("cmc", {}) or {}
    if not isinstance(cmc, Mapping):
        raise InputError(f"[uncertainty.{kind}] cmc must be a table: parameter = U")
    for name, v in cmc.items():
        if name not in PARAMETER_NAMES:
            raise InputError(f"[uncertainty.{kind}] cmc {name!r}: not an ISO 230-2 parameter; "
                             f"use one of {', '.join(PARAMETER_NAMES)}")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (
                math.isfinite(v) and v > 0):
            raise InputError(f"[uncertainty.{kind}] cmc {name} = {v!r} must be a number > 0")
    this, other = ((LinearInputs, RotaryInputs) if kind == "linear"
                   else (RotaryInputs, LinearInputs))
    mine, theirs = {f.name for f in fields(this)}, {f.name for f in fields(other)}
    ignored = tuple(k for k in table if k not in mine and k in theirs)
    inputs = {k: v for k, v in table.items() if k not in ignored}
    inputs.update(own)
    return inputs, {k: float(v) for k, v in cmc.items()}, ignored
