"""``axiscal volumetric simulate|map|compensate`` from files (issue 18)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    out = tmp_path_factory.mktemp("vol")
    r = runner.invoke(app, ["volumetric", "simulate", "--out", str(out), "--seed", "2"])
    assert r.exit_code == 0, r.output
    return out


def test_simulate_writes_21_measured_files_and_a_configuration(simulated):
    names = sorted(p.name for p in simulated.iterdir())
    assert "volumetric.toml" in names and len(names) == 19      # 18 motions + config


def test_map_from_files_reports_the_truth_of_a_simulation(simulated, tmp_path):
    """The whole chain from files: the mapped error equals the simulated machine's truth within
    the measurement noise (2 µm: 5 σ of the propagated noise, see the model's truth test)."""
    r = runner.invoke(app, ["volumetric", "map", str(simulated / "volumetric.toml"), "--json",
                            "--plot", str(tmp_path / "v.png"),
                            "--report", str(tmp_path / "v.html")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["chain"] == "X Y | Z" and d["missing"] == []
    assert d["mapped_minus_true_um"] < 2.0
    assert d["largest_um"] == pytest.approx(d["truth"]["largest_um"], abs=2.0)
    assert [x["name"] for x in d["diagonals"]] == ["PPP", "NPP", "PNP", "PPN"]
    assert (tmp_path / "v.png").stat().st_size > 10_000
    html = (tmp_path / "v.html").read_text()
    assert "Simulation: the simulated machine" in html and "ISO 230-6" in html


def test_compensate_verify_reports_before_after_and_reduction(simulated, tmp_path):
    r = runner.invoke(app, ["volumetric", "compensate", str(simulated / "volumetric.toml"),
                            "--controller", "siemens-840d", "--verify", "--json",
                            "--out", str(tmp_path / "t")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert len(d["files"]) == 9
    fig = d["verify"]["figures"]["largest volumetric error"]
    assert fig["after_um"] < fig["before_um"]
    assert fig["reduction"] == pytest.approx(1 - fig["after_um"] / fig["before_um"])
    assert d["verify"]["spindle_tilt_um_per_m"] < 1.0
    assert (tmp_path / "t" / "NC_CEC_Z_X.INI").read_text().startswith("%_N_NC_CEC_INI")


def test_config_with_inline_functions_and_a_missing_motion(tmp_path):
    (tmp_path / "m.toml").write_text(
        '[machine]\nchain = "| X Y Z"\ntravel_mm = { X = [0, 500], Y = [0, 400], Z = [-300, 0] }\n'
        '[errors]\nECX = { positions_mm = [0, 250, 500], values = [-2, 0, 2], unit = "arcsec" }\n'
        'EXX = { polynomial = [0, 0.01], unit = "um" }\n[squareness]\nxy = 20\n')
    r = runner.invoke(app, ["volumetric", "map", str(tmp_path / "m.toml"), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert len(d["missing"]) == 16
    # X from 250 to 500: 2.5 µm of scale; Y 200 mm from the middle: 20 µm/m + the yaw's Abbe
    assert d["range_um"]["X"] > 2.5 * 2


@pytest.mark.parametrize("text, words", [
    ('[machine]\nchain = "X Y | Z"\n', "needs chain and travel_mm"),
    ('[machine]\nchain = "X Y Z"\ntravel_mm = { X = [0, 1], Y = [0, 1], Z = [0, 1] }\n', "'|'"),
    ('[machine]\nchain = "X Y | Z"\ntravel_mm = { X = [0, 1], Y = [0, 1], Z = [0, 1] }\n'
     '[errors]\nEQX = "a.csv"\n', "unknown key [errors] EQX"),
    ('[machine]\nchain = "X Y | Z"\ntravel_mm = { X = [0, 1], Y = [0, 1], Z = [0, 1] }\n'
     '[errors]\nEXX = "nowhere.csv"\n', "nowhere.csv"),
    ('[machine]\nchain = "X Y | Z"\ntravel_mm = { X = [0, 1], Y = [0, 1], Z = [1, 0] }\n',
     "high must exceed low"),
    ('[machine]\nchain = "X Y | Z"\ntravel_mm = { X = [0, 1], Y = [0, 1], Z = [0, 1] }\n'
     '[squareness]\nxy = 1e308\n', "finite number"),
    ('[machin]\n', "unknown table [machin]"),
])
def test_bad_configurations_are_one_line(tmp_path, text, words):
    (tmp_path / "bad.toml").write_text(text)
    r = runner.invoke(app, ["volumetric", "map", str(tmp_path / "bad.toml")])
    assert r.exit_code == 2
    assert words in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_a_file_of_another_axis_is_refused(simulated, tmp_path):
    cfg = (simulated / "volumetric.toml").read_text().replace('EYX = "X_EYX.csv"',
                                                              'EYX = "Y_EXY.csv"')
    (simulated / "swapped.toml").write_text(cfg)
    r = runner.invoke(app, ["volumetric", "map", str(simulated / "swapped.toml")])
    assert r.exit_code == 2 and "the file says direction=X" in r.stderr


def test_verify_needs_a_simulation(tmp_path):
    (tmp_path / "m.toml").write_text(
        '[machine]\nchain = "X Y | Z"\ntravel_mm = { X = [0, 500], Y = [0, 400], Z = [-300, 0] }\n')
    r = runner.invoke(app, ["volumetric", "compensate", str(tmp_path / "m.toml"),
                            "--controller", "csv", "--verify"])
    assert r.exit_code == 2 and "needs a simulated machine" in r.stderr


INLINE = ('[machine]\nchain = "| X Y Z"\ntravel_mm = { X = [0, 500], Y = [0, 400], Z = [-300, 0] }\n'
          '[errors]\nECX = { positions_mm = [0, 250, 500], values = [-2, 0, 2], unit = "arcsec" }\n'
          'EXX = { polynomial = [0, 0.01], unit = "um" }\n[squareness]\nxy = 20\n')


def test_map_states_u_from_the_user_configuration(tmp_path, monkeypatch):
    """``volumetric map`` takes ``[volumetric_uncertainty]`` of the user configuration (here the
    independent model and U of the positioning errors) and states every figure's U: on --json
    the history's record of the same file (:func:`axiscal.store.kinds.with_uncertainty`), in
    its text each figure ± U; a key that is no input is refused in one line, exit 2."""
    from axiscal.store.kinds import evaluate_file, with_uncertainty

    table = {"correlation": "independent", "positioning_a": 0.3, "positioning_b": 1.0}
    cfg = tmp_path / "config.toml"
    cfg.write_text('[volumetric_uncertainty]\ncorrelation = "independent"\n'
                   "positioning_a = 0.3\npositioning_b = 1.0\n")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    (tmp_path / "m.toml").write_text(INLINE)
    r = runner.invoke(app, ["volumetric", "map", str(tmp_path / "m.toml"), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    rec = with_uncertainty(evaluate_file(INLINE.encode(), "m.toml"), table)
    assert d["uncertainty_inputs"] == table
    assert "correlation model: independent" in d["uncertainty_budget"]["method"]
    assert rec.quantities["range_Y"].U is None       # nothing measured acts on E_Y: no U
    for name, q in rec.quantities.items():
        assert d["quantities"][name]["U"] == q.U and (q.U is None or q.U > 0), name
    import axiscal

    assert axiscal.volumetric_map(tmp_path / "m.toml").to_dict() == d     # the API's, too
    text = runner.invoke(app, ["volumetric", "map", str(tmp_path / "m.toml")])
    assert text.exit_code == 0 and "with their expanded uncertainty (k = 2" in text.stdout
    assert f"range_X {rec.budget.value_text('range_X', rec.parameters['range_X'][0])} ± " \
        f"{rec.budget.U_text('range_X')} µm" in text.stdout
    cfg.write_text("[volumetric_uncertainty]\nangualr = 1\n")
    bad = runner.invoke(app, ["volumetric", "map", str(tmp_path / "m.toml"), "--json"])
    assert bad.exit_code == 2 and len(bad.stderr.strip().splitlines()) == 1
    assert "[volumetric_uncertainty] angualr: no such input" in bad.stderr
