"""What a newcomer saw in the reports of the README's tour and the demo, kept from coming back:
each test names the report and what was wrong with it."""

from __future__ import annotations

from pathlib import Path

import pytest

import axiscal

ROOT = Path(__file__).resolve().parents[2]
DEMO_LINEAR = ROOT / "src" / "axiscal" / "data" / "demo_linear.toml"


def test_simulation_report_draws_the_truth_it_announces(tmp_path):
    """``axiscal simulate --report``: the banner says "the simulation's truth is shown beside the
    result", and ``--plot`` draws it; the report's figure lacked the truth line, and its
    measured-beside-truth table had no unit and an unexplained "4σ + |b|"."""
    html = axiscal.simulate(DEMO_LINEAR, seed=1).report(tmp_path / "sim.html").read_text()
    assert "truth (simulation)" in html                  # the figure's legend (inline SVG)
    assert "dashed: the mean deviation the simulation knew" in html
    assert "Measured [µm]" in html and "Truth [µm]" in html
    assert "σ: the simulated repeatability" in html and "b: the simulated backlash" in html


def test_history_compare_keeps_its_columns_for_long_parameter_names():
    """``axiscal history compare 3 4`` of the demo: rows named "iso230-2:2006:R_down" pushed
    their numbers 5 columns right of the others'."""
    from axiscal.store.analysis import Comparison

    c = Comparison(3, 4, (("A", 14.196, 2.464, -11.732, "um"),
                          ("iso230-2:2006:R_down", 2.097, 1.914, -0.183, "um")), None, None)
    lines = str(c).splitlines()
    ends = {len(line.rsplit(" ", 1)[0]) for line in lines[1:]}   # the change column's right edge
    assert len(ends) == 1 and len(lines[0]) == ends.pop(), str(c)


def test_trend_of_tests_stored_on_one_day_estimates_no_drift():
    """``axiscal history trend`` on the demo's history (three tests stored seconds apart, their
    files giving no date) printed "drift -3.771e+06 ± 7.9e+06 um/year"; a test's date is a day,
    so they are one date and no drift is estimated."""
    import datetime as dt

    from axiscal.store.analysis import fit_trend

    day = dt.datetime(2026, 11, 25, 2, 25, 1)
    dates = [day, day + dt.timedelta(seconds=4), day + dt.timedelta(seconds=9)]
    t = fit_trend("E", dates, [11.916, 12.934, 1.099], "um", tolerance=15)
    assert t.drift is None and t.crossing is None
    assert "no drift estimate: the tests were all taken on one date" in str(t)
    later = fit_trend("E", [day, day + dt.timedelta(days=200), day + dt.timedelta(days=400)],
                      [5.0, 6.0, 7.0], "um")
    assert later.drift == pytest.approx(365.25 / 200)      # 1 µm per 200 days, in µm a year


def test_squareness_report_gives_U_as_the_terminal_does(tmp_path):
    """``axiscal squareness circular ... --report``: the terminal said "U (k = 2) = 2.8 µm/m"
    (two significant digits, rounded up, JCGM 100:2008 §7.2.6) and the report "2.72"."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    out = tmp_path / "circ.html"
    r = CliRunner().invoke(app, ["squareness", "circular",
                                 str(ROOT / "examples/squareness_ballbar_150mm.csv"),
                                 "--report", str(out)])
    assert r.exit_code == 0, r.output
    assert "U (k = 2) = 2.8 µm/m" in r.output
    assert "expanded uncertainty [µm/m]</td><td>2.8<" in out.read_text()


def test_rotary_budget_report_gives_the_unit_of_the_terms_of_eq_1(tmp_path):
    """``axiscal rotary budget --report``: "Terms of eq. 1" listed "Quadratic term 0.020" with no
    unit; the terms are in arcsec (their key, ``terms_arcsec``, says so)."""
    from axiscal.report.html import result_tables

    tables = result_tables({"terms_arcsec": {"quadratic": 0.0201, "alpha_beta": 0.157}})
    (caption, _, rows), = tables
    assert caption == "Terms of eq. 1"
    assert [r[1] for r in rows] == ["0.02", "0.16"]
    assert all(r[0].endswith("[arcsec]") for r in rows), rows


def test_the_five_motion_errors_are_drawn_wider_than_tall():
    """``axiscal motion simulate --report x.pdf``: the five errors stacked (7.5 × 10.5 in) were
    squeezed into the print style's 118 mm of height, a third of the page wide, their axis
    labels too small to read; the stacked figures are drawn wider than tall."""
    import numpy as np

    from axiscal.report.motion_plots import five_errors_figure, stability_figure

    theta = np.radians(np.arange(0, 361, 30.0))
    run = type("Run", (), {"theta": theta, **{c: np.zeros_like(theta)
                                              for c in ("ez", "ey", "ex", "dy", "dz")}})()
    w, h = five_errors_figure([run]).get_size_inches()
    assert w > h
    still = type("Still", (), {"time": theta, "measured": run, "uncompensated": run})()
    w, h = stability_figure(still).get_size_inches()
    assert w > h


def test_volumetric_map_draws_the_nominal_grid_it_names():
    """``axiscal volumetric map --plot``: the 3-D panel says "grey nominal, red actual", but its
    light grey nominal grid (0.75 grey) vanished against the panes' own grid lines."""
    from matplotlib.colors import to_rgb

    from axiscal.report.volumetric_plots import volumetric_figure
    from axiscal.standards.volumetric import AXES, GeometricErrors, KinematicChain, map_volume

    errors = GeometricErrors(KinematicChain.parse("X Y | Z"), {}, {"xy": 10e-6}, [0, 0, 0],
                             [0, 0, 0], {a: (0.0, 0.5) for a in AXES})
    ax = volumetric_figure(map_volume(errors, n=5)).axes[0]
    nominal = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"]
    assert nominal and all(max(to_rgb(ln.get_color())) <= 0.5 for ln in nominal)
    assert "grey dashed nominal" in ax.get_title()


def test_motion_analyze_report_speaks_of_no_truth_it_does_not_have(tmp_path):
    """``axiscal motion analyze motion.csv --report``: a measured file has no truth, yet the
    figure's caption said "dashed: the simulation's truth of run 1"."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    csv, report = tmp_path / "motion.csv", tmp_path / "ma.html"
    r = CliRunner().invoke(app, ["motion", "simulate", str(ROOT / "examples/motion_indexing_table.toml"),
                                 "--csv", str(csv), "--report", str(tmp_path / "sim.html")])
    assert r.exit_code == 0, r.output
    assert "dashed: the simulation" in (tmp_path / "sim.html").read_text()
    r = CliRunner().invoke(app, ["motion", "analyze", str(csv), "--report", str(report)])
    assert r.exit_code == 0, r.output
    html = report.read_text()
    assert "Measured errors per run (zeroed at 0°)." in html and "truth" not in html.lower()


def test_a_draft_says_why_it_has_no_number():
    """``axiscal iso230-2 ... --report x.html --draft`` with no configuration: the draft's
    "Certificate number" read "not stated", as if the user had forgotten one; a draft is never
    numbered (the register numbers only an issued certificate)."""
    import tomllib
    from importlib import resources

    from axiscal.procedures.positioning import simulate_from_config
    from axiscal.report.certificate import certificate_info, positioning_certificate
    from axiscal.standards.iso14253_1 import RULE_TEXT, Rule
    from axiscal.standards.iso230_9 import positioning_budget

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    budget = positioning_budget(sim.dataset, sim.result, {"e_ve": 0.8})
    info = certificate_info({})
    assert info.draft
    html = positioning_certificate(sim.dataset, sim.result, budget, info, (),
                                   RULE_TEXT[Rule.ISO_14253_1]).html()
    assert "Certificate number</td><td>none: a draft is not numbered" in html


def test_a_rotary_certificate_writes_degrees_against_the_number(tmp_path):
    """The demo's rotary certificate: "25 targets from 0 to 360 °"; an angle is written 360°."""
    import tomllib
    from importlib import resources

    from axiscal.procedures.positioning import simulate_from_config
    from axiscal.report.certificate import certificate_info, positioning_certificate
    from axiscal.standards.iso14253_1 import RULE_TEXT, Rule
    from axiscal.standards.iso230_9 import positioning_budget

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_rotary.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    budget = positioning_budget(sim.dataset, sim.result, {"e_ve": 0.1})
    html = positioning_certificate(sim.dataset, sim.result, budget, certificate_info({}), (),
                                   RULE_TEXT[Rule.ISO_14253_1]).html()
    assert "targets from 0 to 360°" in html and "360 °" not in html


def test_every_standard_report_caption_reads_as_a_sentence(tmp_path):
    """``axiscal evaluate turntable.csv --standard all --report``: the figure's caption ended
    "drawn as ISO 230-2:2014 does (±2s bands) (arcsec against target in °)"."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    data, out = tmp_path / "t.csv", tmp_path / "eval.html"
    r = CliRunner().invoke(app, ["simulate", str(ROOT / "src/axiscal/data/demo_rotary.toml"),
                                 "--data", str(data)])
    assert r.exit_code == 0, r.output
    r = CliRunner().invoke(app, ["evaluate", str(data), "--standard", "all", "--report", str(out)])
    assert r.exit_code == 0, r.output
    assert "drawn as ISO 230-2:2014 does with ±2s bands (arcsec against target in °)." \
        in out.read_text()
