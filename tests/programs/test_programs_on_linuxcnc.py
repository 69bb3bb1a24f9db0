"""Issue 41, "Proven on LinuxCNC": axiscal's LinuxCNC programs run on the real headless LinuxCNC.

One session of Debian's linuxcnc-uspace 2.9 (:class:`LinuxCNCProgramMachine`: X and Y, each
joint's drive a first-order lag of 9.5 ms) runs, in AUTO mode, the LinuxCNC program axiscal
writes for a linear plan and an ISO 230-4 circular plan. The rotary plan (a full turn with its
overruns) runs on LinuxCNC in ``tests/compensation/test_calibrate_on_linuxcnc.py``, twice (as
found, then with the table loaded), where capture finds its every stop and no other and the
record holds the full turn: one LinuxCNC session fewer here (about 9 s of make test). LinuxCNC's sampler records the fed-back positions every servo period. The issue's checks:

* the record is continuous (no servo run missing);
* ``axiscal capture``'s stillness trigger (:func:`axiscal.procedures.capture.capture_test`, the
  one capture every path uses) turns it into exactly the plan's stops: as many stops as the plan
  has measurements and no other, matched to the same targets, runs, directions and order, each
  reading the target (a drive at rest has no error);
* the circular path matches the plan's circle within the servo's following error (speed × time
  constant) over both data arcs, and its radius shrinks as a first-order lag predicts.

Skipped, with the concrete reason, only where LinuxCNC cannot run (not Debian, not root).
"""

import math

import numpy as np
import pytest

from axiscal.instruments.linuxcnc_controller import platform_reason
from axiscal.io.measured import parse_plan_csv
from axiscal.procedures.capture import Record, capture_test
from axiscal.procedures.circular_plan import plan_circular
from axiscal.procedures.positioning import plan_linear
from axiscal.programs import MachineOptions, write_program

WHY = platform_reason()
pytestmark = pytest.mark.skipif(WHY is not None, reason=f"LinuxCNC cannot run here: {WHY}")

AXES = {"X": (-50.0, 300.0), "Y": (-100.0, 100.0)}
#: Dwell of the stops and the trigger's stillness, s: 60 % of 0.3 s is the shortest stop
#: capture looks for, longer than the drive's settling (10 time constants, 95 ms) takes from it.
DWELL, TRIGGER = 0.3, 0.2


@pytest.fixture(scope="module")
def runs():
    """The two programs run in one LinuxCNC session; the records and the plans."""
    from axiscal.instruments.linuxcnc_program import LinuxCNCProgramMachine

    linear = plan_linear(100.0, n_targets=5, runs=2, dwell=DWELL, overrun=2.0, axis="X")
    circle = plan_circular(30.0, (100.0, 0.0), feed=6000.0, overshoot_deg=45.0)
    out = {"progress": []}
    with LinuxCNCProgramMachine(axes=AXES, velocity=720.0, acceleration=20000.0) as m:
        for key, plan, feed in (("linear", linear, 12000.0), ("circular", circle, 6000.0)):
            opts = MachineOptions(feed=feed, limits=AXES, trigger=TRIGGER)
            seen = out["progress"] if key == "linear" else None
            out[key] = (plan, m.run(write_program(plan, "linuxcnc", opts),
                                    progress=None if seen is None else
                                    lambda line, lines: seen.append((line, lines))))
    return out


def test_progress_follows_the_program(runs):
    """The run reports LinuxCNC's line as it goes (what ``axiscal calibrate``'s bar shows):
    increasing, to the program's last moves."""
    seen = runs["progress"]
    lines = seen[0][1]
    assert len(seen) > 10 and all(n == lines for _, n in seen)
    assert all(a < b for (a, _), (b, _) in zip(seen, seen[1:]))
    assert seen[-1][0] >= lines - 5


def _capture(plan, rec, axis, to_si):
    rows = parse_plan_csv(plan.to_csv())           # the plan as axiscal exports it
    readings = (rec.positions[axis] - plan.targets[0]) * to_si
    record = Record(rec.times, readings, plan.axis_kind.value, sample_rate=1000.0)
    return rows, capture_test(record, rows, window=1.0)


@pytest.mark.parametrize("key, axis, to_si", [("linear", "X", 1e-3)])
def test_capture_finds_exactly_the_plans_stops(runs, key, axis, to_si):
    """Every stop of the plan and no other: same targets, runs, directions and order; each
    reading is the target within 0.01 µm (0.01″): the drive is at rest."""
    plan, rec = runs[key]
    assert rec.gaps == 0 and np.all(np.diff(rec.servo_runs) == 1)
    rows, cap = _capture(plan, rec, axis, to_si)
    measure_rows = [i for i, k in enumerate(rows.kind) if k == "measure"]
    assert len(cap.stops) == plan.n_measurements == len(measure_rows)
    assert [r for _, r in cap.assigned] == measure_rows
    assert [k for k, _ in cap.assigned] == list(range(len(cap.stops)))
    ds = cap.dataset
    np.testing.assert_array_equal(ds.targets, plan.targets)
    assert ds.up.shape == ds.down.shape == (plan.targets.size, plan.runs)
    assert np.nanmax(np.abs(np.concatenate([ds.up, ds.down]))) < 0.01
    assert not np.isnan(ds.up).any() and not np.isnan(ds.down).any()


def test_ballbar_path_matches_the_circle_within_the_following_error(runs):
    """Over both data arcs the sampled path's radius is R within the following error (feed ×
    time constant, 0.95 mm here), in fact within 3 µm of a first-order lag's R/√(1+(ωτ)²) (15 µm
    inside); the data arcs are covered whole, CCW then CW, at the programmed feed."""
    from axiscal.instruments.linuxcnc_program import DRIVE_GAIN, SERVO_PERIOD_S

    plan, rec = runs["circular"]
    x, y = rec.positions["X"] - plan.centre[0], rec.positions["Y"] - plan.centre[1]
    on = np.abs(np.hypot(x, y) - plan.radius) < 0.1          # on the circle (not the set-in)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], on.view(np.int8), [0]))))
    a, b = max(zip(edges[::2], edges[1::2]), key=lambda e: e[1] - e[0])   # the contouring
    x, y = x[a:b], y[a:b]
    r = np.hypot(x, y)
    phi = np.degrees(np.unwrap(np.arctan2(y, x)))
    phi -= 360 * round((phi[0] - plan.arcs()[0].start_deg) / 360)   # the feed-in arc's start
    turn = int(np.argmax(phi))                               # the reversal: largest angle
    k = np.arange(r.size)
    ccw = (k < turn) & (phi >= 0) & (phi <= 360)
    cw = (k > turn) & (phi >= 0) & (phi <= 360)
    lag_deg = math.degrees(plan.feed / 60.0 * -SERVO_PERIOD_S / math.log(1 - DRIVE_GAIN)
                           / plan.radius)      # the following error as an angle: 1.8 deg
    assert 360 + plan.overshoot_deg - lag_deg < phi[turn] <= 360 + plan.overshoot_deg
    for end in (phi[0], phi[-1]):       # the feed-in start, the feed-out end (the lag: within)
        assert end == pytest.approx(-plan.overshoot_deg, abs=lag_deg)
    tau = -SERVO_PERIOD_S / math.log(1 - DRIVE_GAIN)
    v = plan.feed / 60.0
    following = v * tau
    omega = v / plan.radius
    lag_r = plan.radius / math.sqrt(1 + (omega * tau) ** 2)
    for part in (ccw, cw):
        assert np.ptp(phi[part]) > 359.0
        assert np.max(np.abs(r[part] - plan.radius)) <= following
        assert np.max(np.abs(r[part] - lag_r)) < 3e-3
        speed = np.hypot(np.diff(x[part]), np.diff(y[part])) / SERVO_PERIOD_S
        assert np.median(speed) == pytest.approx(v, rel=0.01)
