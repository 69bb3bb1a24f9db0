"""The command line and the workbench go through the public API (issue 33: "The CLI and the
workbench use this same API"): each command's ``--json`` is the API's ``to_dict()`` for the same
input, and each command is seen to call its API entry (the entry replaced by a counting wrapper
while typer's CliRunner runs the command). Dict configurations of every simulated kind are read
by the file's schema; the LinuxCNC 3-D correction is an API entry."""

from __future__ import annotations

import json
import re
import tomllib
from pathlib import Path

import pytest
from typer.testing import CliRunner

import axiscal
from axiscal import api
from axiscal.cli import app

ROOT = Path(__file__).resolve().parents[1]
DEMO_LINEAR = ROOT / "src" / "axiscal" / "data" / "demo_linear.toml"
BALLBAR = ROOT / "examples" / "squareness_ballbar_150mm.csv"
SCALE_SINGLE = ROOT / "examples" / "scale_single.toml"
SCALE_GANTRY = ROOT / "examples" / "scale_gantry.toml"
MOTION = ROOT / "examples" / "motion_indexing_table.toml"
BALLBAR_SIM = ROOT / "examples" / "ballbar_sim.toml"
runner = CliRunner()


def _cli(*args, code: int = 0) -> str:
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == code, r.output
    return r.stdout


def _cli_json(*args, code: int = 0) -> dict:
    return json.loads(_cli(*args, "--json", code=code))


@pytest.fixture(scope="module")
def laser_file(tmp_path_factory) -> Path:
    """A simulated laser test as ``axiscal simulate --data`` writes it."""
    p = tmp_path_factory.mktemp("fe") / "x_axis.csv"
    _cli("simulate", DEMO_LINEAR, "--data", p)
    return p


@pytest.fixture(scope="module")
def volumetric_config(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("vol") / "vol"
    _cli("volumetric", "simulate", "--out", out)
    return out / "volumetric.toml"


# -- each command goes through its API entry ---------------------------------------------------
def _counting(monkeypatch, names: tuple[str, ...]) -> dict:
    """Replace ``axiscal.api.<name>`` (``History.add`` for ``History.add``) by a wrapper that
    counts its calls and calls the real one."""
    calls = dict.fromkeys(names, 0)
    for name in names:
        owner, attr = (api.History, "add") if name == "History.add" else (api, name)
        real = getattr(owner, attr)

        def wrapper(*a, _real=real, _name=name, **kw):
            calls[_name] += 1
            return _real(*a, **kw)

        monkeypatch.setattr(owner, attr, wrapper)
    return calls


COMMANDS = [
    (["iso230-2", "{laser}", "--json"], ("read", "evaluate")),
    (["iso230-2", "{laser}", "--history", "--db", "{db}"], ("read", "evaluate", "History.add")),
    (["evaluate", "{laser}", "-s", "jis-b6192", "--json"], ("read", "evaluate")),
    (["ballbar", "analyze", str(BALLBAR), "--json"], ("read", "evaluate")),
    (["history", "add", "{laser}", "--db", "{db}", "--json"], ("History.add",)),
    (["compensate", "{laser}", "--controller", "csv", "--json"],
     ("compensation_table", "write_table")),
    (["simulate", str(DEMO_LINEAR), "--json"], ("simulate",)),
    (["ballbar", "simulate", str(BALLBAR_SIM), "--json"], ("simulate",)),
    (["rotary", "simulate", str(ROOT / "examples" / "rotary_turntable.toml"), "--json"],
     ("simulate",)),
    (["scale", "home", str(SCALE_SINGLE), "--json"], ("simulate",)),
    (["scale", "gantry", str(SCALE_GANTRY), "--json"], ("simulate",)),
    (["motion", "simulate", str(MOTION), "--json"], ("simulate",)),
    (["compensate-environment", str(ROOT / "examples" / "raw_readings_vmc800_x.csv"),
      "--environment", str(ROOT / "examples" / "environment_log_vmc800_x.csv"), "--out",
      "{tmp}/env.csv", "--json"], ("compensate_environment",)),
    (["volumetric", "map", "{vol}", "--grid", "3", "--json"], ("volumetric_map",)),
    (["volumetric", "compensate", "{vol}", "--controller", "csv", "--json"],
     ("volumetric_compensation",)),
]


@pytest.mark.parametrize("args, entries", COMMANDS, ids=lambda v: " ".join(v)[:40]
                         if isinstance(v, list) else None)
def test_each_command_calls_its_api_entry(args, entries, laser_file, volumetric_config,
                                          tmp_path, monkeypatch):
    """The command's work is done by the API entry: each is called exactly once."""
    calls = _counting(monkeypatch, entries)
    fill = {"laser": str(laser_file), "db": f"sqlite:///{tmp_path / 'h.sqlite'}",
            "vol": str(volumetric_config), "tmp": str(tmp_path)}
    _cli(*[a.format(**fill) for a in args])
    assert calls == dict.fromkeys(entries, 1)


def test_the_workbench_upload_stores_through_history_add(laser_file, tmp_path, monkeypatch):
    """The workbench's upload is History.add over the app's open store (the same bytes)."""
    from fastapi.testclient import TestClient

    from axiscal.web.app import create_app

    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    calls = _counting(monkeypatch, ("History.add",))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": tok},
               files={"file": ("x.csv", laser_file.read_bytes(), "text/csv")})
    assert r.status_code == 200 and "/tests/1" in str(r.url) and calls["History.add"] == 1
    with api.History(f"sqlite:///{tmp_path / 'h.sqlite'}") as h:
        assert h.add(laser_file).duplicate                      # the same bytes, stored once
        ev = h.evaluation(1)
    assert ev.kind == "iso230-2" and ev.result.E == pytest.approx(
        axiscal.evaluate(laser_file).result.E, rel=1e-12)


# -- --json of each moved command equals the API's to_dict() ----------------------------------
def test_ballbar_analyze_with_feed_and_plane_equals_the_api():
    """``--feed``/``--plane`` are ``evaluate(feed=, plane=)``: the same diagnosis, in mm/min."""
    cli = _cli_json("ballbar", "analyze", BALLBAR, "--feed", 1500, "--plane", "ZX")
    ev = axiscal.evaluate(BALLBAR, feed=1500, plane="zx")
    assert cli.pop("file") == str(BALLBAR) and cli == ev.to_dict()
    assert cli["plane"] == "ZX" and cli["feed_mm_per_min"] == pytest.approx(1500)
    with pytest.raises(axiscal.errors.InputError, match="--plane"):
        axiscal.evaluate(BALLBAR, plane="XZ")


def test_iso230_2_with_job_and_drift_check_equals_the_api(laser_file, tmp_path):
    """``--job``, ``--drift-check``, ``--uncertainty`` and ``--tolerance`` as keyword arguments:
    E_VE is the drift check's range (ISO 230-2:2014 Annex A.5) in both."""
    job = tmp_path / "job.toml"
    job.write_text("[uncertainty]\nbeam_offset = 0.05\n", "utf-8")
    drift = tmp_path / "drift.csv"
    drift.write_text("time_s,reading\n0,0.00\n600,0.21\n1200,-0.09\n", "utf-8")
    cli = _cli_json("iso230-2", laser_file, "--job", job, "--drift-check", drift,
                    "--uncertainty", "reference=encoder", "--tolerance", "E=100")
    ev = axiscal.evaluate(laser_file, job=job, drift_check=drift,
                          uncertainty={"reference": "encoder"}, tolerances={"E": 100.0})
    assert ev.to_dict() == cli and ev.conformance_proven is True
    assert cli["uncertainty_budget"]["inputs"]["e_ve"]["value"] == pytest.approx(0.30)
    assert ev.config["uncertainty"]["beam_offset"] == 0.05
    as_dict = axiscal.evaluate(laser_file, job={"uncertainty": {"beam_offset": 0.05}},
                               drift_check=drift, uncertainty={"reference": "encoder"},
                               tolerances={"E": 100.0})
    assert as_dict.to_dict() == cli                     # the job's tables as a dict
    with pytest.raises(axiscal.errors.InputError, match="given twice"):
        axiscal.evaluate(laser_file, drift_check=drift, uncertainty={"e_ve": 1.0})


def test_evaluate_iso230_2_2014_in_the_standards_form(laser_file):
    """``axiscal evaluate -s iso230-2:2014 --tolerance`` is ``form="standards"``, with the
    Annex A budget behind U; the default form stays ``axiscal iso230-2``'s."""
    cli = _cli_json("evaluate", laser_file, "-s", "iso230-2:2014", "--tolerance", "E=100")
    ev = axiscal.evaluate(laser_file, "iso230-2:2014", tolerances={"E": 100.0}, form="standards")
    assert ev.to_dict() == cli and "uncertainty_budget" in cli and "standards" in cli
    assert "standards" not in axiscal.evaluate(laser_file).to_dict()
    with pytest.raises(axiscal.errors.InputError, match="form iso230-2"):
        axiscal.evaluate(laser_file, "jis-b6192", form="iso230-2")


def test_history_add_json_equals_history_add(laser_file, tmp_path):
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    cli = _cli_json("history", "add", laser_file, "--db", url, "--machine", "VMC-1")
    with api.History(url) as h:
        r = h.add(laser_file, machine="VMC-1")
    assert r.duplicate and {"id": r.id, "duplicate": False, "kind": r.kind,
                            "machine": r.machine, "axis": r.axis} == cli
    with pytest.raises(axiscal.errors.InputError, match="filename"):
        api.History(url).add(b"bytes")


def test_compensate_with_travel_and_options_equals_write_table(laser_file, tmp_path):
    """``--travel`` and ``--option`` are ``write_table(travel=, **options)``."""
    cli = _cli_json("compensate", laser_file, "--controller", "fanuc", "--travel", -10,
                    "--travel", 1000, "-o", "axis_number=2", "--out", tmp_path / "cli.txt")
    table = axiscal.compensation_table(laser_file)
    cf = axiscal.write_table(table, "fanuc", tmp_path / "api.txt", travel=(-10.0, 1000.0),
                             axis_number=2)
    assert cf.table.to_dict() == cli["table"] and list(cf.enable) == cli["enable"]
    assert (tmp_path / "api.txt").read_text("utf-8") == (tmp_path / "cli.txt").read_text("utf-8")


def test_simulate_report_and_rtl_equal_the_command(tmp_path):
    """The Simulation's report holds the truth section, as ``--report``; ``write_data`` writes
    Renishaw .rtl as ``--data x.rtl``."""
    _cli("simulate", DEMO_LINEAR, "--seed", 2, "--report", tmp_path / "cli.html",
         "--data", tmp_path / "cli.rtl")
    sim = axiscal.simulate(DEMO_LINEAR, seed=2)
    page = sim.report(tmp_path / "api.html").read_text("utf-8")
    assert "Evaluation beside the truth" in page
    assert (sim.write_data(tmp_path / "api.rtl").read_text("utf-8")
            == (tmp_path / "cli.rtl").read_text("utf-8"))


# -- dict configurations, checked by the file's schema ----------------------------------------
@pytest.mark.parametrize("path, kind", [(SCALE_SINGLE, "scale-homing"),
                                        (SCALE_GANTRY, "gantry-homing"),
                                        (MOTION, "five-dof"), (DEMO_LINEAR, "positioning"),
                                        (BALLBAR_SIM, "ballbar")])
def test_a_dict_configuration_equals_its_file(path, kind):
    """The TOML file's tables as a dict give the same run as the file, for every kind."""
    cfg = tomllib.loads(path.read_text("utf-8"))
    from_dict, from_file = axiscal.simulate(cfg, seed=5), axiscal.simulate(path, seed=5)
    assert from_dict.kind == from_file.kind == kind
    d, f = from_dict.to_dict(), from_file.to_dict()
    if "config" in f:                       # five-DOF and ballbar name their configuration
        assert (d.pop("config"), f.pop("config")) == ("<dict>", str(path))
    assert d == f


@pytest.mark.parametrize("path, table", [(SCALE_SINGLE, "compensator"), (MOTION, "test"),
                                         (BALLBAR_SIM, "servo")])
def test_a_dict_with_an_unknown_key_is_refused_as_the_file_is(path, table, tmp_path):
    """An unknown key is named in the same words for a dict and a file (the schema's)."""
    from axiscal.errors import ConfigError

    cfg = tomllib.loads(path.read_text("utf-8"))
    cfg[table]["spacing_typo"] = 1.0
    with pytest.raises(ConfigError) as from_dict:
        axiscal.simulate(cfg)
    bad = tmp_path / "bad.toml"
    from axiscal.api._config import toml_text

    bad.write_text(toml_text(cfg), "utf-8")
    with pytest.raises(ConfigError) as from_file:
        axiscal.simulate(bad)
    assert "spacing_typo" in str(from_dict.value) and "<dict>" in str(from_dict.value)
    assert str(from_dict.value).replace("<dict>", str(bad)) == str(from_file.value)


def test_a_value_toml_cannot_hold_is_named():
    from axiscal.errors import ConfigError

    with pytest.raises(ConfigError, match=r"laser.head = None"):
        axiscal.simulate({"laser": {"head": None}})


# -- LinuxCNC's 3-D correction ------------------------------------------------------------------
def test_linuxcnc_volumetric_compensation_equals_the_command(volumetric_config, tmp_path):
    """``volumetric_compensation(cfg, "linuxcnc")`` is ``volumetric compensate --controller
    linuxcnc --json``: the COMP_FILEs, the map volcomp.json and the HAL component, byte for
    byte."""
    sim = axiscal.volumetric_compensation(volumetric_config, "linuxcnc", out=tmp_path / "api")
    cli = _cli_json("volumetric", "compensate", volumetric_config, "--controller", "linuxcnc",
                    "--out", tmp_path / "cli")
    assert sim.to_dict() == cli and cli["grid_spacing_mm"] == 50.0
    assert {"x.comp", "y.comp", "z.comp", "volcomp.json", "axiscal_volcomp.py"} <= set(
        cli["files"])
    for name in cli["files"]:
        assert (tmp_path / "api" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()


def test_a_linuxcnc_verification_is_drawn_as_three_bars_per_figure():
    """Bare, tables alone and tables + 3-D, each figure's three bars at its values in µm."""
    from axiscal.compensation.on_controller_volumetric import OnControllerResult
    from axiscal.io.simulation_results import SimulationRun

    result = OnControllerResult(rows=(("largest volumetric error", 30e-6, 12e-6, 4e-6),),
                                moves={}, applied=0.0, settings={})
    run = SimulationRun("volumetric-compensation", None, {}, {"verify": result})
    fig = api.Simulation(run, None, "volumetric-compensation", "v.toml").plot()
    widths = sorted(round(p.get_width(), 9) for p in fig.axes[0].patches)
    assert widths == [4.0, 12.0, 30.0]
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == [
        "bare", "tables alone", "tables + 3-D correction"]


def test_import_of_the_api_package_stays_light():
    """``import axiscal.api`` imports no submodule, no NumPy and no dataclasses machinery of
    its own until a name is used (PEP 562)."""
    import subprocess
    import sys

    code = ("import sys, axiscal.api as a; assert 'numpy' not in sys.modules; "
            "assert not [m for m in sys.modules if m.startswith('axiscal.api.')]; a.History; "
            "assert 'axiscal.api._history' in sys.modules and 'axiscal.api._reading' not in "
            "sys.modules; assert sorted(a.__all__) == sorted(n for n in dir(a) if n in a.__all__)")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_ballbar_simulate_equals_the_api_and_analyze_reads_it(tmp_path):
    """``axiscal.simulate`` of a [ballbar]/[servo] configuration is ``ballbar simulate``: the
    same trace, byte for byte; its ``result`` is ``ballbar analyze`` of that trace (ISO
    230-4:2005 and the diagnosis), and the injected squareness comes back."""
    cli = _cli_json("ballbar", "simulate", BALLBAR_SIM, "--seed", 3, "--out",
                    tmp_path / "cli.csv")
    sim = axiscal.simulate(BALLBAR_SIM, seed=3)
    assert sim.kind == "ballbar" and {**sim.to_dict(), "out": cli["out"]} == cli
    assert (sim.write_data(tmp_path / "api.csv").read_bytes()
            == (tmp_path / "cli.csv").read_bytes())
    analyzed = _cli_json("ballbar", "analyze", tmp_path / "cli.csv")
    assert sim.result.as_dict()["squareness_um_per_m"] == pytest.approx(   # the file holds
        analyzed["squareness_um_per_m"], rel=1e-6)                         # rounded readings
    assert analyzed["squareness_um_per_m"] == pytest.approx(20.0, abs=2.0)   # the truth
    from matplotlib.figure import Figure

    assert isinstance(sim.plot(), Figure)
    assert "Ranked" in sim.report(tmp_path / "b.html").read_text("utf-8")


def test_motion_simulate_without_compensation_equals_the_api():
    """``--no-compensation`` is ``drift_compensation=False`` (Optics Express 2018, eqs. 1-6
    only): the same JSON, and not the compensated one."""
    cli = _cli_json("motion", "simulate", MOTION, "--no-compensation")
    sim = axiscal.simulate(MOTION, drift_compensation=False)
    assert sim.to_dict() == cli and cli["compensated"] is False
    assert axiscal.simulate(MOTION).to_dict() != cli
