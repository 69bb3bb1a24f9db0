"""Thermal expansion and normalisation of lengths to the reference temperature of 20 °C (ISO 1).

ISO 1 fixes 20 °C as the temperature at which a geometrical specification holds. A length
measured on material at another temperature ``t`` is referred to 20 °C by undoing the linear
expansion of the material:

.. math::
    L_{20} = \\frac{L_t}{1 + \\alpha\\,(t - 20\\,^\\circ\\mathrm{C})}

with α the linear expansion coefficient of the material (table :data:`MATERIALS`) and ``t`` the
mean of the material sensors (:func:`mean_temperature`). :func:`normalise_dataset` applies this to
a positioning test (Yüksel et al., Position accuracy and repeatability calibration of turn tables: "If these temperature different from the 20 °C, necessary
correction has to applied yield result to 20 °C").

Examples
--------
>>> steel = material("steel")
>>> round(normalise_length(1000.0, 25.0, steel.alpha), 4)   # 1 m of steel at 25 °C, in mm
999.9425
>>> round(expansion(1000.0, 25.0, steel.alpha) * 1000, 1)   # µm longer than at 20 °C
57.5

References
----------
.. [1] ISO 1:2022, Geometrical product specifications (GPS) — Standard reference temperature for
   the specification of geometrical and dimensional properties.
.. [2] ISO 230-2:2014, test conditions (environment): results are referred to 20 °C, and
   measurements at another temperature are corrected for the expansion of the axis.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from axiscal import units
from axiscal.datasets import AxisKind, PositioningDataset
from axiscal.errors import InputError

__all__ = [
    "REFERENCE_TEMPERATURE",
    "Material",
    "MATERIALS",
    "material",
    "mean_temperature",
    "expansion",
    "length_at",
    "normalise_length",
    "normalise_dataset",
]

#: ISO 1 standard reference temperature, degrees Celsius.
REFERENCE_TEMPERATURE = 20.0


@dataclass(frozen=True)
class Material:
    """A material and its linear thermal expansion coefficient near 20 °C.

    Attributes
    ----------
    name : str
    alpha : float, 1/K
        Typical coefficient used when none was measured.
    alpha_range : tuple of float, 1/K
        The spread found for the grades the name covers (what an uncertainty budget should allow).
    source : str
        Where the value comes from.
    """

    name: str
    alpha: float
    alpha_range: tuple[float, float]
    source: str

    def __str__(self) -> str:
        lo, hi = self.alpha_range
        return (f"{self.name}: α = {self.alpha * 1e6:.2f} × 10⁻⁶/K "
                f"({lo * 1e6:.2f} to {hi * 1e6:.2f}; {self.source})")


def _m(name, alpha_ppm, lo_ppm, hi_ppm, source):
    return Material(name, alpha_ppm * 1e-6, (lo_ppm * 1e-6, hi_ppm * 1e-6), source)


#: Materials of machine structures, scales and work-pieces. Keys are lower-case names.
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        _m("steel", 11.5, 10.5, 12.5,
           "ISO 3650 gauge-block steel, (11.5 ± 1.0) × 10⁻⁶/K; carbon and tool steels"),
        _m("stainless steel", 17.3, 16.0, 17.8,
           "austenitic AISI 304/316, ASM Handbook / CRC Handbook of Chemistry and Physics"),
        _m("cast iron", 10.5, 9.0, 12.0, "grey cast iron, ASM Handbook"),
        _m("aluminium", 23.1, 21.0, 24.0,
           "pure aluminium 23.1 (CRC Handbook); wrought alloys 21 to 24"),
        _m("granite", 7.0, 5.0, 9.0,
           "surface-plate granite and diabase; the value depends on the stone"),
        _m("invar", 1.2, 0.6, 2.0, "Invar 36 (Fe-36Ni), manufacturers' data near 20 °C"),
        _m("glass ceramic", 0.0, -0.1, 0.1,
           "Zerodur-type glass ceramic, expansion class 2, 0 ± 0.1 × 10⁻⁶/K (0 to 50 °C)"),
        _m("fused silica", 0.55, 0.5, 0.6, "fused quartz glass, manufacturers' data"),
        _m("brass", 19.0, 18.0, 21.0, "CuZn brasses, CRC Handbook"),
        _m("copper", 16.5, 16.4, 17.0, "CRC Handbook of Chemistry and Physics"),
        _m("titanium", 8.6, 8.4, 9.4, "CRC Handbook (pure); Ti-6Al-4V about 8.6 to 9.4"),
    )
}

_ALIASES = {
    "aluminum": "aluminium", "al": "aluminium", "fe": "steel", "carbon steel": "steel",
    "tool steel": "steel", "stainless": "stainless steel", "inox": "stainless steel",
    "grey cast iron": "cast iron", "gray cast iron": "cast iron", "zerodur": "glass ceramic",
    "glass-ceramic": "glass ceramic", "invar 36": "invar", "quartz": "fused silica",
    "cu": "copper", "ti": "titanium",
}


def material(name: str) -> Material:
    """Look a material up by name (case-insensitive; ``"aluminum"``, ``"zerodur"`` ... accepted).

    Parameters
    ----------
    name : str
        A key of :data:`MATERIALS` or a common alias.

    Returns
    -------
    Material
        With ``alpha`` in 1/K and the source of the value.

    Raises
    ------
    InputError
        If the name is not in :data:`MATERIALS`; the message lists the known names.
    """
    key = " ".join(str(name).strip().lower().replace("_", " ").split())
    key = _ALIASES.get(key, key)
    if key not in MATERIALS:
        raise InputError(f"material {name!r} is not known; known materials: "
                         f"{', '.join(MATERIALS)} (or give the expansion coefficient)")
    return MATERIALS[key]


def mean_temperature(temperatures, weights=None) -> float:
    """Average of several material sensors, degrees Celsius.

    Parameters
    ----------
    temperatures : array_like, degrees Celsius
        One reading per sensor (at least one).
    weights : array_like, optional, dimensionless
        Relative weights (for instance the length of material each sensor stands for); equal
        weights if omitted.

    Returns
    -------
    float, degrees Celsius
        :math:`\\sum w_k t_k / \\sum w_k`, the material temperature ISO 230-2 asks to record
        (the mean of the sensors on the axis).

    Raises
    ------
    InputError
        No reading, a missing (NaN) reading, or weights that do not match or do not sum to > 0.
        A failed sensor is refused rather than silently left out of the mean.

    Examples
    --------
    >>> mean_temperature([20.4, 20.6, 20.8])
    20.6
    >>> mean_temperature([20.0, 21.0], weights=[3, 1])
    20.25
    """
    t = np.atleast_1d(np.asarray(temperatures, dtype=float))
    if t.ndim != 1 or t.size == 0:
        raise InputError("give at least one material temperature (one value per sensor)")
    if not np.all(np.isfinite(t)):
        i = int(np.argmax(~np.isfinite(t)))
        raise InputError(f"material sensor {i + 1} has no reading ({t[i]}); repair or remove it")
    if weights is None:
        return float(np.mean(t))
    w = np.atleast_1d(np.asarray(weights, dtype=float))
    if w.shape != t.shape:
        raise InputError(f"{w.size} weights for {t.size} material sensors")
    if np.any(w < 0) or not np.sum(w) > 0:
        raise InputError("sensor weights must be >= 0 and not all zero")
    return float(np.sum(w * t) / np.sum(w))


def expansion(length, temperature, alpha):
    """Growth of a length from 20 °C to ``temperature``: :math:`L_{20}\\,\\alpha\\,(t - 20)`.

    Parameters
    ----------
    length : array_like, any length unit (the result is in the same unit)
        Length at 20 °C.
    temperature : array_like, degrees Celsius
    alpha : array_like, 1/K

    Returns
    -------
    float or ndarray, unit of ``length``

    Notes
    -----
    Linear expansion about the ISO 1 reference temperature 20 °C (module docstring).
    """
    return _out(np.asarray(length, dtype=float) * np.asarray(alpha, dtype=float)
                * (np.asarray(temperature, dtype=float) - REFERENCE_TEMPERATURE))


def length_at(length_20, temperature, alpha):
    """Length at ``temperature`` of what measures ``length_20`` at 20 °C.

    Parameters
    ----------
    length_20 : array_like, any length unit
        Length at 20 °C.
    temperature : array_like, degrees Celsius
    alpha : array_like, 1/K

    Returns
    -------
    float or ndarray, unit of ``length_20``

    Notes
    -----
    :math:`L_t = L_{20}(1 + \\alpha\\,(t - 20\\,^\\circ\\mathrm{C}))`, ISO 1 reference temperature.
    """
    return _out(np.asarray(length_20, dtype=float)
                * (1.0 + np.asarray(alpha, dtype=float)
                   * (np.asarray(temperature, dtype=float) - REFERENCE_TEMPERATURE)))


def normalise_length(length, temperature, alpha):
    """Length referred to 20 °C: :math:`L_{20} = L_t / (1 + \\alpha (t - 20))`.

    Parameters
    ----------
    length : array_like, any length unit
        Length measured with the material at ``temperature``.
    temperature : array_like, degrees Celsius
        Material temperature (the mean of its sensors).
    alpha : array_like, 1/K
        Linear expansion coefficient of the material.

    Returns
    -------
    float or ndarray, unit of ``length``

    Notes
    -----
    The inverse of :func:`length_at`, referring a length to the ISO 1 reference temperature
    (ISO 230-2:2014 asks for results at 20 °C; Yüksel et al., Position accuracy and repeatability calibration of turn tables, "necessary correction has to applied").
    """
    return _out(np.asarray(length, dtype=float)
                / (1.0 + np.asarray(alpha, dtype=float)
                   * (np.asarray(temperature, dtype=float) - REFERENCE_TEMPERATURE)))


def normalise_dataset(
    dataset: PositioningDataset,
    *,
    alpha: float | None = None,
    material_name: str | None = None,
    temperature: float | None = None,
    datum: float = 0.0,
) -> PositioningDataset:
    """Refer the deviations of a linear positioning test to 20 °C (ISO 1).

    The laser (already compensated for the air) measures true distances along an axis whose scale
    (or work-piece) is at temperature t. At 20 °C the same material would be shorter by the factor
    :math:`1/(1 + \\alpha(t - 20))`, so each measured actual position is normalised and the
    deviation recomputed:

    .. math::
        P_{ij,20} = d + \\frac{P_{ij} - d}{1 + \\alpha (t - 20)},\\qquad
        x_{ij,20} = P_{ij,20} - P_i,\\qquad P_{ij} = P_i + x_{ij}

    with d the datum (the point that does not move as the material expands: the laser's zero,
    usually the axis zero). Sign: a steel axis at 25 °C whose scale has grown shows positive
    deviations growing along the travel (+57.5 µm over 1 m); normalisation removes them.

    Parameters
    ----------
    dataset : PositioningDataset
        A linear axis test.
    alpha : float, 1/K, optional
        Expansion coefficient; default: the dataset's ``environment.expansion_coefficient``, or
        the coefficient of ``material_name``.
    material_name : str, optional
        A name from :data:`MATERIALS`, used when ``alpha`` is not given and the dataset has none.
    temperature : float, degrees Celsius, optional
        Material temperature; default: the mean of the dataset's material sensors.
    datum : float, in the dataset's target unit
        Fixed point of the expansion (default 0).

    Returns
    -------
    PositioningDataset
        A new dataset with normalised deviations (same units); its metadata notes record the
        normalisation. The input is not changed.

    Raises
    ------
    InputError
        A rotary axis, or no coefficient or no material temperature to use.

    Examples
    --------
    >>> from axiscal.datasets import Environment, Metadata
    >>> md = Metadata(environment=Environment(material_temperature=(24.8, 25.2),
    ...                                        expansion_coefficient=11.5e-6))
    >>> ds = PositioningDataset.from_arrays("linear", [0, 500, 1000], [[0, 0], [28.75, 28.75],
    ...                                     [57.5, 57.5]], metadata=md)
    >>> normalise_dataset(ds).up.round(3).tolist()
    [[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
    """
    if dataset.axis_kind is not AxisKind.LINEAR:
        raise InputError("thermal normalisation to 20 °C applies to linear axes; this dataset is "
                         f"a {dataset.axis_kind.value} axis")
    env = dataset.metadata.environment
    if alpha is None:
        if env.expansion_coefficient is not None and material_name is None:
            alpha = env.expansion_coefficient
        elif material_name is not None:
            alpha = material(material_name).alpha
        else:
            raise InputError("no expansion coefficient: the dataset's environment has none; give "
                             "alpha (1/K) or a material name")
    if temperature is None:
        if not env.material_temperature:
            raise InputError("no material temperature: the dataset's environment has no material "
                             "sensors; give the temperature (°C)")
        temperature = mean_temperature(env.material_temperature)
    alpha = float(alpha)
    temperature = float(temperature)
    if not np.isfinite(alpha) or abs(alpha) > 1e-4:
        raise InputError(f"alpha = {alpha:g} 1/K is not a plausible expansion coefficient "
                         "(|alpha| <= 1e-4 1/K)")
    if not -50.0 <= temperature <= 200.0:
        raise InputError(f"material temperature = {temperature:g} °C is outside -50 to 200 °C")

    k = units.convert(1.0, dataset.target_unit, dataset.deviation_unit)
    rel = ((dataset.targets - float(datum)) * k)[:, None]
    scale = 1.0 + alpha * (temperature - REFERENCE_TEMPERATURE)

    def fix(x):
        return (rel + x) / scale - rel

    note = (f"normalised to 20 °C (ISO 1): alpha = {alpha * 1e6:.3f}e-6/K, material "
            f"temperature {temperature:.3f} °C, datum {datum:g} {dataset.target_unit}")
    notes = f"{dataset.metadata.notes}; {note}" if dataset.metadata.notes else note
    return replace(dataset, up=fix(dataset.up), down=fix(dataset.down),
                   metadata=replace(dataset.metadata, notes=notes))


def _out(x):
    arr = np.asarray(x, dtype=float)
    return float(arr) if arr.ndim == 0 else arr
