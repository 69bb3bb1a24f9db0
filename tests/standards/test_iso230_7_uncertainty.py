"""The uncertainty of the ISO 230-7:2015 error motion values of a five-DOF measurement
(:mod:`axiscal.standards.iso230_7_uncertainty`), on the shipped three-run file
``examples/motion_indexing_table_3runs.csv`` (written by ``axiscal motion repeatability
examples/motion_indexing_table.toml --csv``, the twin of the set-up of Optics Express 2018,
"Method for simultaneous measurement of five DOF motion errors of a rotary axis using a
single-mode fiber-coupled laser"): each U rebuilt by hand from the file's figures and the
documented defaults, the measured run-to-run scatter recomputed from the file's columns."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.errors import ConfigError
from axiscal.store.kinds import evaluate_file, with_uncertainty
from axiscal.standards.iso230_7_uncertainty import MOTION_INPUTS, motion_budget

FILE = Path(__file__).resolve().parents[2] / "examples" / "motion_indexing_table_3runs.csv"


@pytest.fixture(scope="module")
def record():
    return evaluate_file(FILE.read_bytes(), FILE.name)


def _columns(name: str) -> np.ndarray:
    """A channel of the file as runs × angles, read with numpy alone (not axiscal's reader);
    the closing 360° row of each run left out, as ISO 230-7 evaluates one turn."""
    rows = [ln.split(",") for ln in FILE.read_text().splitlines()
            if ln and ln[0].isdigit() and ln.split(",")[1] != "360"]
    head = next(ln for ln in FILE.read_text().splitlines()
                if ln.startswith("run,")).split(",")
    a = np.array([[float(v) for v in r] for r in rows])
    runs = sorted(set(a[:, 0]))
    return np.array([a[a[:, 0] == r, head.index(name)] for r in runs])


def test_radial_y_by_hand_on_the_shipped_file(record):
    """Defaults (the five-DOF method §3: δ resolution 0.04 µm; §3.2: σ 0.04 µm; c = 1 %):
    U(total) = 2·√((√2·0.04/√12)² + (0.01·F)² + (√2·0.04)²); U(synchronous) takes the run-to-run
    scatter s/√3 of the mean of three runs (ISO 230-7:2015 §3) instead of the drift, s pooled
    over the angles from the file's own δy column (the same curve removed from every run leaves
    the variance across the runs unchanged)."""
    ev = with_uncertainty(record, {})
    b = ev.budget
    F = {f: ev.parameters[f"radial_Y_{f}"][0] for f in ("total", "synchronous", "asynchronous")}
    assert F["total"] == pytest.approx(7.187, abs=1e-3)         # as motion analyze prints it
    res, drift = math.sqrt(2) * 0.04 / math.sqrt(12), math.sqrt(2) * 0.04
    assert b.U("radial_Y_total") == pytest.approx(
        2 * math.sqrt(res**2 + (0.01 * F["total"])**2 + drift**2), rel=1e-12)
    s = math.sqrt(np.mean(np.var(_columns("dy_um"), axis=0, ddof=1)))
    assert s == pytest.approx(2.073, abs=1e-3)
    inputs = {i.name: i for i in b.inputs}
    assert inputs["scatter_dy"].value == pytest.approx(s, rel=1e-3)   # four digits shown
    assert not inputs["scatter_dy"].assumed and inputs["scatter_dy"].rule.startswith("measured")
    assert b.U("radial_Y_synchronous") == pytest.approx(
        2 * math.sqrt(res**2 + (0.01 * F["synchronous"])**2 + 2 * s**2 / 3), rel=1e-9)
    assert b.U("radial_Y_asynchronous") == pytest.approx(
        2 * math.sqrt(res**2 + (0.01 * F["asynchronous"])**2 + drift**2), rel=1e-12)
    # every stored figure carries U, each in its own unit; the defaults are marked assumed
    assert all(q.U is not None and q.U > 0 for q in ev.quantities.values())
    assert ev.quantities["tilt_Y_total"].unit == "arcsec"
    assert inputs["resolution_ey"].value == pytest.approx(0.2578) and inputs["resolution_ey"].assumed
    assert any("resolution_ey" in n and "assumed" in n for n in b.notes)
    assert "resolution_dx" not in inputs      # δx is not in the file: its inputs are not listed


def test_given_inputs_crosstalk_and_reference_act_where_the_docstring_says(record):
    """A crosstalk pattern repeats in every run, so it leaves the asynchronous value alone; the
    reference axis's error motion bounds every figure (rectangular, u = X/√3)."""
    base = motion_budget(record.evaluation)
    b = motion_budget(record.evaluation, {"crosstalk_ey": 3.0, "reference_tilt": 0.5,
                                          "calibration": 0.5, "k": 2})
    extra = (3.0 / math.sqrt(3))**2 + (0.5 / math.sqrt(3))**2
    F = record.parameters["tilt_Y_total"][0]
    u_total = base.combined["tilt_Y_total"]
    assert b.combined["tilt_Y_total"] ** 2 == pytest.approx(
        u_total**2 - (0.01 * F)**2 + (0.005 * F)**2 + extra, rel=1e-12)
    F_a = record.parameters["tilt_Y_asynchronous"][0]
    assert b.combined["tilt_Y_asynchronous"] ** 2 == pytest.approx(
        base.combined["tilt_Y_asynchronous"]**2 - (0.01 * F_a)**2 + (0.005 * F_a)**2
        + (0.5 / math.sqrt(3))**2, rel=1e-12)
    assert b.U("radial_Y_total") < base.U("radial_Y_total")     # only the calibration changed
    given = {i.name: i for i in b.inputs}
    assert not given["crosstalk_ey"].assumed and given["resolution_ey"].assumed


def test_one_run_has_no_asynchronous_value_and_its_synchronous_takes_the_drift(tmp_path):
    text = "\n".join(ln for ln in FILE.read_text().splitlines() if not ln[:2] in ("2,", "3,"))
    ev = with_uncertainty(evaluate_file(text.encode(), "one.csv"), {})
    assert "axial_asynchronous" not in ev.parameters
    assert ev.budget.U("axial_synchronous") == pytest.approx(
        2 * math.sqrt(2 * 0.04**2 / 12 + (0.01 * ev.parameters["axial_synchronous"][0])**2
                      + 2 * 0.03**2), rel=1e-12)
    assert not any(i.name.startswith("scatter_") for i in ev.budget.inputs)


@pytest.mark.parametrize("table, needle", [
    ({"resolution_ez": 0.1}, "resolution_ez: no such input"),
    ({"drift_dy": -0.1}, "drift_dy = -0.1: a finite number ≥ 0"),
    ({"k": 0}, "k = 0: a finite number"),
    ({"calibration": True}, "calibration = True"),
    ({"crosstalk_dz": 1e300}, "at most 1e+100")])
def test_a_bad_input_is_refused_by_name(record, table, needle):
    with pytest.raises(ConfigError, match="motion_uncertainty"):
        motion_budget(record.evaluation, table)
    with pytest.raises(ConfigError) as e:
        motion_budget(record.evaluation, table)
    assert needle in str(e.value)
    assert set(MOTION_INPUTS) >= {"resolution_dy", "drift_ex", "crosstalk_ey", "reference_axial"}


def test_motion_analyze_reads_the_table_and_refuses_a_bad_one(tmp_path, monkeypatch, record):
    """``motion analyze --json`` carries the budget of the user configuration's
    ``[motion_uncertainty]`` (the same function as the history); a bad key is one line, exit 2."""
    cfg = tmp_path / "config.toml"
    cfg.write_text("[motion_uncertainty]\ncalibration = 2.0\nresolution_dy = 0.1\n")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    r = CliRunner().invoke(app, ["motion", "analyze", str(FILE), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    want = motion_budget(record.evaluation, {"calibration": 2.0, "resolution_dy": 0.1})
    assert {k: q["U"] for k, q in d["quantities"].items()} == dict(want.expanded)
    assert d["uncertainty_inputs"] == {"calibration": 2.0, "resolution_dy": 0.1}
    assert d["uncertainty_budget"]["inputs"]["calibration"]["assumed"] is False
    text = CliRunner().invoke(app, ["motion", "analyze", str(FILE)]).stdout
    assert "Radial Y error motion, total = 7.19 ± " in text
    cfg.write_text("[motion_uncertainty]\nresolution = 0.1\n")
    r = CliRunner().invoke(app, ["motion", "analyze", str(FILE)])
    assert r.exit_code == 2 and "[motion_uncertainty] resolution: no such input" in r.output
    assert "Traceback" not in r.output and len(r.output.strip().splitlines()) == 1
