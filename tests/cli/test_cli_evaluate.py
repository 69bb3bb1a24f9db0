"""``axiscal evaluate FILE --standard ...`` (typer CliRunner)."""

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from tests.cli.test_cli_positioning import GOOD

runner = CliRunner(env={"COLUMNS": "200"})


@pytest.fixture
def good(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text(GOOD)
    return p


def test_all_prints_one_table_with_each_standards_names(good):
    r = runner.invoke(app, ["evaluate", str(good), "--standard", "all"])
    assert r.exit_code == 0, r.output
    assert "ISO 230-2:2014" in r.stdout and "JIS B 0182-1993 term 346" in r.stdout
    assert "max[3s↑ + 3s↓" in r.stdout and "max[2s↑ + 2s↓" in r.stdout
    assert "VDI/DGQ 3441" in r.stdout and "no public text" in r.stdout and "NMTBA" in r.stdout
    # a standard evaluated in part names what it leaves out, and why
    assert "position uncertainty: not evaluated" in r.stdout and "max 6s_i↑" in r.stdout


def test_json_keys_and_values(good):
    r = runner.invoke(app, ["evaluate", str(good), "-s", "all", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["unit"] == "um" and d["target_unit"] == "mm"
    by = {e["standard"]: e for e in d["standards"]}
    assert set(by["jis-b6192"]) == {"standard", "title", "evaluated", "parameters", "warnings",
                                    "reason", "not_evaluated"}
    # every x↓ is x↑ - 2 µm in GOOD, so the reversal is 2 µm by construction in every standard
    assert by["jis-b6192"]["parameters"]["B"]["value"] == pytest.approx(2.0)
    assert by["iso230-2:2014"]["parameters"]["B"]["value"] == pytest.approx(2.0)
    vdi = by["vdi3441"]
    assert vdi["evaluated"] is True and vdi["parameters"]["U"]["value"] == pytest.approx(2.0)
    assert vdi["parameters"]["U_mean"]["value"] == pytest.approx(2.0)
    assert set(vdi["not_evaluated"]) == {"P", "Ps"} and by["jis-b6192"]["not_evaluated"] == {}
    iso = by["iso230-2:2014"]["parameters"]
    # the 2006 band is the 2014 band; the 1988 spread is 6s instead of 4s
    assert by["iso230-2:2006"]["parameters"]["R_up"]["value"] == iso["R_up"]["value"]
    assert by["iso230-2:1988"]["parameters"]["R_up"]["value"] == pytest.approx(
        1.5 * iso["R_up"]["value"])
    assert by["nmtba"]["evaluated"] is False and "no public text" in by["nmtba"]["reason"]


def test_single_unavailable_standard_is_one_line_exit_2(good):
    r = runner.invoke(app, ["evaluate", str(good), "-s", "asme-b5.54"])
    assert r.exit_code == 2
    assert r.stderr.startswith("axiscal: error: ASME B5.54: not evaluated")
    assert r.stdout == ""


def test_tolerance_verdict_and_exit_code(good):
    r = runner.invoke(app, ["evaluate", str(good), "-s", "jis-b6192", "--tolerance", "R=1",
                            "--json"])
    assert r.exit_code == 1
    d = json.loads(r.stdout)
    assert d["accepted"] is False and d["acceptance"][0]["parameter"] == "R"
    assert d["decision_rule"] == "simple" and d["acceptance"][0]["U"] is None
    ok = runner.invoke(app, ["evaluate", str(good), "-s", "jis-b6192", "--tolerance", "B=2.5"])
    assert ok.exit_code == 0
    assert "conformance proven" in ok.stdout and "uncertainty not estimated" in ok.stdout


@pytest.mark.parametrize("args, message", [
    (["-s", "din9999"], "use one of"),
    (["-s", "all", "--tolerance", "R=1"], "needs one --standard"),
    (["-s", "jis-b6192", "--plot", "x.png"], "iso230-2:2014"),
    (["-s", "jis-b6192", "--tolerance", "A=1"], "not a JIS"),
    (["-s", "vdi3441", "--tolerance", "P=1"], "VDI/DGQ 3441 P, position uncertainty: not "
                                              "evaluated"),
])
def test_user_errors_are_one_line(good, args, message):
    r = runner.invoke(app, ["evaluate", str(good), *args])
    assert r.exit_code == 2 and message in r.stderr and "Traceback" not in r.output


def test_plot_for_iso_2014(good, tmp_path):
    png = tmp_path / "p.png"
    r = runner.invoke(app, ["evaluate", str(good), "-s", "iso230-2:2014", "--plot", str(png)])
    assert r.exit_code == 0, r.output
    assert png.stat().st_size > 1000
