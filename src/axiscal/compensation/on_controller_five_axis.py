"""The five-axis correction proven through a live LinuxCNC (issue 43): the twin reads the joint
positions LinuxCNC's own trt kinematics compute while it runs the probing and R-test poses.

:func:`measure_on_linuxcnc` measures the planned set-ups so (the records the identification
reads); :func:`verify_on_linuxcnc` re-measures them before and after the correction.

Every planned set-up is run through the controller, with ``xyzac-trt-kins`` (``xyzbc-trt-kins``)
active, twice: with the pins as they were, and after the correction of
:func:`~axiscal.compensation.five_axis.trt_correction` (pins set by ``setp``, the tilting joint's
``HOME_OFFSET`` in the INI and, where orientation errors were identified, the external offsets
``axiscal_trtcomp.py`` drives). Each state is one LinuxCNC session; the twin puts its true axis
lines behind the drives (the joints' ``motor-pos-cmd``, in which a changed ``HOME_OFFSET`` and the
external offsets show) and measures static poses from those joints (a userspace probe trip would
add milliseconds of latency, several µm at normal probing feeds):

* **R-test**: the nest's nominal place (table frame) at each pose is commanded as a world pose;
  the simulated R-test reads the tool sphere's displacement from the nest in the table frame;
* **probing**: at each pose the controller puts the probe at a start point
  ``PROBE_CLEARANCE`` outside the nominal sphere along each contact normal (a world point: the
  nominal centre plus the normal turned into the table frame with the nominal angles); the
  simulated probe travels from the joints LinuxCNC reached along the normal until it touches
  (:meth:`~axiscal.instruments.touch_probe.SimulatedTouchProbe.touch_from`); the sphere fit's
  centre less the controller's own idea of it (the start points less their clearance and
  radius, mean) is the deviation, turned into the table frame with the nominal angles: what a
  part machined at that pose would be out by.

The range of a set-up is the largest peak-to-valley over X, Y, Z of its deviations
(:class:`~axiscal.compensation.five_axis.Verification`); ``after_unmodelled`` is the range after
the correction from the same joints without the instruments' noise, and ``explained`` what the
range after is expected to be from those noise-free deviations plus the instruments' noise
(:func:`~axiscal.compensation.five_axis.explain_range`: the probe's touches and the R-test's
readings propagated through the sphere fit and the sensors' directions, sampled), so the
measured range is accounted for to within 1 µm.
"""

from __future__ import annotations

import numpy as np

from axiscal.compensation.five_axis import (TrtCorrection, Verification, explain_range,
                                            noise_maps)
from axiscal.physics.rotary_location import machine_to_table
from axiscal.procedures.five_axis import PROBING, R_TEST, ProbingRecord, RTestRecord
from axiscal.standards.sphere_fit import fit_sphere
from axiscal.units import DEG, MM

__all__ = ["verify_on_linuxcnc", "measure_on_linuxcnc", "r_test_on_linuxcnc", "world_poses",
           "PROBE_CLEARANCE"]

#: Distance (m) outside the nominal sphere at which the controller puts the probe before a touch.
PROBE_CLEARANCE = 2e-3


def world_poses(machine, setup) -> np.ndarray:
    """The world poses (N, 5: X, Y, Z mm in the table frame, tilt and C degrees) the controller
    is commanded to for one set-up: the nest's place at each pose (R-test), or each touch's
    start point at each pose, pose after pose (probing)."""
    place = np.asarray(setup.place, float)
    if setup.kind == R_TEST:
        return np.array([(*(place / MM), a / DEG, c / DEG)
                         for a, c in zip(setup.tilt_angle, setup.c_angle)])
    d = _directions(setup.instrument)
    reach = setup.instrument.effective_radius + PROBE_CLEARANCE
    out = []
    for a, c in zip(setup.tilt_angle, setup.c_angle):
        g = machine.geometry
        dt = machine_to_table(g, {}, a, c, d) - machine_to_table(g, {}, a, c, np.zeros(3))
        out += [(*((place + reach * v) / MM), a / DEG, c / DEG) for v in dt]
    return np.array(out)


def r_test_on_linuxcnc(machine, setup, joints, rng=None):
    """One R-test set-up measured by the twin from the joints LinuxCNC reached (N, 5; mm,
    degrees): the record (``commanded`` the joints' X, Y, Z in m, the angles the drives reached
    in rad) and the displacements the same joints give without noise (m)."""
    place = np.asarray(setup.place, float)
    xyz, a, c = joints[:, :3] * MM, joints[:, 3] * DEG, joints[:, 4] * DEG
    d = setup.instrument.measure(machine, a, c, xyz, place, rng)
    rec = RTestRecord(machine.tilt, a, c, xyz, d, setup.instrument.noise, setup.u_gain, place,
                      setup.label)
    return rec, setup.instrument.measure(machine, a, c, xyz, place, None)


def probing_on_linuxcnc(machine, setup, joints, rng=None) -> np.ndarray:
    """Sphere-centre deviations (N, 3; m, table frame) of one probing set-up from the joints
    LinuxCNC reached at the touches' start points (module docstring)."""
    probe = setup.instrument
    d = _directions(probe)
    n = len(d)
    reach = probe.effective_radius + PROBE_CLEARANCE
    out = []
    for i in range(setup.poses):
        j = joints[i * n:(i + 1) * n]
        starts = j[:, :3] * MM
        a, c = j[0, 3] * DEG, j[0, 4] * DEG
        touches = probe.touch_from(machine, a, c, setup.place, starts, rng)
        fit = fit_sphere(touches, probe.effective_radius, setup.tolerance,
                         f"{setup.label} pose {i + 1}")
        dev = fit.center - (starts - reach * d).mean(axis=0)
        g = machine.geometry
        ta, tc = setup.tilt_angle[i], setup.c_angle[i]
        out.append(machine_to_table(g, {}, ta, tc, dev)[0]
                   - machine_to_table(g, {}, ta, tc, np.zeros(3))[0])
    return np.array(out)


def measure_on_linuxcnc(machine, plan, seed: int = 1, z_rot_point: float = 0.0) -> tuple:
    """Every planned set-up measured through a live LinuxCNC holding the machine's nominal
    geometry in its trt pins (one session): the probing cycle's moves and the R-test's poses
    run by the controller, the twin measuring from the joints it reached (module docstring).
    Returns the records :func:`axiscal.procedures.five_axis.measure` returns (touches and
    commanded positions are the joints' X, Y, Z; the angles those the drives reached); the
    identification reads them as it reads files. ``z_rot_point`` in mm."""
    from axiscal.compensation.five_axis import nominal_pins
    from axiscal.instruments.linuxcnc_trt import joints_for_world_poses

    poses = [world_poses(machine, s) for s in plan.setups]
    cuts = np.cumsum([0] + [len(p) for p in poses])
    joints = joints_for_world_poses(machine.tilt, nominal_pins(machine.geometry,
                                                               z_rot_point * 1e-3),
                                    0.0, np.vstack(poses))
    rng = np.random.default_rng(seed)
    out = []
    for s, lo, hi in zip(plan.setups, cuts[:-1], cuts[1:]):
        j = joints[lo:hi]
        if s.kind == R_TEST:
            rec, _ = r_test_on_linuxcnc(machine, s, j, rng)
            out.append(RTestRecord(rec.tilt, rec.tilt_angle, rec.c_angle, rec.commanded,
                                   rec.displacement, s.instrument.noise, s.u_gain, s.place,
                                   s.label, s.u_direction,
                                   np.asarray(s.instrument.directions, float)))
            continue
        n = len(_directions(s.instrument))
        a, c = j[::n, 3] * DEG, j[::n, 4] * DEG
        touches = tuple(s.instrument.touch_from(machine, a[i], c[i], s.place,
                                                j[i * n:(i + 1) * n, :3] * MM, rng)
                        for i in range(s.poses))
        p = s.instrument
        out.append(ProbingRecord(s.tilt, a, c, touches, p.sphere_radius, p.stylus_radius,
                                 p.noise, s.u_offset, s.tolerance, s.place, s.label))
    return tuple(out)


def verify_on_linuxcnc(machine, plan, correction: TrtCorrection, seed: int = 7,
                       z_rot_point: float = 0.0) -> Verification:
    """Deviation ranges of every planned set-up through LinuxCNC before and after the
    correction (module docstring); ``z_rot_point`` in mm as set on the controller."""
    from axiscal.instruments.linuxcnc_trt import joints_for_world_poses

    setups = plan.setups
    poses = [world_poses(machine, s) for s in setups]
    cuts = np.cumsum([0] + [len(p) for p in poses])
    states = ((0, 0.0, None),
              (1, correction.home_offset.get(machine.tilt, 0.0), correction.external_offsets))
    ranges, left = [], ()
    for which, home, eo in states:
        pins = {p: v[which] for p, v in correction.pins.items()}
        pins["z-rot-point"] = z_rot_point
        joints = joints_for_world_poses(machine.tilt, pins, home, np.vstack(poses), trtcomp=eo)
        rng = np.random.default_rng(seed)
        got, clean = [], []
        for s, lo, hi in zip(setups, cuts[:-1], cuts[1:]):
            if s.kind == PROBING:
                got.append(probing_on_linuxcnc(machine, s, joints[lo:hi], rng))
                clean.append(probing_on_linuxcnc(machine, s, joints[lo:hi], None))
            else:
                rec, noise_free = r_test_on_linuxcnc(machine, s, joints[lo:hi], rng)
                got.append(rec.displacement)
                clean.append(noise_free)
        ranges.append(tuple(_ptp(v) for v in got))
        left = tuple(_ptp(v) for v in clean)      # after: the same joints without noise
    rng = np.random.default_rng([seed, 43])
    why = tuple(explain_range(u, *noise_maps(machine, s), rng) for u, s in zip(clean, setups))
    return Verification(tuple(s.label for s in setups), ranges[0], ranges[1], left, why)


def _directions(probe) -> np.ndarray:
    d = np.asarray(probe.directions, float)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def _ptp(v) -> float:
    return float(np.ptp(v, axis=0).max())
