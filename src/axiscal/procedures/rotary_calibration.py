"""Rotary axis calibration with an angular interferometer and a counter-rotating calibrator.

The procedure of Renishaw, Interferometric calibration of rotary axes, run on simulated instruments. A run on real instruments would take
the same steps through the interfaces :class:`~axiscal.instruments.laser.AngularLaser` and
:class:`~axiscal.instruments.rotary_calibrator.RotaryCalibrator`; the simulated chain
(:mod:`axiscal.procedures._rotary_chain`) instead calls the simulators' vectorised physics
directly, for speed (a test checks the protocol adapters read the same):

1. **Set-up checks** (:func:`setup_checks`): the dial-gauge TIR on the calibrator's mounting ring
   gives the tilt of the mounting face, ``TIR/(2r)``; the offset of the beam returned by the
   reflector's rear target at the laser's shutter gives the laser's misalignment, ``d/(2L)``;
   the paper's thresholds (TIR < 0.04 mm at 50 mm, return within 1 mm at 1 m, axes coincident
   within ±0.5 mm) are checked and the bounds on α and β are carried into the error budget.
2. **Optics self-calibration** at 0°, +5°, −5° of the calibrator (K and the reflector's
   misalignment at the datum), then the calibrator turns the reflector square to the beams and
   the laser is re-datumed (:func:`axiscal.physics.interferometry.optics_self_calibration`).
3. **Capture**: the ISO 230-2 plan (:class:`~axiscal.procedures.positioning.TestPlan`: targets,
   runs, linear or pilgrim cycle, overrun, dwell) is executed; at every step the calibrator
   counter-rotates to minus the target, and at each target the deviation is
   ``(laser reading + calibrator angle) − target`` (Renishaw, Interferometric calibration of rotary axes: the target compared with "the
   arithmetic sum of the angular readings from the laser interferometer and the XR20"), with the
   calibrator's angle expressed in the sense of the axis under test.
4. The deviations form a :class:`~axiscal.datasets.PositioningDataset` (deg / arcsec) that
   :func:`axiscal.standards.iso230_2.evaluate` evaluates; the simulation also returns the truth.

Sign: issue 4 words the capture as "the target minus the sum"; ISO 230-2 (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 1)
defines the deviation as actual minus target, which is what this module returns (the truth tests
inject a known error and recover it with its sign).

The deviations are relative to the datum (the axis at 0° approached in the positive direction),
as a real capture is: the truth returned is the axis's true deviation minus its true deviation at
the datum.

References
----------
Renishaw, Interferometric calibration of rotary axes (whole); Yüksel et al., Position accuracy and repeatability calibration of turn tables §3 (targets every 45°, five
runs each way, 5° overrun, dwell, mounting tolerances).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.datasets import AxisKind, Metadata
from axiscal.errors import InputError
from axiscal.instruments.laser import PERISCOPE_SENSITIVITY, SimulatedAngularInterferometer
from axiscal.instruments.rotary_calibrator import SimulatedRotaryCalibrator
from axiscal.machines.error_functions import ZERO, HarmonicSeries
from axiscal.machines.rotary import RotaryAxis
from axiscal.physics.interferometry import OpticsCalibration, nonparallel_beam_error
from axiscal.physics.misalignment import misalignment_terms, peak_error
from axiscal.procedures._rotary_chain import OffAxisRecord, RotaryCapture
from axiscal.procedures.positioning import TestPlan
from axiscal.procedures.rotary_offaxis import OFFAXIS_EXTRA_ERROR
from axiscal.procedures.rotary_setup import (CALIBRATION_STEP, CALIBRATOR_PERPENDICULARITY, CENTRING_LIMIT,
                                            REFLECTOR_TWIST_TOLERANCE, RETURN_BEAM_LIMIT, SDE_LIMIT,
                                            TARGET_ALIGNMENT, TIR_LIMIT, SetupCheck, setup_checks)
from axiscal.units import ARCSEC, DEG, MM

__all__ = [
    "RotarySetup", "OffAxisSetup", "SetupCheck", "setup_checks", "BudgetItem", "ErrorBudget",
    "RotaryCapture", "OffAxisRecord", "RotaryCalibrationResult", "simulate_rotary_calibration",
    "TIR_LIMIT", "RETURN_BEAM_LIMIT", "CENTRING_LIMIT", "CALIBRATOR_PERPENDICULARITY",
    "TARGET_ALIGNMENT", "REFLECTOR_TWIST_TOLERANCE", "CALIBRATION_STEP",
]

#: Residual of the graduation error after the factory map (our assumption; the paper gives none).
MAP_RESIDUAL = 0.2 * ARCSEC


@dataclass(frozen=True)
class RotarySetup:
    """The physical set-up a simulation knows (radians and metres).

    Attributes
    ----------
    mount_tilt, mount_tilt_direction : float, radians
        Tilt of the mounting face against the axis under test and its direction on the table.
    calibrator_tilt, calibrator_tilt_direction : float, radians
        The calibrator's own axis against its base (within ±0.025°).
    beam_tilt : float, radians
        β, the laser's line of sight out of the plane of rotation.
    target_misalignment : float, radians
        The rear target against the calibrator's axis (within ±0.33 mrad).
    reflector_twist : float, radians
        ω (within ±2.5 mrad).
    lateral_offset : (float, float), metres
        The calibrator's axis from the axis under test, on the table.
    reflector_height : float, metres
    datum_misalignment : float, radians
        Angle of the reflector from square to the beams when the operator datums the laser.
    tir_radius, laser_distance : float, metres
        Where the TIR and the returned beam are read.
    dial_noise, shutter_noise, centring_noise : float, metres
        Reading uncertainty of the dial gauge, the shutter target and the centring.
    counter_rotation, self_calibration : bool
    periscope_drift : float, K/s
        Temperature change rate of the periscope during the test.
    """

    mount_tilt: float = 0.2e-3
    mount_tilt_direction: float = 0.0
    calibrator_tilt: float = 0.2e-3
    calibrator_tilt_direction: float = 1.0
    beam_tilt: float = 0.3e-3
    target_misalignment: float = 0.15e-3
    reflector_twist: float = 1.5e-3
    lateral_offset: tuple[float, float] = (0.2e-3, 0.1e-3)
    reflector_height: float = 0.08
    datum_misalignment: float = 0.1 * DEG
    tir_radius: float = 50e-3
    laser_distance: float = 1.0
    dial_noise: float = 2e-6
    shutter_noise: float = 0.1e-3
    centring_noise: float = 0.02e-3
    counter_rotation: bool = True
    self_calibration: bool = True
    periscope_drift: float = 0.0

    def __post_init__(self) -> None:
        for name in ("mount_tilt", "calibrator_tilt", "beam_tilt", "reflector_twist"):
            if abs(getattr(self, name)) > 20e-3:
                raise InputError(f"{name}={getattr(self, name)!r} rad is beyond 20 mrad: not a "
                                 "misalignment this method can measure through")
        for name in ("tir_radius", "laser_distance"):
            if not getattr(self, name) > 0:
                raise InputError(f"{name}={getattr(self, name)!r} m must be positive")

    @property
    def alpha_vector(self) -> tuple[float, float]:
        """Total tilt of the calibrator's axis against the axis under test, (x, y) radians."""
        ax = (self.mount_tilt * math.cos(self.mount_tilt_direction)
              + self.calibrator_tilt * math.cos(self.calibrator_tilt_direction))
        ay = (self.mount_tilt * math.sin(self.mount_tilt_direction)
              + self.calibrator_tilt * math.sin(self.calibrator_tilt_direction))
        return ax, ay

    @property
    def alpha(self) -> float:
        """α, radians."""
        return math.hypot(*self.alpha_vector)

    @property
    def eta(self) -> float:
        """η, the direction of α, radians."""
        return math.atan2(self.alpha_vector[1], self.alpha_vector[0])


@dataclass(frozen=True)
class OffAxisSetup:
    """An off-axis set-up (Renishaw, Interferometric calibration of rotary axes Figures 25-27), radians and metres.

    Attributes
    ----------
    radius, phase : float
        Position of the calibrator's axis on the table, polar (metres, radians).
    interferometer_distance : float, metres
        Distance of the interferometer from the axis under test along the beam.
    alignment_angles : tuple of 3 float, radians
    alignment_noise : float, metres
        How well the operator centres the beam at each alignment point.
    beam_yaw : float, radians
        Misalignment of the beams with the direction of the separation change.
    linear_yaw : HarmonicSeries
        Yaw of the linear axis (radians) as a function of its position (metres).
    profile_moving_optic : {"interferometer", "reflector"}
    profile_direction_sign : int
    stated_sign : int or None
        The sign the user states for the subtraction (None: derive it from the records).
    profile_noise : float, radians
    rotary_letter, linear_letter : str
    feed : float, mm/min
    """

    radius: float = 0.15
    phase: float = 0.0
    interferometer_distance: float = 0.5
    alignment_angles: tuple[float, float, float] = (-60 * DEG, 0.0, 60 * DEG)
    alignment_noise: float = 0.02e-3
    beam_yaw: float = 2e-3
    linear_yaw: HarmonicSeries = ZERO
    profile_moving_optic: str = "interferometer"
    profile_direction_sign: int = 1
    stated_sign: int | None = None
    profile_noise: float = 0.05 * ARCSEC
    rotary_letter: str = "C"
    linear_letter: str = "Y"
    feed: float = 1000.0


@dataclass(frozen=True)
class BudgetItem:
    """One contribution to the measurement error budget: ± ``value`` radians."""

    name: str
    value: float
    source: str

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", float(self.value))


@dataclass(frozen=True)
class ErrorBudget:
    """The measurement's error budget (each item a ± bound, radians).

    ``worst_case`` adds the items; ``rss`` is their root sum of squares. The truth tests hold
    the simulated measurement to ``worst_case``.
    """

    items: tuple[BudgetItem, ...]

    @property
    def worst_case(self) -> float:
        """Sum of the items, radians."""
        return float(sum(i.value for i in self.items))

    @property
    def rss(self) -> float:
        """Root sum of squares of the items, radians."""
        return float(math.sqrt(sum(i.value**2 for i in self.items)))

    def __str__(self) -> str:
        lines = ["error budget (± arcsec):"]
        lines += [f"  {i.name:<44} {i.value / ARCSEC:6.3f}   {i.source}" for i in self.items]
        lines.append(f"  {'worst case (sum)':<44} {self.worst_case / ARCSEC:6.3f}")
        lines.append(f"  {'root sum of squares':<44} {self.rss / ARCSEC:6.3f}")
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class RotaryCalibrationResult:
    """A complete simulated rotary calibration with its truth.

    Attributes
    ----------
    plan : TestPlan
    setup : SetupCheck
    optics : OpticsCalibration or None
        None when the self-calibration was switched off.
    capture : RotaryCapture
    result, truth_result : Iso230_2Result
        Evaluation of the measured and of the true deviations.
    budget : ErrorBudget
    expected : MisalignmentTerms
        Equation 1 at the targets for the set-up's true α, β, ω and η.
    offaxis : OffAxisRecord or None
    true_setup : RotarySetup
    """

    plan: TestPlan
    setup: SetupCheck
    optics: OpticsCalibration | None
    capture: RotaryCapture
    result: Any
    truth_result: Any
    budget: ErrorBudget
    expected: Any
    true_setup: RotarySetup
    offaxis: OffAxisRecord | None = None

    @property
    def reading_errors(self) -> np.ndarray:
        """Measured minus true deviation of every reading, arcsec, less their mean (an angle
        calibration is defined up to a constant; no ISO 230-2 parameter depends on it)."""
        ds, tr = self.capture.dataset, self.capture.truth
        d = np.concatenate([ds.up.ravel() - tr.up.ravel(), ds.down.ravel() - tr.down.ravel()])
        d = d[np.isfinite(d)]
        return d - d.mean()

    @property
    def mean_errors(self) -> np.ndarray:
        """Per-target mean deviations (both directions) measured minus true, less their mean,
        arcsec."""
        m = np.concatenate([self.result.mean_up, self.result.mean_down])
        t = np.concatenate([self.truth_result.mean_up, self.truth_result.mean_down])
        d = (m - t)[np.isfinite(m - t)]
        return d - d.mean()

    def summary(self) -> dict[str, Any]:
        """Plain data for ``--json`` (keys documented in :mod:`axiscal.cli.rotary`)."""
        return _summary(self)

    def __str__(self) -> str:
        s = self.summary()
        key = "A" if s["measured"]["A"] is not None else "A_up"
        return (f"rotary calibration of axis {self.plan.axis or '-'}: {s['n_readings']} readings; "
                f"{key} = {s['measured'][key]:.2f} arcsec (truth {s['truth'][key]:.2f}); largest "
                f"per-target error {s['max_mean_error_arcsec']:.3f} arcsec within the budget "
                f"± {s['budget']['worst_case_arcsec']:.2f} arcsec: {s['within_budget']}")


# -- the simulated procedure ------------------------------------------------------------------
def simulate_rotary_calibration(axis: RotaryAxis, plan: TestPlan, setup: RotarySetup,
                                laser: SimulatedAngularInterferometer,
                                calibrator: SimulatedRotaryCalibrator, rng: np.random.Generator,
                                speed: float = 10.0, offaxis: OffAxisSetup | None = None,
                                metadata: Metadata | None = None) -> RotaryCalibrationResult:
    """Run the whole calibration on simulated instruments and evaluate it with its truth.

    Parameters
    ----------
    axis : RotaryAxis
        The machine under test.
    plan : TestPlan
        A rotary plan in degrees.
    setup : RotarySetup
    laser : SimulatedAngularInterferometer (its ``beam_tilt`` is replaced by the set-up's β)
    calibrator : SimulatedRotaryCalibrator
    rng : numpy.random.Generator
    speed : float, deg/s
        Speed of the axis between targets (Yüksel et al., Position accuracy and repeatability calibration of turn tables: 10°/s).
    offaxis : OffAxisSetup, optional
    metadata : Metadata, optional

    Raises
    ------
    SignalLossError
        If the reflector turns more than the laser's limit (for example without counter-rotation).
    SignConventionError
        Off axis, if the stated yaw sign contradicts the records.
    """
    from dataclasses import replace

    from axiscal.procedures import _rotary_chain as chain
    from axiscal.standards.iso230_2 import evaluate

    if plan.axis_kind is not AxisKind.ROTARY or plan.target_unit != "deg":
        raise InputError("simulate_rotary_calibration needs a rotary plan in degrees")
    if not speed > 0:
        raise InputError(f"speed={speed!r} deg/s must be positive")
    axis.check_in_travel(np.array([s.position for s in plan.steps()]) * DEG)
    laser = replace(laser, beam_tilt=setup.beam_tilt + 0.0)
    check = chain.read_setup(setup, rng, offaxis)
    rig = chain.Rig(axis, setup, laser, calibrator, offaxis)
    datum = rig.datum(rng)
    optics = None
    if setup.self_calibration:
        optics, datum = rig.self_calibrate(datum, rng)
    capture, offaxis_record = rig.capture(plan, datum, rng, speed, metadata)
    result = evaluate(capture.dataset)
    truth_result = evaluate(capture.truth)
    budget = error_budget(check, laser, capture, optics, setup, offaxis)
    th = plan.targets * DEG
    expected = misalignment_terms(th, setup.alpha, setup.beam_tilt, setup.reflector_twist, setup.eta)
    return RotaryCalibrationResult(plan, check, optics, capture, result, truth_result, budget,
                                   expected, setup, offaxis_record)


def error_budget(check: SetupCheck, laser: SimulatedAngularInterferometer, capture: RotaryCapture,
                 optics: OpticsCalibration | None, setup: RotarySetup,
                 offaxis: OffAxisSetup | None) -> ErrorBudget:
    """The measurement's error budget from the set-up check and the instruments' specifications.

    Every item is a ± bound in radians with its source; see :class:`ErrorBudget`.
    """
    span = capture.time[-1] - capture.time[0] if capture.time.size else 0.0
    lateral = check.centring + CENTRING_LIMIT * 0.1
    nu = 15 * ARCSEC
    k_rel = 2e-5 if optics is not None else 0.1 / 30.0
    items = [
        BudgetItem("misalignment, eq. 1 at the set-up bounds",
                   peak_error(check.alpha_bound, check.beta_bound, check.omega_bound),
                   "Renishaw, Interferometric calibration of rotary axes, eq. 1 with α, β from the set-up check, ω = 2.5 mrad"),
        BudgetItem("encoder sub-divisional error", SDE_LIMIT, "Renishaw, Interferometric calibration of rotary axes: kept below ±0.25 arcsec"),
        BudgetItem("graduation error after the error map", MAP_RESIDUAL,
                   "assumed (Renishaw, Interferometric calibration of rotary axes: 'largely eliminated by error mapping')"),
        BudgetItem("non-parallel beams × lateral motion", nonparallel_beam_error(lateral, nu, 30e-3),
                   "Renishaw, Interferometric calibration of rotary axes: 0.5 arcsec per mm at 15 arcsec non-parallelism"),
        BudgetItem("periscope temperature", PERISCOPE_SENSITIVITY * abs(setup.periscope_drift) * span,
                   "Renishaw, Interferometric calibration of rotary axes: 13.8 µrad/°C × the drift over the test"),
        BudgetItem("retro-reflector spacing (K)", k_rel * capture.max_laser_angle,
                   "relative K error × largest laser angle" + (
                       " (after self-calibration)" if optics else " (0.1 mm in 30 mm, uncalibrated)")),
        BudgetItem("laser noise and resolution", 2 * laser.noise + 0.5 * laser.resolution,
                   "2σ of the reading noise + half the resolution"),
    ]
    if offaxis is not None:
        items.append(BudgetItem("off-axis separation change", OFFAXIS_EXTRA_ERROR,
                                "Renishaw, Interferometric calibration of rotary axes: add ±0.5 arcsec off axis"))
    return ErrorBudget(tuple(items))


def _summary(r: RotaryCalibrationResult) -> dict[str, Any]:
    params = r.result.parameters()
    truth = r.truth_result.parameters()
    me = r.mean_errors
    re = r.reading_errors
    out: dict[str, Any] = {
        "axis": r.plan.axis,
        "n_targets": int(r.plan.targets.size),
        "n_runs": int(r.plan.runs),
        "n_readings": int(r.plan.n_measurements),
        "measured": params,
        "truth": truth,
        "max_mean_error_arcsec": float(np.max(np.abs(me))) if me.size else 0.0,
        "max_reading_error_arcsec": float(np.max(np.abs(re))) if re.size else 0.0,
        "setup": {"tir_mm": r.setup.tir / MM, "return_offset_mm": r.setup.return_offset / MM,
                  "centring_mm": r.setup.centring / MM, "alpha_bound_mrad": r.setup.alpha_bound * 1e3,
                  "beta_bound_mrad": r.setup.beta_bound * 1e3, "passed": r.setup.passed,
                  "warnings": list(r.setup.warnings)},
        "optics": None if r.optics is None else {
            "k": r.optics.k, "datum_misalignment_arcsec": r.optics.datum_misalignment / ARCSEC},
        "budget": {"items": [{"name": i.name, "arcsec": i.value / ARCSEC, "source": i.source}
                             for i in r.budget.items],
                   "worst_case_arcsec": r.budget.worst_case / ARCSEC,
                   "rss_arcsec": r.budget.rss / ARCSEC},
        "true_misalignment_mrad": {"alpha": r.true_setup.alpha * 1e3, "beta": r.true_setup.beam_tilt * 1e3,
                                   "omega": r.true_setup.reflector_twist * 1e3,
                                   "eta_deg": math.degrees(r.true_setup.eta)},
        "max_laser_angle_arcsec": r.capture.max_laser_angle / ARCSEC,
        "offaxis": None,
        "warnings": list(r.result.warnings),
    }
    out["within_budget"] = out["max_mean_error_arcsec"] <= out["budget"]["worst_case_arcsec"]
    if r.offaxis is not None:
        out["offaxis"] = {"radius_mm": r.offaxis.alignment.radius / MM,
                          "phase_deg": math.degrees(r.offaxis.alignment.phase),
                          "yaw_sign": r.offaxis.sign,
                          "yaw_removed_arcsec": r.offaxis.yaw_removed / ARCSEC,
                          "program_lines": r.offaxis.program.count("\n")}
    return out

