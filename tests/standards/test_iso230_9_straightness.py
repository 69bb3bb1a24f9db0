"""The budget of an ISO 230-1:2012 straightness test (standards/iso230_9_straightness.py,
axiscal's reading of ISO/TR 230-9:2005's general form, JCGM 100:2008 eq. 10): each contributor
by hand, the reading noise measured from the data (and checked against a known injected noise),
a real shipped file, the ``[straightness_uncertainty]`` table checked in one line, and the
command line's ``--json`` carrying the stored record's U."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import ConfigError
from axiscal.standards.iso230_9_geometry import slope_uncertainty
from axiscal.standards.iso230_9_straightness import reading_noise, straightness_budget

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SQ3 = math.sqrt(3)


def test_each_contributor_by_hand():
    """Readings 0, 1, 0, 1, 0 µm at 0..400 mm, every input given: reference 0.3 µm, gain 2 %,
    resolution 0.5 µm, E_VE 0.6 µm, reference direction 1 µm/m, k = 3. Both straightness
    figures are 1 µm, the slope 0; σ = 0.8 µm (second differences 1, −1, 1: 2.6667 µm² over
    E₁ = 4.5 − 1/3); the slope fit 2 µm/m (residuals −0.4, 0.6 ... over Σ(x − x̄)² = 0.1 m²)."""
    b = straightness_budget([0, .1, .2, .3, .4], [0, 1e-6, 0, 1e-6, 0],
                            {"reference_u": 0.3, "gain": 2.0, "resolution": 0.5, "e_ve": 0.6,
                             "reference_slope_u": 1.0, "k": 3.0})
    u = {c.name: c.u for c in b.contributors}
    assert u["u_REF"] == 0.3
    assert u["u_GAIN,LS"] == pytest.approx(1 * 0.02 / SQ3, rel=1e-9)
    assert u["u_RES"] == pytest.approx(math.sqrt(2) * 0.5 / math.sqrt(12), rel=1e-12)
    assert u["u_NOISE"] == pytest.approx(math.sqrt(2) * 0.8, rel=1e-9)
    assert u["u_EVE"] == pytest.approx(0.6 / (2 * SQ3), rel=1e-12)
    assert u["u_FIT"] == pytest.approx(2.0, rel=1e-9)
    assert u["u_GAIN,SLOPE"] == pytest.approx(0.0, abs=1e-9)
    assert u["u_EVE,SLOPE"] == pytest.approx(0.6 / (2 * SQ3) / 0.4, rel=1e-12)
    straight = math.sqrt(0.3**2 + (0.02 / SQ3)**2 + 0.5**2 / 6 + 2 * 0.64 + 0.36 / 12)
    assert b.U("straightness") == pytest.approx(3 * straight, rel=1e-9)
    assert b.U("straightness_min_zone") == pytest.approx(3 * straight, rel=1e-9)
    assert b.U("slope") == pytest.approx(3 * math.sqrt(4 + 1 + (0.6 / (2 * SQ3) / 0.4)**2),
                                         rel=1e-9)
    assert b.k == 3.0 and not [i.name for i in b.assumed]
    noise = next(i for i in b.inputs if i.name == "reading_noise")
    assert noise.value == pytest.approx(0.8) and noise.rule.startswith("measured: ")


def test_minimum_zone_and_least_squares_differ_only_by_their_gain_term():
    """A tilted zigzag: the least-squares band (residuals about the fitted line) is wider than
    the minimum zone; with gain 10 % their U differ by the gain term alone."""
    x = np.linspace(0, 0.5, 6)
    y = np.array([0, 2, 0.5, 2.5, 1, 3]) * 1e-6
    b = straightness_budget(x, y, {"gain": 10.0})
    g = {c.name: c.u for c in b.contributors}
    rest = b.U("straightness")**2 / 4 - g["u_GAIN,LS"]**2
    assert b.U("straightness_min_zone")**2 / 4 - g["u_GAIN,MZ"]**2 == \
        pytest.approx(rest, rel=1e-12)
    assert g["u_GAIN,LS"] != pytest.approx(g["u_GAIN,MZ"])


def test_the_reading_noise_is_measured_on_a_curved_trajectory():
    """Truth test: a bent axis (δy = 4Sx²/L², S = 10 µm over L = 800 mm, M.A.V. Chapman,
    "Calibration of machine squareness", Appendix I eq. 1) read at 17 positions with white
    noise σ = 0.2 µm: the curvature leaves the second differences constant, so the estimate is
    the noise's: the mean of σ̂² over 400 runs is σ² within 5 %; without noise σ̂ is 0."""
    x = np.linspace(-0.4, 0.4, 17)
    bend = 4 * 10e-6 * x**2 / 0.8**2
    assert reading_noise(x, bend).sigma == pytest.approx(0.0, abs=1e-15)
    rng = np.random.default_rng(7)
    s2 = [reading_noise(x, bend + rng.normal(0, 0.2e-6, x.size)).sigma**2 for _ in range(400)]
    assert np.mean(s2) == pytest.approx(0.2e-6**2, rel=0.05)
    shuffled = rng.permutation(x.size)            # the file's order does not matter
    assert reading_noise(x[shuffled], bend[shuffled]).sigma == pytest.approx(0.0, abs=1e-15)


def test_a_long_record_is_measured_in_linear_time():
    """200,000 readings (a continuous capture) with σ = 0.05 µm on a bow, unevenly spaced: the
    estimate is made without an n × n matrix (which would take 320 GB) and is σ within 2 %;
    the few positions equal to the nanometre by chance (about 10) enter by their means, not as
    a pooled standard deviation of 10 degrees of freedom (which gave 0.061 µm)."""
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0, 2.0, 200_000))
    y = 5e-6 * (x - 1) ** 2 + rng.normal(0, 0.05e-6, x.size)
    assert reading_noise(x, y).sigma == pytest.approx(0.05e-6, rel=0.02)


def test_repeated_runs_give_the_pooled_standard_deviation():
    """Two runs at the same five positions, differing by ±0.1 µm: s_p = √(Σd²/2 / 5) with the
    pair differences d = 0.2 µm, i.e. 0.1·√2 µm (JCGM 100:2008 §4.2.4)."""
    x = np.tile(np.linspace(0, 0.4, 5), 2)
    y = np.r_[np.full(5, 0.1e-6), np.full(5, -0.1e-6)] + 1e-6 * x
    n = reading_noise(x, y)
    assert n.degrees_of_freedom == 5 and "pooled" in n.how
    assert n.sigma == pytest.approx(0.1e-6 * math.sqrt(2), rel=1e-9)


def test_too_few_readings_leave_the_noise_out_and_say_so():
    b = straightness_budget([0, .1, .2], [0, 1e-6, 0])
    noise = next(i for i in b.inputs if i.name == "reading_noise")
    assert noise.assumed and "not measured" in noise.rule
    assert any("not measured" in n for n in b.notes)
    assert {c.name: c.u for c in b.contributors}["u_NOISE"] == 0.0


def test_a_real_shipped_file():
    """examples/squareness_L180_x.csv (a 10 µm bow over ±400 mm, 17 readings): σ measured from
    its readings is below 0.2 µm, so the straightness's U (defaults) is about 2·√(0.5² + 2σ² +
    ...) ≈ 1.04 µm, each term as the module docstring states; the slope's U is the line fit's
    (the bow is in the residuals) with the gain's, about 7 µm/m."""
    from axiscal.io.straightness import read_straightness

    d = read_straightness(EXAMPLES / "squareness_L180_x.csv")
    b = straightness_budget(d.positions, d.deviations)
    sigma = reading_noise(d.positions, d.deviations).sigma * 1e6
    assert 0.01 < sigma < 0.2
    F = 9.996810878070585                     # axiscal straightness ... --json straightness_um
    u = math.sqrt(0.5**2 + (F * 0.005 / SQ3)**2 + 0.1**2 / 6 + 2 * sigma**2)
    assert b.U("straightness") == pytest.approx(2 * u, rel=1e-9)
    assert b.U("straightness") == pytest.approx(1.038, abs=0.001)
    fit = slope_uncertainty(d.positions, d.deviations)
    assert b.U("slope") == pytest.approx(2 * fit, rel=1e-3) and 6.9 < b.U("slope") < 7.2
    assert [i.name for i in b.assumed] == ["reference_u", "gain", "resolution", "e_ve",
                                           "reference_slope_u", "k"]
    assert sum(n.startswith("assumed: ") for n in b.notes) == 5


@pytest.mark.parametrize("table,match", [
    ({"laser_ppm": 1.0}, r"^\[straightness_uncertainty\] laser_ppm: no such input; use "),
    ({"gain": -1.0}, r"^\[straightness_uncertainty\] gain = -1.0: a finite number ≥ 0 \(at "
                     r"most 1e\+100\) in %$"),
    ({"k": 0}, r"^\[straightness_uncertainty\] k = 0: "),
    ({"resolution": "0.1 s"}, r"resolution = .*0.1 s"),          # text of another kind's unit
    ({"reference_u": 1e200}, r"reference_u = 1e\+200: .*at most 1e\+100"),   # squared: inf
])
def test_a_bad_table_is_refused_in_one_line(table, match):
    with pytest.raises(ConfigError, match=match) as e:
        straightness_budget([0, .1, .2, .3], [0, 1e-6, 0, 1e-6], table)
    assert "\n" not in str(e.value)


def test_a_value_with_its_unit_is_read_in_the_inputs_unit():
    """The budgets' one rule (iso230_9_entry.checked_table): "100 nm" is 0.1 µm, the same U."""
    a = straightness_budget([0, .1, .2, .3], [0, 1e-6, 0, 1e-6], {"resolution": 0.1})
    b = straightness_budget([0, .1, .2, .3], [0, 1e-6, 0, 1e-6], {"resolution": "100 nm"})
    assert a.U("straightness") == b.U("straightness")


def test_the_command_line_carries_the_stored_records_U(tmp_path, monkeypatch):
    """``axiscal straightness FILE --json`` with the user configuration's
    ``[straightness_uncertainty]``: its ``quantities`` are the stored record's (``history add``
    with the same configuration; ``history show --json``; both reports' tables of U), U moved by the declared reference (2 µm) and marked given."""
    from typer.testing import CliRunner

    from axiscal.cli import app
    from axiscal.store import open_store

    cfg = tmp_path / "config.toml"
    cfg.write_text("[straightness_uncertainty]\nreference_u = 2.0\n", encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    f = EXAMPLES / "squareness_L180_x.csv"
    r = CliRunner().invoke(app, ["straightness", str(f), "--json"])
    assert r.exit_code == 0, r.output
    j = json.loads(r.stdout)
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    t = st.get(st.add(f.read_bytes(), f.name, machine="VMC").id)
    assert j["quantities"] == t.result["quantities"]
    shown = CliRunner().invoke(app, ["history", "show", str(t.summary.id), "--json", "--db",
                                     f"sqlite:///{tmp_path / 'h.sqlite'}"])
    assert shown.exit_code == 0 and json.loads(shown.stdout)["quantities"] == j["quantities"]
    for args in (["history", "show", str(t.summary.id), "--db",           # the same U tables
                  f"sqlite:///{tmp_path / 'h.sqlite'}", "--report", str(tmp_path / "h.html")],
                 ["straightness", str(f), "--report", str(tmp_path / "c.html")]):
        assert CliRunner().invoke(app, args).exit_code == 0
    for name in ("h.html", "c.html"):
        page = (tmp_path / name).read_text("utf-8")
        assert "<td>Straightness, minimum-zone line</td><td>10.0</td><td>4.1</td>" in page, name
        assert "Uncertainty budget: U narrow" not in page and "reading noise σ" in page
    assert j["quantities"]["straightness"]["value"] == j["straightness_um"]
    assert 4.0 < j["quantities"]["straightness"]["U"] < 4.2          # 2·√(2² + ...)
    assert j["uncertainty_budget"]["inputs"]["reference_u"]["assumed"] is False
    plain = CliRunner().invoke(app, ["straightness", str(f)])
    assert "least squares U = 4.1 µm" in plain.output, plain.output
