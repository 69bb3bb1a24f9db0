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
    (["-s", "nmtba", "--plot", "x.png"], "NMTBA: not evaluated"),
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


def test_report_for_any_standard_names_sources_gaps_and_acceptance(good, tmp_path):
    """--report works for every standard: each parameter with its source, what is not evaluated
    and why, the acceptance with its decision rule, and the per-target figure."""
    html = tmp_path / "vdi.html"
    r = runner.invoke(app, ["evaluate", str(good), "-s", "vdi3441", "--tolerance", "U=1.5",
                            "--report", str(html)])
    assert r.exit_code == 1, r.output  # U = 2 µm in GOOD, beyond 1.5
    page = html.read_text()
    assert "Positioning test x.csv by VDI/DGQ 3441" in page and "Rexroth R310DE" in page
    assert "position scatter: not evaluated" in page and "<svg" in page
    assert "simple acceptance (ILAC-G8" in page and ">FAIL<" in page
    both = tmp_path / "all.html"
    r = runner.invoke(app, ["evaluate", str(good), "-s", "all", "--report", str(both)])
    assert r.exit_code == 0, r.output
    page = both.read_text()
    for title in ("ISO 230-2:2014", "ISO 230-2:1988", "JIS B 6192", "VDI/DGQ 3441", "AMT"):
        assert title in page
    assert "<h2>Not evaluated</h2>" in page and "NMTBA" in page


def test_iso_report_with_a_tolerance_shows_the_iso14253_decision(good, tmp_path):
    """Regression: `evaluate -s iso230-2:2014 --tolerance ... --report` raised AttributeError
    (the report expected the old verdict type); it now shows U and the ISO 14253-1 rule."""
    html = tmp_path / "iso.html"
    r = runner.invoke(app, ["evaluate", str(good), "-s", "iso230-2:2014", "--tolerance", "E=100",
                            "--report", str(html)])
    assert r.exit_code == 0, r.output
    page = html.read_text()
    assert "Decision rule: ISO 14253-1:2017" in page and ">PASS<" in page
    assert "U (k = 2)" in page and "not estimated" not in page


@pytest.mark.parametrize("key, band", [("jis-b6192", "x̄ ± 3s"), ("iso230-2:1988", "x̄ ± 3s"),
                                       ("iso230-2:2006", "x̄ ± 2s"), ("vdi3441", None)])
def test_plot_for_any_standard_draws_its_band_and_parameters(good, tmp_path, key, band):
    """--plot for a standard other than ISO 230-2:2014: its own band (none for VDI/DGQ 3441,
    whose scatter factor is not public) and its own parameters in the box."""
    svg = tmp_path / "p.svg"
    r = runner.invoke(app, ["evaluate", str(good), "-s", key, "--plot", str(svg)])
    assert r.exit_code == 0, r.output
    text = svg.read_text()
    from axiscal.standards.positioning_standards import STANDARDS

    assert STANDARDS[key].title in text
    if band is None:
        assert "x̄ ± " not in text and "Pa" in text
    else:
        assert band in text


ONE_RUN = """# target_unit=mm deviation_unit=um machine=VMC axis=X
target,direction,run,deviation
0,+,1,1.0
0,-,1,-1.0
210,+,1,2.0
210,-,1,0.5
600,+,1,0.0
600,-,1,-0.5
"""


def test_a_test_iso_refuses_but_vdi_evaluates_still_has_its_plot_and_report(tmp_path):
    """One approach each way: ISO 230-2:2014, its editions and JIS need two readings (no s), VDI
    evaluates with a warning. The plot and report follow what is evaluated; each refusal names
    its standard."""
    f = tmp_path / "one.csv"
    f.write_text(ONE_RUN)
    r = runner.invoke(app, ["evaluate", str(f), "-s", "all"])
    assert r.exit_code == 0, r.output
    assert "not evaluated (ISO 230-2:2014):" in r.stdout and "not evaluated (JIS" in r.stdout
    for key in ("vdi3441", "all"):
        png, html = tmp_path / f"{key}.png", tmp_path / f"{key}.html"
        r = runner.invoke(app, ["evaluate", str(f), "-s", key, "--plot", str(png), "--report",
                                str(html)])
        assert r.exit_code == 0, r.output
        assert png.stat().st_size > 1000 and "VDI/DGQ 3441" in html.read_text()
    # no standard at all: one direction, one run
    f.write_text("\n".join(line for line in ONE_RUN.splitlines() if ",-," not in line) + "\n")
    r = runner.invoke(app, ["evaluate", str(f), "-s", "all", "--plot", str(tmp_path / "n.png")])
    assert r.exit_code == 2 and "no standard evaluates this test" in r.stderr
    assert not (tmp_path / "n.png").exists()


def test_report_acceptance_uses_the_parameter_labels_of_the_result_table(good, tmp_path):
    html = tmp_path / "r.html"
    r = runner.invoke(app, ["evaluate", str(good), "-s", "iso230-2:1988", "--tolerance",
                            "R_up=100", "--report", str(html)])
    assert r.exit_code == 0, r.output
    acceptance = html.read_text().split("<h3>Acceptance</h3>")[1].split("</table>")[0]
    assert "<td>R↑</td>" in acceptance and "R_up" not in acceptance
