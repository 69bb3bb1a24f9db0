"""A table read back from a controller file, compared with the deviations it should correct.

Some writers shift a table so that its value at the reference point is zero: the SINUMERIK
840D's, after the 808D manual's advice (no jump when the compensation becomes active), and
FANUC's, whose data are increments counted from the reference point (parameter 3620). Such a
table corrects the deviations *up to a constant*: compared as it stands, every residual carries
that constant (issue 42: "largest residual 35.6 µm" that was only the shift). :func:`compare`
undoes it, and says so: the correction the table would hold at its reference point before the
shift is −(deviation there), interpolated linearly between the measured targets (held beyond
them, as the tables are).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ReadBack", "compare", "ZEROED_AT_REFERENCE"]

#: Controllers whose tables are zero at the reference point as written.
ZEROED_AT_REFERENCE = ("siemens-840d", "fanuc")


@dataclass(frozen=True)
class ReadBack:
    """Deviations, corrections and residuals at the measured targets.

    Attributes
    ----------
    rows : tuple of dict
        Per target: ``target`` (position unit), ``deviation``, ``correction``, ``residual`` =
        deviation + correction (correction unit), the correction after the shift was undone.
    largest_residual : float, correction unit
    shift : float, correction unit
        Added to every correction of the table to undo the reference shift (0 if none).
    note : str
        What was undone, or ``""``.
    """

    rows: tuple
    largest_residual: float
    shift: float
    note: str


def compare(table, targets, deviations, controller: str = "") -> ReadBack:
    """Compare ``table`` with the mean ``deviations`` at ``targets`` (undoing the reference shift).

    Parameters
    ----------
    table : CompensationTable
    targets : array_like, ``table.position_unit``
    deviations : array_like, ``table.correction_unit``
        Mean bidirectional deviations x̄ (ISO 230-2:2014 eq. 4).
    controller : str
        The format the table was read from; tables of :data:`ZEROED_AT_REFERENCE` that are zero at
        their reference point get the shift undone.

    Returns
    -------
    ReadBack
    """
    t = np.asarray(targets, dtype=float)
    dev = np.asarray(deviations, dtype=float)
    corr = 0.5 * (table.correction_at(t, 1) + table.correction_at(t, -1))
    shift, note = 0.0, ""
    ref = table.reference_position
    at_ref = float(table.mean[table.reference_index])
    if controller in ZEROED_AT_REFERENCE and abs(at_ref) < 1e-9:
        order = np.argsort(t)
        shift = -float(np.interp(ref, t[order], dev[order]))
        corr = corr + shift
        note = (f"the {controller} table is zero at its reference point {ref:g} "
                f"{table.position_unit} (the writer shifts it there); compared after undoing "
                f"that shift: {shift:+.4g} {table.correction_unit} (−deviation at {ref:g}) added "
                "to every correction")
    res = dev + corr
    rows = tuple(dict(target=float(a), deviation=float(x), correction=float(c), residual=float(r))
                 for a, x, c, r in zip(t, dev, corr, res))
    return ReadBack(rows, float(np.max(np.abs(res))), shift, note)
