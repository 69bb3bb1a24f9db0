"""Location errors of the rotary axes of a table-table five-axis machine, identified by least
squares from spheres probed at many rotary poses and from R-tests, with their uncertainty.

What the fit solves
-------------------
Each *set-up* is one instrument placed once: a precision sphere on the table probed at N poses
(the stylus-ball fits give N sphere centres in the machine frame), or an R-test whose nest sits on
the table while the machine keeps the tool sphere at the nest's nominal place (N displacements of
the tool sphere relative to the nest, in the table-fixed frame). The unknowns are the ten location
errors of :mod:`axiscal.physics.rotary_location` and, per set-up, the place of the sphere (or
nest) on the table, which no one knows to a micrometre. The model is that module's exact
kinematics; the fit is Gauss–Newton, weighted by each instrument's reading uncertainty.

What a set-up can and cannot see
--------------------------------
Because the sphere's place is unknown, a turn of the table about C moves it as a change of the
C zero would (E_C0C is never seen), and a change of the tilting axis's zero turns the C line
about the tilting axis as a tilt of C would (E_A0A and E_A0C, for B/C E_B0B and E_B0C, are seen
only as their sum). The convention that fixes them (the one KinematicsOpt-like cycles use): the C
zero is that of the set-up (E_C0C := 0) and the tilt of C about the tilting axis is counted in
the tilting axis's zero (E_A0C := 0), so the fit reports ``E_A0A+E_A0C``. Before any measurement
:func:`check_plan` computes the sensitivity matrix at the planned poses (columns equilibrated), its
rank and condition number, and names every location error that no planned pose sees with the
test that would see it; such an error is never reported as a number.

Uncertainty (JCGM 100:2008, GUM, 5.2 and F.2.4.5; ISO/TR 230-9:2005, 6)
----------------------------------------------------------------------
With W the weights (1/u² of the instruments' reading uncertainty), the covariance of the
identified parameters is

    V = (JᵀWJ)⁻¹ · max(χ²/ν, 1) + Σ_k (K g_k)(K g_k)ᵀ,   K = (JᵀWJ)⁻¹ JᵀW,

the first term Type A from the residuals (the reduced chi-square χ²/ν, ν = observations −
parameters, never below the instruments' own statement), the second Type B from each
calibration input of an instrument that acts on all readings of a set-up at once (g_k the change
of the readings per unit of input k times its standard uncertainty): the probe's stylus offset
and length (x, y, z; fully correlated with E_Z0A, E_X0C and E_Y0C, calibrated separately) and
the R-test's sensor gains. Expanded uncertainty U = k·u with k = 2.

Squareness of the linear axes (``squareness=True``)
---------------------------------------------------
The three squareness errors of X, Y, Z (ISO 230-1:2012 names E_C(0X)Y, E_B(0X)Z, E_A(0Y)Z;
:func:`~axiscal.physics.rotary_location.squareness_matrix`) may be added to the unknowns: the
linear axes' readings of a probed centre are ``(I + S)⁻¹`` of where it is, and an R-test's tool
is at ``(I + S)`` of its commanded readings. A rotary axis turning the sphere traces circles in
the XY, YZ and XZ planes, which a squareness makes elliptical and no location error does, so the
shipped plans separate them (rank 20 of 20, condition 7.6 for the A/C example).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError
from axiscal.physics.rotary_location import (SQUARENESS, Geometry, is_angle, machine_to_table,
                                              squareness_matrix, table_to_machine,
                                              transform_many)
from axiscal.standards.location_budget import systematic_inputs

__all__ = ["SetUp", "PlanCheck", "LocationError", "Unidentified", "LocationIdentification",
           "check_plan", "identify_location_errors", "conventions", "PROBING", "R_TEST"]

PROBING = "probing"
R_TEST = "r-test"
_H = 1e-7          # finite-difference step, m or rad
_NULL = 1e-7       # singular value below which (relative) a direction is unseen
_SEEN = 1e-3       # null-space component above which a parameter is unseen
#: Largest rms residual (m) a fit of location errors may leave: beyond it the readings are not
#: of this machine's kinematics (a wrong geometry, angle sign or set-up), and no number is given.
MAX_RESIDUAL = 0.1e-3


@dataclass(frozen=True, eq=False)
class SetUp:
    """One instrument set-up measured at N rotary poses (SI units).

    Attributes
    ----------
    kind : str
        ``"probing"`` (sphere on the table) or ``"r-test"``.
    tilt_angle, c_angle : numpy.ndarray, shape (N,), rad
        Commanded angles (LinuxCNC sign, :mod:`axiscal.physics.rotary_location`).
    values : numpy.ndarray, shape (N, 3), m, or None
        Probing: fitted sphere centres in the machine frame. R-test: displacement of the tool
        sphere relative to the nest, table frame. None for a plan not yet measured.
    commanded : numpy.ndarray, shape (N, 3), m, or None
        R-test only: commanded machine positions of the tool sphere's centre.
    nominal : tuple of float, m
        Nominal place of the sphere (nest) in the table frame: used by the plan check.
    u_reading : float, m
        Standard uncertainty of one coordinate of one value (instrument noise, sphere form).
    u_offset : tuple of float, m
        Probing: standard uncertainty of the stylus offset (x, y) and length (z) calibration.
    u_gain : float
        R-test: relative standard uncertainty of each sensor's gain.
    u_direction : float, rad
        R-test: standard uncertainty of each sensor's measuring direction (about each of the two
        axes normal to it).
    directions : numpy.ndarray, shape (3, 3), or None
        R-test: the sensors' nominal measuring directions (rows, table frame) through which the
        instrument turned its readings into X, Y, Z; None: along X, Y, Z.
    label : str
    """

    kind: str
    tilt_angle: np.ndarray
    c_angle: np.ndarray
    values: np.ndarray | None = None
    commanded: np.ndarray | None = None
    nominal: tuple[float, float, float] = (0.0, 0.0, 0.0)
    u_reading: float = 0.5e-6
    u_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    u_gain: float = 0.0
    u_direction: float = 0.0
    directions: np.ndarray | None = None
    label: str = ""

    def __post_init__(self) -> None:
        if self.kind not in (PROBING, R_TEST):
            raise InputError(f"set-up kind {self.kind!r}: use {PROBING!r} or {R_TEST!r}")
        n = np.size(self.tilt_angle)
        if n < 1 or np.size(self.c_angle) != n:
            raise InputError(f"set-up {self.label or self.kind}: give one tilt and one C angle "
                             "per pose")
        for name in ("tilt_angle", "c_angle", "values", "commanded"):
            v = getattr(self, name)
            if v is not None and not np.all(np.isfinite(v)):
                raise InputError(f"set-up {self.label or self.kind}: {name} holds a value that "
                                 "is not a finite number")
        if self.values is not None and np.shape(self.values) != (n, 3):
            raise InputError(f"set-up {self.label or self.kind}: {n} poses need {n} values "
                             f"(x, y, z), got shape {np.shape(self.values)}")
        if self.kind == R_TEST and self.commanded is not None and np.shape(self.commanded) != (n, 3):
            raise InputError(f"set-up {self.label or self.kind}: {n} poses need {n} commanded "
                             "positions")
        if not self.u_reading > 0:
            raise InputError(f"set-up {self.label or self.kind}: u_reading = {self.u_reading!r} "
                             "must be > 0")

    @property
    def poses(self) -> int:
        return int(np.size(self.tilt_angle))


@dataclass(frozen=True)
class Unidentified:
    """A location error (or sum) the set-ups cannot see: its name, why, and the test that would."""

    name: str
    reason: str

    def __str__(self) -> str:
        return f"{self.name}: not identified ({self.reason})"


@dataclass(frozen=True)
class LocationError:
    """One identified location error: value and standard uncertainty in SI (m or rad), with its
    ISO 230-1 name; ``value_display``/``U_display`` in µm or µrad."""

    name: str
    value: float
    u: float
    k: float = 2.0
    components: dict = field(default_factory=dict)

    @property
    def unit(self) -> str:
        return "µrad" if is_angle(self.name) else "µm"

    @property
    def U(self) -> float:
        return self.k * self.u

    @property
    def value_display(self) -> float:
        return self.value * 1e6

    @property
    def U_display(self) -> float:
        return self.U * 1e6

    def __str__(self) -> str:
        return (f"{self.name} = {self.value_display:+.2f} {self.unit}, "
                f"U = {self.U_display:.2f} {self.unit} (k = {self.k:g})")


@dataclass(frozen=True)
class PlanCheck:
    """What a plan of set-ups can separate, said before measuring.

    Attributes
    ----------
    tilt : str
    poses, observations : int
    rank : int
        Rank of the sensitivity matrix of the location errors (after the convention) and the
        set-ups' sphere places.
    columns : int
        Its number of columns.
    condition : float
        Condition number of the equilibrated sensitivity matrix of what is identifiable.
    identifiable : tuple of str
    unidentified : tuple of Unidentified
    """

    tilt: str
    poses: int
    observations: int
    rank: int
    columns: int
    condition: float
    identifiable: tuple[str, ...]
    unidentified: tuple[Unidentified, ...]
    head: bool = False

    @property
    def convention(self) -> str:
        return conventions(self.tilt, self.head)

    def __str__(self) -> str:
        lines = [f"{self.poses} poses, {self.observations} observations: sensitivity matrix rank "
                 f"{self.rank} of {self.columns} columns (location errors and each set-up's "
                 f"sphere place), condition {self.condition:.3g}",
                 f"identifiable: {', '.join(self.identifiable) or 'none'}"]
        lines += [f"  {u}" for u in self.unidentified]
        lines.append(f"convention: {self.convention}")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        return {"tilt_axis": self.tilt, "kind": "head-table" if self.head else "table-table",
                "poses": self.poses, "observations": self.observations,
                "rank": self.rank, "columns": self.columns, "condition": self.condition,
                "identifiable": list(self.identifiable),
                "unidentified": [{"name": u.name, "reason": u.reason} for u in self.unidentified],
                "convention": self.convention}


@dataclass(frozen=True, eq=False)
class LocationIdentification:
    """The identified location errors, their uncertainty and correlation, and the residual.

    Attributes
    ----------
    plan : PlanCheck
    errors : tuple of LocationError
    correlation : numpy.ndarray
        Correlation matrix of ``errors`` (same order).
    places : tuple of numpy.ndarray, m
        Fitted place of each set-up's sphere (or nest) in the table frame.
    residual_rms, residual_max : float, m
        Of all readings after the fit.
    residual_by_setup : tuple of float, m
        RMS residual of each set-up.
    chi2_per_dof : float
        Reduced chi-square of the weighted fit (1 when the residual is the instruments' noise).
    dof : int
    """

    plan: PlanCheck
    errors: tuple[LocationError, ...]
    correlation: np.ndarray
    places: tuple
    residual_rms: float
    residual_max: float
    residual_by_setup: tuple[float, ...]
    chi2_per_dof: float
    dof: int

    def __getitem__(self, name: str) -> LocationError:
        for e in self.errors:
            if e.name == name:
                return e
        for u in self.plan.unidentified:
            if u.name == name:
                raise KeyError(f"{name} is not identified: {u.reason}")
        raise KeyError(name)

    @property
    def unidentified(self) -> tuple[Unidentified, ...]:
        return self.plan.unidentified

    @property
    def unmodelled(self) -> str:
        """What the residual suggests: noise only, or errors the model does not hold."""
        if self.chi2_per_dof <= 4.0:
            return ("the residual is as large as the instruments' noise: nothing large is left "
                    "unmodelled")
        return (f"the residual ({self.residual_rms * 1e6:.2f} µm rms) is "
                f"{np.sqrt(self.chi2_per_dof):.1f} times the instruments' noise: errors the "
                "location model does not hold remain (error motions or angular positioning "
                "errors of the rotary axes, errors of the linear axes, or a moving set-up)")

    def __str__(self) -> str:
        kind = "spindle-head" if self.plan.head else "table-table"
        lines = [f"location errors of the {self.plan.tilt}/C {kind} axes "
                 f"({self.plan.poses} poses, rank {self.plan.rank}, condition "
                 f"{self.plan.condition:.3g}):"]
        lines += [f"  {e}" for e in self.errors]
        lines += [f"  {u}" for u in self.plan.unidentified]
        lines.append(f"residual {self.residual_rms * 1e6:.2f} µm rms, largest "
                     f"{self.residual_max * 1e6:.2f} µm; {self.unmodelled}")
        lines.append(f"convention: {self.plan.convention}")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis identify`` (µm, µrad; documented there)."""
        return {
            "plan": self.plan.to_dict(),
            "errors": [{"name": e.name, "value": e.value_display, "U": e.U_display, "k": e.k,
                        "unit": e.unit,
                        "u_components": {k: v * 1e6 for k, v in e.components.items()}}
                       for e in self.errors],
            "unidentified": [{"name": u.name, "reason": u.reason} for u in self.unidentified],
            "correlation": np.round(self.correlation, 4).tolist(),
            "places_mm": [(np.asarray(p) * 1e3).tolist() for p in self.places],
            "residual_rms_um": self.residual_rms * 1e6,
            "residual_max_um": self.residual_max * 1e6,
            "residual_by_setup_um": [r * 1e6 for r in self.residual_by_setup],
            "chi2_per_dof": self.chi2_per_dof, "dof": self.dof,
            "unmodelled": self.unmodelled,
        }


def conventions(tilt: str, head: bool = False) -> str:
    """The convention that fixes what a sphere of unknown place cannot see (module docstring)."""
    if head:
        across = "X" if tilt == "B" else "Y"
        return (f"E_C0C := 0 (the C zero is the set-up's) and E_{tilt}0{tilt} := 0 (the head's "
                f"zero tilts the tool, which moves its tip across as a stylus offset would: "
                f"E_{across}0C and E_{across}0{tilt} are taken relative to the tool tip at "
                f"{tilt} = 0, the zero counted in them); the head turns the tool right-handed, "
                f"the table turns right-handed by the commanded angle (LinuxCNC trt sign); the "
                f"tool length (pivot) is calibrated separately, fully correlated with E_Z0{tilt}")
    return (f"E_C0C := 0 (the C zero is the set-up's) and E_{tilt}0C := 0 (the tilt of C about "
            f"{tilt} is counted in the zero of {tilt}, reported as E_{tilt}0{tilt}+E_{tilt}0C); "
            "rotary angles turn the table right-handed (LinuxCNC trt kinematics, opposite to "
            "ISO 841)")


def check_plan(geometry: Geometry, setups, squareness: bool = False) -> PlanCheck:
    """Rank, condition and the unseen location errors of planned set-ups, before measuring.

    Parameters
    ----------
    geometry : Geometry
    setups : sequence of SetUp
        Their ``nominal`` places and angles are used; values are not needed.
    squareness : bool
        Also the linear axes' three squareness errors (module docstring).

    Returns
    -------
    PlanCheck
    """
    setups = _checked(setups)
    places = [np.asarray(s.nominal, float) for s in setups]
    names = _names(geometry, squareness)
    theta = np.zeros(len(names))
    J = _jacobian(geometry, setups, theta, places, _nominal_commands(geometry, setups), names)[0]
    return _plan(geometry, setups, J * _weights(setups)[:, None], names)[0]


def identify_location_errors(geometry: Geometry, setups, iterations: int = 4,
                             squareness: bool = False) -> LocationIdentification:
    """Identify the location errors from measured set-ups (module docstring).

    Parameters
    ----------
    geometry : Geometry
        Nominal geometry (the machine's kinematics parameters as the controller holds them).
    setups : sequence of SetUp
        Each with ``values`` (and for an R-test ``commanded``).
    iterations : int
        Gauss–Newton iterations.
    squareness : bool
        Also the linear axes' three squareness errors (module docstring).

    Returns
    -------
    LocationIdentification

    Raises
    ------
    InputError
        A set-up without values, or no set-up.
    """
    setups = _checked(setups)
    for s in setups:
        if s.values is None or (s.kind == R_TEST and s.commanded is None):
            raise InputError(f"set-up {s.label or s.kind} has no measured values")
    commands = [s.commanded for s in setups]
    w = _weights(setups)
    y = np.concatenate([s.values.ravel() for s in setups])
    names = _names(geometry, squareness)
    n = len(names)
    theta = np.zeros(n)
    places = _start_places(geometry, setups)
    J, f = _jacobian(geometry, setups, theta, places, commands, names)
    plan, free = _plan(geometry, setups, J * w[:, None], names)
    for _ in range(iterations):
        Jw = J[:, free] * w[:, None]
        step = np.linalg.lstsq(Jw, (y - f) * w, rcond=None)[0]
        full = np.zeros(J.shape[1])
        full[free] = step
        theta = theta + full[:n]
        places = [p + full[n + 3 * i:n + 3 + 3 * i] for i, p in enumerate(places)]
        J, f = _jacobian(geometry, setups, theta, places, commands, names)
        if np.abs(step).max() < 1e-12:
            break
    r = y - f
    if np.sqrt(np.mean(r ** 2)) > MAX_RESIDUAL:
        raise InputError(
            f"the readings do not fit the machine's kinematics: {np.sqrt(np.mean(r ** 2)) * 1e3:.3f}"
            f" mm rms left after the fit (at most {MAX_RESIDUAL * 1e3:g} mm for location errors); "
            "check the nominal geometry, the sign of the rotary angles (the table turns "
            "right-handed, as LinuxCNC's trt kinematics) and that each file is one set-up")
    Jw = J[:, free] * w[:, None]
    N = np.linalg.inv(Jw.T @ Jw)
    K = N @ Jw.T * w                                   # parameters per reading
    dof = max(len(y) - len(free), 1)
    chi2 = float(((r * w) ** 2).sum() / dof)
    cov_a = N * max(chi2, 1.0)
    contributions = {"residual": np.sqrt(np.diag(cov_a))}
    cov = cov_a.copy()
    for name, g in systematic_inputs(setups, len(y)).items():
        d = K @ g
        cov += np.outer(d, d)
        contributions[name] = np.abs(d)
    loc = [i for i in free if i < n]
    idx = [free.index(i) for i in loc]
    sd = np.sqrt(np.diag(cov))[idx]
    corr = cov[np.ix_(idx, idx)] / np.outer(sd, sd)
    errors = tuple(LocationError(_label(names[i], geometry.tilt, geometry.head), float(theta[i]),
                                 float(sd[j]),
                                 components={k: float(v[idx[j]]) for k, v in contributions.items()})
                   for j, i in enumerate(loc))
    sizes = np.cumsum([0] + [3 * s.poses for s in setups])
    by = tuple(float(np.sqrt(np.mean(r[a:b] ** 2))) for a, b in zip(sizes[:-1], sizes[1:]))
    return LocationIdentification(plan=plan, errors=errors, correlation=corr,
                                  places=tuple(places), residual_rms=float(np.sqrt(np.mean(r ** 2))),
                                  residual_max=float(np.abs(r).max()), residual_by_setup=by,
                                  chi2_per_dof=chi2, dof=dof)


# -- the pieces -------------------------------------------------------------------------------

def _checked(setups) -> list[SetUp]:
    setups = list(setups)
    if not setups:
        raise InputError("no set-up: give at least one probed sphere or R-test")
    for s in setups:
        if not isinstance(s, SetUp):
            raise InputError(f"{s!r} is not a SetUp")
    return setups


def _weights(setups) -> np.ndarray:
    return np.concatenate([np.full(3 * s.poses, 1.0 / s.u_reading) for s in setups])


def _nominal_commands(geometry, setups):
    return [table_to_machine(geometry, {}, s.tilt_angle, s.c_angle, s.nominal)
            if s.kind == R_TEST else None for s in setups]


def _start_places(geometry, setups):
    """First estimate of each sphere's (nest's) place from the nominal kinematics."""
    out = []
    for s in setups:
        if s.kind == PROBING:
            out.append(machine_to_table(geometry, {}, s.tilt_angle, s.c_angle, s.values).mean(0))
        else:
            t = machine_to_table(geometry, {}, s.tilt_angle, s.c_angle, s.commanded)
            out.append((t - s.values).mean(0))
    return out


def _names(geometry: Geometry, squareness: bool) -> tuple[str, ...]:
    """The fit's parameters: the ten location errors, then (``squareness``) the linear axes'."""
    return geometry.names + (SQUARENESS if squareness else ())


def _jacobian(geometry, setups, theta, places, commands, names=None):
    """Model values ``f`` and their derivatives ``J`` by the parameters ``names`` (the ten
    location errors, and the three squareness errors where named) and the set-ups' places
    (central differences of the exact kinematics, all in one vectorised pass per set-up)."""
    names = geometry.names if names is None else names
    n = len(names)
    base = dict(zip(names, theta))
    sets = [base]
    for name in names:
        for sign in (1.0, -1.0):
            e = dict(base)
            e[name] += sign * _H
            sets.append(e)
    sets += [base] * 6
    shifts = np.zeros((len(sets), 1, 3))
    for j in range(3):
        shifts[1 + 2 * n + 2 * j, 0, j], shifts[2 + 2 * n + 2 * j, 0, j] = _H, -_H
    square = n > 10
    if square:
        M = np.array([squareness_matrix(e) for e in sets])          # (sets, 3, 3)
    rows, fs = [], []
    ncol = n + 3 * len(setups)
    for k, (s, place, cmd) in enumerate(zip(setups, places, commands)):
        if s.kind == PROBING:
            v = transform_many(geometry, sets, s.tilt_angle, s.c_angle, place + shifts)
            if square:                       # the readings of where the centre is
                v = np.linalg.solve(M, np.swapaxes(v, 1, 2)).swapaxes(1, 2)
        else:
            pts = np.einsum("kij,nj->kni", M, cmd) if square else cmd
            v = transform_many(geometry, sets, s.tilt_angle, s.c_angle, pts, inverse=True)
            v = v - (place + shifts)
        v = v.reshape(len(sets), -1)
        fs.append(v[0])
        d = (v[1::2][:n + 3] - v[2::2][:n + 3]) / (2 * _H)   # the parameters, then the place
        block = np.zeros((v.shape[1], ncol))
        block[:, :n] = d[:n].T
        block[:, n + 3 * k:n + 3 + 3 * k] = d[n:n + 3].T
        rows.append(block)
    return np.vstack(rows), np.concatenate(fs)


def _fixed(tilt: str, head: bool = False) -> tuple[int, ...]:
    """Columns fixed by the convention: the C zero, and on a table-table machine the tilt of C
    about the tilting axis (seen only in its sum with the tilting axis's zero), on a spindle head
    the head's zero (seen only with the tool tip's offset and the C position, conventions())."""
    if head:
        return 4, 9
    return (7 if tilt == "A" else 8), 9


def _label(name: str, tilt: str, head: bool = False) -> str:
    zero = f"E_{tilt}0{tilt}"
    return f"{zero}+E_{tilt}0C" if name == zero and not head else name


def _plan(geometry, setups, Jw, names=None) -> tuple[PlanCheck, list[int]]:
    """Equilibrated SVD of the weighted sensitivity matrix: rank, condition, the unseen."""
    tilt, head = geometry.tilt, geometry.head
    names = geometry.names if names is None else names
    n = len(names)
    cols = [i for i in range(Jw.shape[1]) if i not in _fixed(tilt, head)]
    unseen: list[int] = []
    for _ in range(10):
        A = Jw[:, cols]
        norms = np.linalg.norm(A, axis=0)
        dead = [c for c, n in zip(cols, norms) if n == 0.0]
        if dead:
            unseen += [c for c in dead if c < n]
            cols = [c for c in cols if c not in dead]
            continue
        _, sv, vt = np.linalg.svd(A / norms, full_matrices=False)
        null = vt[sv < _NULL * sv[0]] if len(sv) else vt
        if len(sv) < len(cols):      # fewer observations than columns
            null = np.vstack([null, _complement(vt, len(cols))])
        if null.shape[0] == 0:
            break
        weight = np.linalg.norm(null, axis=0)
        loc = [(weight[j], c) for j, c in enumerate(cols) if c < n and weight[j] > _SEEN]
        if not loc:
            break
        worst = max(loc)[1]
        unseen.append(worst)
        cols = [c for c in cols if c != worst]
    A = Jw[:, cols]
    sv = np.linalg.svd(A / np.linalg.norm(A, axis=0), compute_uv=False)
    rank = int((sv > _NULL * sv[0]).sum()) if len(sv) else 0
    cond = float(sv[0] / sv[-1]) if len(sv) and sv[-1] > 0 else float("inf")
    fixed = [Unidentified(names[9], "a sphere or nest of unknown place on the table sees no C "
                          "zero; set by the convention E_C0C := 0 (the C zero is the set-up's); "
                          "measure it against a datum on the table at a known angle")]
    if head:
        fixed.insert(0, Unidentified(names[4], f"the head's zero moves the tool tip across as a "
                                     f"stylus offset would; set by the convention "
                                     f"E_{tilt}0{tilt} := 0 and counted in the C and head "
                                     f"positions; measure the tool's tilt at {tilt} = 0 (a "
                                     f"level, or the tip at {tilt} = ±90°) to separate it"))
    out = [Unidentified(_label(names[c], tilt, head), _hint(names[c], tilt))
           for c in sorted(unseen)]
    plan = PlanCheck(tilt=tilt, head=head, poses=sum(s.poses for s in setups), observations=Jw.shape[0],
                     rank=rank, columns=len(cols) + len(unseen),
                     condition=cond,
                     identifiable=tuple(_label(names[c], tilt, head) for c in cols if c < n),
                     unidentified=tuple(out + fixed))
    return plan, cols


def _complement(vt, n):
    """Directions of R^n outside the row space of ``vt`` (an under-determined system)."""
    q, _ = np.linalg.qr(np.vstack([vt, np.eye(n)]).T)
    return q[:, vt.shape[0]:n].T


def _hint(name: str, tilt: str) -> str:
    """Why no planned pose sees ``name`` and the test that would."""
    if name in SQUARENESS:
        return ("no planned pose moves the sphere along both linear axes of this squareness; "
                "probe it at several C and tilt angles so that it traces circles in that plane")
    if name == f"E_{tilt}0{tilt}":
        return (f"seen as the tilt of the C line about {tilt}: probe at three or more C angles, "
                f"or at two or more {tilt} angles besides 0")
    if name[-1] == tilt:
        return (f"no planned pose separates the {tilt} axis's line; probe at three or more {tilt} "
                f"angles (for example 0, ∓45, ∓90°) at several C angles")
    if name in ("E_X0C", "E_Y0C"):
        return "no planned pose turns C enough; probe at three or more C angles (for example every 90°)"
    return (f"no planned pose separates the C axis's tilt; probe at three or more C angles at "
            f"{tilt} ≠ 0, or with the sphere above the {tilt} axis")
