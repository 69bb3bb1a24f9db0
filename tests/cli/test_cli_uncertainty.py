"""Every assumed input of an uncertainty budget in the open: ``axiscal iso230-2`` on a real PSI/ESS
ecmc file, the demo's test, the tolerance that can never be proven, U never shown as zero.

The ecmc file ``tests/data/ecmc/sls_fat_sat_ISO230.dat`` is an ISO 230-2 input file written by
ecmc's data-collection scripts at PSI (targets -10 … 10.48 mm, so a 20.48 mm travel, 5 cycles;
reference PV ``sls-sioc-ecat01:m0s001-Enc01-PosAct``, an encoder's actual position).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "sls_fat_sat_ISO230.dat"
L_MM = 10.48 - (-10.0)      # the file's travel, first to last TGT_DATA
SQ3 = math.sqrt(3)


@pytest.fixture(autouse=True)
def _no_user_config(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "absent.toml"))
    monkeypatch.setenv("COLUMNS", "160")


def _json(*args):
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--json", *args])
    assert r.exit_code in (0, 1), r.output
    return json.loads(r.stdout)


def _thermal_u2(L_um: float) -> float:
    """Σu² of the three temperature contributors with every default (ISO 230-2:2014 Annex A.4):
    α = 11.5 µm/(m·K) ± 10 %, temperature not stated so |T − 20 °C| = 3 K (shop 17-23 °C),
    sensor ± 0.1 K, sensor place ± 0.2 K, each rectangular (u = a/√3)."""
    alpha = 11.5e-6
    return ((0.1 * alpha * L_um * 3 / SQ3) ** 2 + (0.1 * alpha * L_um / SQ3) ** 2
            + (0.2 * alpha * L_um / SQ3) ** 2)


def test_ecmc_reference_is_the_encoder_the_file_names():
    """REF_PV ``…-Enc01-PosAct`` makes the reference an encoder, shown as taken from the file:
    its ±5 µm/m scale accuracy replaces the laser's ppm, there is no beam to misalign, and U(A)
    is the root sum of squares computed here by hand."""
    d = _json()
    b = d["uncertainty_budget"]
    ref = b["inputs"]["reference"]
    assert ref["value"] == "encoder" and ref["assumed"] is False
    assert "Enc01-PosAct" in ref["rule"] and "data file" in ref["rule"]
    assert "beam_offset" not in b["inputs"] and "laser_accuracy_ppm" not in b["inputs"]
    enc = b["inputs"]["encoder_accuracy"]
    assert (enc["value"], enc["unit"], enc["assumed"]) == (5.0, "µm/m", True)
    names = [c["name"] for c in b["contributors"]]
    assert "u_MISALIGNMENT" not in names and "u_EVE" not in names
    u2 = (5.0 * L_MM * 1e-3 / SQ3) ** 2 + (0.001 / (2 * SQ3)) ** 2 + _thermal_u2(L_MM * 1e3)
    assert d["uncertainty"]["A"] == pytest.approx(2 * math.sqrt(u2), rel=1e-9)


def test_ecmc_as_laser_states_the_assumed_beam_offset():
    """Declared a laser test, the budget shows its beam offset as assumed, with the rule it
    comes from (HP 5528A guide: 0.25 mm perceptible return-dot motion, d = 0.125 mm), in the
    terminal and in --json."""
    d = _json("--uncertainty", "reference=laser")
    beam = d["uncertainty_budget"]["inputs"]["beam_offset"]
    assert beam["value"] == 0.125 and beam["unit"] == "mm" and beam["assumed"] is True
    assert "5528A" in beam["rule"] and "--uncertainty beam_offset=" in beam["set_with"]
    assert "beam_offset" in d["uncertainty_budget"]["assumed"]
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--uncertainty", "reference=laser"])
    lines = r.stdout.splitlines()
    i = next(i for i, ln in enumerate(lines) if "beam offset over the travel" in ln)
    assert "0.125 mm" in lines[i] and "assumed" in lines[i]
    assert lines[i + 1].startswith("│ beam_offset ")   # its NAME under it (the input column)


def test_ecmc_given_beam_offset_changes_U_as_the_budget_predicts():
    """With the offset given, only the cosine-error contributor changes: e = d²/(2L) over
    L = 20.48 mm, u = e/(2√3) (ISO 230-2:2014 Annex A.3). U(A) from 0.125 to 0.5 mm computed
    here from the contributors' models, independently of the budget's code."""
    L_um = L_MM * 1e3
    u_dev = 0.5e-6 * L_um / 2          # 0.5 ppm at k = 2
    u_res = 0.001 / (2 * SQ3)

    def U(d_mm):
        e = (d_mm * 1e3) ** 2 / (2 * L_um)
        return 2 * math.sqrt(u_dev**2 + u_res**2 + (e / (2 * SQ3)) ** 2 + _thermal_u2(L_um))

    small = _json("--uncertainty", "reference=laser")
    big = _json("--uncertainty", "reference=laser", "--uncertainty", "beam_offset=0.5")
    assert small["uncertainty"]["A"] == pytest.approx(U(0.125), rel=1e-9)
    assert big["uncertainty"]["A"] == pytest.approx(U(0.5), rel=1e-9)
    assert big["uncertainty"]["A"] == pytest.approx(3.525, abs=1e-3)   # the 3.52 µm
    assert big["uncertainty_display"]["A"] == "3.6"
    assert big["uncertainty_budget"]["inputs"]["beam_offset"]["assumed"] is False


def test_tolerance_smaller_than_U_is_said_at_once():
    """--tolerance A=1 with U(A) = 3.6 µm can never be proven (ISO 14253-1:2017 §5.2): one
    warning naming the parameter, T and U, in --json "warnings" and on the terminal; the
    encoder budget of the same file (U(A) = 0.16 µm) gives no such warning."""
    args = ["--uncertainty", "reference=laser", "--uncertainty", "beam_offset=0.5",
            "--tolerance", "A=1"]
    d = _json(*args)
    warn = [w for w in d["warnings"] if w.startswith("tolerance A")]
    assert len(warn) == 1 and "A = 1 µm" in warn[0] and "U = 3.6 µm" in warn[0]
    assert "never be proven" in warn[0]
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), *args])
    assert r.exit_code == 1
    assert sum("warning: tolerance A = 1 µm" in ln for ln in r.stdout.splitlines()) == 1
    ok = _json("--tolerance", "A=1")
    assert ok["uncertainty_display"]["A"] == "0.16"
    assert not any(w.startswith("tolerance") for w in ok["warnings"])


def test_missing_E_VE_is_named_and_left_out():
    """No drift check, no declared E_VE: the budget says so (missing input, a note) and Annex
    A's narrow U(R) is the reading's alone: 2 · q/(2√3) µm (the SLS file's readings step by
    0.001 µm, the default); the printed U(R) adds the sampling of the runs (issue 38)."""
    d = _json()
    b = d["uncertainty_budget"]
    q = b["inputs"]["resolution"]["value"]
    assert q == pytest.approx(0.001)
    assert b["missing_inputs"] == ["e_ve"] and b["inputs"]["e_ve"]["value"] is None
    assert any("E_VE not given" in n and "drift check" in n for n in b["notes"])
    assert b["U_narrow"]["R"] == pytest.approx(q / SQ3, rel=1e-12)
    assert d["uncertainty"]["R"] > 10 * b["U_narrow"]["R"]
    assert d["uncertainty_display"]["R"] == "0.034"
    declared = _json("--uncertainty", "e_ve=0.3")
    assert declared["uncertainty_budget"]["missing_inputs"] == []
    assert declared["uncertainty_budget"]["U_narrow"]["R"] == pytest.approx(
        2 * math.hypot(q / (2 * SQ3), 0.3 / (2 * SQ3)), rel=1e-12)


def test_runs_stated():
    """R and B rest on 5 runs: the relative standard uncertainty of s, 1/√(2·4) = 35 %
    (JCGM 100:2008 Annex E.4.3), is stated."""
    notes = _json()["uncertainty_budget"]["notes"]
    assert any("5 runs per direction" in n and "35 %" in n for n in notes)


@pytest.mark.parametrize("item, message", [
    ("beam_offset", "write NAME=VALUE"),
    ("beam_ofset=0.1", "unknown key"),
    ("beam_offset=-1", "implausible: give 0 to 25 mm"),
    ("reference=tracker", "use laser or encoder"),
])
def test_bad_uncertainty_option_is_one_line(item, message):
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--uncertainty", item])
    assert r.exit_code == 2
    assert message in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert "Traceback" not in r.output


def test_demo_U_of_R_is_not_zero(tmp_path):
    """The demo's linear test (src/axiscal/data/demo_linear.toml, seed 1): U(R) is the budget's
    value rounded up to two significant digits, never "0.00" (JCGM 100:2008 §7.2.6); its raw
    value is kept in --json. Since issue 38 it holds the sampling of the 5 runs (1.6 µm, R =
    5.81 µm), Annex A's narrow 0.00058 µm (the reading alone) kept as U_narrow; against R ≤ 5
    the verdict is decided with the U printed and is the zone, no longer FAIL."""
    import tomllib
    from importlib import resources

    from axiscal.io.csv import format_positioning_csv
    from axiscal.procedures.positioning import simulate_from_config
    from axiscal.standards.iso230_2 import evaluate
    from axiscal.standards.iso230_9 import positioning_budget, round_up

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    ds = simulate_from_config(cfg, seed=1).dataset
    budget = positioning_budget(ds, evaluate(ds))
    assert round_up(budget.U("R")) == 1.6 and round_up(budget.narrow["R"]) == 0.00058
    path = tmp_path / "linear_data.csv"
    path.write_text(format_positioning_csv(ds))
    r = CliRunner().invoke(app, ["iso230-2", str(path), "--json", "--tolerance", "R=5"])
    d = json.loads(r.stdout)
    assert d["uncertainty"]["R"] == pytest.approx(budget.U("R"), rel=1e-9)   # via the CSV
    assert d["uncertainty_display"]["R"] == "1.6" and d["acceptance"][0]["U"] == 1.6
    assert d["acceptance"][0]["outcome"] == "uncertainty zone"
    r = CliRunner().invoke(app, ["iso230-2", str(path), "--tolerance", "R=5"])
    row = next(ln for ln in r.stdout.splitlines() if ln.startswith("│ R ") and "ZONE" in ln)
    assert "1.6" in row and "0.00 " not in row


def test_evaluate_shows_the_same_budget_and_warning(tmp_path):
    """``axiscal evaluate -s iso230-2:2014`` decides with the same budget as ``iso230-2`` (the
    same --uncertainty inputs), says the unprovable tolerance, shows the inputs, and its report
    carries the uncertainty section with every input and the warning."""
    args = ["evaluate", str(ECMC), "-s", "iso230-2:2014", "--tolerance", "A=1",
            "--uncertainty", "reference=laser", "--uncertainty", "beam_offset=0.5"]
    r = CliRunner().invoke(app, [*args, "--json"])
    d = json.loads(r.stdout)
    same = _json("--uncertainty", "reference=laser", "--uncertainty", "beam_offset=0.5")
    assert d["acceptance"][0]["U"] == float(same["uncertainty_display"]["A"])   # as printed
    assert d["acceptance"][0]["U_display"] == "3.6"
    assert len(d["warnings"]) == 1 and "tolerance A = 1 µm" in d["warnings"][0]
    assert d["uncertainty_budget"]["inputs"]["beam_offset"]["assumed"] is False
    r = CliRunner().invoke(app, [*args, "--report", str(tmp_path / "r.html")])
    assert r.exit_code == 1 and "warning: tolerance A = 1 µm" in r.stdout
    assert "beam offset over the travel" in r.stdout
    page = (tmp_path / "r.html").read_text()
    assert "Measurement uncertainty" in page and "tolerance A = 1 µm" in page
    assert "beam offset over the travel" in page and "5528A" not in page   # declared, no rule
    assert "environmental variation error E<sub>VE</sub>" in page
    assert "missing: left out of U" in page
    assert "beam_offset" not in page and "[uncertainty]" not in page   # no keys on the page


def test_E_VE_measured_by_a_drift_check(tmp_path):
    """--drift-check FILE: E_VE is the range of the still set-up's readings (ISO 230-2:2014
    Annex A.5), shown as measured, not assumed; Annex A's U(R) = 2·√((r/(2√3))² +
    (E_VE/(2√3))²), r the encoder's step from the data."""
    drift = tmp_path / "drift.csv"
    drift.write_text("# X at rest, 30 min\ntime_s,reading\n0,0.00\n600,0.21\n1200,-0.09\n1800,0.15\n")
    d = _json("--drift-check", str(drift))
    e_ve = d["uncertainty_budget"]["inputs"]["e_ve"]
    assert e_ve["value"] == pytest.approx(0.30) and e_ve["assumed"] is False
    assert "drift check" in e_ve["rule"] and d["uncertainty_budget"]["missing_inputs"] == []
    q = d["uncertainty_budget"]["inputs"]["resolution"]["value"]
    assert d["uncertainty_budget"]["U_narrow"]["R"] == pytest.approx(
        2 * math.hypot(q / (2 * SQ3), 0.30 / (2 * SQ3)), rel=1e-9)
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--drift-check", str(drift),
                                 "--uncertainty", "e_ve=1"])
    assert r.exit_code == 2 and "given twice" in r.stderr
    drift.write_text("time_s,temperature\n0,20\n")
    r = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--drift-check", str(drift)])
    assert r.exit_code == 2 and "no 'reading' or 'deviation' column" in r.stderr


def test_evaluate_report_lists_U_per_parameter_without_tolerances(tmp_path):
    """Without a tolerance the report still shows U of each parameter, as displayed everywhere
    (R: 0.034 µm with the sampling of the runs since issue 38, never 0.00)."""
    r = CliRunner().invoke(app, ["evaluate", str(ECMC), "-s", "iso230-2:2014",
                                 "--report", str(tmp_path / "r.html")])
    assert r.exit_code == 0, r.output
    page = (tmp_path / "r.html").read_text()
    row = page.split("U (k = 2) [µm]</td>", 1)[1].split("</tr>", 1)[0]
    cells = [c.split("</td>")[0] for c in row.split("<td>")[1:]]
    assert cells[0] == "0.16" and "0.034" in cells and "0.00" not in cells
