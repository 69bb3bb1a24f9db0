"""What a customer sees: plots and reports that say what they show (review of the user's path)."""

import dataclasses
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import InputError
from axiscal.report.html import Report, positioning_report, target_label
from axiscal.report.motion_plots import ring_step
from axiscal.report.plots import _parameter_box, iso230_2_figure
from axiscal.standards.iso230_2 import evaluate

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _dataset(targets=(0.0, 34.736, 121.64321, 800.0), machine="VMC 800", axis="X"):
    t = np.asarray(targets)
    rng = np.random.default_rng(2)
    up = 1.0 + 0.3 * rng.standard_normal((t.size, 5))
    down = -1.0 + 0.3 * rng.standard_normal((t.size, 5))
    return PositioningDataset(AxisKind.LINEAR, t, up, down, "mm", "um",
                              Metadata(machine=machine, axis=axis))


def test_target_label_keeps_the_planned_target():
    """A 34.736 mm target rounded to the table's 2 decimals read 34.74 mm."""
    assert [target_label(v) for v in (0.0, 34.736, 45.0, -100.0, 0.5, -1e-7)] == \
        ["0", "34.736", "45", "-100", "0.5", "0"]


def test_positioning_report_shows_targets_as_planned_and_units_in_headers():
    ds = _dataset()
    html = positioning_report(ds, evaluate(ds)).html()
    assert "<td>34.736</td>" in html and "<td>34.74</td>" not in html
    assert "<td>121.6432</td>" in html
    assert "x̄↑ [µm]" in html and "R<sub>i</sub> [µm]" in html   # ISO 230-2:2014 writes R with subscript i


def test_iso230_2_plot_names_machine_and_axis_when_it_leaves_the_report():
    ds = _dataset()
    fig = iso230_2_figure(evaluate(ds), ds)
    title = fig.axes[0].get_title(loc="left")
    assert title == "Positioning deviation, ISO 230-2:2014 — VMC 800 axis X"
    fig2 = iso230_2_figure(evaluate(ds))
    assert fig2.axes[0].get_title(loc="left") == "Positioning deviation, ISO 230-2:2014"
    import matplotlib.pyplot as plt

    plt.close(fig)
    plt.close(fig2)


def test_parameter_box_aligns_the_mean_reversal_value():
    """B̄ is B plus a combining macron: padding by code points shifted its value by one column."""
    ds = _dataset()
    lines = _parameter_box(evaluate(ds), "µm").splitlines()
    b = next(x for x in lines if x.startswith("B "))
    bbar = next(x for x in lines if x.startswith("B̄"))
    assert len(b) == len(bbar) - 1          # one combining character, same visible width


def test_report_metadata_says_yes_not_true():
    html = Report("t", metadata={"Drift compensation": True, "Heads": False}).html()
    assert "<td>yes</td>" in html and "<td>no</td>" in html and "True" not in html


def test_ring_step_is_round_and_gives_one_to_two_rings():
    for peak in (0.037, 0.94, 1.0, 1.94, 3.95, 7.2, 14.36, 250.0):
        step = ring_step(peak)
        mantissa = step / 10 ** np.floor(np.log10(step))
        assert mantissa == pytest.approx(1.0) or mantissa == pytest.approx(2.0) or \
            mantissa == pytest.approx(5.0)
        assert 0.5 <= peak / step <= 2.0 + 1e-12


def test_polar_plot_has_a_labelled_radial_scale():
    """Before: no radial ticks, only the radius of the zero circle; the error could not be read."""
    import matplotlib.pyplot as plt

    from axiscal.report.motion_plots import polar_figure
    from axiscal.standards.iso230_7 import MotionErrorData, evaluate as evaluate_7
    from axiscal.units import UM

    th = np.radians(np.arange(0, 360, 30.0))
    zero = np.zeros((1, th.size))
    data = MotionErrorData(th, ez=zero, ey=zero + 2e-6 * np.sin(2 * th), ex=zero,
                           dy=(1.5 * np.sin(3 * th) * UM)[None, :],
                           dz=(0.8 * np.cos(2 * th) * UM)[None, :])
    fig = polar_figure(evaluate_7(data))
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert "0" in labels and any(re.fullmatch(r"[+-]\d+(\.\d+)?", x) for x in labels if x != "0")
    assert "rings every" in ax.get_title()
    plt.close(fig)


@pytest.fixture(scope="module")
def rotary_result():
    from axiscal.procedures.rotary_config import run_rotary_config

    cfg = tomllib.loads((EXAMPLES / "rotary_turntable.toml").read_text())
    return run_rotary_config(cfg)


def test_rotary_error_plot_keeps_an_error_beyond_the_budget_on_the_plot(rotary_result):
    """The y range was fixed at 1.3 × the budget: an error outside the budget (the case the plot
    exists to show) fell off the plot."""
    import matplotlib.pyplot as plt

    from axiscal.report.rotary import common_offset, rotary_error_figure

    r = rotary_result
    bump = np.zeros(r.plan.targets.size)
    bump[3] = 5.0                               # arcsec, far beyond the ±1.1 arcsec budget
    truth = dataclasses.replace(r.truth_result, mean_up=r.truth_result.mean_up + bump)
    bad = dataclasses.replace(r, truth_result=truth)
    fig = rotary_error_figure(bad)
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    err = bad.result.mean_up - truth.mean_up - common_offset(bad)
    assert err.min() < -4.0
    assert lo < err.min() and hi > err.max()
    assert f"{common_offset(bad):+.2f} arcsec" in ax.get_title(loc="left")  # arcsec to 0.01
    plt.close(fig)


def test_rotary_report_explains_the_common_offset_and_signs_the_difference(rotary_result):
    from axiscal.report.rotary import common_offset, rotary_report

    html = rotary_report(rotary_result).html()
    assert f"common mean ({common_offset(rotary_result):+.2f} arcsec)" in html
    assert "Measured − true [arcsec]" in html
    assert re.search(r"<td>[+-]\d\.\d\d</td>", html)
    assert "x̄↑ [arcsec]" in html
    optics_row = html.split("<td>optics self-calibration</td>")[1][:40]
    assert optics_row.startswith("<td>at 0, ±5")            # the label is not repeated


def test_referencing_plot_legend_is_outside_the_signals_and_the_file_is_checked(tmp_path):
    import matplotlib.pyplot as plt

    from axiscal.io.scale_config import axis_from_config, homing_from_config, read_scale_config
    from axiscal.procedures.referencing import simulate_referencing
    from axiscal.report.scale_plot import referencing_figure, save_referencing_plot

    cfg = read_scale_config(EXAMPLES / "scale_single.toml")
    axis = axis_from_config(cfg)
    run = simulate_referencing(axis, **homing_from_config(cfg, axis))
    fig = referencing_figure(run)
    fig.canvas.draw()
    signals = fig.axes[2]
    legend = signals.get_legend().get_window_extent()
    assert legend.y0 >= signals.get_window_extent().y1 - 1     # above the panel, not over it
    plt.close(fig)
    with pytest.raises(InputError, match="extension"):
        save_referencing_plot(run, tmp_path / "home.txt")
    assert list(tmp_path.iterdir()) == []
    out = save_referencing_plot(run, tmp_path / "home.svg")
    assert out.read_text().lstrip().startswith("<?xml")


def test_compensation_plot_of_a_part_turn_uses_the_tested_range():
    """A rotary table over 0-90° was drawn on fixed 0-360° ticks, squeezed into a quarter."""
    import matplotlib.pyplot as plt

    from axiscal.compensation.loop import run_compensation_loop
    from axiscal.report.compensation_plots import compensation_figure

    cfg = tomllib.loads((EXAMPLES / "compensation_rotary.toml").read_text())
    cfg["test"]["travel_deg"] = 90
    cfg["compensation"] = {"controller": "csv", "spacing": 10.0, "bidirectional": True,
                           "resolution": 0.36}
    fig = compensation_figure(run_compensation_loop(cfg))
    lo, hi = fig.axes[0].get_xlim()
    assert -5.0 < lo < 0.0 and 90.0 < hi < 95.0
    assert fig.axes[0].get_title(loc="left").endswith("every 10°")
    plt.close(fig)


def test_stability_legends_sit_beside_the_traces():
    import matplotlib.pyplot as plt

    from axiscal.instruments.five_dof import FiveDofSystem
    from axiscal.procedures.motion_errors import stability_test
    from axiscal.report.motion_plots import stability_figure

    run = stability_test(FiveDofSystem(), np.random.default_rng(1), duration=600.0)
    fig = stability_figure(run)
    fig.canvas.draw()
    for ax in fig.axes:
        assert ax.get_legend().get_window_extent().x0 >= ax.get_window_extent().x1 - 1
    plt.close(fig)
