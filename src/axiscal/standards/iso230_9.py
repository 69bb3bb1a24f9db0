"""Measurement uncertainty of machine-tool tests: ISO 230-2:2014 Annex A, ISO/TR 230-9 form.

An :class:`UncertaintyBudget` is a list of :class:`Contributor` (each a standard uncertainty in the
test's deviation unit, with its distribution, the clause it comes from and the parameters it acts
on) and, per parameter, the combined standard uncertainty u_c and the expanded uncertainty
U = k·u_c (k = 2). A budget is plain data: any standard module (ISO 230-2, VDI 3441, ASME B5.54 ...)
can build one for its own parameters, and :mod:`axiscal.standards.iso14253_1` decides conformance
from any (value, U) pair.

Builders
--------
:func:`linear_budget`
    ISO 230-2:2014 Annex A for a linear axis measured with a laser interferometer:

    ===============  ===============================================  ============================
    contributor      model                                            distribution
    ===============  ===============================================  ============================
    u_DEVICE         laser: accuracy a [ppm, expanded with k_cal] × L  normal, u = a·L/k_cal
                     encoder: scale accuracy ± a [µm/m] × L            rectangular, u = a·L/√3
    u_RESOLUTION     resolution r of the reading                      rectangular, u = r/(2√3)
    u_MISALIGNMENT   laser only: cosine error e = L·θ²/2 = d²/(2L),    rectangular 0…e, u = e/(2√3)
                     beam offset d over the travel
    u_E,MACHINE      uncertainty of α (half-width a_α) × L × |T − 20|  rectangular, u = a_α·L·ΔT/√3
    u_M,MACHINE      temperature measurement (half-width a_T) × α × L  rectangular, u = a_T·α·L/√3
    u_M,POSITION     sensor position (half-width a_P) × α × L          rectangular, u = a_P·α·L/√3
    u_EVE            environmental variation error E_VE (drift check)  rectangular, u = E_VE/(2√3)
    ===============  ===============================================  ============================

    with L the measured travel. E, M, A and their unidirectional forms carry every contributor
    (ISO 230-2:2014 A.2-A.4, A.6); R and B carry the reading (resolution) and E_VE only (A.5-A.7):
    a scale or length error acts on the span between targets, not on the scatter at one target.

    The temperature-deviation contributor is ISO/TR 16015:2003's uncertainty of the expansion
    coefficient (case b: mean temperature not 20 °C, corrected) in ISO 230-2:2014 Annex A.4::

        u_E,MACHINE = L · ΔT · u(α),   u(α) = a_α/√3,   ΔT = |T − 20 °C|

    with T the stated material temperature or, when none is stated, the end of the declared
    shop range farthest from 20 °C (ΔT = max(|T_min − 20|, |T_max − 20|); default 17-23 °C,
    ΔT = 3 K, shown as assumed). An 800 mm steel axis in a 23 °C shop: 800 mm × 3 K ×
    1.15 µm/(m·K)/√3 = 1.59 µm.

    E_VE is never assumed: without a drift check or a declared value it is left out of U and
    named in :attr:`UncertaintyBudget.missing_inputs` (a certificate is then a draft).
:func:`rotary_budget`
    The same for a rotary axis measured with a rotary calibrator: the calibrator's accuracy in
    arcsec, its resolution, the misalignment of Renishaw, "Interferometric calibration of rotary
    axes", eq. 1 (half of the range of E(θ) over a turn; a constant does not change any ISO 230-2
    parameter) and E_VE.
:func:`chain_budget`
    The error budget of a rotary calibration (what ``axiscal rotary simulate`` prints, each item a
    ± bound) turned into GUM form: each bound a rectangular distribution, u = a/√3.

:func:`combine` forms u_c by the law of propagation of uncertainty (GUM, JCGM 100:2008, eq. 10)
with GTC (GUM Tree Calculator) when it is installed, and in plain arithmetic otherwise;
:func:`~axiscal.standards.iso230_9_montecarlo.monte_carlo_linear` propagates the distributions
of the *input quantities* (laser error, cosine error from a misalignment angle, the product
α·ΔT ...) through the measurement model by
Monte Carlo (JCGM 101:2008, GUM Supplement 1) as an independent check of the linear budget.

Readings chosen where the standard leaves a choice (stated on every certificate): E_VE is taken
as the full range of a drift check, so ±E_VE/2 rectangular; the cosine error is a one-sided
rectangular 0…e; the uncertainty of α defaults to ±10 % of α when no value is declared. Every
default is a :class:`~axiscal.standards.iso230_9_inputs.BudgetInput` marked assumed, with the
rule it comes from (:mod:`axiscal.standards.iso230_9_inputs`).

U is displayed by :func:`format_uncertainty`: two significant digits, rounded up (JCGM 100:2008
§7.2.6), never as zero.

References
----------
ISO 230-2:2014, Annex A (informative), Measurement uncertainty estimation for linear positioning.
ISO/TR 230-9:2005, Estimation of measurement uncertainty for machine tool tests according to
series ISO 230, basic equations.
JCGM 100:2008 (GUM), JCGM 101:2008 (GUM Supplement 1, Monte Carlo method).
Renishaw, Interferometric calibration of rotary axes: Renishaw, "Interferometric calibration of rotary axes", eq. 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.iso230_9_inputs import (
    BudgetInput,
    LinearInputs,
    RotaryInputs,
    environmental_variation,
    resolve_linear,
    resolve_rotary,
    runs_statement,
    split_table,
)
from axiscal.standards.uncertainty_reporting import format_uncertainty, round_up

__all__ = [
    "Contributor",
    "UncertaintyBudget",
    "LinearInputs",
    "RotaryInputs",
    "combine",
    "linear_budget",
    "rotary_budget",
    "chain_budget",
    "positioning_budget",
    "environmental_variation",
    "round_up",
    "format_uncertainty",
    "COVERAGE_FACTOR",
    "DISTANCE_PARAMETERS",
    "SCATTER_PARAMETERS",
]

#: Coverage factor of the expanded uncertainty (ISO/TR 230-9 and ISO 230-2 Annex A: k = 2).
COVERAGE_FACTOR = 2.0
#: Parameters formed from deviations at different targets: every contributor acts on them.
DISTANCE_PARAMETERS = ("A", "A_up", "A_down", "E", "E_up", "E_down", "M")
#: Parameters formed at one target (scatter, reversal): length-proportional errors cancel.
SCATTER_PARAMETERS = ("R", "R_up", "R_down", "B", "B_mean")
_ALL = DISTANCE_PARAMETERS + SCATTER_PARAMETERS
_SQ3 = math.sqrt(3.0)
_ANNEX = "ISO 230-2:2014 Annex A"
#: How a user sets an input (job or configuration file, or the commands' ``--uncertainty``).
SET_WITH = "[uncertainty] {key} in the job or configuration file, or --uncertainty {key}=VALUE"


@dataclass(frozen=True)
class Contributor:
    """One contribution to the uncertainty budget.

    Attributes
    ----------
    name : str
        Symbol as ISO 230-2 Annex A writes it (``u_DEVICE``, ``u_EVE`` ...).
    quantity : str
        What it is, for a reader.
    u : float, deviation unit
        Standard uncertainty.
    distribution : str
        ``normal`` or ``rectangular``.
    clause : str
        Where the model comes from.
    basis : str
        How ``u`` was formed from the inputs (numbers and units), for the certificate.
    applies_to : tuple of str
        Parameters it acts on, with sensitivity coefficient 1 (the ``u`` is already in the
        deviation unit of the parameter).
    """

    name: str
    quantity: str
    u: float
    distribution: str
    clause: str
    basis: str
    applies_to: tuple[str, ...] = _ALL

    def __post_init__(self) -> None:
        if not (math.isfinite(self.u) and self.u >= 0):
            raise InputError(
                f"uncertainty contributor {self.name}: u = {self.u!r} must be a "
                "finite number >= 0"
            )


@dataclass(frozen=True)
class UncertaintyBudget:
    """Contributors and, per parameter, the combined and expanded uncertainty.

    Attributes
    ----------
    unit : str
        Deviation unit of every ``u`` and ``U`` (``um``, ``arcsec`` ...).
    k : float
        Coverage factor.
    contributors : tuple of Contributor
    combined : mapping of str to float
        u_c per parameter, ``unit``.
    expanded : mapping of str to float
        U = k·u_c per parameter, ``unit``.
    method : str
        How u_c was formed (``GTC`` or ``plain arithmetic``), for the certificate.
    notes : tuple of str
        What a reader must know, in plain words: each assumed input with its rule, each input
        left out of U, the number of runs behind R and B.
    inputs : tuple of BudgetInput
        Every input with its value, unit, whether it was assumed, how to set it and its rule.
    missing_inputs : tuple of str
        Names of inputs U could not include (``e_ve`` when no drift check or value was given).
    narrow : mapping of str to float
        ISO 230-2:2014 Annex A's U of each parameter the sampling of the runs was added to
        (R, R↑, R↓, B, B̄): the measuring chain's alone; ``expanded`` holds the wider U.
    cmc : mapping of str to float
        The laboratory's CMC (an expanded uncertainty, ``unit``) of each parameter that has one.
    floored : tuple of str
        The parameters whose U is the CMC: the budget's U was smaller (ILAC-P14:09/2020 §5.4:
        an uncertainty below the CMC is never stated).
    """

    unit: str
    k: float
    contributors: tuple[Contributor, ...]
    combined: Mapping[str, float]
    expanded: Mapping[str, float]
    method: str = "GTC"
    notes: tuple[str, ...] = ()
    inputs: tuple[BudgetInput, ...] = ()
    missing_inputs: tuple[str, ...] = ()
    narrow: Mapping[str, float] = field(default_factory=dict)
    cmc: Mapping[str, float] = field(default_factory=dict)
    floored: tuple[str, ...] = ()

    def U(self, parameter: str) -> float | None:
        """Expanded uncertainty of ``parameter`` (None if the budget does not cover it)."""
        return self.expanded.get(parameter)

    def stated(self, parameter: str) -> float | None:
        """U of ``parameter`` as it is printed (two significant digits, rounded up: JCGM
        100:2008 §7.2.6): the U every decision of conformity uses, so the verdict follows from
        the numbers on the page (:func:`axiscal.standards.iso14253_1.decide_all`)."""
        U = self.U(parameter)
        return None if U is None else round_up(U)

    def value_text(self, parameter: str, value: float) -> str:
        """``value`` rounded to the last digit of the printed U of ``parameter``
        (ILAC-P14:09/2020 §5.3; :func:`~axiscal.standards.uncertainty_reporting.format_value`)."""
        from axiscal.standards.uncertainty_reporting import format_value

        return format_value(value, self.U(parameter))

    def U_text(self, parameter: str) -> str:
        """U of ``parameter`` as displayed: :func:`format_uncertainty` ("—" if not covered)."""
        return format_uncertainty(self.U(parameter))

    @property
    def assumed(self) -> tuple[BudgetInput, ...]:
        """The inputs neither the user nor the data file gave (defaults and missing ones)."""
        return tuple(i for i in self.inputs if i.assumed)

    @property
    def missing(self) -> tuple[str, ...]:
        """Each missing input in words (what a certificate lists as missing)."""
        by = {i.name: i for i in self.inputs}
        return tuple(f"{by[m].label} ({by[m].rule})" if m in by else m
                     for m in self.missing_inputs)

    def rows(self, parameter: str) -> list[tuple[str, float]]:
        """``(name, u)`` of the contributors acting on ``parameter``."""
        return [(c.name, c.u) for c in self.contributors if parameter in c.applies_to]

    def to_json(self, parameters=None) -> dict[str, Any]:
        """The budget as stable JSON: ``unit``, ``k``, ``method``, ``U`` (raw floats),
        ``U_display`` (as shown), ``contributors``, ``inputs`` (name -> ``value``, ``unit``,
        ``assumed``, ``set_with``, ``rule``, ``label``), ``assumed`` (names),
        ``missing_inputs``, ``notes``, and (issue 38) ``U_stated`` (as printed and decided
        with), ``U_narrow`` (Annex A's U of R and B without the sampling of the runs), ``cmc``
        and ``floored`` (parameters whose U is the CMC)."""
        names = [p for p in (parameters or self.expanded) if p in self.expanded]
        return {
            "unit": self.unit, "k": self.k, "method": self.method,
            "U": {p: self.expanded[p] for p in names},
            "U_display": {p: self.U_text(p) for p in names},
            "U_stated": {p: self.stated(p) for p in names},
            "U_narrow": {p: v for p, v in self.narrow.items() if p in names},
            "cmc": dict(self.cmc), "floored": list(self.floored),
            "contributors": [{"name": c.name, "quantity": c.quantity, "u": c.u,
                              "distribution": c.distribution, "basis": c.basis,
                              "clause": c.clause, "applies_to": list(c.applies_to)}
                             for c in self.contributors],
            "inputs": {i.name: i.to_json() for i in self.inputs},
            "assumed": [i.name for i in self.assumed],
            "missing_inputs": list(self.missing_inputs),
            "notes": list(self.notes),
        }

    def __str__(self) -> str:
        lines = [f"uncertainty budget ({self.unit}, k = {self.k:g}):"]
        lines += [
            f"  {c.name:<14} u = {c.u:8.4f}  {c.distribution:<11} {c.clause}"
            for c in self.contributors
        ]
        lines += [f"  U({p}) = {self.U_text(p)}" for p in self.expanded]
        return "\n".join(lines)


def combine(
    contributors, unit: str, k: float = COVERAGE_FACTOR, parameters=None, notes=(),
    engine: str = "plain",
) -> UncertaintyBudget:
    """Combine contributors per parameter (GUM eq. 10, sensitivity 1, uncorrelated inputs).

    ``engine="plain"`` evaluates eq. 10 directly (the root sum of squares, exact for this model
    and free of start-up cost); ``engine="gtc"`` forms the same sum with GTC's uncertain real
    numbers (GUM Tree Calculator), an independent implementation the tests compare with. GTC
    costs over a second to import, which every ``iso230-2`` run would pay.

    Parameters
    ----------
    contributors : sequence of Contributor
    unit : str
    k : float
        Coverage factor (ISO/TR 230-9: 2).
    parameters : sequence of str, optional
        Parameters to form; default every parameter any contributor names.
    notes : sequence of str

    Returns
    -------
    UncertaintyBudget

    Examples
    --------
    >>> b = combine([Contributor("u1", "a", 3.0, "normal", "x", "", ("E",)),
    ...              Contributor("u2", "b", 4.0, "normal", "x", "", ("E",))], "um")
    >>> b.U("E")
    10.0
    """
    contributors = tuple(contributors)
    if not (math.isfinite(k) and k > 0):
        raise InputError(f"coverage factor k = {k!r} must be a number > 0")
    names = parameters or list(dict.fromkeys(p for c in contributors for p in c.applies_to))
    if engine not in ("plain", "gtc"):
        raise InputError(f"engine = {engine!r}; plain or gtc")
    if engine == "gtc":
        combined, method = _combine_gtc(contributors, names), "GTC (GUM Tree Calculator)"
    else:
        combined, method = _combine_plain(contributors, names), "GUM eq. 10 (root sum of squares)"
    return UncertaintyBudget(
        unit,
        float(k),
        contributors,
        combined,
        {p: k * u for p, u in combined.items()},
        method,
        tuple(notes),
    )


def _combine_gtc(contributors, names) -> dict[str, float]:
    """u_c per parameter with GTC: each contributor an uncertain real number, the model a sum."""
    import GTC

    inputs = {c.name: GTC.ureal(0.0, c.u, label=c.name) for c in contributors}
    out = {}
    for p in names:
        terms = [inputs[c.name] for c in contributors if p in c.applies_to]
        out[p] = float(GTC.uncertainty(sum(terms[1:], terms[0]))) if terms else 0.0
    return out


def _combine_plain(contributors, names) -> dict[str, float]:
    return {p: math.sqrt(sum(c.u**2 for c in contributors if p in c.applies_to)) for p in names}


def linear_budget(
    travel_mm: float,
    inputs: LinearInputs = LinearInputs(),
    unit: str = "um",
    k: float = COVERAGE_FACTOR,
) -> UncertaintyBudget:
    """ISO 230-2:2014 Annex A budget of a linear positioning test.

    Parameters
    ----------
    travel_mm : float, mm
        Measured travel L (last target − first target).
    inputs : LinearInputs
    unit : str
        Deviation unit of the test (``um`` or ``mm``).
    k : float

    Returns
    -------
    UncertaintyBudget
        For A, A↑, A↓, E, E↑, E↓, M, R, R↑, R↓, B, B̄; without E_VE when ``inputs.e_ve`` is
        None (then ``missing_inputs == ("e_ve",)``).

    Notes
    -----
    The contributors and their models are in the module's table. The temperature-deviation
    contributor is u_E,MACHINE = L·ΔT·a_α/√3 (ISO 230-2:2014 Annex A.4; ISO/TR 16015:2003
    case b), ΔT = :attr:`LinearInputs.temperature_deviation`.

    Examples
    --------
    >>> b = linear_budget(1000.0, LinearInputs(e_ve=1.0, material_temperature=21.0))
    >>> round(b.U("E"), 3), round(b.U("R"), 3)
    (3.341, 0.577)
    """
    if not (math.isfinite(travel_mm) and travel_mm > 0):
        raise InputError(f"travel {travel_mm!r} mm: an uncertainty budget needs a travel > 0")
    to_unit = {"um": 1.0, "mm": 1e-3, "nm": 1e3}.get(unit)
    if to_unit is None:
        raise InputError(f"linear uncertainty budget in {unit!r}: use um or mm")
    L_um, i = travel_mm * 1e3, inputs
    d, s = DISTANCE_PARAMETERS, _ALL
    c = [_device(i, travel_mm), Contributor(
        "u_RESOLUTION", "resolution of the reading", i.resolution / (2 * _SQ3), "rectangular",
        f"{_ANNEX}, A.2; ISO/TR 230-9 §5", f"resolution {i.resolution:g} µm", s)]
    if i.reference == "laser":
        cos_e = (i.beam_offset * 1e3) ** 2 / (2 * L_um)
        c.append(Contributor(
            "u_MISALIGNMENT", "cosine error of the beam alignment", cos_e / (2 * _SQ3),
            "rectangular", f"{_ANNEX}, A.3 (misalignment)",
            f"beam offset {i.beam_offset:g} mm over {travel_mm:g} mm: e = d²/2L = {cos_e:.3g} µm",
            d))
    c += _thermal(i, L_um)
    if i.e_ve is not None:
        c.append(Contributor(
            "u_EVE", "environmental variation error", i.e_ve / (2 * _SQ3), "rectangular",
            f"{_ANNEX}, A.5 (environmental variation error E_VE)",
            f"E_VE = {i.e_ve:g} µm ({i.e_ve_source})", s))
    c = [replace(x, u=x.u * to_unit) for x in c]
    return combine(c, unit, k, _ALL)


def _device(i: LinearInputs, travel_mm: float) -> Contributor:
    """u_DEVICE of the reference: a laser's ppm (normal, k_cal) or an encoder's ± µm/m."""
    if i.reference == "encoder":
        return Contributor(
            "u_DEVICE", "encoder scale accuracy", i.encoder_accuracy * travel_mm * 1e-3 / _SQ3,
            "rectangular", f"{_ANNEX}, A.2 (measuring device); ISO/TR 230-9 §5",
            f"± {i.encoder_accuracy:g} µm/m over {travel_mm:g} mm", DISTANCE_PARAMETERS)
    return Contributor(
        "u_DEVICE", "laser measurement accuracy",
        i.laser_accuracy_ppm * 1e-3 * travel_mm / i.laser_accuracy_k, "normal",
        f"{_ANNEX}, A.2 (measuring device)",
        f"{i.laser_accuracy_ppm:g} ppm (k = {i.laser_accuracy_k:g}) over {travel_mm:g} mm",
        DISTANCE_PARAMETERS)


def _thermal(i: LinearInputs, L_um: float) -> list[Contributor]:
    """u_E,MACHINE (α's uncertainty over ΔT), u_M,MACHINE and u_M,POSITION, µm."""
    a_alpha, dT, d = i.alpha_halfwidth, i.temperature_deviation, DISTANCE_PARAMETERS
    where = (f"|T − 20 °C| = {dT:.3g} K" if i.material_temperature is not None else
             f"T not stated: shop {i.shop_temperature_min:g}-{i.shop_temperature_max:g} °C, "
             f"largest |T − 20 °C| = {dT:.3g} K")
    clause = f"{_ANNEX}, A.4 (machine temperature compensation)"
    return [
        Contributor("u_E,MACHINE", "uncertainty of the expansion coefficient",
                    a_alpha * L_um * dT / _SQ3, "rectangular", f"{clause}; ISO/TR 16015:2003",
                    f"L·ΔT·u(α): α ± {a_alpha * 1e6:.3g} µm/(m·K), {where}", d),
        Contributor("u_M,MACHINE", "material temperature measurement",
                    i.temperature_halfwidth * i.expansion_coefficient * L_um / _SQ3,
                    "rectangular", clause, f"sensor ± {i.temperature_halfwidth:g} K, "
                    f"α = {i.expansion_coefficient * 1e6:.3g} µm/(m·K)", d),
        Contributor("u_M,POSITION", "material sensor position",
                    i.sensor_position_halfwidth * i.expansion_coefficient * L_um / _SQ3,
                    "rectangular", f"{_ANNEX}, A.4; ISO/TR 230-9 §6 (temperature)",
                    f"sensor place vs scale ± {i.sensor_position_halfwidth:g} K", d),
    ]


def rotary_budget(
    inputs: RotaryInputs = RotaryInputs(), unit: str = "arcsec", k: float = COVERAGE_FACTOR
) -> UncertaintyBudget:
    """ISO 230-2 Annex A budget of a rotary positioning test (rotary calibrator).

    Without E_VE (``inputs.e_ve`` None) the budget leaves it out (see :func:`linear_budget`).

    Examples
    --------
    >>> round(rotary_budget(RotaryInputs(e_ve=0.5)).U("E"), 3)
    1.091
    """
    from axiscal.physics.misalignment import half_range
    from axiscal.units import ARCSEC, convert

    i = inputs
    mis = half_range(i.alpha * 1e-3, i.beta * 1e-3, i.omega * 1e-3) / ARCSEC
    d, s = DISTANCE_PARAMETERS, _ALL
    c = [
        Contributor("u_DEVICE", "rotary calibrator accuracy", i.calibrator_accuracy /
                    i.calibrator_k, "normal", f"{_ANNEX}, A.2 (measuring device)",
                    f"± {i.calibrator_accuracy:g} arcsec (k = {i.calibrator_k:g})", d),
        Contributor("u_RESOLUTION", "resolution of the reading", i.resolution / (2 * _SQ3),
                    "rectangular", f"{_ANNEX}, A.2; ISO/TR 230-9 §5",
                    f"resolution {i.resolution:g} arcsec", s),
        Contributor("u_MISALIGNMENT", "misalignment (Renishaw, Interferometric calibration of "
                    "rotary axes, eq. 1)", mis / _SQ3, "rectangular",
                    f"{_ANNEX}, A.3; Renishaw eq. 1",
                    f"α = {i.alpha:g}, β = {i.beta:g}, ω = {i.omega:g} mrad: ± {mis:.3g} arcsec", d),
    ]
    if i.e_ve is not None:
        c.append(Contributor("u_EVE", "environmental variation error", i.e_ve / (2 * _SQ3),
                             "rectangular", f"{_ANNEX}, A.5 (environmental variation error E_VE)",
                             f"E_VE = {i.e_ve:g} arcsec ({i.e_ve_source})", s))
    f = convert(1.0, "arcsec", unit)
    return combine([replace(x, u=x.u * f) for x in c], unit, k, _ALL)


def chain_budget(
    error_budget, unit: str = "arcsec", k: float = COVERAGE_FACTOR
) -> UncertaintyBudget:
    """A rotary calibration's error budget (± bounds, radians) in GUM form.

    Parameters
    ----------
    error_budget : ErrorBudget
        From :func:`axiscal.procedures.rotary_calibration.error_budget`: each item a ± bound.
    unit : str
    k : float

    Notes
    -----
    Each ± bound is read as a rectangular distribution (ISO/TR 230-9 §5, GUM 4.3.7): u = a/√3.
    The bounds act on the deviations, so on every parameter formed between targets; on R and B
    only the reading noise acts (the other items are the same on both approaches to a target).
    """
    from axiscal.units import ARCSEC, convert

    f = convert(1.0, "arcsec", unit) / ARCSEC
    out = []
    for item in error_budget.items:
        scatter = "noise" in item.name
        out.append(
            Contributor(
                item.name,
                item.name,
                item.value * f / _SQ3,
                "rectangular",
                "ISO/TR 230-9 §5 (rectangular ± bound)",
                item.source,
                _ALL if scatter else DISTANCE_PARAMETERS,
            )
        )
    return combine(out, unit, k, _ALL)


def positioning_budget(
    dataset, result, table: Mapping[str, Any] | None = None, k: float = COVERAGE_FACTOR,
    set_with: str = SET_WITH,
) -> UncertaintyBudget:
    """The Annex A budget of an evaluated ISO 230-2 test, linear or rotary, with its inputs.

    Parameters
    ----------
    dataset : PositioningDataset
        Supplies α, the material temperature and the reference's kind where ``table`` does not.
    result : Iso230_2Result
        Supplies the travel (first to last target), the deviation unit and the number of runs.
    table : mapping, optional
        The ``[uncertainty]`` table of the configuration (keys of :class:`LinearInputs` or
        :class:`RotaryInputs`); absent keys take the documented defaults, marked assumed.
    k : float
    set_with : str
        How a user sets an input, ``{key}`` replaced by its name (a front end names its option).

    Returns
    -------
    UncertaintyBudget
        With ``inputs`` (every input, assumed ones marked), ``missing_inputs`` (``e_ve`` when
        neither measured nor declared: left out of U) and ``notes`` (the same in plain words,
        and what the number of runs means for R and B).
    """
    kind = "rotary" if dataset.axis_kind.value == "rotary" else "linear"
    table, cmc, ignored = split_table(table, kind)
    if kind == "rotary":
        inputs, records, missing = resolve_rotary(table, set_with, dataset)
        b = rotary_budget(inputs, result.deviation_unit, k)
    else:
        from axiscal.units import convert

        travel = float(convert(float(np.ptp(result.targets)), result.target_unit, "mm"))
        inputs, records, missing = resolve_linear(table, dataset, set_with)
        b = linear_budget(travel, inputs, result.deviation_unit, k)
    b = _with_sampling(b, result)
    b = _with_cmc(b, cmc, kind)
    notes = (_notes(inputs, records, missing) + [runs_statement(result.n_runs)]
             + _which_U(b, result) + _cmc_notes(b, kind) + _ignored_note(ignored, kind))
    return replace(b, notes=tuple(notes), inputs=records, missing_inputs=missing)


def _with_sampling(b: UncertaintyBudget, result) -> UncertaintyBudget:
    """The budget with the sampling of the runs added to R, R↑, R↓, B, B̄
    (:mod:`axiscal.standards.iso230_9_sampling`); Annex A's U of those kept as ``narrow``."""
    from axiscal.standards.iso230_9_sampling import sampling_contributors

    extra = [Contributor(**c) for c in sampling_contributors(result)]
    if not extra:
        return b
    wide = combine(b.contributors + tuple(extra), b.unit, b.k, list(b.expanded))
    narrow = {p: b.expanded[p] for c in extra for p in c.applies_to}
    return replace(wide, notes=b.notes, narrow=narrow)


def _with_cmc(b: UncertaintyBudget, cmc: Mapping[str, float], kind: str) -> UncertaintyBudget:
    """U never below the laboratory's CMC (ILAC-P14:09/2020 §5.4). A parameter without its own
    CMC takes that of its family (A for A↑ and A↓, E for E↑ and E↓, R for R↑ and R↓, B for
    B̄). The CMC is given in µm (linear) or arcsec (rotary) and converted to the budget's unit."""
    if not cmc:
        return b
    from axiscal.units import convert

    base = "um" if kind == "linear" else "arcsec"
    floors = {}
    for p in b.expanded:
        v = cmc.get(p, cmc.get({"B_mean": "B"}.get(p, p.split("_")[0])))
        if v is not None:
            floors[p] = float(convert(v, base, b.unit))
    floored = tuple(p for p in b.expanded if p in floors and b.expanded[p] < floors[p])
    expanded = {p: max(U, floors.get(p, 0.0)) for p, U in b.expanded.items()}
    combined = {p: expanded[p] / b.k for p in expanded}
    return replace(b, expanded=expanded, combined=combined, cmc=floors, floored=floored)


def _which_U(b: UncertaintyBudget, result) -> list[str]:
    """Which U of R and B is printed, and why (issue 38: say it, not leave it to the reader)."""
    if not b.narrow:
        return []
    names = ", ".join(_SYMBOL.get(p, p) for p in b.narrow)
    shown = "; ".join(f"{_SYMBOL.get(p, p)}: Annex A {format_uncertainty(v)}, printed "
                      f"{b.U_text(p)}" for p, v in b.narrow.items())
    return [f"U of {names} printed is the wider one: ISO 230-2:2014 Annex A's narrow U holds "
            f"the reading and E_VE only, but a statement that R or B conforms is about the "
            f"machine's scatter, which {result.n_runs} runs only estimate, so the sampling "
            f"uncertainty of their standard deviations and means (JCGM 100:2008 Annex E.4.3) "
            f"is added ({shown} {_unit_text(b.unit)})"]


def _cmc_notes(b: UncertaintyBudget, kind: str) -> list[str]:
    if not b.cmc:
        return [f"no CMC declared for a {kind} axis ([uncertainty.{kind}] cmc): U is the "
                "budget's, not checked against the laboratory's calibration and measurement "
                "capability"]
    if not b.floored:
        return []
    names = ", ".join(f"{_SYMBOL.get(p, p)} {format_uncertainty(b.cmc[p])}" for p in b.floored)
    return [f"U stated at the laboratory's CMC where the budget gives less ({names} "
            f"{_unit_text(b.unit)}): an uncertainty below the CMC is never stated "
            "(ILAC-P14:09/2020 §5.4)"]


def _ignored_note(ignored: tuple[str, ...], kind: str) -> list[str]:
    if not ignored:
        return []
    other = "linear" if kind == "rotary" else "rotary"
    return [f"[uncertainty] {', '.join(ignored)}: not an input of a {kind} axis's budget "
            f"(they serve {other} axes), ignored"]


_SYMBOL = {"R_up": "R↑", "R_down": "R↓", "B_mean": "B̄", "A_up": "A↑", "A_down": "A↓",
           "E_up": "E↑", "E_down": "E↓"}


def _unit_text(unit: str) -> str:
    return {"um": "µm"}.get(unit, unit)


def _notes(inputs, records, missing) -> list[str]:
    """The inputs in plain words: each assumed one with its rule, each missing one, the
    reference without a beam, an E_VE declared rather than measured."""
    out, by = [], {r.name: r for r in records}
    for r in records:
        if r.name in missing or not r.assumed or r.name == "shop_temperature_max":
            continue
        if r.name == "shop_temperature_min":
            hi = by["shop_temperature_max"]
            out.append(f"assumed: material temperature not stated, shop temperature "
                       f"{r.value:g}-{hi.value:g} °C ({r.rule}); set with "
                       f"{r.set_with} and {hi.set_with}")
        elif r.name != "material_temperature":
            out.append(f"assumed: {r.label} {r.value_text} ({r.rule}); set with {r.set_with}")
    for m in missing:
        r = by[m]
        out.append(f"{r.label} not given: U leaves it out; measure it by a drift check over the "
                   f"test's duration (ISO 230-2:2014 Annex A.5) or declare it with {r.set_with}")
    if getattr(inputs, "reference", "") == "encoder":
        out.append("reference is an encoder: no laser beam, so no beam-misalignment contributor")
    if inputs.e_ve is not None and inputs.e_ve_source == "declared":
        out.append(f"E_VE = {by['e_ve'].value_text} declared, not measured by a drift check")
    return out
