"""JIS positioning vocabulary (JIS B 0182-1993) as used by the JIS positioning test (JIS B 6192).

What this module can cite, and therefore implements
---------------------------------------------------
The text of JIS B 6192 itself was not available to this project. The Japanese vocabulary standard
for machine-tool tests, JIS B 0182-1993 *Machine tools — Test codes — Vocabulary* (工作機械−試験及び
検査用語), is public (kikakurui.com/b0/B0182-1993-01.html; its terms are also quoted one by one at
kk.jisw.com/00530/), and defines, for one target position:

=====  ============================================================  ===============================
term   definition (JIS B 0182-1993, clause 3 (3))                    equation here
=====  ============================================================  ===============================
342    reversal value at a position (反転差): the mean unidirectional  B_i = x̄_i↑ - x̄_i↓
       positioning deviation in the positive direction minus that
       in the negative direction
346    bidirectional repeatability of positioning at a target        R_i = max[3s_i↑ + 3s_i↓ + |B_i|;
       (両方向繰返し位置決め精度): the largest of (1) three times the        6 s_i↑; 6 s_i↓]
       positive-direction standard-deviation estimate plus three
       times the negative one plus the absolute reversal value,
       (2) six times the positive estimate, (3) six times the
       negative estimate
=====  ============================================================  ===============================

x̄_i↑, x̄_i↓ are the mean unidirectional deviations and s_i↑, s_i↓ the estimates of the standard
deviation at target i (n - 1 in the denominator), exactly as ISO 230-2 forms them: they are taken
from :func:`axiscal.standards.iso230_2.evaluate`, not computed a second time. The JIS repeatability
uses ±3 s where ISO 230-2:2014 uses ±2 s (compare Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 12: 2 s↑ + 2 s↓ + |B_i|, 4 s).

Axis values: JIS B 0182 term 346 is defined *at a target*. For the axis this module reports the
largest value over the targets, ``R = max R_i`` and ``B = max |B_i|``; that is the reading chosen
here (it is how ISO 230-2:2014 forms R and B from R_i and B_i, Yüksel et al., Position accuracy and repeatability calibration of turn tables eqs. 6 and 15), not a quoted
JIS clause. The JIS accuracy of positioning, the number of targets and the number of runs are not
implemented: their definitions were not available publicly.

A bidirectional repeatability cannot be formed from a test in one direction: such a test is
refused (:class:`~axiscal.errors.InputError`), as is a target with fewer than 2 readings in a
direction (:class:`~axiscal.errors.InsufficientRunsError`, from the ISO 230-2 statistics).

References
----------
JIS B 0182-1993, Machine tools — Test codes — Vocabulary, terms 342 and 346.
JIS B 6192, Test code for numerically controlled machine tools — positioning (not available here).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.datasets import PositioningDataset
from axiscal.errors import InputError
from axiscal.standards._parameters import described_parameters

__all__ = ["JisB6192Result", "evaluate", "PARAMETERS"]

#: name -> (description, clause) of the axis parameters this module forms.
PARAMETERS = {
    "R": ("bidirectional repeatability, max[3s↑ + 3s↓ + |B_i|; 6s↑; 6s↓]",
          "JIS B 0182-1993 term 346"),
    "B": ("reversal value, max |B_i|, B_i = x̄↑ − x̄↓", "JIS B 0182-1993 term 342"),
}


@dataclass(frozen=True, eq=False)
class JisB6192Result:
    """JIS repeatability and reversal of one positioning test, in ``deviation_unit``.

    Attributes
    ----------
    deviation_unit : str
    targets : ndarray, the dataset's target unit
    reversal : ndarray
        B_i = x̄_i↑ - x̄_i↓ (term 342), signed.
    R_i : ndarray
        max[3 s_i↑ + 3 s_i↓ + |B_i|; 6 s_i↑; 6 s_i↓] (term 346).
    R, B : float
        Largest R_i and largest |B_i| over the targets.
    warnings : tuple of str
    """

    deviation_unit: str
    targets: np.ndarray
    reversal: np.ndarray
    R_i: np.ndarray
    R: float
    B: float
    warnings: tuple[str, ...] = field(default_factory=tuple)

    def parameters(self) -> dict[str, tuple[float, str, str]]:
        """Axis parameters: name -> (value, unit, description with its clause)."""
        return described_parameters(self, PARAMETERS)


def evaluate(dataset: PositioningDataset) -> JisB6192Result:
    """Bidirectional repeatability and reversal value by JIS B 0182-1993 terms 342 and 346.

    Parameters
    ----------
    dataset : PositioningDataset
        A bidirectional test (deviations per target, direction and run; NaN = missing).

    Returns
    -------
    JisB6192Result

    Raises
    ------
    InputError
        If the test is unidirectional (term 346 needs both directions).
    InsufficientRunsError
        If a target has fewer than 2 readings in a direction.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays(
    ...     "linear", [0, 500], up=[[1, 3], [2, 2]], down=[[0, 0], [1, 1]])
    >>> r = evaluate(ds)
    >>> round(r.R, 6), r.B
    (8.485281, 2.0)
    """
    from axiscal.standards import iso230_2

    if dataset.up.shape[1] == 0 or dataset.down.shape[1] == 0:
        raise InputError("JIS B 0182-1993 term 346 (bidirectional repeatability) needs readings "
                         "in both directions; this test has one direction only")
    base = iso230_2.evaluate(dataset)
    s_up, s_down, rev = base.s_up, base.s_down, base.reversal
    R_i = np.maximum.reduce([3 * s_up + 3 * s_down + np.abs(rev), 6 * s_up, 6 * s_down])
    R_i.flags.writeable = False
    warn = tuple(w for w in base.warnings if "missing" in w)
    return JisB6192Result(
        deviation_unit=dataset.deviation_unit, targets=base.targets, reversal=base.reversal,
        R_i=R_i, R=float(np.max(R_i)), B=float(np.max(np.abs(rev))), warnings=warn,
    )
