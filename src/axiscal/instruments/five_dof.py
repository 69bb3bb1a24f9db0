"""The five-DOF optical measuring system of Optics Express 2018, Five-DOF motion errors of a rotary axis as geometry, and its reconstruction.

Frames (all SI, right-handed, ISO 841 signs):

* **axis frame**: Z along the target axis of rotation, origin on the table face; X the nominal
  beam direction (from the measurement unit towards the sensitive unit), Y horizontal across it.
* **beam frame**: the measurement unit's frame. Its origin is the plane of M1, the QDs and the
  drift pivot, at ``x = -l`` and height ``height``; it is turned from the axis frame by the
  mounting errors ``beam_yaw`` (about Z) and ``beam_pitch`` (about Y).
* **unit frame**: the sensitive unit on the reference axis. RR1's apex is at
  ``(0, +h/2, height)``, RR2's at ``(0, -h/2, height)``; BS1 (normal ``-X``) is on RR1's base.

The target axis turns by θ + εz and carries the reference axis (mounted with an eccentricity and
a tilt); the reference axis turns back by θref (Optics Express 2018, Five-DOF motion errors of a rotary axis section 2.1). The sensitive unit's world
pose is traced through the optics exactly (no small-angle step):

* a corner cube maps the ray ``(p, u)`` to ``(2c − p, −u)`` (point inversion through its apex c);
* a plane mirror reflects ``u`` to ``u − 2 (u·n) n``;
* a lens of focal length f puts a beam of direction d at ``f · d_t / |d_x|`` in its focal plane.

Detector senses (the fold optics M2 in front of PSD1 and the split to PSD2 decide them) are
chosen so that Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 1, 2, 4, 5 and 7 hold as printed: PSD1 reads ``(-d_y, +d_z)``,
PSD2 ``(-d_y, -d_z)`` of the returning direction d; the QDs read the return spot in beam-frame
(Y, Z). The ± of eqs. 8-9 then follows (see :mod:`axiscal.physics.five_dof`).

Mounting errors that make crosstalk appear (:class:`Mounting`): beam yaw and pitch against the
axis, eccentricity and tilt of the reference axis on the target table, offset of the sensitive
unit from the reference axis, rotation of each detector about its normal, focal-length and
reflector-separation errors. Detector noise, ADC quantisation and air-induced beam jitter
(independent per beam) make the readings noisy.

References
----------
Optics Express 2018, Five-DOF motion errors of a rotary axis, section 2 (Figs. 2-3, eqs. 1-9) and section 3 (parts: QD
QP50-6SD2-DIAG 0.08 µm, PSD DL16-7-PCBA3 0.5 µm, f = 200 mm, h = 30 mm, l = 250 mm).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np

from axiscal.errors import InputError
from axiscal.machines.rotary import Pose
from axiscal.physics import five_dof as eq
from axiscal.units import ARCSEC, UM

__all__ = ["Detector", "Mounting", "FiveDofSystem", "Readings", "FiveErrors", "reconstruct",
           "motion_at_unit", "rotation", "FiveDofSensor", "SimulatedFiveDofSensor"]


@runtime_checkable
class FiveDofSensor(Protocol):
    """What the five-DOF measuring system does for a procedure (real driver or simulator).

    A real driver samples the four detectors' spot positions; the reconstruction
    (:func:`reconstruct`) turns them into the five errors. The simulator
    :class:`SimulatedFiveDofSensor` implements it on :class:`FiveDofSystem`;
    :mod:`axiscal.procedures.motion_errors` calls the same physics in vectorised form
    (:meth:`FiveDofSystem.read` over all angles at once) for speed.
    """

    def read_detectors(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Spot positions (Y, Z) on PSD1, PSD2, QD1 and QD2 now, each of shape (2,), metres."""
        ...


@dataclass(frozen=True)
class Detector:
    """A position detector (PSD or quadrant detector).

    Attributes
    ----------
    resolution : float, metres
        The data-sheet resolution (used for the resolutions of Optics Express 2018, Five-DOF motion errors of a rotary axis section 3).
    noise : float, metres
        Standard deviation of the white noise of one recorded reading, per axis.
    adc_step : float, metres
        Quantisation step of the recorded reading (0: none).
    rotation : float, radians
        Mounting rotation of the detector about its normal (mixes its Y and Z readings).
    """

    resolution: float
    noise: float = 0.0
    adc_step: float = 0.0
    rotation: float = 0.0

    def __post_init__(self) -> None:
        for name in ("resolution", "noise", "adc_step"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v >= 0):
                raise InputError(f"detector {name} = {v!r} m must be a finite number >= 0")
        if not self.resolution > 0:
            raise InputError(f"detector resolution = {self.resolution!r} m must be > 0")

    def read(self, y, z, rng: np.random.Generator | None):
        """Turn true spot positions (metres) into recorded readings ``(N, 2)``."""
        c, s = np.cos(self.rotation), np.sin(self.rotation)
        out = np.stack([c * y - s * z, s * y + c * z], axis=-1)
        if rng is not None and self.noise > 0:
            out = out + rng.normal(0.0, self.noise, out.shape)
        if self.adc_step > 0:
            out = np.round(out / self.adc_step) * self.adc_step
        return out


#: Optics Express 2018, Five-DOF motion errors of a rotary axis section 3 detectors with the noise levels of this project (see FiveDofSystem Notes).
PSD_DL16 = Detector(resolution=0.5 * UM, noise=0.5 * UM / 6, adc_step=7e-3 / 2**16)
QD_QP50 = Detector(resolution=0.08 * UM, noise=0.08 * UM / 6, adc_step=160 * UM / 2**16)


@dataclass(frozen=True)
class Mounting:
    """Mounting and manufacturing errors of the set-up (all SI; zero = perfect).

    Attributes
    ----------
    beam_yaw, beam_pitch : float, radians
        Beam direction against the axis frame's X (about Z and about Y).
    ref_eccentricity : tuple of float, metres
        Centre of the reference axis on the target table (x, y in the table frame).
    ref_tilt : tuple of float, radians
        Tilt of the reference axis against the target axis (about X, about Y).
    unit_offset : tuple of float, metres
        Centre of the reflector pair from the reference axis (x, y in the unit frame).
    focal_error : float
        Relative error of both focal lengths (actual = nominal · (1 + focal_error)).
    separation_error : float, metres
        Actual minus nominal separation of RR1 and RR2.
    """

    beam_yaw: float = 0.0
    beam_pitch: float = 0.0
    ref_eccentricity: tuple[float, float] = (0.0, 0.0)
    ref_tilt: tuple[float, float] = (0.0, 0.0)
    unit_offset: tuple[float, float] = (0.0, 0.0)
    focal_error: float = 0.0
    separation_error: float = 0.0

    @classmethod
    def realistic(cls) -> "Mounting":
        """Errors a careful set-up leaves: 1 arcmin beam, 10 µm / 10 arcsec reference axis,
        0.5 mm unit offset, 0.5 % focal length, 0.1 mm separation (detector rotations: see
        :meth:`FiveDofSystem.with_realistic_mounting`)."""
        am = 60 * ARCSEC
        return cls(beam_yaw=am, beam_pitch=am, ref_eccentricity=(10 * UM, -6 * UM),
                   ref_tilt=(10 * ARCSEC, -8 * ARCSEC), unit_offset=(0.5e-3, 0.3e-3),
                   focal_error=0.005, separation_error=0.1e-3)


@dataclass(frozen=True)
class Readings:
    """Recorded readings of one measurement (N positions or samples), metres and radians.

    ``psd1``, ``psd2``, ``qd1``, ``qd2`` are ``(N, 2)`` arrays of (Y, Z) spot positions;
    ``theta`` the commanded target angle and ``theta_ref`` the reference encoder reading.
    """

    theta: np.ndarray
    theta_ref: np.ndarray
    psd1: np.ndarray
    psd2: np.ndarray
    qd1: np.ndarray
    qd2: np.ndarray

    def __len__(self) -> int:
        return int(np.size(self.theta))


@dataclass(frozen=True)
class FiveErrors:
    """The five measured (or true) errors at N positions, radians and metres.

    Attributes
    ----------
    theta : ndarray, radians
    ez, ey, ex : ndarray, radians
        Angular positioning error and tilt error motions about Y and X.
    dy, dz : ndarray, metres
        Radial (along Y) and axial error motions at the sensitive unit.
    """

    theta: np.ndarray
    ez: np.ndarray
    ey: np.ndarray
    ex: np.ndarray
    dy: np.ndarray
    dz: np.ndarray

    CHANNELS = ("ez", "ey", "ex", "dy", "dz")

    def relative(self, index: int = 0) -> "FiveErrors":
        """Every channel minus its value at ``index`` (a measurement's zero)."""
        return FiveErrors(self.theta, *(getattr(self, c) - getattr(self, c)[index]
                                        for c in self.CHANNELS))

    def __sub__(self, other: "FiveErrors") -> "FiveErrors":
        return FiveErrors(self.theta, *(getattr(self, c) - getattr(other, c) for c in self.CHANNELS))

    def __str__(self) -> str:
        lines = ["θ [deg]   εz [″]   εy [″]   εx [″]   δy [µm]  δz [µm]"]
        for i in range(np.size(self.theta)):
            lines.append(f"{np.degrees(self.theta[i]):7.2f} {self.ez[i] / ARCSEC:8.2f} "
                         f"{self.ey[i] / ARCSEC:8.2f} {self.ex[i] / ARCSEC:8.2f} "
                         f"{self.dy[i] / UM:8.3f} {self.dz[i] / UM:8.3f}")
        return "\n".join(lines)


@dataclass(frozen=True)
class FiveDofSystem:
    """The measuring system of Optics Express 2018, Five-DOF motion errors of a rotary axis with its parts and mounting (SI units).

    Attributes
    ----------
    f1, f2 : float, metres
        Focal lengths of L1 (PSD1) and L2 (PSD2); 200 mm in the paper.
    h : float, metres
        Separation of RR1 and RR2 (and of the two beams); 30 mm.
    l : float, metres
        Working distance from the measurement unit to the sensitive unit; 250 mm.
    height : float, metres
        Height of the reflectors above the target table (where δy, δz are measured).
    psd1, psd2, qd1, qd2 : Detector
    mounting : Mounting
    beam_jitter : float, radians
        Standard deviation of the air-induced pointing jitter of each beam, independent between
        the beams and between readings (not common-path, so not compensated).

    Notes
    -----
    Noise levels (documented choice): a data-sheet "resolution" is read as the ±3σ band of one
    recorded reading, so σ = resolution/6 (PSD 0.083 µm, QD 0.013 µm); ADC quantisation is 16 bit
    over the PSD's 7 mm and over the QDs' ±80 µm calibrated range (Optics Express 2018, Five-DOF motion errors of a rotary axis section 3.1). The beam
    jitter (0.07 µrad) is not a data-sheet figure: it is chosen so that the simulated εx stability
    matches the paper's 0.19 arcsec (the detectors alone give 0.065 arcsec), i.e. air turbulence
    over 250 mm that the common path cannot remove because it differs between the two beams.
    """

    f1: float = 0.200
    f2: float = 0.200
    h: float = 0.030
    l: float = 0.250
    height: float = 0.050
    psd1: Detector = PSD_DL16
    psd2: Detector = PSD_DL16
    qd1: Detector = QD_QP50
    qd2: Detector = QD_QP50
    mounting: Mounting = field(default_factory=Mounting)
    beam_jitter: float = 0.07e-6

    def __post_init__(self) -> None:
        for name in ("f1", "f2", "h", "l"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise InputError(f"five-DOF system {name} = {v!r} m must be positive")
        if not (np.isfinite(self.beam_jitter) and self.beam_jitter >= 0):
            raise InputError(f"beam_jitter = {self.beam_jitter!r} rad must be >= 0")

    def resolutions(self) -> eq.Resolutions:
        """Resolutions of the five errors from the parts (Optics Express 2018, Five-DOF motion errors of a rotary axis section 3)."""
        return eq.resolutions(self.f1, self.h, self.psd1.resolution, self.qd1.resolution)

    def with_realistic_mounting(self) -> "FiveDofSystem":
        """The same system with :meth:`Mounting.realistic` and detectors turned by 0.5°."""
        from dataclasses import replace

        turn = np.radians(0.5)
        return replace(self, mounting=Mounting.realistic(),
                       psd1=replace(self.psd1, rotation=turn), psd2=replace(self.psd2, rotation=-turn),
                       qd1=replace(self.qd1, rotation=turn), qd2=replace(self.qd2, rotation=-0.6 * turn))

    def noiseless(self) -> "FiveDofSystem":
        """The same geometry with no detector noise, quantisation or jitter."""
        from dataclasses import replace

        quiet = {k: replace(getattr(self, k), noise=0.0, adc_step=0.0)
                 for k in ("psd1", "psd2", "qd1", "qd2")}
        return replace(self, beam_jitter=0.0, **quiet)

    def read(self, pose: Pose, theta_ref, drift=(0.0, 0.0),
             rng: np.random.Generator | None = None) -> "Readings":
        """Detector readings for the target axis at ``pose`` and the reference axis at θref.

        Parameters
        ----------
        pose : Pose
            True six-DOF error of the target axis at commanded angles ``pose.theta`` (radians,
            metres; error motions of the table frame's origin).
        theta_ref : array_like, radians
            Actual angle the reference axis turned back (the encoder reading is the procedure's
            business).
        drift : tuple of array_like, radians
            Angular drift (Δβ, Δγ) of the beam: its direction's Y and Z components.
        rng : numpy.random.Generator, optional
            Noise source; None for noise-free readings.
        """
        th = np.atleast_1d(np.asarray(pose.theta, float))
        n = th.size
        tref = np.broadcast_to(np.asarray(theta_ref, float), (n,))
        world_r, world_p = self._unit_in_beam_frame(pose, th, tref)
        beta = np.broadcast_to(np.asarray(drift[0], float), (n,))
        gamma = np.broadcast_to(np.asarray(drift[1], float), (n,))
        u1 = self._beam(beta, gamma, n, rng)
        u2 = self._beam(beta, gamma, n, rng)
        half = 0.5 * self.h
        qd1 = _corner_cube_spot(world_p[0], u1, np.array([0.0, half, 0.0]))
        qd2 = _corner_cube_spot(world_p[1], u2, np.array([0.0, -half, 0.0]))
        normal = world_r @ np.array([-1.0, 0.0, 0.0])
        r = u1 - 2.0 * np.einsum("ij,ij->i", u1, normal)[:, None] * normal
        f1 = self.f1 * (1 + self.mounting.focal_error)
        f2 = self.f2 * (1 + self.mounting.focal_error)
        psd1 = (-f1 * r[:, 1] / np.abs(r[:, 0]), f1 * r[:, 2] / np.abs(r[:, 0]))
        d2 = -u2
        psd2 = (-f2 * d2[:, 1] / np.abs(d2[:, 0]), -f2 * d2[:, 2] / np.abs(d2[:, 0]))
        return Readings(
            theta=th, theta_ref=np.array(tref),
            psd1=self.psd1.read(*psd1, rng), psd2=self.psd2.read(*psd2, rng),
            qd1=self.qd1.read(qd1[:, 1], qd1[:, 2], rng), qd2=self.qd2.read(qd2[:, 1], qd2[:, 2], rng),
        )

    def _beam(self, beta, gamma, n, rng):
        jy = jz = 0.0
        if rng is not None and self.beam_jitter > 0:
            jy, jz = rng.normal(0.0, self.beam_jitter, (2, n))
        u = np.stack([np.ones(n), beta + jy, gamma + jz], axis=-1)
        return u / np.linalg.norm(u, axis=-1, keepdims=True)

    def _unit_in_beam_frame(self, pose: Pose, th, tref):
        """Rotation (N,3,3) of the unit and apex positions [(N,3), (N,3)] in the beam frame."""
        m = self.mounting
        n = th.size
        bc = lambda a: np.broadcast_to(np.asarray(a, float), (n,))  # noqa: E731
        r_target = rotation("x", bc(pose.ex)) @ rotation("y", bc(pose.ey)) @ rotation("z", th + bc(pose.ez))
        r_mount = rotation("x", m.ref_tilt[0]) @ rotation("y", m.ref_tilt[1])
        r_unit = r_target @ r_mount @ rotation("z", -tref)
        d = np.stack([bc(pose.dx), bc(pose.dy), bc(pose.dz)], axis=-1)
        ecc = np.array([m.ref_eccentricity[0], m.ref_eccentricity[1], 0.0])
        r_beam_t = (rotation("z", m.beam_yaw) @ rotation("y", m.beam_pitch)).T
        origin = np.array([-self.l, 0.0, self.height])
        half = 0.5 * (self.h + m.separation_error)
        apexes = []
        for y in (half, -half):
            p_unit = np.array([m.unit_offset[0], m.unit_offset[1] + y, self.height])
            p_table = ecc + np.einsum("ij,nj->ni", r_mount, (rotation("z", -tref) @ p_unit))
            p_world = d + np.einsum("nij,nj->ni", r_target, p_table)
            apexes.append(np.einsum("ij,nj->ni", r_beam_t, p_world - origin))
        return r_beam_t @ r_unit, apexes


def _corner_cube_spot(apex, u, start):
    """Return-spot (beam frame, plane x = 0) of the ray from ``start`` along ``u`` (N,3)."""
    s = 2.0 * apex[:, 0] / u[:, 0]
    spot = 2.0 * apex - start - s[:, None] * u
    return spot - start


def rotation(axis: str, angle):
    """Rotation matrices about ``axis`` ('x', 'y' or 'z') by ``angle`` (radians, array -> (N,3,3))."""
    a = np.asarray(angle, float)
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    rows = {"x": [[o, z, z], [z, c, -s], [z, s, c]],
            "y": [[c, z, s], [z, o, z], [-s, z, c]],
            "z": [[c, -s, z], [s, c, z], [z, z, o]]}[axis]
    m = np.array(rows, dtype=float)
    return np.moveaxis(m, (0, 1), (-2, -1)) if a.ndim else m


def motion_at_unit(pose: Pose, height: float) -> FiveErrors:
    """The true five errors at the sensitive unit (on the axis at ``height``), SI units.

    The reflectors sit at ``(0, 0, height)``; a tilt εx moves them by ``-height·εx`` along Y, so
    the radial error motion seen there is ``δy − height·εx`` (ISO 230-7 radial error motion at
    that axial location). δz, εx, εy, εz are those of the axis.
    """
    th = np.asarray(pose.theta, float)
    bc = lambda a: np.broadcast_to(np.asarray(a, float), th.shape).copy()  # noqa: E731
    return FiveErrors(th, bc(pose.ez), bc(pose.ey), bc(pose.ex),
                      bc(pose.dy) - height * bc(pose.ex), bc(pose.dz))


def reconstruct(readings: Readings, system: FiveDofSystem, compensate: bool = True,
                zero: int = 0, drift_window: int = 1) -> tuple[FiveErrors, np.ndarray]:
    """The five errors from the readings by Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 1-9 (nominal f1, f2, h, l).

    Parameters
    ----------
    readings : Readings
    system : FiveDofSystem
        Its nominal f1, f2, h and l are used (the reconstruction does not know mounting errors).
    compensate : bool
        Apply the common-path drift compensation (eqs. 7-9); False shows the raw eqs. 1-6.
    zero : int
        Index of the reading taken as the zero of every spot ("change in position").
    drift_window : int
        Odd number of consecutive PSD2 readings averaged (centred) for Δβ, Δγ: the drift is
        slow (Optics Express 2018, Five-DOF motion errors of a rotary axis section 2.4), so a short mean cuts PSD2's noise. 1 = no averaging.

    Returns
    -------
    errors : FiveErrors
        δy and δz are the mean of QD1 and QD2 (the two expressions of eqs. 4-5 averaged: this
        refers δz to the midpoint of the reflectors, free of εx·h/2).
    drift : ndarray, shape (N, 2), radians
        Δβ, Δγ from eq. 7.
    """
    if not (isinstance(drift_window, int) and drift_window >= 1 and drift_window % 2 == 1):
        raise InputError(f"drift_window = {drift_window!r} must be an odd whole number >= 1")
    if not 0 <= zero < len(readings):
        raise InputError(f"zero index {zero} is outside the {len(readings)} readings")
    rel = {k: getattr(readings, k) - getattr(readings, k)[zero] for k in ("psd1", "psd2", "qd1", "qd2")}
    drift = eq.beam_drift(_moving_mean(rel["psd2"], drift_window), system.f2)
    dref = readings.theta_ref - readings.theta_ref[zero]
    dth = readings.theta - readings.theta[zero]
    ez = eq.positioning_error(rel["psd1"][:, 0], system.f1, dref, dth)
    ey = eq.autocollimation_angle(rel["psd1"][:, 1], system.f1)
    dy1, dz1 = (eq.retroreflector_displacement(rel["qd1"][:, i]) for i in (0, 1))
    dy2, dz2 = (eq.retroreflector_displacement(rel["qd2"][:, i]) for i in (0, 1))
    ex = eq.tilt_from_quadrants(rel["qd1"][:, 1], rel["qd2"][:, 1], system.h)
    dy, dz = 0.5 * (dy1 + dy2), 0.5 * (dz1 + dz2)
    if compensate:
        ez = eq.compensate_angle(ez, drift[:, 0], +1)
        ey = eq.compensate_angle(ey, drift[:, 1], -1)
        dy = eq.compensate_displacement(dy, drift[:, 0], system.l)
        dz = eq.compensate_displacement(dz, drift[:, 1], system.l)
    return FiveErrors(np.array(readings.theta), ez, ey, ex, dy, dz), drift


def _moving_mean(a, window: int):
    if window == 1 or len(a) < 2:
        return a
    k = window // 2
    padded = np.concatenate([np.repeat(a[:1], k, axis=0), a, np.repeat(a[-1:], k, axis=0)])
    c = np.cumsum(np.concatenate([np.zeros((1, a.shape[1])), padded]), axis=0)
    return (c[window:] - c[:-window]) / window


class SimulatedFiveDofSensor:
    """The :class:`FiveDofSensor` interface on a simulated :class:`FiveDofSystem`.

    A small stateful adapter: the simulated world sets the pose of the target axis, the angle the
    reference axis turned back and the beam drift (:meth:`place`); :meth:`read_detectors`
    samples the detectors there, with noise drawn from ``rng`` (None: noise-free).
    """

    def __init__(self, system: FiveDofSystem, rng: np.random.Generator | None = None) -> None:
        self.system = system
        self.rng = rng
        self._state: tuple | None = None

    def place(self, pose: Pose, theta_ref: float, drift=(0.0, 0.0)) -> None:
        """The simulated world: a one-angle ``pose`` (radians, metres), the reference axis's
        actual angle θref (radians) and the beam drift (Δβ, Δγ) (radians)."""
        if np.size(pose.theta) != 1:
            raise InputError(f"place() takes the pose at one angle, not {np.size(pose.theta)}")
        self._state = (pose, float(theta_ref), (float(drift[0]), float(drift[1])))

    def read_detectors(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Spot positions (Y, Z) on PSD1, PSD2, QD1, QD2, metres."""
        if self._state is None:
            raise InputError("simulated five-DOF sensor: no pose placed; call place(pose, "
                             "theta_ref) first")
        pose, tref, drift = self._state
        r = self.system.read(pose, tref, drift, self.rng)
        return r.psd1[0], r.psd2[0], r.qd1[0], r.qd2[0]
