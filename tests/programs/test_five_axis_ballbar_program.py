"""The five-axis ballbar program (``axiscal plan fiveaxis --ballbar``, :class:`axiscal.programs.
BallbarProgram`): written in joint space with the nominal kinematics, every programmed point and
every straight move between two keeps the spindle ball on its place on the table within the
tolerance and the program's resolution, and LinuxCNC's own interpreter reads it to the end."""

from __future__ import annotations

import re
import tomllib
from importlib import resources

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.api import fiveaxis
from axiscal.cli import app
from axiscal.physics.rotary_location import machine_to_table
from axiscal.programs import BallbarProgram, MachineOptions, ProgramError, write_program

_G1 = re.compile(r"^G1 X(\S+) Y(\S+) Z(\S+) A(\S+) C(\S+) F")


def _short():
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    return dict(cfg, ballbar=[dict(cfg["ballbar"][0], C_deg=[0, 90], points=7),
                              dict(cfg["ballbar"][5], A_deg=[0, -30], C_deg=[0, 90], points=7)])


def test_every_programmed_point_and_move_keeps_the_spindle_ball_in_place():
    """Tolerance 1 µm: at each G1 end point the nominal kinematics put the spindle ball within
    0.5·√3 µm (0.001 mm rounding of X, Y, Z; the angles are rounded to 0.001° before X, Y, Z
    are computed) of its place, and at the middle of each move within 1 µm more."""
    planned = fiveaxis.ballbar.plan(_short())
    text = write_program(BallbarProgram(planned.setups, planned.machine, tolerance=1.0),
                         "linuxcnc", MachineOptions(feed=2000.0, safe={"Z": 300.0}))
    rows = np.array([[float(v) for v in m.groups()] for m in map(_G1.match, text.splitlines())
                     if m])
    g = planned.machine.geometry
    starts = [i for i, line in enumerate(text.splitlines()) if line.startswith("G4")][::2]
    assert len(starts) == 2 and len(rows) > 100
    blocks = np.split(rows, np.flatnonzero(np.diff(rows[:, 4]) < 0) + 1)   # C restarts
    for s, pts in zip(planned.setups, blocks):
        a, c = np.radians(pts[:, 3]), np.radians(pts[:, 4])
        at = machine_to_table(g, {}, a, c, pts[:, :3] * 1e-3)
        assert np.linalg.norm(at - s.spindle_ball, axis=1).max() < 0.5 * np.sqrt(3) * 1e-6
        mid = machine_to_table(g, {}, (a[1:] + a[:-1]) / 2, (c[1:] + c[:-1]) / 2,
                               (pts[1:, :3] + pts[:-1, :3]) / 2 * 1e-3)
        assert np.linalg.norm(mid - s.spindle_ball, axis=1).max() < 1.9e-6
        assert pts[-1, 4] == pytest.approx(90.0) and np.degrees(s.c_angle[-1]) == 90.0


def test_linuxcncs_interpreter_reads_the_program_to_its_end(tmp_path, rs274):
    f = tmp_path / "bb.ngc"
    r = CliRunner().invoke(app, ["plan", "fiveaxis", "--ballbar", "--program", str(f),
                                 "--controller", "linuxcnc", "--safe", "Z=300", "--tolerance",
                                 "5", "--json"])
    assert r.exit_code == 0, r.output
    feeds = sum(line.startswith("G1 ") for line in f.read_text().splitlines())
    out = rs274(f)
    assert out.count("STRAIGHT_FEED(") == feeds and "PROGRAM_END" in out


def test_a_bad_tolerance_or_no_safe_z_is_refused():
    planned = fiveaxis.ballbar.plan(_short())
    with pytest.raises(ProgramError, match="tolerance"):
        write_program(BallbarProgram(planned.setups, planned.machine, tolerance=0.0),
                      "linuxcnc", MachineOptions(safe={"Z": 300.0}))
    with pytest.raises(ProgramError, match="safe Z"):
        write_program(BallbarProgram(planned.setups, planned.machine), "linuxcnc",
                      MachineOptions())
