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
    u_DEVICE         accuracy a [ppm, expanded with k_cal] × L       normal, u = a·L/k_cal
    u_RESOLUTION     resolution r of the reading                      rectangular, u = r/(2√3)
    u_MISALIGNMENT   cosine error e = L·θ²/2 = d²/(2L), beam offset d  rectangular 0…e, u = e/(2√3)
    u_E,MACHINE      uncertainty of α (half-width a_α) × L × |T − 20|  rectangular, u = a_α·L·ΔT/√3
    u_M,MACHINE      temperature measurement (half-width a_T) × α × L  rectangular, u = a_T·α·L/√3
    u_M,POSITION     sensor position (half-width a_P) × α × L          rectangular, u = a_P·α·L/√3
    u_EVE            environmental variation error E_VE (drift check)  rectangular, u = E_VE/(2√3)
    ===============  ===============================================  ============================

    with L the measured travel. E, M, A and their unidirectional forms carry every contributor
    (ISO 230-2:2014 A.2-A.4, A.6); R and B carry the reading (resolution) and E_VE only (A.5-A.7):
    a scale or length error acts on the span between targets, not on the scatter at one target.
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
rectangular 0…e; the uncertainty of α defaults to ±10 % of α when no value is declared.

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
from dataclasses import dataclass, fields, replace
from typing import Any, Mapping

import numpy as np

from axiscal.errors import InputError

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
        Assumptions a reader must know (defaults used, E_VE declared rather than measured ...).
    """

    unit: str
    k: float
    contributors: tuple[Contributor, ...]
    combined: Mapping[str, float]
    expanded: Mapping[str, float]
    method: str = "GTC"
    notes: tuple[str, ...] = ()

    def U(self, parameter: str) -> float | None:
        """Expanded uncertainty of ``parameter`` (None if the budget does not cover it)."""
        return self.expanded.get(parameter)

    def rows(self, parameter: str) -> list[tuple[str, float]]:
        """``(name, u)`` of the contributors acting on ``parameter``."""
        return [(c.name, c.u) for c in self.contributors if parameter in c.applies_to]

    def __str__(self) -> str:
        lines = [f"uncertainty budget ({self.unit}, k = {self.k:g}):"]
        lines += [
            f"  {c.name:<14} u = {c.u:8.4f}  {c.distribution:<11} {c.clause}"
            for c in self.contributors
        ]
        lines += [f"  U({p}) = {v:.4f}" for p, v in self.expanded.items()]
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


def _check_inputs(inputs, signed: tuple, k: str) -> None:
    """Every input a finite number >= 0 (``signed`` ones may be negative), ``e_ve_source``
    one of its two words, and the coverage factor ``k`` positive."""
    for f in fields(inputs):
        v = getattr(inputs, f.name)
        if f.name == "e_ve_source":
            if v not in ("drift check", "declared"):
                raise InputError(
                    f"uncertainty e_ve_source = {v!r}: use 'drift check' or 'declared'")
        elif v is not None and (isinstance(v, bool) or not isinstance(v, (int, float))
                                or not math.isfinite(v) or (v < 0 and f.name not in signed)):
            raise InputError(f"uncertainty {f.name} = {v!r} must be a finite number >= 0")
    if getattr(inputs, k) <= 0:
        raise InputError(f"uncertainty {k} must be > 0")


def _known_keys(cls, d: Mapping[str, Any]) -> dict:
    """``d`` as keyword arguments of ``cls``, an unknown key refused by name."""
    from axiscal._schema import refuse_unknown

    refuse_unknown(dict(d) if not isinstance(d, dict) else d, {f.name for f in fields(cls)},
                   "[uncertainty]")
    return dict(d)


@dataclass(frozen=True)
class LinearInputs:
    """What a linear ISO 230-2 budget needs; each field settable in the test metadata or a config.

    Attributes
    ----------
    laser_accuracy_ppm : float, ppm
        Accuracy of the laser measurement (wavelength, air compensation) from its calibration
        certificate, an expanded uncertainty with coverage factor ``laser_accuracy_k``.
    laser_accuracy_k : float
    resolution : float, deviation unit (µm)
        Resolution of the reading.
    beam_offset : float, mm
        Lateral offset of the beam over the travel (alignment as set up).
    expansion_coefficient : float, 1/K
        α of the machine's scale (the dataset's value when it has one).
    expansion_coefficient_halfwidth : float or None, 1/K
        Half-width of the rectangular distribution of α (None: 10 % of α).
    material_temperature : float, °C
        Mean temperature of the machine (the dataset's value when it has one).
    temperature_halfwidth : float, K
        Accuracy of the material temperature sensor (half-width).
    sensor_position_halfwidth : float, K
        Largest difference between the sensor's place and the scale's mean temperature.
    e_ve : float, deviation unit (µm)
        Environmental variation error: range of a drift check over the test's duration.
    e_ve_source : str
        ``drift check`` or ``declared``.
    """

    laser_accuracy_ppm: float = 0.5
    laser_accuracy_k: float = 2.0
    resolution: float = 0.001
    beam_offset: float = 0.5
    expansion_coefficient: float = 11.5e-6
    expansion_coefficient_halfwidth: float | None = None
    material_temperature: float = 20.0
    temperature_halfwidth: float = 0.1
    sensor_position_halfwidth: float = 0.2
    e_ve: float = 0.0
    e_ve_source: str = "declared"

    def __post_init__(self) -> None:
        _check_inputs(self, signed=("material_temperature",), k="laser_accuracy_k")

    @classmethod
    def from_mapping(cls, d: Mapping[str, Any], dataset=None) -> "LinearInputs":
        """From a config table (``[uncertainty]``), filling α and T from the dataset if absent."""
        kw = _known_keys(cls, d)
        if dataset is not None:
            env = dataset.metadata.environment
            if "expansion_coefficient" not in kw and env.expansion_coefficient is not None:
                kw["expansion_coefficient"] = env.expansion_coefficient
            if "material_temperature" not in kw and env.material_temperature:
                kw["material_temperature"] = float(np.mean(env.material_temperature))
        return cls(**kw)


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
        For A, A↑, A↓, E, E↑, E↓, M, R, R↑, R↓, B, B̄.

    Examples
    --------
    >>> b = linear_budget(1000.0, LinearInputs(e_ve=1.0, material_temperature=21.0))
    >>> round(b.U("E"), 3), round(b.U("R"), 3)
    (3.342, 0.577)
    """
    if not (math.isfinite(travel_mm) and travel_mm > 0):
        raise InputError(f"travel {travel_mm!r} mm: an uncertainty budget needs a travel > 0")
    to_unit = {"um": 1.0, "mm": 1e-3, "nm": 1e3}.get(unit)
    if to_unit is None:
        raise InputError(f"linear uncertainty budget in {unit!r}: use um or mm")
    L_um = travel_mm * 1e3
    i = inputs
    a_alpha = (
        0.1 * i.expansion_coefficient
        if i.expansion_coefficient_halfwidth is None
        else i.expansion_coefficient_halfwidth
    )
    dT = abs(i.material_temperature - 20.0)
    cos_e = (i.beam_offset * 1e3) ** 2 / (2 * L_um)
    d, s = DISTANCE_PARAMETERS, _ALL
    c = [
        Contributor(
            "u_DEVICE",
            "laser measurement accuracy",
            i.laser_accuracy_ppm * 1e-6 * L_um / i.laser_accuracy_k,
            "normal",
            f"{_ANNEX}, A.2 (measuring device)",
            f"{i.laser_accuracy_ppm:g} ppm (k = {i.laser_accuracy_k:g}) over {travel_mm:g} mm",
            d,
        ),
        Contributor(
            "u_RESOLUTION",
            "resolution of the reading",
            i.resolution / (2 * _SQ3),
            "rectangular",
            f"{_ANNEX}, A.2; ISO/TR 230-9 §5",
            f"resolution {i.resolution:g} µm",
            s,
        ),
        Contributor(
            "u_MISALIGNMENT",
            "cosine error of the beam alignment",
            cos_e / (2 * _SQ3),
            "rectangular",
            f"{_ANNEX}, A.3 (misalignment)",
            f"beam offset {i.beam_offset:g} mm over {travel_mm:g} mm: e = d²/2L = {cos_e:.3g} µm",
            d,
        ),
        Contributor(
            "u_E,MACHINE",
            "uncertainty of the expansion coefficient",
            a_alpha * L_um * dT / _SQ3,
            "rectangular",
            f"{_ANNEX}, A.4 (machine temperature compensation)",
            f"α ± {a_alpha * 1e6:.3g} µm/(m·K), |T − 20 °C| = {dT:.3g} K",
            d,
        ),
        Contributor(
            "u_M,MACHINE",
            "material temperature measurement",
            i.temperature_halfwidth * i.expansion_coefficient * L_um / _SQ3,
            "rectangular",
            f"{_ANNEX}, A.4 (machine temperature compensation)",
            f"sensor ± {i.temperature_halfwidth:g} K, "
            f"α = {i.expansion_coefficient * 1e6:.3g} µm/(m·K)",
            d,
        ),
        Contributor(
            "u_M,POSITION",
            "material sensor position",
            i.sensor_position_halfwidth * i.expansion_coefficient * L_um / _SQ3,
            "rectangular",
            f"{_ANNEX}, A.4; ISO/TR 230-9 §6 (temperature)",
            f"sensor place vs scale ± {i.sensor_position_halfwidth:g} K",
            d,
        ),
        Contributor(
            "u_EVE",
            "environmental variation error",
            i.e_ve / (2 * _SQ3),
            "rectangular",
            f"{_ANNEX}, A.5 (environmental variation error E_VE)",
            f"E_VE = {i.e_ve:g} µm ({i.e_ve_source})",
            s,
        ),
    ]
    c = [
        Contributor(
            x.name, x.quantity, x.u * to_unit, x.distribution, x.clause, x.basis, x.applies_to
        )
        for x in c
    ]
    return combine(c, unit, k, _ALL, _notes(i))


def _notes(i: LinearInputs) -> list[str]:
    notes = []
    if i.expansion_coefficient_halfwidth is None:
        notes.append("uncertainty of the expansion coefficient taken as ±10 % of α (not declared)")
    if i.e_ve_source == "declared":
        notes.append(f"E_VE = {i.e_ve:g} µm declared, not measured by a drift check")
    return notes


@dataclass(frozen=True)
class RotaryInputs:
    """What a rotary ISO 230-2 budget needs (angles in arcsec, misalignments in mrad).

    Attributes
    ----------
    calibrator_accuracy : float, arcsec
        Accuracy of the rotary calibrator from its certificate, expanded with ``calibrator_k``.
    calibrator_k : float
    resolution : float, arcsec
    alpha, beta, omega : float, mrad
        Misalignments of Renishaw, "Interferometric calibration of rotary axes", eq. 1: axes (α),
        laser line of sight (β), reflector twist (ω).
    e_ve : float, arcsec
    e_ve_source : str
    """

    calibrator_accuracy: float = 1.0
    calibrator_k: float = 2.0
    resolution: float = 0.1
    alpha: float = 0.5
    beta: float = 1.0
    omega: float = 2.5
    e_ve: float = 0.0
    e_ve_source: str = "declared"

    def __post_init__(self) -> None:
        _check_inputs(self, signed=(), k="calibrator_k")

    @classmethod
    def from_mapping(cls, d: Mapping[str, Any]) -> "RotaryInputs":
        """From a config table (``[uncertainty]``)."""
        return cls(**_known_keys(cls, d))



def rotary_budget(
    inputs: RotaryInputs = RotaryInputs(), unit: str = "arcsec", k: float = COVERAGE_FACTOR
) -> UncertaintyBudget:
    """ISO 230-2 Annex A budget of a rotary positioning test (rotary calibrator).

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
        Contributor(
            "u_DEVICE",
            "rotary calibrator accuracy",
            i.calibrator_accuracy / i.calibrator_k,
            "normal",
            f"{_ANNEX}, A.2 (measuring device)",
            f"± {i.calibrator_accuracy:g} arcsec (k = {i.calibrator_k:g})",
            d,
        ),
        Contributor(
            "u_RESOLUTION",
            "resolution of the reading",
            i.resolution / (2 * _SQ3),
            "rectangular",
            f"{_ANNEX}, A.2; ISO/TR 230-9 §5",
            f"resolution {i.resolution:g} arcsec",
            s,
        ),
        Contributor(
            "u_MISALIGNMENT",
            "misalignment (Renishaw, Interferometric calibration of " "rotary axes, eq. 1)",
            mis / _SQ3,
            "rectangular",
            f"{_ANNEX}, A.3; Renishaw eq. 1",
            f"α = {i.alpha:g}, β = {i.beta:g}, ω = {i.omega:g} mrad: ± {mis:.3g} arcsec",
            d,
        ),
        Contributor(
            "u_EVE",
            "environmental variation error",
            i.e_ve / (2 * _SQ3),
            "rectangular",
            f"{_ANNEX}, A.5 (environmental variation error E_VE)",
            f"E_VE = {i.e_ve:g} arcsec ({i.e_ve_source})",
            s,
        ),
    ]
    f = convert(1.0, "arcsec", unit)
    c = [
        Contributor(x.name, x.quantity, x.u * f, x.distribution, x.clause, x.basis, x.applies_to)
        for x in c
    ]
    notes = (
        [f"E_VE = {i.e_ve:g} arcsec declared, not measured by a drift check"]
        if i.e_ve_source == "declared"
        else []
    )
    return combine(c, unit, k, _ALL, notes)


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
    dataset, result, table: Mapping[str, Any] | None = None, k: float = COVERAGE_FACTOR
) -> UncertaintyBudget:
    """The Annex A budget of an evaluated ISO 230-2 test, linear or rotary.

    Parameters
    ----------
    dataset : PositioningDataset
        Its environment supplies α and the material temperature where ``table`` does not.
    result : Iso230_2Result
        Supplies the travel (first to last target) and the deviation unit.
    table : mapping, optional
        The ``[uncertainty]`` table of the configuration (keys of :class:`LinearInputs` or
        :class:`RotaryInputs`); absent keys take the documented defaults.
    k : float

    Returns
    -------
    UncertaintyBudget
    """
    table = dict(table or {})
    if dataset.axis_kind.value == "rotary":
        return rotary_budget(RotaryInputs.from_mapping(table), result.deviation_unit, k)
    from axiscal.units import convert

    travel = float(convert(float(np.ptp(result.targets)), result.target_unit, "mm"))
    env = dataset.metadata.environment
    notes = []
    if "material_temperature" not in table and not env.material_temperature:
        notes.append(
            "material temperature not stated: 20 °C assumed, so the uncertainty of α "
            "contributes nothing; state it in the data file or [uncertainty]"
        )
    if "expansion_coefficient" not in table and env.expansion_coefficient is None:
        notes.append("expansion coefficient not stated: 11.5 µm/(m·K) (steel) assumed")
    b = linear_budget(travel, LinearInputs.from_mapping(table, dataset), result.deviation_unit, k)
    return replace(b, notes=b.notes + tuple(notes))
