"""The simulated measurement chain of a rotary calibration (private to rotary_calibration).

:class:`Rig` holds the machine, the set-up and the two instruments, and performs the steps of
:func:`axiscal.procedures.rotary_calibration.simulate_rotary_calibration`: the set-up readings,
the datum, the optics self-calibration and the capture, whose records it returns
(:class:`RotaryCapture`, :class:`OffAxisRecord`, re-exported by ``rotary_calibration``). Every reading is computed from the
physical state (axis angle, calibrator shaft angle, reflector pose, beam directions); no error
formula of the paper is added on top, so equation 1 and the read-head cancellation are results.

The rig drives the simulators' vectorised methods (``path_difference``, ``check_signal``,
``read``; ``move``, ``read``), not the one-reading interfaces a real driver implements
(:class:`~axiscal.instruments.laser.AngularLaser`,
:class:`~axiscal.instruments.rotary_calibrator.RotaryCalibrator`): a whole test is one array
operation. :class:`~axiscal.instruments.laser.SimulatedAngularLaser` gives the same readings one
at a time (tests/instruments/test_review_protocols.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import SignalLossError
from axiscal.physics.interferometry import optics_self_calibration
from axiscal.physics.misalignment import reflector_pose
from axiscal.procedures.rotary_offaxis import (
    OffAxisAlignment, YawProfile, part_program, subtract_linear_yaw, three_point_alignment,
    yaw_subtraction_sign)
from axiscal.procedures.rotary_setup import setup_checks
from axiscal.units import ARCSEC, DEG

TWO_PI = 2.0 * math.pi
#: Largest step, radians, at which :meth:`Rig.check_moves` follows a move for loss of signal.
MOVE_CHECK_STEP = 0.25 * DEG


@dataclass(frozen=True, eq=False)
class RotaryCapture:
    """What the capture measured, reading by reading (in the order of the plan's steps).

    Attributes
    ----------
    dataset : PositioningDataset
        Measured deviations, deg / arcsec.
    truth : PositioningDataset
        True deviations relative to the datum, same layout.
    commanded, laser, calibrator : ndarray, radians
        Target, laser reading and calibrator angle (sense of the axis under test) per reading.
    time : ndarray, seconds
    linear_positions : ndarray or None, metres
        Off axis: the linear axis's commanded position per reading.
    """

    dataset: PositioningDataset
    truth: PositioningDataset
    commanded: np.ndarray
    laser: np.ndarray
    calibrator: np.ndarray
    time: np.ndarray
    linear_positions: np.ndarray | None = None

    @property
    def max_laser_angle(self) -> float:
        """Largest |laser reading| during the capture, radians."""
        return float(np.max(np.abs(self.laser)))


@dataclass(frozen=True, eq=False)
class OffAxisRecord:
    """Off-axis by-products: the alignment fit, the part program and the yaw correction."""

    alignment: OffAxisAlignment
    program: str
    profile: YawProfile
    sign: int
    yaw_removed: float  # largest |correction| applied, radians


def read_setup(setup, rng: np.random.Generator, offaxis=None):
    """Simulated readings of the set-up checks (dial gauge, shutter, centring) -> SetupCheck."""
    tir = abs(2.0 * setup.tir_radius * setup.mount_tilt + rng.normal(0.0, setup.dial_noise))
    ret = abs(2.0 * setup.laser_distance * (setup.beam_tilt + setup.target_misalignment)
              + rng.normal(0.0, setup.shutter_noise))
    if offaxis is None:
        centring = abs(math.hypot(*setup.lateral_offset) + rng.normal(0.0, setup.centring_noise))
    else:  # off axis the beam is kept on the reflector by the alignment: its error is the offset
        centring = 2.0 * offaxis.alignment_noise
    return setup_checks(tir, ret, centring, setup.tir_radius, setup.laser_distance)


@dataclass(frozen=True)
class Datum:
    """State at the datum: axis actual angle, calibrator command and reading, path difference."""

    theta: float
    phi: float
    psi: float
    dl: float
    y: float
    k: float = 1.0


class Rig:
    """The simulated calibration rig: machine, set-up, laser, calibrator (and off-axis linear axis)."""

    def __init__(self, axis, setup, laser, calibrator, offaxis=None):
        self.axis, self.setup, self.laser, self.cal, self.off = axis, setup, laser, calibrator, offaxis
        self.alignment = None
        if offaxis is not None:
            self.offset = (offaxis.radius * math.cos(offaxis.phase),
                           offaxis.radius * math.sin(offaxis.phase))
        else:
            self.offset = tuple(setup.lateral_offset)

    # -- geometry ---------------------------------------------------------------------
    def _pose(self, theta, phi, y):
        """Reflector direction and centre, interferometer position and yaw for a state."""
        s = self.setup
        u, c = reflector_pose(theta, phi, s.alpha, s.eta, s.reflector_twist, s.reflector_height,
                              self.offset)
        if self.off is None:
            return u, c, np.array([1.0, 0.0, 0.0]), 0.0
        yy = np.atleast_1d(np.asarray(y, dtype=float))
        interferometer = np.stack([np.full_like(yy, self.off.interferometer_distance), yy,
                                   np.zeros_like(yy)], -1)
        return u, c, interferometer, self.off.beam_yaw + self.off.linear_yaw(yy)

    def path(self, theta, phi, y=None) -> np.ndarray:
        """Path difference (m) for actual axis and shaft angles; raises on loss of signal."""
        u, c, interferometer, yaw = self._pose(theta, phi, y)
        self.laser.check_signal(u, yaw)
        return self.laser.path_difference(u, c, interferometer, yaw)

    def check_moves(self, plan, datum: Datum) -> None:
        """Raise SignalLossError if the reflector leaves the laser's limit during any move.

        Every move of the plan (from the datum at 0°, overrun and approach moves included) is
        followed in steps of at most :data:`MOVE_CHECK_STEP`, not only its end: Renishaw, Interferometric calibration of rotary axes "only
        suitable ... over a range of about ±10°" holds all along the path, and a real laser
        loses the whole run when the beams are lost mid-move. With counter-rotation the
        calibrator is driven opposite to the axis during the move (Renishaw, Interferometric calibration of rotary axes: "as the axis under
        test is rotated ... the XR20 is driven in the opposite direction"). Commanded angles
        are used: the axis's errors (arcseconds) do not matter against a 10° limit.
        """
        steps = plan.steps()
        ends = np.concatenate(([0.0], [st.position for st in steps])) * DEG
        n = np.maximum(2, np.ceil(np.abs(np.diff(ends)) / MOVE_CHECK_STEP).astype(int) + 1)
        move = np.repeat(np.arange(len(steps)), n)
        frac = np.concatenate([np.linspace(0.0, 1.0, k) for k in n])
        cmd = ends[move] + frac * (ends[move + 1] - ends[move])
        phi = datum.phi - cmd if self.setup.counter_rotation else np.full_like(cmd, datum.phi)
        u, _, _, yaw = self._pose(datum.theta + cmd, phi, self.linear_position(cmd))
        turn = self.laser.turn(u, yaw)
        bad = np.flatnonzero(np.abs(turn) > self.laser.max_angle)
        if bad.size:
            k = int(move[bad[0]])
            st = steps[k]
            worst = turn[move == k][np.argmax(np.abs(turn[move == k]))]
            raise SignalLossError(
                f"laser signal lost during move {st.seq} of the plan ({st.kind} move of run "
                f"{st.run}, {math.degrees(ends[k]):g}° to {st.position:g}°): the reflector turns "
                f"{math.degrees(worst):+.1f}° from the beams (limit "
                f"±{math.degrees(self.laser.max_angle):g}°); a real laser loses the whole run: "
                "counter-rotate the calibrator to keep the reflector facing the laser, or reduce "
                "the travel or the overrun")

    def align(self, rng: np.random.Generator) -> None:
        """Off axis: the operator's three-point alignment (beam centred at three angles)."""
        th = np.asarray(self.off.alignment_angles, dtype=float)
        true_y = self.offset[0] * np.sin(th) + self.offset[1] * np.cos(th)
        self.alignment = three_point_alignment(th, true_y + rng.normal(0, self.off.alignment_noise, 3))

    def linear_position(self, theta):
        """Off axis: the commanded linear position for commanded angles; None on axis."""
        return None if self.alignment is None else self.alignment.position(theta)

    # -- datum and self-calibration ---------------------------------------------------
    def datum(self, rng: np.random.Generator) -> Datum:
        """Axis at 0° (approached +), reflector turned by the operator's datum misalignment."""
        if self.off is not None:
            self.align(rng)
        theta = float(self.axis.move(0.0, 1, rng, 0.0))
        return self._datum_at(theta, self.setup.datum_misalignment, 1.0, rng)

    def _datum_at(self, theta, phi_cmd, k, rng) -> Datum:
        phi = self.cal.move(phi_cmd, rng)
        y = self.linear_position(0.0)
        dl = float(self.path(theta, phi, y)[0])
        return Datum(theta, float(phi_cmd), float(self.cal.read(phi, rng)[0]), dl,
                     0.0 if y is None else float(y), k)

    def self_calibrate(self, datum: Datum, rng: np.random.Generator):
        """Optics calibration at 0, +5°, −5° of the calibrator; re-datum square to the beams."""
        step = 5.0 * DEG
        cmds = datum.phi + np.array([step, -step, 0.0])
        phi = self.cal.move(cmds, rng)
        ref = self.cal.read(phi, rng) - datum.psi           # the calibrator's own reading of the steps
        y = None if self.alignment is None else np.full(3, datum.y)
        dl = self.path(np.full(3, datum.theta), phi, y) - datum.dl
        dl = dl + rng.normal(0.0, self.laser.noise * self.laser.spacing, 3)
        cal = optics_self_calibration(dl[0], dl[1], self.laser.nominal_spacing, ref[0], ref[1],
                                      dl[2], ref[2])
        return cal, self._datum_at(datum.theta, datum.phi - cal.datum_misalignment, cal.k, rng)

    # -- capture ----------------------------------------------------------------------
    def capture(self, plan, datum: Datum, rng: np.random.Generator, speed: float,
                metadata: Metadata | None):
        """Execute the plan; return (RotaryCapture, OffAxisRecord or None)."""
        self.check_moves(plan, datum)
        steps = plan.steps()
        pos = np.array([s.position for s in steps])
        is_meas = np.array([s.kind == "measure" for s in steps])
        moves = np.abs(np.diff(np.concatenate(([0.0], pos)))) / speed
        time = np.cumsum(moves + plan.dwell * is_meas)[is_meas]
        meas = [s for s in steps if s.kind == "measure"]
        target = np.array([s.position for s in meas]) * DEG
        direction = np.array([1 if s.direction == "+" else -1 for s in meas])
        theta = self.axis.move(target, direction, rng, time)
        phi = self.cal.move(datum.phi - target if self.setup.counter_rotation
                            else np.full(target.shape, datum.phi), rng)
        psi = self.cal.read(phi, rng)
        y = self.linear_position(target)
        dl = self.path(theta, phi, y) - datum.dl
        laser = self.laser.read(dl, datum.k, self.setup.periscope_drift * time, rng)
        calib = -(psi - datum.psi)
        dev = laser + calib - target
        record = None
        if self.off is not None:
            dev, record = self._remove_yaw(plan, dev, y, datum, rng)
        truth = theta - target - datum.theta
        meta = metadata or Metadata(axis=plan.axis)
        ds = _dataset(plan, meas, dev / ARCSEC, meta)
        tr = _dataset(plan, meas, truth / ARCSEC, meta)
        for a in (target, laser, calib, time):
            a.flags.writeable = False
        return RotaryCapture(ds, tr, target, laser, calib, time, y), record

    def _remove_yaw(self, plan, dev, y, datum, rng):
        off = self.off
        lo, hi = float(np.min(y)) - 5e-3, float(np.max(y)) + 5e-3
        grid = np.linspace(lo, hi, 41)
        sense = (-1 if off.profile_moving_optic == "interferometer" else 1) * off.profile_direction_sign
        readings = sense * (off.linear_yaw(grid) - off.linear_yaw(grid[0]))
        readings = readings + rng.normal(0.0, off.profile_noise, grid.size)
        profile = YawProfile(grid, readings, off.profile_moving_optic, off.profile_direction_sign)
        sign = yaw_subtraction_sign(profile, "interferometer", 1, off.stated_sign)
        corrected = subtract_linear_yaw(dev, y, datum.y, profile, sign)
        program = part_program(plan, self.alignment, off.rotary_letter, off.linear_letter, off.feed)
        return corrected, OffAxisRecord(self.alignment, program, profile, sign,
                                        float(np.max(np.abs(corrected - dev))))


def _dataset(plan, meas, values, meta) -> PositioningDataset:
    up = np.full((plan.targets.size, plan.runs), np.nan)
    down = np.full((plan.targets.size, plan.runs if plan.bidirectional else 0), np.nan)
    for s, v in zip(meas, values):
        (up if s.direction == "+" else down)[s.target_index, s.run - 1] = v
    return PositioningDataset(AxisKind.ROTARY, plan.targets, up, down, "deg", "arcsec", meta)
