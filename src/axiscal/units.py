"""Units of length and angle, and their conversion.

Inside the core every quantity is SI (metres, radians, seconds, pascals; temperatures in degrees
Celsius as the domain writes them). Datasets carry the *display* unit of their axis: mm and µm for
linear axes, degrees and arcseconds for rotary axes. This module converts between the two.

A unit is named by a short string; aliases (``"µm"``, ``"micron"``, ``"arcsec"``, ``'"'``) are
accepted and normalised by :func:`canonical`.

Examples
--------
>>> convert(1.0, "deg", "arcsec")
3600.0
>>> convert(12.5, "um", "mm")
0.0125
>>> dimension("arcsec")
'angle'
"""

from __future__ import annotations

import math
import re
from typing import Literal

import numpy as np

from axiscal.errors import UnitError

__all__ = [
    "display",
    "LENGTH_UNITS",
    "ANGLE_UNITS",
    "canonical",
    "dimension",
    "factor",
    "convert",
    "to_si",
    "from_si",
    "ARCSEC",
    "DEG",
    "UM",
    "MM",
    "quantity",
]

Dimension = Literal["length", "angle"]

#: Size of one unit in metres.
LENGTH_UNITS: dict[str, float] = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "nm": 1e-9,
    "in": 25.4e-3,
    "uin": 25.4e-9,
}

#: Size of one unit in radians.
ANGLE_UNITS: dict[str, float] = {
    "rad": 1.0,
    "mrad": 1e-3,
    "urad": 1e-6,
    "deg": math.pi / 180.0,
    "arcmin": math.pi / (180.0 * 60.0),
    "arcsec": math.pi / (180.0 * 3600.0),
}

#: One arcsecond, one degree, one micrometre and one millimetre in SI.
ARCSEC = ANGLE_UNITS["arcsec"]
DEG = ANGLE_UNITS["deg"]
UM = LENGTH_UNITS["um"]
MM = LENGTH_UNITS["mm"]

_ALIASES: dict[str, str] = {
    "metre": "m", "meter": "m", "metres": "m", "meters": "m",
    "millimetre": "mm", "millimeter": "mm", "millimetres": "mm", "millimeters": "mm",
    "µm": "um", "μm": "um", "micron": "um", "microns": "um", "micrometre": "um",
    "micrometer": "um", "micrometres": "um", "micrometers": "um",
    "nanometre": "nm", "nanometer": "nm",
    "inch": "in", "inches": "in", '"in': "in",
    "µin": "uin", "μin": "uin", "microinch": "uin",
    "radian": "rad", "radians": "rad",
    "µrad": "urad", "μrad": "urad",
    "degree": "deg", "degrees": "deg", "°": "deg",
    "arcminute": "arcmin", "arcminutes": "arcmin", "'": "arcmin",
    "arcsecond": "arcsec", "arcseconds": "arcsec", "sec": "arcsec", '"': "arcsec", "as": "arcsec",
}


#: Canonical names as people write them (the code's names are ASCII).
_DISPLAY = {"um": "µm", "deg": "°", "urad": "µrad", "uin": "µin", "um/m": "µm/m"}


def display(unit: str) -> str:
    """A unit as people write it: ``µm`` for ``um``, ``°`` for ``deg``; others as they are.

    >>> display("um"), display("deg"), display("arcsec")
    ('µm', '°', 'arcsec')
    """
    return _DISPLAY.get(unit, unit)


def canonical(unit: str) -> str:
    """Return the canonical name of a unit of length or angle.

    Parameters
    ----------
    unit : str
        A unit name or alias, case-insensitive (``"µm"``, ``"Microns"``, ``"arcsec"`` ...).

    Raises
    ------
    UnitError
        If the name is not a known unit of length or angle.

    Examples
    --------
    >>> canonical("µm"), canonical("Degrees"), canonical('"')
    ('um', 'deg', 'arcsec')
    """
    if not isinstance(unit, str):
        raise UnitError(f"unit must be a string, got {unit!r}")
    key = unit.strip()
    if key in LENGTH_UNITS or key in ANGLE_UNITS:
        return key
    low = key.lower()
    if low in LENGTH_UNITS or low in ANGLE_UNITS:
        return low
    if key in _ALIASES:
        return _ALIASES[key]
    if low in _ALIASES:
        return _ALIASES[low]
    known = ", ".join(list(LENGTH_UNITS) + list(ANGLE_UNITS))
    raise UnitError(f"unknown unit {unit!r}; known units: {known}")


def dimension(unit: str) -> Dimension:
    """Return ``"length"`` or ``"angle"`` for a unit name."""
    name = canonical(unit)
    return "length" if name in LENGTH_UNITS else "angle"


def factor(unit: str, expected: Dimension | None = None) -> float:
    """Size of one ``unit`` in SI (metres or radians).

    Parameters
    ----------
    unit : str
        Unit name or alias.
    expected : {"length", "angle"}, optional
        If given, a unit of the other dimension raises :class:`UnitError`.
    """
    name = canonical(unit)
    dim = dimension(name)
    if expected is not None and dim != expected:
        raise UnitError(f"unit {unit!r} is an {dim} unit where a {expected} unit is needed")
    return LENGTH_UNITS[name] if dim == "length" else ANGLE_UNITS[name]


def convert(value, from_unit: str, to_unit: str):
    """Convert ``value`` (scalar or array) from one unit to another of the same dimension.

    Raises
    ------
    UnitError
        If a unit is unknown or the two units are of different dimensions.
    """
    if dimension(from_unit) != dimension(to_unit):
        raise UnitError(
            f"cannot convert {from_unit!r} ({dimension(from_unit)}) to {to_unit!r} "
            f"({dimension(to_unit)})"
        )
    k = factor(from_unit) / factor(to_unit)
    if isinstance(value, (int, float)):
        return float(value) * k
    return np.asarray(value, dtype=float) * k


def to_si(value, unit: str):
    """Convert ``value`` in ``unit`` to metres or radians."""
    k = factor(unit)
    if isinstance(value, (int, float)):
        return float(value) * k
    return np.asarray(value, dtype=float) * k


def from_si(value, unit: str):
    """Convert ``value`` in metres or radians to ``unit``."""
    k = factor(unit)
    if isinstance(value, (int, float)):
        return float(value) / k
    return np.asarray(value, dtype=float) / k


_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_REGISTRY = None
#: Longest text read as a value with its unit, characters.
_LONGEST = 100


def quantity(text: str, unit: str, *, difference: bool = False) -> float:
    """A value written with its unit (``"11.5 um/(m K)"``, ``"20.5 degC"``), in ``unit``.

    Parameters
    ----------
    text : str
        A number, then a unit pint understands (``µm``, ``°C``, ``1/K``, ``ppm``, ``mrad`` ...;
        ``·`` is read as a product). A number alone is already in ``unit``.
    unit : str
        The unit wanted, as pint writes it (``"um/(m*K)"``, ``"degC"``, ``"K"``).
    difference : bool
        ``unit`` is a temperature difference (K): ``°C`` or ``°F`` in ``text`` then means a
        difference of temperature (0.1 °C = 0.1 K), not a temperature (0.1 °C = 273.25 K).

    Returns
    -------
    float
        The value in ``unit``.

    Raises
    ------
    UnitError
        No number at the start, a unit pint does not know, or one of another dimension.

    Notes
    -----
    pint (the units library) is imported only here, when a value comes with its unit, so a
    command given plain numbers never loads it (start-up, issue 30).

    Examples
    --------
    >>> quantity("11.5 um/(m K)", "1/K")
    1.15e-05
    >>> round(quantity("293.15 K", "degC"), 9), quantity("0.1 degC", "K", difference=True)
    (20.0, 0.1)
    >>> quantity("2.5", "mm")
    2.5
    """
    text = str(text)
    if len(text) > _LONGEST:   # pint's parser on a megabyte of text takes minutes
        raise UnitError(f"{text[:40]!r}…: {len(text)} characters; a value with its unit is "
                        f"at most {_LONGEST}")
    m = _NUMBER.match(text)
    if m is None:
        raise UnitError(f"{text!r}: write a number, then its unit (e.g. '11.5 um/(m K)')")
    number, written = float(m.group(1)), m.group(2).replace("·", "*").replace("⋅", "*")
    if not written:
        return number
    global _REGISTRY
    import pint

    if _REGISTRY is None:
        _REGISTRY = pint.UnitRegistry()
    try:
        q = _REGISTRY.Quantity(number, written)
        if difference and not q._is_multiplicative:   # °C, °F: a difference of temperature
            q = _REGISTRY.Quantity(number, f"delta_{q.units}")
        return float(q.to(unit).magnitude)
    except pint.DimensionalityError:
        raise UnitError(f"{text!r}: {written} cannot be converted to {unit}") from None
    except Exception as e:   # pint's parser raises many kinds (tokenize, syntax) on odd text
        raise UnitError(f"{text!r}: unknown unit {written!r} ({e})") from None
