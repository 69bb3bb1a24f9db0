"""What a newcomer saw in the terminal on the README's tour and in ``axiscal demo``, kept from
coming back: parameters in their ISO 230-2 symbols (B mean, A↑), never the ``--json`` keys
(B_mean, A_up), and units in table titles that Rich's markup had swallowed."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from axiscal.cli import app

ROOT = Path(__file__).resolve().parents[2]
ENV = {"COLUMNS": "120"}


def test_simulate_truth_table_speaks_in_symbols():
    r = CliRunner().invoke(app, ["simulate", str(ROOT / "src/axiscal/data/demo_linear.toml")],
                           env=ENV)
    assert r.exit_code == 0, r.output
    truth = r.output.split("Measured beside the simulation's truth [µm]")[1]
    assert "B mean" in truth and "B_mean" not in truth


def test_rotary_simulate_truth_table_has_its_unit_and_symbols():
    r = CliRunner().invoke(app, ["rotary", "simulate", str(ROOT / "examples/rotary_turntable.toml")],
                           env=ENV)
    assert r.exit_code == 0, r.output
    assert "Measured beside the truth [arcsec]" in r.output
    truth = r.output.split("Measured beside the truth [arcsec]")[1].split("set-up check")[0]
    assert "A↑" in truth and "B mean" in truth
    assert "A_up" not in truth and "B_mean" not in truth


def test_compensation_loop_table_keeps_its_unit_and_symbols():
    """``compensate --verify`` of a rotary axis: the title's "[arcsec]" was swallowed by Rich's
    markup and the rows were named A_up, B_mean."""
    r = CliRunner().invoke(app, ["compensate", "--verify",
                                 str(ROOT / "examples/compensation_rotary.toml")], env=ENV)
    assert r.exit_code == 0, r.output
    assert "ISO 230-2 before and after [arcsec]" in r.output
    table = r.output.split("before and after [arcsec]")[1].split("E fell by")[0]
    assert "A↑" in table and "B mean" in table and "A_up" not in table


def test_rotary_budget_tables_keep_the_unit_of_alpha_and_beta():
    """``rotary budget``: the corner header "β \\ α [mrad]" lost "[mrad]" to Rich's markup."""
    r = CliRunner().invoke(app, ["rotary", "budget", "--alpha", "0.62", "--beta", "1.23"], env=ENV)
    assert r.exit_code == 0, r.output
    assert r.output.count("β \\ α [mrad]") == 2


def test_config_is_shown_as_its_file_writes_it(tmp_path):
    """``axiscal config`` after ``--init`` printed each table as a Python dict
    ("[company] {'name': ...}"); it is shown as TOML-like ``key = value`` lines."""
    env = {**ENV, "AXISCAL_CONFIG": str(tmp_path / "config.toml")}
    r = CliRunner().invoke(app, ["config", "--init"], env=env)
    assert r.exit_code == 0, r.output
    assert "{'" not in r.output
    assert '[company]\n  name = "Your Calibration Company Ltd"' in r.output
    assert "[[instrument]]\n  name = \"Laser interferometer\"" in r.output
    assert "[uncertainty]\n  (none declared: the uncertainty budget assumes each input" in r.output


def test_history_list_keeps_its_columns_for_a_long_machine_name(tmp_path):
    """``axiscal history list`` of the demo: "Turntable TT-2 (simulated)" (26 characters) pushed
    its axis, kind and result out of the 20-character column the other rows kept."""
    import re

    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    for name, f in (("VMC-800 (simulated)", "x"), ("Turntable TT-2 (simulated)", "y")):
        r = CliRunner().invoke(app, ["history", "add", str(ROOT / f"examples/squareness_L180_{f}.csv"),
                                     "--machine", name, "--db", db], env=ENV)
        assert r.exit_code == 0, r.output
    r = CliRunner().invoke(app, ["history", "list", "--db", db], env=ENV)
    lines = r.output.splitlines()
    assert len(lines) == 2
    starts = {re.search(r" [XY] +straightness", line).start() for line in lines}
    assert len(starts) == 1, r.output


def test_motion_crosstalk_speaks_in_the_papers_symbols():
    """``axiscal motion simulate``: the crosstalk table and the spurious motion named the errors
    by code keys (ez, dy) and gave the residual without units; they are εz … δz with arcsec/µm
    (Optics Express 2018, Five-DOF motion errors of a rotary axis)."""
    r = CliRunner().invoke(app, ["motion", "simulate",
                                 str(ROOT / "examples/motion_indexing_table.toml")], env=ENV)
    assert r.exit_code == 0, r.output
    block = r.output.split("leak [out/in]")[1].split("ISO 230-7")[0]
    assert "εz" in block and "δy" in block
    assert " ez " not in block and " dy " not in block
    assert "once-per-turn component: εz 0.000 arcsec" in block


def test_compensate_summary_writes_micrometres_as_every_other_output(tmp_path):
    """``axiscal compensate ... --out x.ini``: "largest corr. 5.9 um" where every table and report
    writes µm."""
    data = tmp_path / "x.csv"
    data.write_text("# target_unit=mm deviation_unit=um axis=X\ntarget,direction,run,deviation\n"
                    + "".join(f"{t},{d},{r},{t / 100 + (r - 1) * 0.1}\n" for t in (0, 100, 200)
                              for d in "+-" for r in (1, 2)))
    r = CliRunner().invoke(app, ["compensate", str(data), "--controller", "csv",
                                 "--out", str(tmp_path / "x.table.csv")], env=ENV)
    assert r.exit_code == 0, r.output
    assert "largest corr." in r.output and " µm (correction = −deviation)" in r.output


def test_squareness_comparison_tables_are_titled_and_captioned_unbroken():
    """``axiscal squareness simulate --machine 3``: the table was titled "results" and its caption
    broke over two lines ("columns: test centre" / "(x, y) in mm") at the narrow table's width."""
    r = CliRunner().invoke(app, ["squareness", "simulate", "--machine", "3", "--scope", "global"],
                           env=ENV)
    assert r.exit_code == 0, r.output
    assert "squareness by each method [µm/m]" in r.output
    assert r.output.count("columns: test centre (x, y) in mm") == 2


def test_history_speaks_in_micrometres(tmp_path):
    """``history list``, ``compare`` and ``trend`` wrote "E 1.099 um", "-11.732 um", "um/year"
    where every table and report writes µm."""
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    data = []
    for k, shift in enumerate((0.0, 1.0, 2.0)):
        p = tmp_path / f"t{k}.csv"
        p.write_text(f"# target_unit=mm deviation_unit=um machine=M axis=X date=202{k}-01-01\n"
                     "target,direction,run,deviation\n"
                     + "".join(f"{t},{d},{r},{t / 100 + shift + (r - 1) * 0.1}\n"
                               for t in (0, 100, 200) for d in "+-" for r in (1, 2)))
        data.append(p)
        r = CliRunner().invoke(app, ["history", "add", str(p), "--db", db], env=ENV)
        assert r.exit_code == 0, r.output
    outputs = [CliRunner().invoke(app, args + ["--db", db], env=ENV).output for args in
               (["history", "list"], ["history", "compare", "1", "2"],
                ["history", "trend", "--machine", "M", "--axis", "X", "--parameter", "E"])]
    for out in outputs:
        assert "µm" in out and " um" not in out, out


def test_uncertainty_inputs_leave_the_rule_room_on_a_100_column_terminal(tmp_path):
    """``axiscal iso230-2 FILE`` at 100 columns: NAME had a column of its own, 33 characters wide,
    and the rule or source was folded into 15 (60 lines of table); NAME now stands under its
    input, whole, and the rule has more than twice that room."""
    data = tmp_path / "x.csv"
    r = CliRunner().invoke(app, ["simulate", str(ROOT / "src/axiscal/data/demo_linear.toml"),
                                 "--data", str(data)], env=ENV)
    assert r.exit_code == 0, r.output
    r = CliRunner().invoke(app, ["iso230-2", str(data)], env={"COLUMNS": "100"})
    assert r.exit_code == 0, r.output
    table = r.output.split("Uncertainty inputs")[1].split("└")[0]
    assert "│ expansion_coefficient_halfwidth " in table and "…" not in table
    header = next(line for line in table.splitlines() if "rule or source" in line)
    assert len(header.split("┃")[-2]) > 30
