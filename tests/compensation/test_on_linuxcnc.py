"""The compensation loop measured through a real LinuxCNC (issue 32).

``axiscal compensate --verify CONFIG --controller linuxcnc --on-controller``: the ISO 230-2:2014
test (both directions) run through a headless LinuxCNC on the bare axis, the table written by
axiscal's LinuxCNC writer and loaded as ``[JOINT_0] COMP_FILE``, the test run again. Issue 32,
"Must show": on the shipped linear example E falls by ≥ 80 % measured through LinuxCNC, and the
trim LinuxCNC applied equals the table within 1e-6 mm at every target and direction.

Skipped, with the concrete reason, only where LinuxCNC cannot run (not Debian, not root, not
installed); the refusals at the end run everywhere.
"""

import json
import tomllib
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.compensation.on_controller import run_on_linuxcnc
from axiscal.instruments.linuxcnc_controller import (
    LINUXCNC_LOCK, leftover_segments, platform_reason, running_processes, session_lock)

ROOT = Path(__file__).resolve().parents[2]
# Skipped only where no install can help (not Debian, not root); on Debian as root a missing
# LinuxCNC fails these tests: make test installs it (make linuxcnc).
WHY = platform_reason()
live = pytest.mark.skipif(WHY is not None, reason=f"LinuxCNC cannot run here: {WHY}")
runner = CliRunner()


def _small(**test):
    """The shipped linear example's machine, a short test (9 targets, 2 runs), LinuxCNC table."""
    cfg = tomllib.loads((ROOT / "examples/compensation_linear.toml").read_text())
    cfg["test"].update(n_targets=9, runs=2, **test)
    cfg["compensation"] = dict(controller="linuxcnc", spacing=100.0, bidirectional=True,
                               resolution=0.1)
    return cfg


@live
def test_shipped_linear_example_E_falls_by_80_percent_through_linuxcnc():
    """examples/compensation_linear.toml, 81 targets × 5 runs × 2 directions, twice, through
    LinuxCNC: E falls by ≥ 80 % (issue 32), and at all 162 targets and directions the applied
    trim is the table's within 1e-6 mm (1e-3 µm)."""
    r = runner.invoke(app, ["compensate", "--verify", str(ROOT / "examples/compensation_linear.toml"),
                            "--controller", "linuxcnc", "--on-controller", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    for k in ("E", "A", "M", "R", "B"):
        assert d["before"][k] is not None and d["after"][k] is not None
    assert d["before"]["E"] > 8.0
    assert d["reduction"] >= 0.80, (d["before"]["E"], d["after"]["E"])
    assert d["on_controller"]["comp_file_type"] == 1 and d["on_controller"]["machine_units"] == "mm"
    assert d["on_controller"]["dwell_s"] == 0.0 and d["on_controller"]["plan_dwell_s"] == 1.0
    assert len(d["applied"]) == 162 == d["on_controller"]["n_applied"]
    assert {a["direction"] for a in d["applied"]} == {"+", "-"}
    assert all(a["n"] == 5 for a in d["applied"])
    assert max(a["difference"] for a in d["applied"]) <= 1e-3
    assert max(abs(a["table"]) for a in d["applied"]) > 3.0        # micrometres of trim, applied
    with session_lock():
        assert running_processes() == [] and leftover_segments() == []
        assert not LINUXCNC_LOCK.exists()


@live
@pytest.mark.parametrize("options", [dict(file_type=0), dict(file_type=1, unit="inch")])
def test_short_loop_type_0_and_inch(options):
    """The loop with a type-0 file and on an inch machine: E falls, trims are the table's."""
    r, applied, hook = run_on_linuxcnc(_small(), seed=2, options=options)
    assert hook.file_type == options["file_type"] and hook.units == options.get("unit", "mm")
    assert r.reduction >= 0.6, str(r)        # 100 mm table points under a 100 mm lead-error wave
    assert len(applied) == 18
    assert max(a.difference for a in applied) <= 1e-3


@live
def test_rotary_joint_through_linuxcnc():
    """The shipped rotary example's turntable (every 30° over a full turn, 2 runs), a type-0 file
    in degrees on an ANGULAR joint: E falls by ≥ 80 %, every trim is the table's within
    1e-3 arcsec."""
    cfg = tomllib.loads((ROOT / "examples/compensation_rotary.toml").read_text())
    cfg["test"].update(step_deg=30, runs=2)
    cfg["compensation"] = dict(controller="linuxcnc", spacing=30.0, bidirectional=True,
                               resolution=0.36, options=dict(file_type=0))
    r, applied, hook = run_on_linuxcnc(cfg, seed=1)
    assert hook.units == "deg" and r.unit == "arcsec"
    assert r.before.E > 5.0 and r.reduction >= 0.80, str(r)
    assert len(applied) == 26
    assert max(a.difference for a in applied) <= 1e-3
    assert max(abs(a.table) for a in applied) > 2.0


def test_on_controller_needs_linuxcnc_and_verify():
    """--on-controller with another controller, or without --verify: one line, exit 2."""
    r = runner.invoke(app, ["compensate", "--verify", str(ROOT / "examples/compensation_linear.toml"),
                            "--on-controller"])
    assert r.exit_code == 2
    assert "give --controller linuxcnc" in r.output and "Traceback" not in r.output
    r = runner.invoke(app, ["compensate", str(ROOT / "examples/compensation_linear.toml"),
                            "--on-controller"])
    assert r.exit_code == 2 and "--on-controller" in r.output


def test_where_linuxcnc_cannot_run_the_command_says_why(monkeypatch, tmp_path):
    """Not Debian, not root or not installed: one line naming the reason, exit 2, no traceback."""
    import axiscal.instruments.linuxcnc_controller as live_module

    monkeypatch.setattr(live_module, "unavailable_reason",
                        lambda: "not Debian: axiscal runs LinuxCNC from Debian's linuxcnc-uspace package")
    cfg = tmp_path / "small.toml"
    cfg.write_text((ROOT / "examples/compensation_linear.toml").read_text())
    r = runner.invoke(app, ["compensate", "--verify", str(cfg), "--controller", "linuxcnc",
                            "--on-controller"])
    assert r.exit_code == 2, r.output
    assert "LinuxCNC cannot run here: not Debian" in r.output and "Traceback" not in r.output
