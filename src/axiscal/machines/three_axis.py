"""A simulated three-axis machine with all 21 geometric errors, moved by an exact kinematic chain.

The simulated machine is the truth the volumetric model (:mod:`axiscal.standards.volumetric`)
is checked against, so it is built independently of that model's first-order formula: each
axis is a rigid link whose translation and rotation errors are applied as exact homogeneous
transforms, in the order of the kinematic chain from the work-piece to the tool::

    P(q) = T_1(q_1) T_2(q_2) T_3(q_3) · t,   T_i(u) = Trans(u d_i + δ_i(u)) · Rot(ε_i(u))

with ``d_i`` the axis direction (the squareness tilts Y and Z: ``d_Y = (−sin θ_xy, cos θ_xy, 0)``,
``d_Z ∝ (−θ_zx, −θ_yz, 1)``), ``δ_i`` and ``ε_i`` its error motions (relative motions of the tool
with respect to the work-piece) and ``t`` the tool offset. Rotations are exact (Rodrigues), so
the simulation holds the second-order terms the model leaves out.

The errors of :func:`simulated_machine` follow the squareness paper's Appendix I (Chapman,
"Calibration of machine squareness"): a guideway bent by a quadratic ``4 S u² / L²`` gives the
straightness and, through a rigid carriage, the associated angular error ``8 S u / L²``; to these
are added a linear scale error and a periodic error for positioning, and small independent
angular and roll errors, with amplitudes typical of a machining centre.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.volumetric import AXES, PAIRS, KinematicChain

__all__ = ["ThreeAxisMachine", "ErrorProfile", "simulated_machine", "rotation_matrices"]


@dataclass(frozen=True)
class ErrorProfile:
    """A smooth error function of a centred, normalised position ``s = 2(u − mid)/L ∈ [−1, 1]``.

    ``value = linear·s + quadratic·s² + cubic·s³ + amplitude·sin(2π u / period + phase)``
    (units of the error: m or rad; ``period`` in m, 0 for none).
    """

    linear: float = 0.0
    quadratic: float = 0.0
    cubic: float = 0.0
    amplitude: float = 0.0
    period: float = 0.0
    phase: float = 0.0

    def __call__(self, u, lo: float, hi: float) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        s = (2.0 * u - (lo + hi)) / (hi - lo)
        v = self.linear * s + self.quadratic * s ** 2 + self.cubic * s ** 3
        if self.period > 0 and self.amplitude:
            v = v + self.amplitude * np.sin(2 * np.pi * u / self.period + self.phase)
        return v

    def slope(self, u, lo: float, hi: float) -> np.ndarray:
        """d value / d u (per metre)."""
        u = np.asarray(u, dtype=float)
        s = (2.0 * u - (lo + hi)) / (hi - lo)
        d = (self.linear + 2 * self.quadratic * s + 3 * self.cubic * s ** 2) * 2.0 / (hi - lo)
        if self.period > 0 and self.amplitude:
            d = d + self.amplitude * 2 * np.pi / self.period * np.cos(
                2 * np.pi * u / self.period + self.phase)
        return d


@dataclass(frozen=True, eq=False)
class ThreeAxisMachine:
    """A three-axis machine with 21 geometric errors (module docstring).

    Attributes
    ----------
    chain : KinematicChain
    travel : dict of str to (float, float), m
    errors : dict of str to ErrorProfile
        ``EXX`` ... ``ECZ`` (m or rad); missing ones are zero.
    squareness : dict of str to float, rad
        ``xy``, ``yz``, ``zx``, positive when the angle exceeds 90°.
    name : str
    """

    chain: KinematicChain
    travel: dict
    errors: dict = field(default_factory=dict)
    squareness: dict = field(default_factory=dict)
    name: str = "simulated three-axis machine"

    def __post_init__(self) -> None:
        for a in AXES:
            lo, hi = self.travel[a]
            if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo and hi - lo <= 100):
                raise InputError(f"travel of {a} = {self.travel[a]!r} m: give low < high, "
                                 "at most 100 m")
        if set(self.squareness) - set(PAIRS):
            raise InputError(f"squareness pairs are {PAIRS}, not {sorted(self.squareness)}")

    def directions(self) -> dict[str, np.ndarray]:
        """Unit directions of the axes' motions in the work-piece frame."""
        sq = self.squareness
        dz = np.array([-sq.get("zx", 0.0), -sq.get("yz", 0.0), 1.0])
        return {"X": np.array([1.0, 0.0, 0.0]),
                "Y": np.array([-np.sin(sq.get("xy", 0.0)), np.cos(sq.get("xy", 0.0)), 0.0]),
                "Z": dz / np.linalg.norm(dz)}

    def error(self, name: str, u) -> np.ndarray:
        """The true error motion ``name`` at positions ``u`` (m) of its axis."""
        prof = self.errors.get(name)
        u = np.asarray(u, dtype=float)
        if prof is None:
            return np.zeros_like(u)
        return prof(u, *self.travel[name[-1]])

    def pose(self, x, y, z, tool_offset=(0.0, 0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
        """Exact tool position (m) and orientation in the work-piece frame.

        Returns
        -------
        position : numpy.ndarray, shape (N, 3), m
        rotation : numpy.ndarray, shape (N, 3, 3)
        """
        q = dict(zip(AXES, (np.ravel(np.asarray(v, float)) for v in
                            np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float),
                                                np.asarray(z, float)))))
        n = q["X"].size
        d = self.directions()
        p = np.zeros((n, 3))
        r = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        for a in self.chain.loop:
            u = q[a]
            trans = u[:, None] * d[a] + np.stack([self.error(e + a, u)
                                                  for e in ("EX", "EY", "EZ")], axis=1)
            p += np.einsum("nij,nj->ni", r, trans)
            rot = rotation_matrices(np.stack([self.error(e + a, u)
                                              for e in ("EA", "EB", "EC")], axis=1))
            r = np.einsum("nij,njk->nik", r, rot)
        p += np.einsum("nij,j->ni", r, np.asarray(tool_offset, float))
        return p, r


def rotation_matrices(rotvec: np.ndarray) -> np.ndarray:
    """Exact rotation matrices (Rodrigues) of rotation vectors, shape (N, 3) -> (N, 3, 3)."""
    rv = np.asarray(rotvec, dtype=float)
    theta = np.linalg.norm(rv, axis=1)
    k = np.where(theta[:, None] > 0, rv / np.where(theta > 0, theta, 1.0)[:, None], 0.0)
    kx = np.zeros((rv.shape[0], 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    kx[:, 1, 0], kx[:, 2, 0], kx[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    s, c = np.sin(theta)[:, None, None], np.cos(theta)[:, None, None]
    return np.eye(3) + s * kx + (1 - c) * np.einsum("nij,njk->nik", kx, kx)


def simulated_machine(rng: np.random.Generator, chain: str = "X Y | Z",
                      travel_mm=((0, 800), (0, 500), (-500, 0)),
                      squareness_um_per_m=(25.0, -15.0, 30.0),
                      angular_scale: float = 1.0) -> ThreeAxisMachine:
    """A machining centre with all 21 errors, drawn around typical magnitudes (module docstring).

    Each axis has a bent guideway in both lateral directions (straightness 2-5 µm over the travel)
    with its associated angular errors (the slope of the bend, Appendix I eq. 2's ``8 S u / L²``),
    independent angular errors of 1-5 µrad, a roll of a few µrad, and a positioning error of a
    scale error of 5-15 µm/m plus a 1-3 µm cubic and a 0.5 µm periodic error of 25 mm pitch.
    Squareness errors are the given values in µm/m (xy, yz, zx). ``angular_scale`` multiplies
    every angular error (0 gives a machine whose errors tables can remove entirely).
    """
    if not (np.isfinite(angular_scale) and 0 <= angular_scale <= 100):
        raise InputError(f"angular_scale = {angular_scale!r}: between 0 and 100")
    travel = {a: (lo * 1e-3, hi * 1e-3) for a, (lo, hi) in zip(AXES, travel_mm)}
    errors = {}
    for a in AXES:
        lo, hi = travel[a]
        length = hi - lo
        i = AXES.index(a)
        errors[f"E{a}{a}"] = ErrorProfile(
            linear=rng.uniform(5, 15) * 1e-6 * length / 2 * rng.choice([-1, 1]),
            cubic=rng.uniform(1, 3) * 1e-6 * rng.choice([-1, 1]),
            amplitude=0.5e-6, period=0.025, phase=rng.uniform(0, 2 * np.pi))
        for step in (1, 2):
            other = AXES[(i + step) % 3]
            errors[f"E{other}{a}"] = ErrorProfile(
                quadratic=rng.uniform(2, 5) * 1e-6 * rng.choice([-1, 1]))
        for r in "ABC":
            errors[f"E{r}{a}"] = ErrorProfile(linear=rng.uniform(-3, 3) * 1e-6,
                                              quadratic=rng.uniform(-2, 2) * 1e-6)
        _associate(errors, a, travel)
        for r in "ABC":
            p = errors[f"E{r}{a}"]
            errors[f"E{r}{a}"] = ErrorProfile(linear=p.linear * angular_scale,
                                              quadratic=p.quadratic * angular_scale)
    sq = dict(zip(PAIRS, (v * 1e-6 for v in squareness_um_per_m)))
    return ThreeAxisMachine(KinematicChain.parse(chain), travel, errors, sq,
                            name="simulated machining centre")


def _associate(errors: dict, a: str, travel: dict) -> None:
    """Add to axis ``a``'s angular errors the slope of its bends (rigid carriage).

    A bend ``δ_j(u)`` of axis ``a`` towards axis ``j`` turns the carriage about the third axis
    ``k`` by ``±dδ_j/du``: the rotation about +k that takes +a towards +j is positive when
    (a, j, k) is a cyclic order (right-hand rule).
    """
    lo, hi = travel[a]
    i = AXES.index(a)
    for j in AXES:
        if j == a:
            continue
        k = AXES[3 - i - AXES.index(j)]
        cyclic = (AXES.index(j) - i) % 3 == 1
        bend = errors[f"E{j}{a}"]
        # d(q s²)/du with s = 2(u − mid)/L is (4q/L) s: a linear term in s
        slope_linear = bend.quadratic * 4.0 / (hi - lo)
        name = f"E{'ABC'[AXES.index(k)]}{a}"
        old = errors[name]
        errors[name] = ErrorProfile(linear=old.linear + (slope_linear if cyclic else -slope_linear),
                                    quadratic=old.quadratic)
