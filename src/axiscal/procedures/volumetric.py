"""Measuring the 21 geometric errors and the body diagonals of a simulated three-axis machine.

Each axis is measured as a calibration engineer measures it, along one line through the
reference point with the other two axes parked there (ISO 230-1:2012 straightness and angular
tests, ISO 230-2:2014 positioning): the laser reads the displacement along the axis, straightness
optics the two lateral deviations (their least-squares line removed, ISO 230-1 reference straight
line), an angular interferometer and a level the three rotations. The machine's frame is its own:
the X motion is the first direction and the XY motion plane the first plane, so the least-squares
slopes of the Y and Z straightness against it are the squareness errors (the method of measuring
squareness with straightness optics and an optical square, ISO 230-1; Chapman, "Calibration of
machine squareness", method 1). The four body diagonals are measured as ISO 230-6:2002 asks,
with a laser aligned to each diagonal.

A procedure measures; it does not evaluate (the map is :mod:`axiscal.standards.volumetric`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.volumetric import (AXES, BodyDiagonal, ErrorFunction, GeometricErrors,
                                          diagonal_corners)

__all__ = ["MeasurementNoise", "datum_frame", "measure_errors", "measure_tests",
           "measure_diagonals", "true_field"]


@dataclass(frozen=True)
class MeasurementNoise:
    """Standard deviations of the simulated instruments.

    Attributes
    ----------
    positioning : float, m
        Laser reading (0.1 µm).
    straightness : float, m
        Straightness optics (0.2 µm).
    angular : float, rad
        Angular interferometer and level (0.2 µrad, 0.04″).
    squareness : float, rad
        Optical square (0.5 µm/m).
    """

    positioning: float = 0.1e-6
    straightness: float = 0.2e-6
    angular: float = 0.2e-6
    squareness: float = 0.5e-6

    def __post_init__(self) -> None:
        for k, v in vars(self).items():
            if not (np.isfinite(v) and 0 <= v <= 1e-3):
                raise InputError(f"noise {k} = {v!r}: must be between 0 and 1e-3")


def datum_frame(machine, reference, tool_offset, points: int = 21) -> np.ndarray:
    """The machine's frame (columns e1, e2, e3): X's motion, then the XY motion plane.

    e1 is the least-squares direction of the tool's path along X through the reference point,
    e3 is normal to e1 and to Y's least-squares direction, e2 = e3 × e1.
    """
    d = {a: _line_direction(machine, a, reference, tool_offset, points) for a in ("X", "Y")}
    e1 = d["X"]
    e3 = np.cross(e1, d["Y"])
    e3 /= np.linalg.norm(e3)
    return np.column_stack([e1, np.cross(e3, e1), e3])


def measure_errors(machine, rng: np.random.Generator, **kwargs) -> GeometricErrors:
    """The errors of :func:`measure_tests` alone."""
    return measure_tests(machine, rng, **kwargs)[0]


def measure_tests(machine, rng: np.random.Generator, *, points: int = 21, reference=None,
                  tool_offset=(0.0, 0.0, 0.0), noise: MeasurementNoise = MeasurementNoise(),
                  runs: int = 5) -> tuple[GeometricErrors, dict]:
    """Measure the 18 error motions and 3 squareness errors of ``machine``.

    Parameters
    ----------
    machine : ThreeAxisMachine
    rng : numpy.random.Generator
    points : int
        Targets per axis (equidistant over the travel).
    reference : array_like of 3, m, optional
        Where the measuring lines cross; default the middle of the travel.
    tool_offset : array_like of 3, m
    noise : MeasurementNoise

    runs : int
        Runs per direction of each positioning test (ISO 230-2:2014 asks for 5).

    Returns
    -------
    errors : GeometricErrors
        As measured (straightness with its least-squares line removed, positioning the mean
        bidirectional deviation of the ISO 230-2 test; zero-referenced at the reference point by
        the model).
    positioning : dict of str to PositioningDataset
        The three positioning tests (mm, µm), each reading with the laser's noise
        (``noise.positioning`` is the noise of their mean).
    """
    if not 2 <= int(points) <= 10_000:
        raise InputError(f"points = {points!r}: between 2 and 10000 targets per axis")
    c = _reference(machine, reference)
    t = np.asarray(tool_offset, float)
    if not 2 <= int(runs) <= 100:
        raise InputError(f"runs = {runs!r}: between 2 and 100 per direction")
    frame = datum_frame(machine, c, t)
    functions, slopes, tests = {}, {}, {}
    for a in AXES:
        i = AXES.index(a)
        u = np.linspace(*machine.travel[a], int(points))
        dev, rot = _line(machine, a, u, c, t, frame)
        tests[a] = _positioning_test(a, u, dev[:, i], rng, noise.positioning, int(runs))
        functions[f"E{a}{a}"] = ErrorFunction(
            u, (tests[a].up.mean(axis=1) + tests[a].down.mean(axis=1)) / 2 * 1e-6, "simulation")
        for j, b in enumerate(AXES):
            if b == a:
                continue
            slope, offset = np.polyfit(u, dev[:, j], 1)
            slopes[(a, b)] = slope
            functions[f"E{b}{a}"] = ErrorFunction(
                u, dev[:, j] - (slope * u + offset) + rng.normal(0, noise.straightness, u.size),
                "simulation")
        for j, r in enumerate("ABC"):
            functions[f"E{r}{a}"] = ErrorFunction(
                u, rot[:, j] + rng.normal(0, noise.angular, u.size), "simulation")
    sq = {"xy": -slopes[("Y", "X")], "zx": -slopes[("Z", "X")], "yz": -slopes[("Z", "Y")]}
    sq = {k: float(v + rng.normal(0, noise.squareness)) for k, v in sq.items()}
    return GeometricErrors(machine.chain, functions, sq, c, t, dict(machine.travel)), tests


def _positioning_test(axis, u, deviation, rng, sigma_mean, runs):
    """An ISO 230-2 bidirectional test of ``runs`` runs whose mean has the noise ``sigma_mean``."""
    from axiscal.datasets import Metadata, PositioningDataset

    s = sigma_mean * np.sqrt(2 * runs)
    up = deviation[:, None] + rng.normal(0, s, (u.size, runs))
    down = deviation[:, None] + rng.normal(0, s, (u.size, runs))
    return PositioningDataset("linear", u * 1e3, up * 1e6, down * 1e6, "mm", "um",
                              Metadata(machine="simulated machining centre", axis=axis,
                                       notes="simulated volumetric positioning test"))


def measure_diagonals(machine, rng: np.random.Generator, *, points: int = 21, reference=None,
                      tool_offset=(0.0, 0.0, 0.0), noise: MeasurementNoise = MeasurementNoise(),
                      frame=None) -> list[BodyDiagonal]:
    """The ISO 230-6:2002 body diagonal displacement test on ``machine`` (laser noise added)."""
    c = _reference(machine, reference)
    t = np.asarray(tool_offset, float)
    f = datum_frame(machine, c, t) if frame is None else frame
    out = []
    for name, (s, e) in diagonal_corners(machine.travel).items():
        k = np.linspace(0.0, 1.0, int(points))
        q = s[:, None] + (e - s)[:, None] * k
        p, _ = machine.pose(*q, t)
        u = (e - s) / np.linalg.norm(e - s)
        along = ((p - p[0]) @ f) @ u - k * np.linalg.norm(e - s)
        along = along + rng.normal(0, noise.positioning, along.size)
        out.append(BodyDiagonal(name, s, e, k * np.linalg.norm(e - s), along - along[0]))
    return out


def true_field(machine, reference=None, tool_offset=(0.0, 0.0, 0.0), measured_tool_offset=None):
    """The machine's true volumetric error as a function ``field(x, y, z) -> (3, ...)``, m.

    Expressed in the machine's frame (:func:`datum_frame`, set by the tool offset used while
    measuring, default ``tool_offset``) and zero at the reference point, as the model's map is,
    so the two can be compared point by point.
    """
    c = _reference(machine, reference)
    t = np.asarray(tool_offset, float)
    f = datum_frame(machine, c, t if measured_tool_offset is None
                    else np.asarray(measured_tool_offset, float))
    p0, _ = machine.pose(*c, t)

    def field(x, y, z):
        x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
        p, _ = machine.pose(x, y, z, t)
        q = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
        e = (p - p0) @ f - (q - c)
        return e.T.reshape((3,) + x.shape)

    return field


def _reference(machine, reference) -> np.ndarray:
    if reference is None:
        return np.array([sum(machine.travel[a]) / 2 for a in AXES])
    c = np.asarray(reference, float)
    if c.shape != (3,) or not np.isfinite(c).all():
        raise InputError(f"reference = {reference!r}: give x, y, z in m")
    return c


def _line(machine, axis, u, c, t, frame):
    """Deviation (N, 3) and rotation (N, 3) along ``axis`` through ``c``, in ``frame``."""
    i = AXES.index(axis)
    q = np.repeat(c[None, :], u.size, axis=0)
    q[:, i] = u
    p, r = machine.pose(q[:, 0], q[:, 1], q[:, 2], t)
    p0, r0 = machine.pose(*c, t)
    dev = (p - p0) @ frame - (q - c)
    rel = np.einsum("nij,kj->nik", r, r0[0])        # R(u) R(c)^T
    w = 0.5 * np.stack([rel[:, 2, 1] - rel[:, 1, 2], rel[:, 0, 2] - rel[:, 2, 0],
                        rel[:, 1, 0] - rel[:, 0, 1]], axis=1)
    return dev, w @ frame


def _line_direction(machine, axis, c, t, points) -> np.ndarray:
    u = np.linspace(*machine.travel[axis], int(points))
    i = AXES.index(axis)
    q = np.repeat(np.asarray(c, float)[None, :], u.size, axis=0)
    q[:, i] = u
    p, _ = machine.pose(q[:, 0], q[:, 1], q[:, 2], t)
    slope = np.polyfit(u, p, 1)[0]
    return slope / np.linalg.norm(slope)
