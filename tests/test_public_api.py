"""The public API (axiscal.api) as a notebook uses it: read -> evaluate -> plot -> report ->
compensation table -> history, through ``axiscal.<name>`` only, with the same numbers as the
command line's ``--json`` for the same file (the API and the CLI call one library)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app

ROOT = Path(__file__).resolve().parents[1]
DEMO_LINEAR = ROOT / "src" / "axiscal" / "data" / "demo_linear.toml"
BALLBAR = ROOT / "examples" / "squareness_ballbar_150mm.csv"
runner = CliRunner()


def _cli_json(*args) -> dict:
    r = runner.invoke(app, [str(a) for a in args] + ["--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


@pytest.fixture(scope="module")
def laser_file(tmp_path_factory) -> Path:
    """A simulated laser test written as the demo writes it (``axiscal simulate --data``)."""
    p = tmp_path_factory.mktemp("api") / "x_axis.csv"
    r = runner.invoke(app, ["simulate", str(DEMO_LINEAR), "--data", str(p)])
    assert r.exit_code == 0, r.output
    return p


def test_notebook_flow_equals_the_cli(laser_file, tmp_path):
    """read -> evaluate -> plot -> report -> table -> history, each equal to its command."""
    from matplotlib.figure import Figure

    ds = axiscal.read(laser_file)
    ev = axiscal.evaluate(ds)
    assert ev.to_dict() == _cli_json("iso230-2", laser_file)
    assert ev.standard == "iso230-2:2014" and ev.result.E == ev.to_dict()["E"]
    assert isinstance(ev.plot(), Figure)
    html = ev.report(tmp_path / "x.html").read_text("utf-8")
    assert "ISO 230-2" in html and f"{ev.result.E:.2f}" in html
    notebook = ev._repr_html_()
    assert "<table>" in notebook and "<svg" in notebook
    # in the reports' words: the standard's title, labels with units, the unit's decimals
    assert "by ISO 230-2:2014" in notebook and "<th>E, bidirectional systematic error [µm]</th>" \
        f"<td>{ev.result.E:.2f}</td>" in notebook
    assert "A_up" not in notebook and "<th>Machine</th>" in notebook
    assert "E↑ =" in str(ev) and "µm" in str(ev) and " um" not in str(ev)

    table = axiscal.compensation_table(ev, spacing=10)
    cf = axiscal.write_table(table, "siemens-840d", tmp_path / "x.ini")
    cli = _cli_json("compensate", laser_file, "--controller", "siemens-840d", "--spacing", 10,
                    "--out", tmp_path / "cli.ini")
    assert (tmp_path / "x.ini").read_text("utf-8") == (tmp_path / "cli.ini").read_text("utf-8")
    assert cf.text == (tmp_path / "x.ini").read_text("utf-8")
    assert cf.table.to_dict() == cli["table"] and table.n_points == cli["n_points"]

    with axiscal.History(f"sqlite:///{tmp_path / 'h.sqlite'}") as h:
        added = h.add(laser_file, machine="VMC-1")
        assert not added.duplicate and h.add(laser_file, machine="VMC-1").duplicate
        (stored,) = h.tests()
        assert stored.parameters["E"][0] == pytest.approx(ev.result.E, rel=1e-12)


def test_other_standards_equal_axiscal_evaluate(laser_file, tmp_path):
    """``standard=KEY`` and ``all`` give ``axiscal evaluate --standard KEY --json``'s object."""
    for key in ("jis-b6192", "all"):
        ev = axiscal.evaluate(laser_file, key)
        assert ev.to_dict() == _cli_json("evaluate", laser_file, "--standard", key)
    assert ev.report(tmp_path / "all.html").exists()


def test_tolerances_decided_as_the_cli(laser_file):
    """``tolerances=`` decides as ``--tolerance`` (ISO 14253-1:2017 with U of ISO 230-2 Annex A)."""
    ev = axiscal.evaluate(laser_file, tolerances={"E": 100.0, "R": 0.5})
    r = runner.invoke(app, ["iso230-2", str(laser_file), "--tolerance", "E=100",
                            "--tolerance", "R=0.5", "--json"])
    assert r.exit_code == 1   # R = 0.5 um is not met by the simulated axis
    assert ev.to_dict() == json.loads(r.stdout)
    assert ev.to_dict()["accepted"] is False


def test_uncertainty_inputs_as_the_cli(laser_file):
    """``uncertainty=`` is ``--uncertainty NAME=VALUE``: E_VE declared (ISO 230-2:2014 Annex A.5)
    enters U of every parameter, as in ``axiscal iso230-2 --uncertainty e_ve=0.3 --json``."""
    ev = axiscal.evaluate(laser_file, uncertainty={"e_ve": 0.3})
    cli = _cli_json("iso230-2", laser_file, "--uncertainty", "e_ve=0.3")
    assert ev.to_dict() == cli
    without = axiscal.evaluate(laser_file).to_dict()["uncertainty"]
    assert ev.to_dict()["uncertainty"]["R"] > without["R"]


def test_ballbar_file_equals_ballbar_analyze():
    """A ballbar file read by content, diagnosed as ``axiscal ballbar analyze --json``."""
    ev = axiscal.evaluate(BALLBAR)
    cli = _cli_json("ballbar", "analyze", BALLBAR)
    assert ev.kind == "ballbar"
    assert ev.to_dict() == {k: v for k, v in cli.items() if k != "file"}
    same = axiscal.evaluate(axiscal.read(BALLBAR))    # in memory: the same one evaluation
    assert same.to_dict() == ev.to_dict()


def test_simulate_equals_axiscal_simulate(tmp_path):
    """``axiscal.simulate`` is ``axiscal simulate --json`` (and ``--data``) for the same seed."""
    sim = axiscal.simulate(DEMO_LINEAR, seed=3)
    assert sim.to_dict() == _cli_json("simulate", DEMO_LINEAR, "--seed", 3, "--data",
                                      tmp_path / "cli.csv")
    assert (sim.write_data(tmp_path / "api.csv").read_text("utf-8")
            == (tmp_path / "cli.csv").read_text("utf-8"))


def test_errors_name_the_problem(tmp_path):
    from axiscal.errors import AxiscalError

    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n", "utf-8")
    with pytest.raises(AxiscalError, match=r"bad.csv:1: header 'a,b' must name the columns"):
        axiscal.read(bad)   # the file, the line and the header, as axiscal iso230-2 says
    with pytest.raises(AxiscalError, match="standard 'iso9999'"):
        axiscal.evaluate(_laser(tmp_path), "iso9999")


def _laser(tmp_path) -> Path:
    p = tmp_path / "l.csv"
    assert runner.invoke(app, ["simulate", str(DEMO_LINEAR), "--data", str(p)]).exit_code == 0
    return p


def test_import_is_light():
    """``import axiscal`` imports none of the API's modules until a name is used (PEP 562)."""
    code = ("import sys, axiscal; assert 'axiscal.api' not in sys.modules; "
            "assert 'numpy' not in sys.modules; axiscal.read; assert 'axiscal.api' in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_mypy_on_the_public_api():
    """The public API's type hints hold (mypy on the axiscal.api package and axiscal/__init__.py
    only)."""
    files = [str(p) for p in sorted((ROOT / "src" / "axiscal" / "api").glob("*.py"))]
    files.append(str(ROOT / "src" / "axiscal" / "__init__.py"))
    r = subprocess.run([sys.executable, "-m", "mypy", "--follow-imports=silent",
                        "--ignore-missing-imports", "--no-error-summary", *files],
                       capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stdout + r.stderr


def test_straightness_and_diagonal_files_equal_their_commands(tmp_path):
    """The other kinds through ``axiscal.evaluate(path)``: the history's evaluation object, with
    the numbers of ``axiscal straightness --json`` and ``axiscal squareness diagonal --json``."""
    from matplotlib.figure import Figure

    f = ROOT / "examples" / "squareness_L180_x.csv"
    ev, cli = axiscal.evaluate(f), _cli_json("straightness", f)
    assert ev.kind == "straightness" and ev.standard == "iso230-1"
    for method in ("least_squares", "minimum_zone"):
        assert ev.to_dict()[method] == cli["methods"][method]
    f = ROOT / "examples" / "squareness_diagonal_600x800.csv"
    ev, cli = axiscal.evaluate(f), _cli_json("squareness", "diagonal", "--file", f)
    assert ev.to_dict()["squareness"]["um_per_m"] == cli["squareness"]["um_per_m"]
    assert isinstance(ev.plot(), Figure)
    assert "Diagonal squareness" in ev.report(tmp_path / "d.html").read_text("utf-8")


def test_motion_file_equals_motion_analyze(tmp_path):
    """A five-error file (ISO 230-7) evaluated as ``axiscal motion analyze``: the stored totals
    are SI (m, rad), the command's in µm and arcsec."""
    from axiscal import units

    f = tmp_path / "motion.csv"
    cfg = ROOT / "examples" / "motion_indexing_table.toml"
    assert runner.invoke(app, ["motion", "simulate", str(cfg), "--csv", str(f)]).exit_code == 0
    ev, cli = axiscal.evaluate(f), _cli_json("motion", "analyze", f)
    assert ev.kind == "motion" and ev.standard == "iso230-7"
    shown = {m["name"]: m for m in cli["iso230_7"]["motions"]}
    for m in ev.to_dict()["motions"]:
        scale = units.UM if shown[m["name"]]["unit"] == "um" else units.ARCSEC
        assert m["total"] / scale == pytest.approx(shown[m["name"]]["total"], rel=1e-9)
    assert ev.report(tmp_path / "m.html").exists() and "<svg" in ev._repr_html_()


def test_rotary_calibration_equals_rotary_simulate(tmp_path):
    """A configuration with a [calibrator] is a rotary calibration: ``axiscal rotary simulate
    --json`` for the same seed (Renishaw, "Interferometric calibration of rotary axes")."""
    cfg = ROOT / "src" / "axiscal" / "data" / "rotary_turntable.toml"
    sim = axiscal.simulate(cfg, seed=4)
    assert sim.kind == "rotary-calibration"
    assert sim.to_dict() == _cli_json("rotary", "simulate", cfg, "--seed", 4)
    assert sim.dataset.axis_kind.value == "rotary"
    assert sim.report(tmp_path / "r.html").exists() and "<svg" in sim._repr_html_()


def test_per_target_table_as_a_dataframe(laser_file):
    """``to_dataframe("targets")``: the ``targets`` rows of the JSON indexed by target, every
    other column, the units in ``attrs``."""
    ev = axiscal.evaluate(laser_file)
    df = ev.to_dataframe("targets")
    rows = ev.to_dict()["targets"]
    assert len(df) == len(rows) and list(df.columns) == list(rows[0])[1:]
    assert df.reset_index().to_dict("records") == rows
    assert df.attrs["units"]["target"] == "mm" and df.attrs["units"]["mean_up"] == "um"


def test_parameters_as_a_dataframe_with_u(laser_file):
    """``to_dataframe()``: one row per quantity with value, U, k, unit and verdict, equal to
    the ``quantities`` of ``--json`` and to the attributes (``ev.E.U``)."""
    ev = axiscal.evaluate(laser_file, uncertainty={"e_ve": 0.3}, tolerances={"E": 100})
    df = ev.to_dataframe()
    q = ev.to_dict()["quantities"]
    assert list(df.index) == list(q) and ev.to_dict()["schema_version"] == 1
    assert df.loc["E", "U"] == q["E"]["U"] == ev.E.U == ev.budget.U("E") > 0
    assert df.loc["E", "value"] == ev.result.E and df.loc["E", "k"] == 2.0
    assert df.loc["E", "verdict"] == "conformance proven" and df.loc["E", "tolerance"] == 100
    assert df.loc["R_up", "symbol"] == "R↑" and ev["R_up"] is ev.quantities["R_up"]
    with pytest.raises(AttributeError, match="no attribute or quantity 'Z'"):
        ev.Z


def test_dataframe_without_pandas_says_how_to_get_it(laser_file, monkeypatch):
    """pandas is optional: without it, one error that says how to install it."""
    import sys

    from axiscal.errors import AxiscalError

    monkeypatch.setitem(sys.modules, "pandas", None)     # import pandas raises ImportError
    with pytest.raises(AxiscalError, match="pip install pandas"):
        axiscal.evaluate(laser_file).to_dataframe()


SCALE_SINGLE = ROOT / "examples" / "scale_single.toml"
SCALE_GANTRY = ROOT / "examples" / "scale_gantry.toml"
MOTION = ROOT / "examples" / "motion_indexing_table.toml"
RAW = ROOT / "examples" / "raw_readings_vmc800_x.csv"
ENV_LOG = ROOT / "examples" / "environment_log_vmc800_x.csv"


def _figure_and_report(sim, path: Path, title: str) -> None:
    from matplotlib.figure import Figure

    assert isinstance(sim.plot(), Figure)
    assert title in sim.report(path).read_text("utf-8")
    assert "<svg" in sim._repr_html_()


def test_scale_homing_equals_scale_home(tmp_path):
    """A configuration with [laser], [compensator], [switch], [homing]: referencing of one
    laser-scale axis, as 'axiscal scale home --json' (with and without --seed)."""
    sim = axiscal.simulate(SCALE_SINGLE)
    assert sim.kind == "scale-homing"
    d = sim.to_dict()
    assert d == _cli_json("scale", "home", SCALE_SINGLE)
    assert d["homed"] is True and "tracking" in d
    assert axiscal.simulate(SCALE_SINGLE, seed=7).to_dict() == _cli_json(
        "scale", "home", SCALE_SINGLE, "--seed", 7)
    _figure_and_report(sim, tmp_path / "home.html", "Laser scale referencing")


def test_gantry_homing_equals_scale_gantry(tmp_path):
    sim = axiscal.simulate(SCALE_GANTRY)
    assert sim.kind == "gantry-homing"
    assert sim.to_dict() == _cli_json("scale", "gantry", SCALE_GANTRY)
    assert sim.to_dict()["required_skew_limit"] > 256   # above one period of counts
    _figure_and_report(sim, tmp_path / "gantry.html", "Twin-axis homing")


def test_five_dof_equals_motion_simulate(tmp_path):
    """Five motion errors and ISO 230-7, as 'axiscal motion simulate --json'."""
    sim = axiscal.simulate(str(MOTION))
    assert sim.kind == "five-dof"
    d = sim.to_dict()
    assert d == _cli_json("motion", "simulate", str(MOTION))
    assert sim.result.n_runs == 1 and d["iso230_7"]["n_runs"] == 1
    assert len(sim.dataset.theta) == len(d["positions"]) == 13   # 0° to 360° by 30° (closure)
    _figure_and_report(sim, tmp_path / "motion.html", "Five motion errors")
    runner.invoke(app, ["motion", "simulate", str(MOTION), "--csv", str(tmp_path / "cli.csv")])
    api_csv = sim.write_data(tmp_path / "api.csv")
    assert api_csv.read_text("utf-8") == (tmp_path / "cli.csv").read_text("utf-8")
    assert axiscal.evaluate(api_csv).kind == "motion"


def test_volumetric_map_equals_volumetric_map_command(tmp_path):
    r = runner.invoke(app, ["volumetric", "simulate", "--out", str(tmp_path / "vol")])
    assert r.exit_code == 0, r.output
    cfg = tmp_path / "vol" / "volumetric.toml"
    vm = axiscal.volumetric_map(cfg, grid=6)
    d = vm.to_dict()
    assert d == _cli_json("volumetric", "map", cfg, "--grid", 6)
    assert d["grid_points"] == 6 ** 3 and len(d["diagonals"]) == 4
    assert d["mapped_minus_true_um"] < d["largest_um"]
    _figure_and_report(vm, tmp_path / "vol.html", "olumetric")
    with pytest.raises(axiscal.errors.InputError, match="grid"):
        axiscal.volumetric_map(cfg, grid=1)

    comp = axiscal.volumetric_compensation(cfg, "siemens-840d", out=tmp_path / "api",
                                           receiving={"zx": "X"}, verify=True)
    cli = _cli_json("volumetric", "compensate", cfg, "--controller", "siemens-840d", "--out",
                    tmp_path / "cli", "--receiving", "zx=X", "--verify")
    assert comp.to_dict() == cli and cli["receiving"]["zx"] == "X"
    for name in cli["files"]:
        assert (tmp_path / "api" / name).read_text("utf-8") == (
            tmp_path / "cli" / name).read_text("utf-8")
    assert cli["verify"]["figures"]["largest volumetric error"]["reduction"] > 0
    _figure_and_report(comp, tmp_path / "comp.html", "Volumetric compensation")


def test_compensate_environment_equals_the_cli(tmp_path):
    """Raw readings + environment log: the same JSON, the same compensated file, and its
    ISO 230-2 evaluation equal to 'axiscal iso230-2' of the file the command wrote."""
    comp = axiscal.compensate_environment(RAW, ENV_LOG, out=tmp_path / "api.csv")
    cli = _cli_json("compensate-environment", RAW, "--environment", ENV_LOG, "--out",
                    tmp_path / "cli.csv")
    d = comp.to_dict()
    assert d.pop("out") == str(tmp_path / "api.csv") and cli.pop("out") == str(tmp_path / "cli.csv")
    assert d == cli and d["readings"] == 30
    assert (tmp_path / "api.csv").read_text("utf-8") == (tmp_path / "cli.csv").read_text("utf-8")
    ev = axiscal.evaluate(axiscal.read(tmp_path / "api.csv"))
    assert ev.to_dict() == _cli_json("iso230-2", tmp_path / "cli.csv")
    assert "Ciddor" in str(comp)
    _figure_and_report(comp, tmp_path / "env.html", "Environmental compensation")
    with pytest.raises(axiscal.errors.InputError, match="unknown condition"):
        axiscal.compensate_environment(RAW, ENV_LOG, temperature=20.0)
