"""The five-axis correction proven through a live LinuxCNC (issue 43): the twin reads the joint
positions LinuxCNC's own trt kinematics compute while it runs the R-test's poses.

For each R-test pose the nest's nominal place (table frame, mm) and the two rotary angles are
commanded as a world pose by MDI with ``xyzac-trt-kins`` (``xyzbc-trt-kins``) active; LinuxCNC
computes the joints from its pins; the twin puts its true axis lines behind the drives (the
joints' ``motor-pos-cmd``, in which a changed ``HOME_OFFSET`` shows) and the simulated R-test
reads the tool sphere's displacement from the nest in the table frame. This is done with the
pins as they were and again with the correction of :func:`~axiscal.compensation.five_axis.
trt_correction` (pins set by ``setp``, the tilting joint's ``HOME_OFFSET`` in the INI), and the
deviation ranges are compared. Probing set-ups are not run through the controller here (a
probing cycle runs with identity kinematics, where the controller adds nothing to the twin).
"""

from __future__ import annotations

import numpy as np

from axiscal.compensation.five_axis import TrtCorrection, Verification
from axiscal.errors import InputError
from axiscal.procedures.five_axis import R_TEST, RTestRecord
from axiscal.units import DEG, MM

__all__ = ["verify_on_linuxcnc", "r_test_on_linuxcnc"]


def r_test_on_linuxcnc(machine, setup, pins: dict, home_offset: float, rng=None,
                       noise_free: bool = False) -> RTestRecord | tuple[RTestRecord, np.ndarray]:
    """Run one planned R-test set-up through a live LinuxCNC (trt kinematics, ``pins`` in mm,
    the tilting joint's ``home_offset`` in degrees) on the twin.

    Returns the record with ``commanded`` the joints' X, Y, Z (m) and the angles the drives
    reached (rad), as the twin used them; with ``noise_free`` also the displacements the same
    joints give without the instrument's noise (m).
    """
    from axiscal.instruments.linuxcnc_trt import joints_for_world_poses

    place = np.asarray(setup.place, float)
    poses = [(*(place / MM), a / DEG, c / DEG) for a, c in zip(setup.tilt_angle, setup.c_angle)]
    joints = joints_for_world_poses(machine.tilt, pins, home_offset, poses)
    xyz, a, c = joints[:, :3] * MM, joints[:, 3] * DEG, joints[:, 4] * DEG
    d = setup.instrument.measure(machine, a, c, xyz, place, rng)
    rec = RTestRecord(machine.tilt, a, c, xyz, d, setup.instrument.noise, setup.u_gain, place,
                      setup.label)
    if noise_free:
        return rec, setup.instrument.measure(machine, a, c, xyz, place, None)
    return rec


def verify_on_linuxcnc(machine, plan, correction: TrtCorrection, seed: int = 7,
                       z_rot_point: float = 0.0) -> Verification:
    """R-test deviation ranges through LinuxCNC before and after the correction (module
    docstring); ``z_rot_point`` in mm as set on the controller."""
    setups = [s for s in plan.setups if s.kind == R_TEST]
    if not setups:
        raise InputError("--on-controller runs the R-test set-ups through LinuxCNC: the "
                         "configuration has none")
    ranges = []
    for which, home in ((0, 0.0), (1, correction.home_offset.get(machine.tilt, 0.0))):
        pins = {p: v[which] for p, v in correction.pins.items()}
        pins["z-rot-point"] = z_rot_point
        rng = np.random.default_rng(seed)
        runs = [r_test_on_linuxcnc(machine, s, pins, home, rng, noise_free=True) for s in setups]
        ranges.append(tuple(_ptp(r.displacement) for r, _ in runs))
    left = tuple(_ptp(d) for _, d in runs)       # after: the same joints without noise
    return Verification(tuple(s.label for s in setups), ranges[0], ranges[1], left)


def _ptp(v) -> float:
    return float(np.ptp(v, axis=0).max())
