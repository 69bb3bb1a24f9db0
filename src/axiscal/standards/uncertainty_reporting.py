"""How an expanded uncertainty is stated: at most two significant digits, rounded up rather than
to the nearest digit (JCGM 100:2008 §7.2.6), never shown as zero.

Every front end (terminal, ``--json`` text fields, reports, certificates) shows U through
:func:`format_uncertainty`; the budgets of :mod:`axiscal.standards.iso230_9` round with
:func:`round_up`. Both names are also importable from :mod:`axiscal.standards.iso230_9`.

References
----------
JCGM 100:2008 (GUM), §7.2.6.
"""

from __future__ import annotations

import math

__all__ = ["round_up", "format_uncertainty", "format_value"]


def round_up(U: float, digits: int = 2) -> float:
    """``U`` rounded up to ``digits`` significant digits (JCGM 100:2008 §7.2.6).

    A value already at ``digits`` digits stays (2.4 stays 2.4, not 2.5, in spite of its binary
    representation); 0 stays 0; NaN and infinities are returned as they are.

    Examples
    --------
    >>> round_up(0.000577), round_up(2.41), round_up(3.52), round_up(12.01), round_up(2.4)
    (0.00058, 2.5, 3.6, 13.0, 2.4)
    """
    if not math.isfinite(U) or U <= 0:
        return U
    e = math.floor(math.log10(U)) - (digits - 1)
    scaled = U / 10.0**e
    whole = round(scaled)
    n = whole if abs(scaled - whole) <= 1e-9 * scaled else math.ceil(scaled)
    return round(n * 10.0**e, max(0, -e))


def format_uncertainty(U: float | None, digits: int = 2) -> str:
    """U as displayed everywhere: :func:`round_up` to two significant digits, never "0.00".

    None or NaN (not covered, not estimated) is a dash; an exact 0 (a budget with no
    contributor for the parameter) is "0".

    Examples
    --------
    >>> format_uncertainty(0.000577), format_uncertainty(2.41), format_uncertainty(0.998)
    ('0.00058', '2.5', '1.0')
    >>> format_uncertainty(123.4), format_uncertainty(None)
    ('130', '—')
    """
    if U is None or (isinstance(U, float) and math.isnan(U)):
        return "—"
    if U == 0 or not math.isfinite(U):
        return f"{U:g}"
    r = round_up(float(U), digits)
    decimals = max(0, digits - 1 - math.floor(math.log10(r)))
    return f"{r:.{decimals}f}"


def format_value(value: float, U: float | None, digits: int = 2) -> str:
    """A measured value rounded to the last digit of its printed U (ILAC-P14:09/2020 §5.3:
    the value is stated to the same number of digits as the uncertainty).

    ``U`` None, NaN, zero or infinite: the value at 2 decimals (no U to round it to).

    Examples
    --------
    >>> format_value(74.7682, 0.655), format_value(204.76, 143.2), format_value(5.8123, 0.00058)
    ('74.77', '205', '5.81230')
    """
    if U is None or not math.isfinite(U) or U <= 0:
        return f"{value:.2f}"
    text = format_uncertainty(U, digits)
    decimals = len(text.split(".", 1)[1]) if "." in text else 0
    return f"{value:.{decimals}f}"
