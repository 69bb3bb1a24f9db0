"""Squareness test methods as sequences of commanded positions on a simulated XY plane.

Each test (Chapman, Calibration of machine squareness "Simulation modes" a-e) is a small frozen description: where it is (its
centre, metres, in the machine's centred coordinates), how large, and how it is oriented. A
``measure_*`` function drives an :class:`~axiscal.machines.xy_plane.XYPlaneMachine` through the
test's commanded positions and returns what the instrument reads (a procedure never evaluates);
``evaluate_*`` turns those readings into a squareness with the ``standards`` modules, and
:func:`run_test` does both.

Geometry of the bi-axial straightness tests (Chapman, Calibration of machine squareness Figures 3-8, 14), orientations in degrees
clockwise, the test square spanning ``centre ± size/2``:

======  ============================================  ==============================================
config  trajectory of X (a line at y = ...)           trajectory of Y (a line at x = ...)
======  ============================================  ==============================================
L 0     bottom edge                                   left edge (corner bottom-left, the letter L)
L 90    top edge                                      left edge (corner top-left)
L 180   top edge                                      right edge (corner top-right)
L 270   bottom edge                                   right edge (corner bottom-right)
T 0     top edge (the straightedge, the T's bar)      middle (the stem)
T 90    middle (the stem)                             right edge (the bar)
T 180   bottom edge (inverted T)                      middle
T 270   middle                                        left edge
\\+      middle                                        middle (straightedge on a 90° indexer)
======  ============================================  ==============================================

Chapman, Calibration of machine squareness names the orientations but shows them only in its figures: "T" 0° is the T with its bar
at the top and "T" 180° the inverted T (the paper's set-up for a vertical axis), 90° turns the
equipment clockwise (the paper's Figure 14 note); "L" 0° is the letter L. The paper's remark that
with a vertical axis the "L" orientations 0° and 90° are the easy ones suggests that its "L" 90°
may be the mirror image with the corner at the bottom right (here "L" 270°). Either way the four
results are the same set; only their labels could differ.

The straightness readings are the deviations perpendicular to each reference: δy along the X
trajectory, δx along the Y trajectory (plus the tilt of a reference square with an angle error).
A ballbar test reads ``|P(φ) - P(centre)| - R`` with P the actual positions; a diagonal test
reads the displacement along each diagonal from its start, in both directions, averaged to
remove backlash (Chapman, Calibration of machine squareness Method 5).

Local tests (Chapman, Calibration of machine squareness Figures 19-23) are at five locations: the centre of the plane and the
centres of its four quadrants, each over a quarter of each axis (200 mm on 800 mm). The paper
shows the locations only in its figures; this choice is documented here and in
:func:`local_locations`.

References
----------
Chapman, Calibration of machine squareness, "Simulation modes", Figures 13-26, Appendix I (last paragraph).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.xy_plane import XYPlaneMachine
from axiscal.standards.iso230_1 import (
    Squareness,
    correct_reference_angle,
    orientation_sign,
    squareness_from_trajectories,
)
from axiscal.standards.iso230_4 import CircularResult, CircularRun, evaluate_circular
from axiscal.standards.iso230_6 import DiagonalResult, diagonal_squareness

__all__ = [
    "BiaxialTest",
    "DiagonalTest",
    "BallbarTest",
    "BiaxialReadings",
    "DiagonalReadings",
    "MethodResult",
    "biaxial_lines",
    "measure_biaxial",
    "measure_diagonal",
    "measure_ballbar",
    "evaluate_biaxial",
    "evaluate_diagonal",
    "run_test",
    "local_locations",
    "ballbar_row",
]

CONFIGS = ("L", "T", "+")


@dataclass(frozen=True)
class BiaxialTest:
    """A bi-axial straightness test in "L", "T" or "+" configuration (Chapman, Calibration of machine squareness Methods 1-3).

    Attributes
    ----------
    config : {"L", "T", "+"}
    orientation : {0, 90, 180, 270}
        Degrees clockwise.
    centre : tuple of float, m
    size : tuple of float, m
        Travel of X and of Y used by the test.
    n_points : int
        Readings along each trajectory.
    square_error : float, rad
        Angle error of the square (optical prism error or mechanical square) in orientation 0.
    """

    config: str = "L"
    orientation: int = 0
    centre: tuple[float, float] = (0.0, 0.0)
    size: tuple[float, float] = (0.8, 0.8)
    n_points: int = 17
    square_error: float = 0.0

    def __post_init__(self):
        if self.config not in CONFIGS:
            raise InputError(f"config={self.config!r}: must be one of L, T, +")
        orientation_sign(self.orientation)
        _check_size(self.size, self.n_points)

    @property
    def label(self) -> str:
        """``"L 90"``, ``"T 0"`` or ``"+"``."""
        return "+" if self.config == "+" else f"{self.config} {self.orientation}"


@dataclass(frozen=True)
class DiagonalTest:
    """A laser diagonal test over a rectangle (Chapman, Calibration of machine squareness Method 5, ISO 230-6)."""

    centre: tuple[float, float] = (0.0, 0.0)
    size: tuple[float, float] = (0.8, 0.8)
    n_points: int = 11

    def __post_init__(self):
        _check_size(self.size, self.n_points)

    label = "diagonal"


@dataclass(frozen=True)
class BallbarTest:
    """A circular test with a telescoping ballbar (Chapman, Calibration of machine squareness Method 4, ISO 230-4).

    Attributes
    ----------
    centre : tuple of float, m
    radius : float, m
    n_points : int
        Readings per direction.
    arc_deg : float
        Arc contoured, degrees (360, or a partial arc of at least 220).
    start_deg : float
        Angle at which the arc starts, degrees counter-clockwise from +X.
    """

    centre: tuple[float, float] = (0.0, 0.0)
    radius: float = 0.4
    n_points: int = 360
    arc_deg: float = 360.0
    start_deg: float = 0.0

    def __post_init__(self):
        if not self.radius > 0 or self.n_points < 8 or not 0 < self.arc_deg <= 360:
            raise InputError(f"ballbar test radius={self.radius!r} m, n_points={self.n_points!r},"
                             f" arc_deg={self.arc_deg!r}: need R > 0, >= 8 points, arc in (0, 360]")

    label = "ballbar"

    def angles(self) -> np.ndarray:
        """Nominal angles of the readings, rad."""
        full = self.arc_deg >= 360.0
        a = np.linspace(0.0, np.radians(self.arc_deg), self.n_points, endpoint=not full)
        return a + np.radians(self.start_deg)


@dataclass(frozen=True, eq=False)
class BiaxialReadings:
    """Straightness readings of the two trajectories of a bi-axial test (metres)."""

    test: BiaxialTest
    x_positions: np.ndarray
    x_deviations: np.ndarray
    y_positions: np.ndarray
    y_deviations: np.ndarray


@dataclass(frozen=True, eq=False)
class DiagonalReadings:
    """Displacement errors along D1 (−X, +Y) and D2 (+X, +Y), metres, at distances s."""

    test: DiagonalTest
    s: np.ndarray
    errors_d1: np.ndarray
    errors_d2: np.ndarray


@dataclass(frozen=True)
class MethodResult:
    """One method's squareness at one place, as in Chapman, Calibration of machine squareness's result boxes.

    Attributes
    ----------
    method : str
        ``"ballbar"``, ``"diagonal"``, ``"+"``, ``"T 0"`` ... ``"L 270"``.
    centre : tuple of float, m
    size : tuple of float, m
        Extent of the test (for a ballbar, the circle's diameter).
    squareness : Squareness
    label_at : tuple of float, m
        Where a plot places the result (the crossing of the two trajectories, or the centre).
    group : str
        For tests that belong together (a row of ballbar tests), the row's name; else ``""``.
    """

    method: str
    centre: tuple[float, float]
    size: tuple[float, float]
    squareness: Squareness
    label_at: tuple[float, float]
    group: str = ""

    def __str__(self) -> str:
        return (f"{self.method:<9} at ({self.centre[0] * 1e3:+.0f}, {self.centre[1] * 1e3:+.0f}) "
                f"mm: {self.squareness.um_per_m:+.2f} µm/m")


def biaxial_lines(test: BiaxialTest) -> tuple[float, float]:
    """The y of the X trajectory and the x of the Y trajectory, metres (module table)."""
    (xc, yc), (sx, sy) = test.centre, test.size
    hx, hy = sx / 2, sy / 2
    if test.config == "+":
        return yc, xc
    table = {
        "L": {0: (-hy, -hx), 90: (hy, -hx), 180: (hy, hx), 270: (-hy, hx)},
        "T": {0: (hy, 0.0), 90: (0.0, hx), 180: (-hy, 0.0), 270: (0.0, -hx)},
    }
    dy, dx = table[test.config][test.orientation]
    return yc + dy, xc + dx


def measure_biaxial(machine: XYPlaneMachine, test: BiaxialTest, *,
                    rng: np.random.Generator | None = None, noise: float = 0.0) -> BiaxialReadings:
    """Drive the machine along both trajectories and read the straightness (Chapman, Calibration of machine squareness d, e, c).

    Parameters
    ----------
    machine : XYPlaneMachine
    test : BiaxialTest
    rng : numpy.random.Generator, optional
        Needed when ``noise`` > 0.
    noise : float, m
        Standard deviation of the indicator's random reading error.

    Returns
    -------
    BiaxialReadings
    """
    y_line, x_line = biaxial_lines(test)
    (xc, yc), (sx, sy) = test.centre, test.size
    xs = np.linspace(xc - sx / 2, xc + sx / 2, test.n_points)
    ys = np.linspace(yc - sy / 2, yc + sy / 2, test.n_points)
    _, dy = machine.deviation(xs, np.full_like(xs, y_line), vx=1.0)
    dx, _ = machine.deviation(np.full_like(ys, x_line), ys, vy=1.0)
    # the reference of Y is turned by the square's error: +Y reference towards -X by e_ref
    e_ref = correct_reference_angle(test.square_error, test.orientation)
    dx = dx + e_ref * (ys - yc)
    dx, dy = _add_noise(dx, rng, noise), _add_noise(dy, rng, noise)
    return BiaxialReadings(test, xs, dy, ys, dx)


def evaluate_biaxial(readings: BiaxialReadings, *, square_error: float = 0.0,
                     method: str = "least_squares"):
    """Squareness from bi-axial readings (ISO 230-1 §3.6.7), square error corrected."""
    return squareness_from_trajectories(
        readings.x_positions, readings.x_deviations, readings.y_positions, readings.y_deviations,
        method=method,  # type: ignore[arg-type]
        reference_excess=correct_reference_angle(square_error, readings.test.orientation))


def measure_diagonal(machine: XYPlaneMachine, test: DiagonalTest, *,
                     rng: np.random.Generator | None = None, noise: float = 0.0
                     ) -> DiagonalReadings:
    """Laser displacement along both diagonals, each run both ways and averaged (Chapman, Calibration of machine squareness b)."""
    (xc, yc), (sx, sy) = test.centre, test.size
    d0 = float(np.hypot(sx, sy))
    s = np.linspace(0.0, d0, test.n_points)
    starts = {"d1": (xc + sx / 2, yc - sy / 2, -sx / d0, sy / d0),
              "d2": (xc - sx / 2, yc - sy / 2, sx / d0, sy / d0)}
    errors = {}
    for key, (x0, y0, ux, uy) in starts.items():
        runs = []
        for sense in (1.0, -1.0):
            px, py = x0 + s * ux, y0 + s * uy
            ax, ay = machine.actual(px, py, vx=sense * ux, vy=sense * uy)
            disp = (ax - ax[0]) * ux + (ay - ay[0]) * uy
            runs.append(_add_noise(disp - s, rng, noise))
        errors[key] = 0.5 * (runs[0] + runs[1])
    return DiagonalReadings(test, s, errors["d1"], errors["d2"])


def evaluate_diagonal(readings: DiagonalReadings) -> DiagonalResult:
    """Squareness from the end errors of the two diagonals (ISO 230-6, Chapman, Calibration of machine squareness's choice)."""
    sx, sy = readings.test.size
    return diagonal_squareness(sx, sy, float(readings.errors_d1[-1]),
                               float(readings.errors_d2[-1]))


#: Angle before a ballbar sample at which its velocity (backlash side) is taken, radians.
_APPROACH = 1e-7


def measure_ballbar(machine: XYPlaneMachine, test: BallbarTest, *,
                    rng: np.random.Generator | None = None, noise: float = 0.0
                    ) -> tuple[CircularRun, CircularRun]:
    """Ballbar readings, counter-clockwise then clockwise (Chapman, Calibration of machine squareness a, ISO 230-4).

    The centre pivot sits where the machine puts the tool when commanded to the centre. Each
    axis carries the backlash of the side it last moved on: the velocity is taken a hair before
    the sample along the direction of travel, so a sample exactly on a reversal point (0°, 90°,
    180°, 270°) keeps the approach side's backlash in both directions (issue 21).
    """
    phi = test.angles()
    xc, yc = test.centre
    cx, cy = machine.actual(xc, yc)
    px, py = xc + test.radius * np.cos(phi), yc + test.radius * np.sin(phi)
    runs = []
    for direction, sense in (("ccw", 1.0), ("cw", -1.0)):
        before = phi - sense * _APPROACH   # approach side: velocity just before the sample
        ax, ay = machine.actual(px, py, vx=-sense * np.sin(before), vy=sense * np.cos(before))
        dr = np.hypot(ax - cx, ay - cy) - test.radius
        runs.append(CircularRun(phi, _add_noise(dr, rng, noise), direction))
    return runs[0], runs[1]


def run_test(machine: XYPlaneMachine, test, rng: np.random.Generator | None = None,
             noise: float = 0.0) -> MethodResult:
    """Measure and evaluate one test on the machine; the result as a :class:`MethodResult`.

    ``noise`` (metres, standard deviation) adds the instrument's random reading error, drawn
    from ``rng``; without it the readings are the model's exact values.

    Examples
    --------
    >>> from axiscal.machines.xy_plane import seed004_machine
    >>> print(run_test(seed004_machine(3), BiaxialTest("L", 0)))
    L 0       at (+0, +0) mm: -35.00 µm/m
    """
    if isinstance(test, BiaxialTest):
        sq = evaluate_biaxial(measure_biaxial(machine, test, rng=rng, noise=noise),
                              square_error=test.square_error).squareness
        y_line, x_line = biaxial_lines(test)
        return MethodResult(test.label, test.centre, test.size, sq, (x_line, y_line))
    if isinstance(test, DiagonalTest):
        sq = evaluate_diagonal(measure_diagonal(machine, test, rng=rng, noise=noise)).squareness
        return MethodResult(test.label, test.centre, test.size, sq, test.centre)
    if isinstance(test, BallbarTest):
        res: CircularResult = evaluate_circular(measure_ballbar(machine, test, rng=rng, noise=noise),
                                                test.radius)
        d = 2 * test.radius
        return MethodResult(test.label, test.centre, (d, d), res.squareness, test.centre)
    raise InputError(f"test={test!r}: not a BiaxialTest, DiagonalTest or BallbarTest")


def local_locations(machine: XYPlaneMachine) -> list[tuple[float, float]]:
    """The five local test centres: the middle and the quadrant centres, metres."""
    qx, qy = machine.length_x / 4, machine.length_y / 4
    return [(0.0, 0.0), (-qx, qy), (qx, qy), (-qx, -qy), (qx, -qy)]


def ballbar_row(machine: XYPlaneMachine, radius: float, count: int, *,
                arrangement: str = "adjacent") -> list[BallbarTest]:
    """Several ballbar tests in a line along the longer axis (Chapman, Calibration of machine squareness Figures 24-26).

    Parameters
    ----------
    machine : XYPlaneMachine
    radius : float, m
    count : int
        Number of circles (at least 1).
    arrangement : {"adjacent", "overlapping"}
        ``"adjacent"``: circles side by side from the middle (``count * 2R`` must fit);
        ``"overlapping"``: evenly spaced with equal overlap from one end of the axis to the other.

    Returns
    -------
    list of BallbarTest

    Examples
    --------
    >>> from axiscal.machines.xy_plane import seed004_machine
    >>> [round(t.centre[0] * 1e3, 1) for t in ballbar_row(seed004_machine(6), 0.125, 4,
    ...                                                     arrangement="overlapping")]
    [-250.0, -83.3, 83.3, 250.0]
    """
    if count < 1:
        raise InputError(f"count={count!r}: need at least one ballbar test")
    along_x = machine.length_x >= machine.length_y
    length = machine.length_x if along_x else machine.length_y
    if arrangement == "adjacent":
        if count * 2 * radius > length * (1 + 1e-9):
            raise InputError(f"{count} adjacent circles of R = {radius * 1e3:g} mm need "
                             f"{count * 2 * radius * 1e3:g} mm; the axis has {length * 1e3:g} mm")
        pos = (np.arange(count) - (count - 1) / 2) * 2 * radius
    elif arrangement == "overlapping":
        span = length / 2 - radius
        pos = np.linspace(-span, span, count) if count > 1 else np.zeros(1)
    else:
        raise InputError(f"arrangement={arrangement!r}: must be 'adjacent' or 'overlapping'")
    return [BallbarTest(centre=(float(p), 0.0) if along_x else (0.0, float(p)), radius=radius)
            for p in pos]


def _check_size(size, n_points) -> None:
    sx, sy = size
    if not (sx > 0 and sy > 0) or n_points < 2:
        raise InputError(f"size={size!r} m, n_points={n_points!r}: need positive travels and "
                         "at least 2 points")


def _add_noise(values: np.ndarray, rng, noise: float) -> np.ndarray:
    if noise <= 0:
        return values
    if rng is None:
        raise InputError("noise > 0 needs an explicit numpy.random.Generator (rng=...)")
    return values + rng.normal(0.0, noise, size=np.shape(values))
