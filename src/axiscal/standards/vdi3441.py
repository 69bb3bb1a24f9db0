"""VDI/DGQ 3441: the parameters whose definitions are public (Pa, U); P and Ps named, not evaluated.

What this module can cite, and therefore implements
---------------------------------------------------
The guideline itself (VDI/DGQ 3441, *Statistische Prüfung der Arbeits- und Positionsgenauigkeit von
Werkzeugmaschinen*, 1977) was not available to this project. Its parameters are defined in words
by Bosch Rexroth, *Linearmodule* catalogue R310DE 2402 (2010-12), p. 151, "Positioniergenauigkeit
nach VDI/DGQ 3441" (manualslib.de/manual/528049/Rexroth-R310De-2402.html?page=151):

=====  ==========================================================  ===================================
name   definition (Rexroth, quoted in translation)                 equation here
=====  ==========================================================  ===================================
U      reversal span (Umkehrspanne): "the difference of the mean   U_j = |x̄_j↑ - x̄_j↓| at every target;
       values of the two approach directions; determined at        U = max U_j, Ū = mean of the U_j
       every measuring position"
Pa     position deviation (Positionsabweichung): "the largest      Pa = max_j x̄_j - min_j x̄_j,
       occurring difference of the mean values of all measuring     x̄_j = (x̄_j↑ + x̄_j↓) / 2
       positions; it describes systematic deviations"
Ps     position scatter (Positionsstreubreite): "describes the     not evaluated
       effect of random deviations; determined at every
       measuring position"
P      position uncertainty (Positionsunsicherheit): "the total    not evaluated
       deviation; it takes account of position deviation,
       reversal span and position scatter"
=====  ==========================================================  ===================================

Test (same page): targets "at uneven intervals over the travel, so that periodic deviations are
also caught", each "approached several times from both sides". A test with one direction cannot
form U and is refused; evenly spaced targets and a single approach at a target give a warning
that names the rule.

Readings chosen here, not quoted from the guideline:

* x̄_j↑, x̄_j↓ are the means of the approaches in each direction at target j, and x̄_j ("the mean
  value of a measuring position") the mean of the two, (x̄_j↑ + x̄_j↓)/2: the mean of every
  approach when both directions have the same number of readings, and, when a reading is
  missing, still free of the reversal (pooling every approach would move x̄_j toward the
  direction with more readings and turn a pure reversal into a position deviation). Missing
  readings (NaN) are left out.
* "Span" is read as a magnitude, so U_j >= 0. The axis values U = max U_j and Ū = mean U_j follow
  the outputs "U max" (reversal error) and "U mean" (mean reversal error) of the Keysight E1733A
  laser calibration software (E1733A_Remote.h, VDI_UMAX and VDI_UMEAN; GitHub 9997433-bit/MD).

Not evaluated, because no public text gives them: the factor that turns the scatter at a target
into Ps (and whether the two directions' standard deviations are pooled), and how P combines Pa,
U and Ps. A retrospective (The importance of being repeatable, WIT Transactions on Engineering
Sciences 23, 1999) says VDI/DGQ 3441 measured repeatability "as a six standard deviation spread",
but not of which readings, so Ps is not formed from it.

References
----------
VDI/DGQ 3441 (1977), not available here.
Bosch Rexroth, Linearmodule R310DE 2402, p. 151.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError
from axiscal.standards._parameters import described_parameters

__all__ = ["Vdi3441Result", "evaluate", "PARAMETERS", "NOT_EVALUATED"]

_SOURCE = "Rexroth R310DE p. 151"

#: name -> (description, source) of the axis parameters this module forms.
PARAMETERS = {
    "Pa": ("position deviation, max x̄_j − min x̄_j, x̄_j = (x̄_j↑ + x̄_j↓)/2", _SOURCE),
    "U": ("reversal span, max U_j, U_j = |x̄_j↑ − x̄_j↓|", _SOURCE),
    "U_mean": ("mean reversal span, mean of the U_j", _SOURCE),
}

#: name -> why axiscal does not evaluate it.
NOT_EVALUATED = {
    "P": "position uncertainty: not evaluated, how it combines Pa, U and Ps is not public",
    "Ps": "position scatter: not evaluated, its factor on s (and any pooling of the two "
          "directions) is not public",
}


@dataclass(frozen=True, eq=False)
class Vdi3441Result:
    """The public VDI/DGQ 3441 parameters of one positioning test, in ``deviation_unit``.

    Attributes
    ----------
    deviation_unit : str
    targets : ndarray, the dataset's target unit
    mean_up, mean_down : ndarray
        x̄_j↑, x̄_j↓: mean of the approaches in each direction at each target.
    mean : ndarray
        x̄_j = (x̄_j↑ + x̄_j↓) / 2 at each target.
    U_j : ndarray
        Reversal span at each target, |x̄_j↑ − x̄_j↓|.
    Pa, U, U_mean : float
    warnings : tuple of str
    """

    deviation_unit: str
    targets: np.ndarray
    mean_up: np.ndarray
    mean_down: np.ndarray
    mean: np.ndarray
    U_j: np.ndarray
    Pa: float
    U: float
    U_mean: float
    warnings: tuple[str, ...] = field(default_factory=tuple)

    def parameters(self) -> dict[str, tuple[float, str, str]]:
        """Pa, U, U_mean: name -> (value, unit, description with its source); P and Ps are in
        :data:`NOT_EVALUATED`."""
        return described_parameters(self, PARAMETERS)


def evaluate(dataset: PositioningDataset) -> Vdi3441Result:
    """Position deviation Pa and reversal span U of VDI/DGQ 3441, as Rexroth defines them.

    Parameters
    ----------
    dataset : PositioningDataset
        Every target approached from both sides, several times (NaN = a missing reading).

    Returns
    -------
    Vdi3441Result

    Raises
    ------
    InputError
        If the test has one direction only, or a target has no reading in a direction.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays(
    ...     "linear", [0, 310, 590], up=[[1, 3], [2, 2], [0, 0]], down=[[0, 0], [1, 1], [3, 3]])
    >>> r = evaluate(ds)
    >>> r.Pa, r.U, r.U_mean
    (0.5, 3.0, 2.0)
    """
    up, down = dataset.up, dataset.down
    if up.shape[1] == 0 or down.shape[1] == 0:
        raise InputError("VDI/DGQ 3441 reversal span U needs approaches from both sides; this "
                         "test has one direction only")
    n_up, n_down = np.sum(~np.isnan(up), axis=1), np.sum(~np.isnan(down), axis=1)
    unit = dataset.target_unit
    for n, arrow in ((n_up, "↑"), (n_down, "↓")):
        if np.any(n == 0):
            t = dataset.targets[int(np.argmax(n == 0))]
            raise InputError(f"VDI/DGQ 3441: target {t:g} {unit} has no reading {arrow}; the "
                             "reversal span needs a mean in each direction at every target")
    mean_up = np.nansum(up, axis=1) / n_up
    mean_down = np.nansum(down, axis=1) / n_down
    mean = 0.5 * (mean_up + mean_down)
    U_j = np.abs(mean_up - mean_down)
    warn: list[str] = []
    if np.any(n_up < 2) or np.any(n_down < 2):
        warn.append("a target has a single approach in a direction; VDI/DGQ 3441 approaches "
                    "every target several times from both sides (Rexroth R310DE p. 151)")
    steps = np.diff(np.sort(dataset.targets))
    if steps.size >= 2 and np.ptp(steps) <= 1e-9 * max(float(np.max(np.abs(steps))), 1e-300):
        warn.append("the targets are evenly spaced; VDI/DGQ 3441 places them at uneven intervals "
                    "so that periodic deviations are caught (Rexroth R310DE p. 151)")
    for a in (mean_up, mean_down, mean, U_j):
        a.flags.writeable = False
    return Vdi3441Result(
        deviation_unit=dataset.deviation_unit, targets=dataset.targets, mean_up=mean_up,
        mean_down=mean_down, mean=mean, U_j=U_j, Pa=float(np.max(mean) - np.min(mean)),
        U=float(np.max(U_j)), U_mean=float(np.mean(U_j)), warnings=tuple(warn))
