"""Ballbar tests of a rotary axis moving with the linear axes (the kinematic tests of ISO
10791-6:2014 as public descriptions give them): which location errors each set-up sees, and the
range of the ballbar's reading with its uncertainty.

The test (this module's reading; the text of ISO 10791-6:2014 was not at hand)
-------------------------------------------------------------------------------
A ballbar joins a ball fixed on the table (the *pivot*, at ``p_w`` in the table frame) and a ball
in the spindle. The controller turns one rotary axis (or both) and moves the linear axes with it
so that, by its *nominal* kinematics, the spindle ball stays at ``p_s = p_w + L n`` in the table
frame: relative to the machine's linear axes the spindle ball runs a circle (or, with both rotary
axes, a path on a sphere) about the rotary axis, relative to the table it stands still. ``n`` is
the bar's direction in the table frame, fixed for the set-up: *radial* (away from the swept
axis's line through the pivot), *tangential* (``u × n_radial``, ``u`` the axis direction) or
*axial* (``u``), one direction per set-up. On a machine with location errors the spindle ball
truly reaches ``p_s + δ(θ)`` in the table frame and the bar reads

    ΔL(θ) = |L n + δ(θ)| − L  ≈  n · δ(θ)                                                  (1)

(first order; the second-order term is ``|δ − (n·δ) n|² / (2L)``, 0.008 µm for |δ| = 40 µm and
L = 100 mm). ``δ`` is what an R-test would read in three directions at once (the R-test of
:mod:`axiscal.instruments.r_test`); the ballbar sees its component along ``n``. The figure is
the *range* of ΔL along the path (max − min): a constant (the ballbar's calibrated length, the
pivot's exact place) does not enter it.

What the public descriptions say: ISO's catalogue gives the standard's scope (kinematic tests of
the paths "described by the simultaneous movement of two or more numerically controlled (NC)
linear and/or rotary axes", machining centres with three linear and one or two rotary axes).
Florussen, Houben, Spaan and Spaan-Burke (2020) name the standard's kinematic tests BK1 and BK2
(which "apply for trunnion or swivel table machines" and give the location and orientation errors
of a rotary axis's average line) and BK4 ("all 5-axes are moving"). Kato, Tsutsumi and Sato
(2012) measure the circular path of simultaneous five-axis motion with a ballbar and show that
the reading depends on the bar's *sensitive direction*; Tsutsumi and Saito (2003) identify the
location errors of a five-axis machine from ballbar paths of one rotary axis moving with two
linear axes; a paper in Proc. IMechE Part B (doi:10.1177/0954405415617448) tests a
tilting-rotary machine's rotary axes with a ballbar one axis at a time. The path above, the three bar directions, the figure (range) and its
uncertainty budget are **this module's reading** of those descriptions, not the standard's text;
its test codes (AK1, BK1, CK1 ...), set-up dimensions and tolerances are not claimed.

Sensitivity (which location errors a set-up sees)
-------------------------------------------------
To first order, with the nominal chain ``T = T_t ∘ T_c`` (C turns the point first, then the
tilting axis; :mod:`axiscal.physics.rotary_location`), ``T_x(p) = q_x + R_x (p − q_x)``, the
table-frame displacement of the spindle ball for a small location error ``e_k`` is
``δ_k = −(R_t R_c)ᵀ ∂T/∂e_k`` with (``v_c = R_c (p − q_c)``, ``x₁ = q_c + v_c``,
``v_t = R_t (x₁ − q_t)``):

* a position of C (``E_X0C``, ``E_Y0C``, direction ``d``): ``∂T = R_t (I − R_c) d``;
* the zero of C (``E_C0C``): ``∂T = R_t (u_c × v_c)``;
* an orientation of C (``E_A0C`` about x, ``E_B0C`` about y, axis ``k``): the line's direction
  turned by ``Q = I + ε[k]×`` about its reference point, so ``R → Q R Qᵀ`` and
  ``∂T = R_t (k × v_c − R_c (k × (p − q_c)))``;
* the same three for the tilting axis at ``x₁`` (``(I − R_t) d``, ``u_t × v_t``,
  ``k × v_t − R_t (k × (x₁ − q_t))``);
* a squareness of the linear axes (ISO 230-1 names, :func:`~axiscal.physics.rotary_location.
  squareness_matrix`): the tool truly at ``(I + S) r`` for readings ``r = T(p_s)``, so
  ``δ_k = (R_t R_c)ᵀ (∂S/∂e_k) r``.

The reading's sensitivity is ``n · δ_k`` at each point of the path; the *range sensitivity* of a
set-up to ``e_k`` is the range of that pattern (µm of range per µm or per µrad of the error
alone). A range sensitivity below :data:`BLIND` means the set-up cannot see the error.

Worked case, a pure offset ``e`` of the C axis centre (``E_X0C = e``), tilt at 0
------------------------------------------------------------------------------------
The true C line passes through ``q_c + e x̂``; a table point ``p`` is at
``Rz(c)(p − e x̂) + e x̂``. The controller commands ``Rz(c) p_s``; the spindle ball is truly at
``p_s + e (x̂ − Rz(−c) x̂) = p_s + e (1 − cos c, sin c, 0)`` in the table frame. For a pivot at
azimuth ``φ`` about the C axis, ``n_radial = (cos φ, sin φ, 0)`` and
``n_tangential = (−sin φ, cos φ, 0)``, so by (1)

    ΔL_radial = e (cos φ − cos(c + φ)),   ΔL_tangential = e (sin(c + φ) − sin φ),
    ΔL_axial = 0,

and over a full turn both the radial and the tangential range are ``2e`` (40 µm for e = 20 µm,
the figure issue 43 quotes); the axial bar does not see the offset.

Uncertainty of the range (JCGM 100:2008 eq. 10, contributors as :mod:`axiscal.standards.
iso230_9` builds them; this module's budget)
--------------------------------------------------------------------------------------------
* ``u_NOISE``: the range is the difference of two readings, each the largest (smallest) of the
  few readings near an extreme, so noise both scatters it and biases it upwards (the expected
  largest of three to five normal readings is about one ``s`` above their mean). Taken here as
  ``s`` at each end, added linearly: ``u = 2 s``, normal, with ``s`` the larger of the ballbar's
  stated noise and the Type A scatter of the readings about a smooth fit (Legendre polynomial of
  degree 10 in the path parameter). On the twin (noise 0.2 µm, 73 points) the measured range
  exceeds the noise-free one by 0.2-0.6 µm, inside U = 0.8-0.9 µm.
* ``u_GAIN``: the transducer's relative calibration uncertainty × the range; normal.
* ``u_DRIFT``: the bar's thermal change of length during the run, ``α L ΔT`` with ``ΔT`` the
  stated change of the bar's temperature (rectangular, half-width ``α L ΔT``, ``u = α L ΔT/√3``).
* ``u_LENGTH``: the calibrator's length uncertainty acts on every reading alike and on no range
  (listed with ``u = 0``, sensitivity 0).

References
----------
ISO 10791-6:2014, Test conditions for machining centres — Part 6: Accuracy of speeds and
interpolations, Scope (ISO catalogue; https://standards.iteh.ai/catalog/standards/iso/
758ac355-b56f-48ca-96b4-e22def85fe29/iso-10791-6-2014).
G. Florussen, K. Houben, H. Spaan, T. Spaan-Burke, "Automating Accuracy Evaluation of 5-Axis
Machine Tools", Int. J. of Automation Technology (received 30 October 2019, accepted
27 December 2019; https://fdocuments.in/document/automating-accuracy-evaluation-of-5-axis-machine-
tools.html), its abstract.
N. Kato, M. Tsutsumi, R. Sato, "Analysis of circular trajectory equivalent to cone-frustum
milling in five-axis machining centers using motion simulator", Int. J. of Machine Tools and
Manufacture (available online 8 August 2012; https://id.scribd.com/document/223394946/), its
abstract.
M. Tsutsumi, A. Saito, "Identification and compensation of systematic deviations particular to
5-axis machining centers", Int. J. of Machine Tools and Manufacture 43(8) (2003) 771-780 (title
and journal from a reference list; that it uses ballbar paths of one rotary axis with two linear
axes is this work's recollection, not checked against its text).
"A method having two steps to identify the imprecision of the rotary axes caused by the
position-independent geometric errors ... using a DBB", Proc. IMechE Part B: J. Engineering
Manufacture, doi:10.1177/0954405415617448 (https://sage.cnpereading.com/doi/10.1177/
0954405415617448), its abstract (Hermle C600U, one axis moving at a time).
ISO 230-1:2012 3.4 and ISO 230-7:2015 Clause 3 (the location errors' names).
JCGM 100:2008 (GUM), 5.1.2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.physics.rotary_location import SQUARENESS, Geometry, table_to_machine
from axiscal.standards.iso230_9 import Contributor, UncertaintyBudget, combine

__all__ = ["DIRECTIONS", "BLIND", "bar_direction", "reading_sensitivity", "range_sensitivity",
           "BallbarRange", "evaluate_ballbar", "SMOOTH_DEGREE", "ALPHA_BAR"]

#: The bar's directions a set-up may take, relative to the swept rotary axis.
DIRECTIONS = ("radial", "tangential", "axial")
#: Range sensitivity (µm of range per µm or per µrad) below which a set-up is blind to an error.
BLIND = 1e-3
#: The bar body's expansion coefficient (1/K) the range's budget takes (u_DRIFT): a steel
#: bar body, assumed; a ballbar file cannot set it.
ALPHA_BAR = 11.5e-6
#: Degree of the Legendre polynomial the readings' Type A scatter is taken about.
SMOOTH_DEGREE = 10

_POSITION = {"E_X0C": (0, "C"), "E_Y0C": (1, "C"), "E_Y0A": (1, "T"), "E_Z0A": (2, "T"),
             "E_X0B": (0, "T"), "E_Z0B": (2, "T")}
_ORIENT = {"E_A0C": (0, "C"), "E_B0C": (1, "C"), "E_B0A": (1, "T"), "E_C0A": (2, "T"),
           "E_A0B": (0, "T"), "E_C0B": (2, "T")}
_ZERO = {"E_C0C": "C", "E_A0A": "T", "E_B0B": "T"}
_DS = {"E_C(0X)Y": (0, 1, -1.0), "E_B(0X)Z": (0, 2, 1.0), "E_A(0Y)Z": (1, 2, -1.0)}


def bar_direction(geometry: Geometry, swept: str, direction: str, pivot, tilt_angle: float,
                  c_angle: float) -> np.ndarray:
    """The bar's unit direction in the table frame (pivot to spindle ball), from the nominal
    line of the swept axis at the start pose (module docstring).

    Parameters
    ----------
    geometry : Geometry
    swept : str
        ``"C"``, the tilting axis's letter, or ``"both"`` (then relative to C).
    direction : str
        ``radial``, ``tangential`` or ``axial``.
    pivot : array_like, shape (3,), m
        The table ball's centre in the table frame.
    tilt_angle, c_angle : float, rad
        The start pose (the tilting axis's line in the table frame turns with C).

    Raises
    ------
    InputError
        An unknown direction, or a radial/tangential bar whose pivot lies on the axis.

    Examples
    --------
    >>> g = Geometry("A", (0.0, -0.06), (0.0, 0.0))
    >>> bar_direction(g, "C", "tangential", [0.0, 0.15, 0.0], 0.0, 0.0).round(12).tolist()
    [-1.0, 0.0, 0.0]
    """
    if direction not in DIRECTIONS:
        raise InputError(f"direction = {direction!r}: use one of {', '.join(DIRECTIONS)}")
    (q_t, u_t, _), (q_c, u_c, _) = geometry.lines({})
    if swept in ("C", "both"):
        q, u = q_c, u_c
    else:
        r_c = _rotations(u_c, np.atleast_1d(float(c_angle)))[0]
        q, u = q_c + r_c.T @ (q_t - q_c), r_c.T @ u_t
    if direction == "axial":
        return u.copy()
    w = np.asarray(pivot, float) - q
    w = w - (w @ u) * u
    if np.linalg.norm(w) < 1e-6:
        raise InputError(f"a {direction} bar needs the pivot off the {swept} axis's line "
                         "(at least 1 µm away); move the pivot or use an axial bar")
    radial = w / np.linalg.norm(w)
    return radial if direction == "radial" else np.cross(u, radial)


def reading_sensitivity(geometry: Geometry, tilt_angle, c_angle, point, direction,
                        names=None) -> np.ndarray:
    """First-order sensitivity of the ballbar's reading to each location error (module
    docstring, 'Sensitivity').

    Parameters
    ----------
    geometry : Geometry
        Nominal geometry (a table-table machine).
    tilt_angle, c_angle : array_like, shape (N,), rad
        The path's poses.
    point : array_like, shape (3,), m
        The spindle ball's place in the table frame (``p_w + L n``).
    direction : array_like, shape (3,)
        The bar's unit direction ``n`` in the table frame.
    names : sequence of str, optional
        Errors to give (default: the ten location errors of ``geometry``); the squareness names
        of :data:`~axiscal.physics.rotary_location.SQUARENESS` are allowed.

    Returns
    -------
    numpy.ndarray, shape (N, P)
        m per m (positions) or m per rad (orientations, zeros, squareness): numerically µm per
        µm and µm per µrad.
    """
    if geometry.head:
        raise InputError("the ballbar test here is for a table-table machine (a spindle head's "
                         "tool turns with the head)")
    names = tuple(geometry.names if names is None else names)
    a = np.atleast_1d(np.asarray(tilt_angle, float))
    c = np.atleast_1d(np.asarray(c_angle, float))
    p = np.asarray(point, float)
    n = np.asarray(direction, float)
    (q_t, u_t, _), (q_c, u_c, _) = geometry.lines({})
    r_c, r_t = _rotations(u_c, c), _rotations(u_t, a)
    v_c = np.einsum("nij,j->ni", r_c, p - q_c)
    x1 = q_c + v_c
    v_t = np.einsum("nij,nj->ni", r_t, x1 - q_t)
    back = np.einsum("nji,nkj->nik", r_c, r_t)       # (R_t R_c)ᵀ per pose
    readings = table_to_machine(geometry, {}, a, c, p)
    out = np.empty((len(a), len(names)))
    for j, name in enumerate(names):
        if name in _DS:
            row, col, sign = _DS[name]
            ds = np.zeros((len(a), 3))
            ds[:, row] = sign * readings[:, col]
            delta = np.einsum("nij,nj->ni", back, ds)
        else:
            delta = -np.einsum("nij,nj->ni", back, _dT(name, geometry, p, q_c, q_t, u_c, u_t,
                                                        r_c, r_t, v_c, x1, v_t))
        out[:, j] = delta @ n
    return out


def range_sensitivity(sensitivity) -> np.ndarray:
    """The range (max − min along the path) of each column of :func:`reading_sensitivity`:
    µm of the reading's range per µm (per µrad) of that error alone."""
    s = np.asarray(sensitivity, float)
    return s.max(axis=0) - s.min(axis=0)


@dataclass(frozen=True)
class BallbarRange:
    """The figure of one ballbar set-up: the range of the reading along the path, with U.

    Attributes
    ----------
    label : str
    range, maximum, minimum : float, m
        Of the deviation readings (reported length − nominal length).
    U : float, m
        Expanded uncertainty of the range (k = ``budget.k``).
    budget : UncertaintyBudget
        In µm, parameter ``range``.
    scatter : float, m
        Type A standard deviation of the readings about the smooth fit.
    points : int
    """

    label: str
    range: float
    maximum: float
    minimum: float
    U: float
    budget: UncertaintyBudget
    scatter: float
    points: int

    def to_dict(self) -> dict:
        """Stable JSON keys, µm: ``label``, ``range_um``, ``U_um``, ``k``, ``max_um``,
        ``min_um``, ``scatter_um``, ``points``, ``budget``."""
        return {"label": self.label, "range_um": self.range * 1e6, "U_um": self.U * 1e6,
                "k": self.budget.k, "max_um": self.maximum * 1e6, "min_um": self.minimum * 1e6,
                "scatter_um": self.scatter * 1e6, "points": self.points,
                "budget": self.budget.to_json()}

    def __str__(self) -> str:
        return (f"{self.label}: range {self.range * 1e6:.2f} µm, U = {self.U * 1e6:.2f} µm "
                f"(k = {self.budget.k:g}), readings {self.minimum * 1e6:+.2f} … "
                f"{self.maximum * 1e6:+.2f} µm, {self.points} points")


def evaluate_ballbar(deviation, *, noise: float, u_gain: float = 0.0, length: float = 0.1,
                     drift: float = 0.0, alpha: float = ALPHA_BAR, u_length: float = 0.0,
                     label: str = "ballbar") -> BallbarRange:
    """Range of the ballbar's deviation readings along the path, with its uncertainty (module
    docstring, 'Uncertainty of the range').

    Parameters
    ----------
    deviation : array_like, shape (N,), m
        Reported length − nominal length at each point, in path order.
    noise : float, m
        The ballbar's stated standard deviation of one reading.
    u_gain : float
        Relative standard uncertainty of the transducer's calibration (scale).
    length : float, m
        The bar's nominal length.
    drift : float, K
        Change of the bar's temperature during the run (stated or assumed).
    alpha : float, 1/K
        The bar body's expansion coefficient.
    u_length : float, m
        Standard uncertainty of the calibrator's length (acts on no range).
    label : str

    Raises
    ------
    InputError
        Fewer than 3 readings, a reading that is not finite, a negative input.

    Examples
    --------
    >>> r = evaluate_ballbar([0.0, 20e-6, 40e-6, 20e-6, 0.0], noise=0.1e-6)
    >>> round(r.range * 1e6, 6), r.U * 1e6 > 0.4
    (40.0, True)
    """
    d = np.asarray(deviation, float).ravel()
    if d.size < 3:
        raise InputError(f"{label}: {d.size} readings; a range needs at least 3")
    if not np.all(np.isfinite(d)):
        raise InputError(f"{label}: reading {int(np.argmin(np.isfinite(d))) + 1} is not a "
                         "finite number")
    for key, v in (("noise", noise), ("u_gain", u_gain), ("length", length), ("drift", drift),
                   ("alpha", alpha), ("u_length", u_length)):
        if not (math.isfinite(v) and v >= 0):
            raise InputError(f"{label}: {key} = {v!r} must be a finite number >= 0")
    rng = float(d.max() - d.min())
    s = max(float(noise), _scatter(d))
    um = 1e6
    contributors = [
        Contributor("u_NOISE", "reading noise at the two extremes, with the bias of picking "
                    "the largest", 2.0 * s * um, "normal",
                    "JCGM 100:2008 5.1.2 and 6.3.1 (two extremes, each s, added linearly)",
                    f"2 × max(stated {noise * um:.3g} µm, Type A {_scatter(d) * um:.3g} µm)",
                    ("range",)),
        Contributor("u_GAIN", "transducer calibration (scale)", rng * u_gain * um, "normal",
                    "ballbar calibration certificate", f"{u_gain:g} × range {rng * um:.3g} µm",
                    ("range",)),
        Contributor("u_DRIFT", "bar length drift during the run", alpha * length * drift
                    / math.sqrt(3) * um, "rectangular", "ISO 230-4:2005 A (thermal), this budget",
                    f"{alpha * 1e6:g} µm/(m·K) × {length * 1e3:g} mm × {drift:g} K / √3",
                    ("range",)),
        Contributor("u_LENGTH", "calibrator length (a constant on every reading)", 0.0,
                    "normal", "sensitivity 0 on a range",
                    f"u = {u_length * um:.3g} µm × sensitivity 0", ("range",)),
    ]
    notes = ("the range of noisy readings is biased upwards by about one scatter at each end; "
             "u_NOISE holds that bias (2 s)",)
    budget = combine(contributors, "um", parameters=["range"], notes=notes)
    return BallbarRange(label, rng, float(d.max()), float(d.min()),
                        budget.expanded["range"] * 1e-6, budget, _scatter(d), int(d.size))


def _scatter(d: np.ndarray) -> float:
    """Type A standard deviation of readings about a Legendre fit in the path parameter."""
    n = d.size
    deg = min(SMOOTH_DEGREE, n - 2)
    if deg < 1 or n - deg - 1 < 1:
        return 0.0
    t = np.linspace(-1.0, 1.0, n)
    fit = np.polynomial.legendre.Legendre.fit(t, d, deg)
    res = d - fit(t)
    return float(np.sqrt(res @ res / (n - deg - 1)))


def _rotations(u, theta) -> np.ndarray:
    """Rotation matrices (N, 3, 3) about unit ``u`` by ``theta`` (N,), right-handed."""
    th = np.asarray(theta, float)
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    s, c = np.sin(th)[:, None, None], np.cos(th)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


def _dT(name, geometry, p, q_c, q_t, u_c, u_t, r_c, r_t, v_c, x1, v_t) -> np.ndarray:
    """Machine-frame change of ``T(p)`` per unit of location error ``name`` (N, 3)."""
    if name not in _POSITION and name not in _ORIENT and name not in _ZERO:
        raise InputError(f"location error {name!r} is not one of "
                         f"{', '.join(geometry.names + SQUARENESS)}")
    if name not in geometry.names:
        raise InputError(f"location error {name!r} is not one of a {geometry.tilt}/C machine: "
                         f"{', '.join(geometry.names)}")
    eye = np.eye(3)
    if name in _POSITION:
        i, which = _POSITION[name]
        d = eye[i]
        if which == "C":
            return np.einsum("nij,nj->ni", r_t, d - np.einsum("nij,j->ni", r_c, d))
        return d - np.einsum("nij,j->ni", r_t, d)
    if name in _ZERO:
        if _ZERO[name] == "C":
            return np.einsum("nij,nj->ni", r_t, np.cross(u_c, v_c))
        return np.cross(u_t, v_t)
    i, which = _ORIENT[name]
    k = eye[i]
    if which == "C":
        inner = np.cross(k, v_c) - np.einsum("nij,j->ni", r_c, np.cross(k, p - q_c))
        return np.einsum("nij,nj->ni", r_t, inner)
    return np.cross(k, v_t) - np.einsum("nij,nj->ni", r_t, np.cross(k, x1 - q_t))

