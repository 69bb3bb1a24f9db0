"""Earlier editions of ISO 230-2 (1988, 2006): the unidirectional repeatability, the one parameter
whose band a public source states; the others named, not evaluated.

What this module can cite, and therefore implements
---------------------------------------------------
The texts of ISO 230-2:1988 (first edition, *Acceptance code for machine tools — Part 2:
Determination of accuracy and repeatability of positioning of numerically controlled machine
tools*), ISO 230-2:1997 and ISO 230-2:2006 were not available to this project. Public sources say
how wide their repeatability band is:

* **1988.** "The old standard of 1988 had much in common with most of the other existing standards
  at that time: BS3800/2 (originally BS4656/16), VDI/DGQ 3441 and the old NMTBA procedure ... All
  these embraced the concept of Repeatability being measured as a six standard deviation spread"
  (*The importance of being repeatable*, WIT Transactions on Engineering Sciences vol. 23, 1999,
  section 1). The Japanese test vocabulary of the same period uses the same factor per direction:
  JIS B 0182-1993 term 346 takes "six times the positive-direction standard-deviation estimate"
  and "six times the negative one" (see :mod:`.jis_b6192`).
* **1997.** The same paper: "'Standard Uncertainty' has replaced 'Standard Deviation', and the
  band width has been reduced". It gives no factor, so the 1997 edition is not evaluated.
* **2006.** The AMT (Association for Manufacturing Technology) announcement of ISO 230-2:2006:
  "instead of using 3 'standard deviations' (old standard), 2 'standard uncertainties' are used ...
  when reporting the resulting accuracy and repeatability. The calculation for 'standard
  uncertainty' is the same as for 'standard deviation.'"

So, with s_i↑, s_i↓ the estimates at target i exactly as ISO 230-2:2014 forms them (eqs. 8, 9 of
Yüksel et al., *Position accuracy and repeatability calibration of turn tables*; taken from
:func:`axiscal.standards.iso230_2.evaluate`, not computed again):

=======  ==============================  =====================================================
edition  evaluated                       equation here
=======  ==============================  =====================================================
1988     R↑, R↓ (unidirectional)         R↑ = max_i 6 s_i↑, R↓ = max_i 6 s_i↓  (±3 s band)
2006     R↑, R↓ (unidirectional)         R↑ = max_i 4 s_i↑, R↓ = max_i 4 s_i↓  (±2 s band; the
                                         same as ISO 230-2:2014 eqs. 10, 11, 13, 14)
=======  ==============================  =====================================================

Readings chosen here, not quoted: the spread is taken per direction at each target, as JIS
B 0182-1993 term 346 does, and the axis value is the largest over the targets, as ISO 230-2:2014
forms R↑ (eq. 13). Not evaluated, because no public text gives their form in these editions: the
accuracy A, the bidirectional repeatability R and the reversal B (names shown with that reason).
Nor are the ISO 230-2:2014 rules on the number of targets and runs (Table 1, §5.2, §5.3) applied
to these editions, since theirs are not public: only a target with fewer than 2 readings in a
measured direction is refused (no s), and missing readings are reported.

References
----------
ISO 230-2:1988, ISO 230-2:1997, ISO 230-2:2006 (not available here).
The importance of being repeatable, WIT Transactions on Engineering Sciences 23 (1999).
AMT, "Test code for machine tools — Part 2 ... ISO 230-2:2006" (amtonline.org, article 133530).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.datasets import PositioningDataset

__all__ = ["EditionResult", "evaluate_1988", "evaluate_2006", "BAND", "NOT_EVALUATED"]

#: Edition -> (factor on s for the repeatability spread, its source).
BAND = {
    "1988": (6.0, "WIT Trans. Eng. Sci. 23, 1999"),
    "2006": (4.0, "AMT announcement of ISO 230-2:2006"),
}

#: name -> why axiscal does not evaluate it (both editions).
NOT_EVALUATED = {
    "A": "accuracy: not evaluated, form not public",
    "R": "bidirectional repeatability: not evaluated, form not public",
    "B": "reversal value: not evaluated, form not public",
}


@dataclass(frozen=True)
class EditionResult:
    """Unidirectional repeatability of one test by an earlier edition, in ``deviation_unit``.

    ``R_up``/``R_down`` are None for a direction the test did not measure.
    """

    edition: str
    deviation_unit: str
    R_up: float | None
    R_down: float | None
    warnings: tuple[str, ...] = field(default_factory=tuple)

    def parameters(self) -> dict[str, tuple[float | None, str, str]]:
        """Axis parameters: name -> (value, unit, description with its source)."""
        k, src = BAND[self.edition]
        return {f"R_{d}": (getattr(self, f"R_{d}"), self.deviation_unit,
                           f"unidirectional repeatability {arrow}, max {k:g}s_i{arrow} ({src})")
                for d, arrow in (("up", "↑"), ("down", "↓"))}


def _evaluate(edition: str, dataset: PositioningDataset) -> EditionResult:
    from axiscal.standards import iso230_2

    base = iso230_2.evaluate(dataset)
    k = BAND[edition][0]
    up = None if base.R_up is None else float(np.max(k * base.s_up))
    down = None if base.R_down is None else float(np.max(k * base.s_down))
    warn = tuple(w for w in base.warnings if "missing" in w)
    return EditionResult(edition, dataset.deviation_unit, up, down, warn)


def evaluate_1988(dataset: PositioningDataset) -> EditionResult:
    """Unidirectional repeatability by ISO 230-2:1988: a six standard deviation spread.

    R↑ = max_i 6 s_i↑ and R↓ = max_i 6 s_i↓ (WIT Transactions on Engineering Sciences 23, 1999;
    JIS B 0182-1993 term 346 for the factor per direction). A target with fewer than 2 readings
    in a measured direction is an :class:`~axiscal.errors.InsufficientRunsError`.

    Examples
    --------
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays("linear", [0, 500], up=[[1, 3], [2, 2]],
    ...                                     down=[[0, 0], [1, 1]])
    >>> r = evaluate_1988(ds)
    >>> round(r.R_up, 6), r.R_down
    (8.485281, 0.0)
    """
    return _evaluate("1988", dataset)


def evaluate_2006(dataset: PositioningDataset) -> EditionResult:
    """Unidirectional repeatability by ISO 230-2:2006: two standard uncertainties either side.

    R↑ = max_i 4 s_i↑ and R↓ = max_i 4 s_i↓ (AMT's announcement of the 2006 edition: 2 standard
    uncertainties, calculated as the standard deviation), the value ISO 230-2:2014 gives.
    """
    return _evaluate("2006", dataset)
