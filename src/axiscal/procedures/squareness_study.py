"""Every squareness method on one simulated machine, globally or locally (Chapman, Calibration of machine squareness Figures 14-26).

:func:`compare_methods` runs the ballbar, the laser diagonal, the "+" test and the "T" and "L"
tests in their four orientations, and adds the averages the paper recommends: "L" results from
opposite corners (0° with 180°, 90° with 270°) and "T" results from opposite sides, and for a
plane whose axes differ in length the average of several ballbar tests along the long axis,
adjacent and evenly overlapping (Chapman, Calibration of machine squareness Figures 24-26).

Global scope: each test over the full travel of both axes, centred; the ballbar radius is half
the shorter axis. Local scope: the five locations of
:func:`~axiscal.procedures.squareness.local_locations`, each test over a quarter of each axis
(200 mm on the paper's 800 mm), ballbar radius an eighth of the shorter axis.

References
----------
Chapman, Calibration of machine squareness, "Global squareness simulation results", "Local squareness simulation results",
"Testing global squareness errors on machines with unequal aspect ratios".
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.procedures.squareness import (
    BallbarTest,
    BiaxialTest,
    DiagonalTest,
    MethodResult,
    ballbar_row,
    local_locations,
    run_test,
)

__all__ = ["MethodComparison", "compare_methods", "tests_at", "OPPOSITE_PAIRS"]

#: Pairs whose average the paper recommends: opposite corners ("L") and opposite sides ("T").
OPPOSITE_PAIRS = (("L 0", "L 180"), ("L 90", "L 270"), ("T 0", "T 180"), ("T 90", "T 270"))
ORIENTATIONS = (0, 90, 180, 270)


@dataclass(frozen=True)
class MethodComparison:
    """Results of every method on one machine.

    Attributes
    ----------
    machine : str
        Description of the machine.
    scope : {"global", "local"}
    results : tuple of MethodResult
        One per test and location.
    averages : tuple of (str, tuple of float, float)
        ``(name, location centre in m, value in µm/m)``: averages of opposite "L"/"T" results
        at each location, and of the ballbar rows.
    truth : float, µm/m
        The machine's global squareness θ0 (seed convention).
    """

    machine: str
    scope: str
    results: tuple[MethodResult, ...]
    averages: tuple[tuple[str, tuple[float, float], float], ...]
    truth: float

    def value(self, method: str, centre: tuple[float, float] = (0.0, 0.0)) -> float:
        """The result of one method at one location, µm/m."""
        for r in self.results:
            if r.method == method and np.allclose(r.centre, centre, atol=1e-9):
                return r.squareness.um_per_m
        raise InputError(f"no result for method {method!r} at {centre!r}")

    def average(self, name: str, centre: tuple[float, float] = (0.0, 0.0)) -> float:
        """One of the averages, µm/m."""
        for n, c, v in self.averages:
            if n == name and np.allclose(c, centre, atol=1e-9):
                return v
        raise InputError(f"no average {name!r} at {centre!r}")

    def locations(self) -> list[tuple[float, float]]:
        """Distinct centres of the non-ballbar tests, in order."""
        seen: list[tuple[float, float]] = []
        for r in self.results:
            if r.method != "ballbar" and r.centre not in seen:
                seen.append(r.centre)
        return seen

    def as_dict(self) -> dict:
        """Plain data for JSON (lengths in mm, squareness in µm/m, seed convention)."""
        return {
            "machine": self.machine, "scope": self.scope, "truth_um_per_m": self.truth,
            "convention": "positive when the angle between +X and +Y exceeds 90°",
            "results": [{"method": r.method, "group": r.group, "centre_mm": [c * 1e3 for c in r.centre],
                         "size_mm": [s * 1e3 for s in r.size],
                         "um_per_m": r.squareness.um_per_m, "arcsec": r.squareness.arcsec,
                         "iso_um_per_m": r.squareness.iso_um_per_m} for r in self.results],
            "averages": [{"name": n, "centre_mm": [x * 1e3 for x in c], "um_per_m": v}
                         for n, c, v in self.averages],
        }

    def __str__(self) -> str:
        lines = [f"{self.machine} — {self.scope} squareness, µm/m (positive when the angle "
                 f"between +X and +Y exceeds 90°); truth θ0 = {self.truth:+.2f}"]
        lines += [f"  {r}" for r in self.results]
        lines += [f"  average {n} at ({c[0] * 1e3:+.0f}, {c[1] * 1e3:+.0f}) mm: {v:+.2f} µm/m"
                  for n, c, v in self.averages]
        return "\n".join(lines)


def tests_at(centre: tuple[float, float], size: tuple[float, float], radius: float,
             n_points: int = 17) -> list:
    """The ballbar, diagonal, "+", four "T" and four "L" tests at one place."""
    tests: list = [BallbarTest(centre=centre, radius=radius),
                   DiagonalTest(centre=centre, size=size),
                   BiaxialTest("+", 0, centre, size, n_points)]
    tests += [BiaxialTest(c, o, centre, size, n_points) for c in "TL" for o in ORIENTATIONS]
    return tests


def compare_methods(machine: XYPlaneMachine, scope: str = "global",
                    rng: np.random.Generator | None = None, noise: float = 0.0) -> MethodComparison:
    """Run every method on the machine (Chapman, Calibration of machine squareness Figures 14-26) and the recommended averages.

    Parameters
    ----------
    machine : XYPlaneMachine
    scope : {"global", "local"}
    rng, noise : optional
        The instruments' random reading error (standard deviation in metres) and its random
        stream; without them every reading is the model's exact value.

    Returns
    -------
    MethodComparison

    Examples
    --------
    >>> from axiscal.machines.xy_plane import seed004_machine
    >>> c = compare_methods(seed004_machine(3))
    >>> round(c.value("L 0"), 3), round(c.value("L 180"), 3), round(c.average("L 0 + L 180"), 3)
    (-35.0, 65.0, 15.0)
    """
    if scope not in ("global", "local"):
        raise InputError(f"scope={scope!r}: must be 'global' or 'local'")
    lx, ly = machine.length_x, machine.length_y
    if scope == "global":
        places = [((0.0, 0.0), (lx, ly), min(lx, ly) / 2)]
    else:
        places = [(c, (lx / 4, ly / 4), min(lx, ly) / 8) for c in local_locations(machine)]
    unequal = scope == "global" and not np.isclose(lx, ly)
    results: list[MethodResult] = []
    averages: list[tuple[str, tuple[float, float], float]] = []
    for centre, size, radius in places:
        tests = tests_at(centre, size, radius)
        if unequal:
            tests = tests[1:]  # one circle cannot cover the plane: ballbar rows below
        here = {t.label: run_test(machine, t, rng, noise) for t in tests}
        results.extend(here.values())
        for a, b in OPPOSITE_PAIRS:
            v = 0.5 * (here[a].squareness.um_per_m + here[b].squareness.um_per_m)
            averages.append((f"{a} + {b}", centre, v))
    if unequal:
        radius = min(lx, ly) / 2
        count = int(np.floor(max(lx, ly) / (2 * radius) + 1e-9))
        for arrangement, n in (("adjacent", count), ("overlapping", count + 1)):
            group = f"{n} {arrangement} ballbar tests"
            row = [replace(run_test(machine, t, rng, noise), group=group)
                   for t in ballbar_row(machine, radius, n, arrangement=arrangement)]
            results.extend(row)
            averages.append((group, (0.0, 0.0),
                             float(np.mean([r.squareness.um_per_m for r in row]))))
    return MethodComparison(str(machine), scope, tuple(results), tuple(averages),
                            machine.squareness * 1e6)
