"""Squareness from two straightness trajectories, with its uncertainty: the one evaluation of
``axiscal squareness biaxial`` and of the workbench's "squareness with another straightness
test" (a pure function: the trajectories and the inputs of the budget in, the result out).

The squareness is the angle between the reference straight lines of the two trajectories, each
read along the other axis (ISO 230-1:2012 §3.6.7; Chapman, *Calibration of machine squareness*,
Methods 1-3), with the reference square's angle error corrected for its orientation; its
expanded uncertainty by ISO/TR 230-9 (:func:`~axiscal.standards.iso230_9_geometry.
squareness_budget_with_inputs`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from axiscal.errors import InputError

__all__ = ["Biaxial", "CONFIGS", "SQUARES", "evaluate_biaxial"]

#: Set-ups of Chapman, Calibration of machine squareness, Methods 1-3.
CONFIGS = ("L", "T", "+")
#: Reference squares of the uncertainty budget.
SQUARES = ("optics", "square", "reversal")


@dataclass(frozen=True)
class Biaxial:
    """Squareness from two trajectories.

    Attributes
    ----------
    result : SquarenessResult
        :func:`~axiscal.standards.iso230_1.squareness_from_trajectories`'s result.
    budget : UncertaintyBudget
        Its ISO/TR 230-9 budget (``U("squareness")`` in µm/m).
    summary : dict
        The JSON ``axiscal squareness biaxial --json`` prints (stable keys).
    """

    result: Any
    budget: Any
    summary: dict

    def __str__(self) -> str:
        return str(self.result)


def evaluate_biaxial(one, two, *, config: str = "L", orientation: int = 0,
                     prism_error: float = 0.0, reference: str = "least_squares",
                     datum: str = "", square: str = "optics",
                     inputs: Mapping[str, float] | None = None) -> Biaxial:
    """Squareness of the plane of two straightness trajectories.

    Parameters
    ----------
    one, two : StraightnessData
        The first axis's trajectory (deviations along the second) and the second's (along the
        first); positions and deviations in m.
    config : {"L", "T", "+"}
        Set-up (Chapman, Methods 1-3).
    orientation : int, degrees
        Equipment orientation, clockwise: 0, 90, 180 or 270.
    prism_error : float, arcsec
        Angle error of the optical or mechanical square in orientation 0 (its angle − 90°).
    reference : {"least_squares", "end_point", "minimum_zone"}
        Reference line (ISO 230-1:2012 §3.4).
    datum : str
        Datum axis of the ISO 230-1 sign (default the first axis).
    square : {"optics", "square", "reversal"}
        Reference square of the uncertainty budget.
    inputs : mapping, optional
        The ``[squareness_uncertainty]`` inputs (the user configuration's table).

    Raises
    ------
    InputError
        A set-up, square or reference not listed; a trajectory not read along the other axis.
    """
    import numpy as np

    from axiscal.standards.iso230_1 import correct_reference_angle, squareness_from_trajectories
    from axiscal.standards.iso230_9_geometry import (slope_uncertainty,
                                                     squareness_budget_with_inputs)
    from axiscal.units import ARCSEC

    config = str(config).upper()
    if config not in CONFIGS:
        raise InputError(f"--config {config!r}: must be L, T or +")
    if square not in SQUARES:
        raise InputError(f"--square {square!r}: use optics, square or reversal")
    axes = (one.axis or "X", two.axis or "Y")
    check_crossed(one, two, axes)
    correction = correct_reference_angle(prism_error * ARCSEC, orientation)
    r = squareness_from_trajectories(one.positions, one.deviations, two.positions,
                                     two.deviations, axes=axes, method=reference,  # type: ignore[arg-type]
                                     datum=datum, reference_excess=correction)
    budget = squareness_budget_with_inputs(
        square, dict(inputs or {}), length_x=float(np.ptp(one.positions)),
        length_y=float(np.ptp(two.positions)),
        slope_fit_x=slope_uncertainty(one.positions, one.deviations),
        slope_fit_y=slope_uncertainty(two.positions, two.deviations))
    d = {"U_um_per_m": budget.U("squareness"),
         "uncertainty": [{"name": c.name, "u_um_per_m": c.u, "clause": c.clause}
                         for c in budget.contributors],
         "squareness": r.squareness.as_dict(), "config": config,
         "orientation": orientation, "reference": reference,
         "prism_error_arcsec": prism_error, "correction_um_per_m": correction * 1e6,
         "slope_first_um_per_m": r.slope_first * 1e6,
         "slope_second_um_per_m": r.slope_second * 1e6,
         "straightness_first_um": r.first.deviation * 1e6,
         "straightness_second_um": r.second.deviation * 1e6}
    return Biaxial(r, budget, d)


def check_crossed(one, two, axes) -> None:
    """Each trajectory's deviations must be read along the other axis (ISO 230-1 §3.6.7)."""
    for data, other in ((one, axes[1]), (two, axes[0])):
        if data.direction and data.direction != other:
            raise InputError(f"{data.source} reads the {data.axis or '?'} axis's deviations along "
                             f"{data.direction}; a bi-axial {''.join(axes)} test needs them along "
                             f"{other}")
