"""Issue 43, the ballbar path through a live LinuxCNC (Debian linuxcnc-uspace 2.9, headless,
``xyzac-trt-kins`` with the example A/C machine's nominal pins): along the ballbar set-ups'
paths (a C sweep and a five-axis sweep of A and C together) the joint positions LinuxCNC's own
trt kinematics command for the spindle ball held on the table (the world pose: the ball's
table-frame place and the two angles) equal the plan's commanded positions (axiscal's nominal
kinematics) within 1e-6 mm and the angles within 1e-9°. The part program's file itself is not
run here (its points are checked against the same kinematics in
tests/programs/test_five_axis_ballbar_program.py). Skipped only where LinuxCNC cannot run."""

from __future__ import annotations

import tomllib
from importlib import resources

import numpy as np
import pytest

from axiscal.api import fiveaxis
from axiscal.compensation.five_axis import nominal_pins
from axiscal.instruments.linuxcnc_controller import platform_reason
from axiscal.instruments.linuxcnc_trt import joints_for_world_poses

WHY = platform_reason()
pytestmark = pytest.mark.skipif(WHY is not None, reason=f"LinuxCNC cannot run here: {WHY}")


def test_linuxcnc_commands_the_plans_joints_along_the_ballbar_paths():
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    cfg["ballbar"] = [dict(cfg["ballbar"][0], points=9),
                      dict(cfg["ballbar"][5], points=9)]
    planned = fiveaxis.ballbar.plan(cfg)
    poses, want = [], []
    for s in planned.setups:
        world = np.broadcast_to(s.spindle_ball * 1e3, (s.points, 3))
        poses.append(np.column_stack([world, np.degrees(s.tilt_angle), np.degrees(s.c_angle)]))
        want.append(np.column_stack([s.commanded * 1e3, np.degrees(s.tilt_angle),
                                     np.degrees(s.c_angle)]))
    poses, want = np.vstack(poses), np.vstack(want)
    assert np.ptp(want[:, 0]) > 100 and np.ptp(want[:, 3]) == pytest.approx(60.0)   # it moves
    joints = joints_for_world_poses("A", nominal_pins(planned.machine.geometry), 0.0, poses)
    np.testing.assert_allclose(joints[:, :3], want[:, :3], atol=1e-6)
    np.testing.assert_allclose(joints[:, 3:], want[:, 3:], atol=1e-9)
