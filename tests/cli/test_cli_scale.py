"""``axiscal scale home | gantry | compensate`` and the TOML configurations in examples/."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.errors import ConfigError
from axiscal.io.scale_config import parse_scale_config, read_scale_config

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_scale_home_prints_events_and_writes_the_plot(tmp_path):
    png = tmp_path / "home.png"
    r = runner.invoke(app, ["scale", "home", str(EXAMPLES / "scale_single.toml"), "--plot",
                            str(png)])
    assert r.exit_code == 0, r.output
    for word in ("A ", "B ", "Z ", "C ", "home (Z)", "compensation factor", "after homing"):
        assert word in r.output
    assert png.stat().st_size > 20_000


def test_scale_home_json():
    r = runner.invoke(app, ["scale", "home", str(EXAMPLES / "scale_single.toml"), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["homed"] is True
    assert [e["nominal_counts"] for e in d["events"]] == [0, 256, 320, 384]
    assert d["events"][2]["uncertainty_counts"] == pytest.approx(0.633 / 0.078125, rel=1e-3)
    assert d["tracking"]["max_pulse_error"] < 1.0
    assert d["tracking"]["count_uncertainty"] == pytest.approx(8.10, abs=0.01)
    assert d["alarms"] == []
    for key in ("virtual_counts", "home_position_mm", "compensation_ppm", "laser_count_rate_hz"):
        assert key in d


def test_scale_gantry_text_and_json():
    r = runner.invoke(app, ["scale", "gantry", str(EXAMPLES / "scale_gantry.toml")])
    assert r.exit_code == 0, r.output
    assert "skew limit" in r.output and "worst case" in r.output
    r = runner.invoke(app, ["scale", "gantry", str(EXAMPLES / "scale_gantry.toml"), "--json"])
    d = json.loads(r.stdout)
    assert d["skew_after_sync"] == d["offset"] == -13
    assert d["required_skew_limit"] > 256
    assert abs(d["homing_skew_min"]) <= 255 and abs(d["homing_skew_max"]) <= 255
    assert len(d["worst_case"]) == 2


def test_scale_gantry_alarm(tmp_path):
    cfg = tmp_path / "g.toml"
    cfg.write_text((EXAMPLES / "scale_gantry.toml").read_text().replace(
        "skew_limit_counts = 300", "skew_limit_counts = 100"))
    r = runner.invoke(app, ["scale", "gantry", str(cfg)])
    assert r.exit_code == 0
    assert "ALARM" in r.output


def test_scale_compensate():
    r = runner.invoke(app, ["scale", "compensate", "--json", "-t", "21", "--material", "steel",
                            "--material-temperature", "22", "--material-temperature", "24",
                            "--length", "2000"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["material_error_um"] == pytest.approx(2000e-3 * 11.5e-6 * 3 * 1e6, rel=1e-9)
    assert d["weather_error_um"] == pytest.approx(-0.95 * 2, abs=0.1)
    r = runner.invoke(app, ["scale", "compensate"])
    assert "ppm" in r.output and "weather" in r.output
    r = runner.invoke(app, ["scale", "compensate", "--period", "30"])
    assert r.exit_code == 2 and "period" in r.output


def test_config_errors_are_clean(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[switch]\nposition = 3\n")
    r = runner.invoke(app, ["scale", "home", str(bad)])
    assert r.exit_code == 2 and "unknown key" in r.output and "Traceback" not in r.output
    r = runner.invoke(app, ["scale", "home", str(tmp_path / "missing.toml")])
    assert r.exit_code == 2
    with pytest.raises(ConfigError, match="unknown table"):
        parse_scale_config("[lazer]\n")
    with pytest.raises(ConfigError, match="TOML"):
        parse_scale_config("[laser\n")
    with pytest.raises(ConfigError, match="whole number"):
        from axiscal.io.scale_config import axis_from_config
        axis_from_config(parse_scale_config("[compensator]\ncounts_per_period = 25.5\n"))
    with pytest.raises(ConfigError, match="direction"):
        from axiscal.io.scale_config import axis_from_config
        axis_from_config(parse_scale_config("[switch]\ndirection = 'up-ish'\n"))


def test_rephase_periods_in_the_configuration(tmp_path):
    """Issue 20: homing at 114000 mm/min with power-up phase 0 raises the input-frequency alarm;
    rephase_periods = "auto" spreads the virtual movement and it does not; bad values and a
    value the gantry cannot honour are one clean line."""
    text = (EXAMPLES / "scale_single.toml").read_text().replace(
        "speed_mm_per_min = 300\n", "speed_mm_per_min = 114000\npower_up_phase = 0\n", 1)
    fast = tmp_path / "fast.toml"
    fast.write_text(text)
    d = json.loads(runner.invoke(app, ["scale", "home", str(fast), "--json"]).stdout)
    assert len(d["alarms"]) == 1 and "input frequency" in d["alarms"][0]
    assert d["peak_input_frequency_khz"] > 170 and d["rephase_periods"] == 1
    fast.write_text(text.replace("co2 = 450", 'co2 = 450\nrephase_periods = "auto"'))
    d = json.loads(runner.invoke(app, ["scale", "home", str(fast), "--json"]).stdout)
    assert d["alarms"] == [] and d["rephase_periods"] > 1
    assert d["peak_input_frequency_khz"] < 100
    fast.write_text(text.replace("co2 = 450", "co2 = 450\nrephase_periods = 0"))
    r = runner.invoke(app, ["scale", "home", str(fast)])
    assert r.exit_code == 2 and "rephase_periods" in r.output and "Traceback" not in r.output
    gantry = tmp_path / "g.toml"
    gantry.write_text((EXAMPLES / "scale_gantry.toml").read_text().replace(
        "counts_per_period = 256", "counts_per_period = 256\nrephase_periods = 2", 1))
    r = runner.invoke(app, ["scale", "gantry", str(gantry)])
    assert r.exit_code == 2 and "rephase_periods" in r.output


def test_examples_parse():
    for p in EXAMPLES.glob("scale_*.toml"):
        assert read_scale_config(p)["_source"] == str(p)


def test_a_homing_start_far_from_the_switch_is_refused_in_counts(tmp_path):
    """A homing start 5 m before the switch was within the 5 m reach and took 19 GB (the
    simulation follows every count of the approach); it is bounded in counts and says how close
    the start must be."""
    from pathlib import Path

    ex = Path(__file__).resolve().parents[2] / "examples" / "scale_single.toml"
    f = tmp_path / "far.toml"
    f.write_text(ex.read_text().replace("start_mm = 99.96", "start_mm = -4899"))
    r = runner.invoke(app, ["scale", "home", str(f)])
    assert r.exit_code == 2
    assert "is 6.4e+07 output counts (78.1 nm each) before the switch" in r.stderr, r.stderr
    assert "start within 117 mm of the switch" in r.stderr


def test_gantry_plot_and_report(tmp_path):
    """scale gantry --plot draws the skew step by step with the limits; --report is marked a
    simulation and carries every figure of --json and the document it follows."""
    png, html = tmp_path / "g.png", tmp_path / "g.html"
    res = runner.invoke(app, ["scale", "gantry", str(EXAMPLES / "scale_gantry.toml"), "--plot",
                              str(png), "--report", str(html), "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    page = html.read_text()
    assert png.stat().st_size > 1000 and "Laser scale axis referencing" in page
    assert "simulation" in page.lower() and "<td>Skew limit needed [counts]</td>" in page
    assert f"<td>{d['required_skew_limit']}</td>" in page


def test_gantry_plot_of_a_long_homing_stays_small(tmp_path):
    """Found by the fuzz harness: a homing from 10 mm before the switch has 128,000 steps; the
    plot keeps each bin's extremes (at most 4,000 points), so the report stays under 1 MB."""
    cfg = tmp_path / "far.toml"
    cfg.write_text((EXAMPLES / "scale_gantry.toml").read_text()
                   .replace("start_1_mm = 99.95", "start_1_mm = 90.0")
                   .replace("start_2_mm = 99.95", "start_2_mm = 90.0"))
    html = tmp_path / "g.html"
    res = runner.invoke(app, ["scale", "gantry", str(cfg), "--report", str(html)])
    assert res.exit_code == 0, res.output
    assert html.stat().st_size < 1_000_000
