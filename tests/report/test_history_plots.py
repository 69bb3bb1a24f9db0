"""The trend figure of ``axiscal history trend --plot``: dates on its axis, the predicted
crossing of the tolerance drawn where :func:`axiscal.store.analysis.fit_trend` puts it."""

from __future__ import annotations

import datetime as dt

import matplotlib.dates as mdates
import pytest

from axiscal.report.history_plots import trend_figure
from axiscal.store.analysis import fit_trend


def test_trend_figure_draws_the_predicted_crossing_on_a_date_axis():
    """fit_trend's docstring example: four yearly tests rising about 1 µm a year from 5 µm
    reach 10 µm in 2025; the crossing is a marker on the tolerance at that date."""
    d = [dt.datetime(2020 + k, 1, 1) for k in range(4)]
    tr = fit_trend("E", d, [5.0, 6.1, 6.9, 8.0], "um", tolerance=10)
    fig = trend_figure(tr)
    ax = fig.axes[0]
    mark = next(ln for ln in ax.get_lines() if ln.get_label().startswith("predicted crossing"))
    assert mdates.date2num(mark.get_xdata()[0]) == pytest.approx(mdates.date2num(tr.crossing))
    assert mark.get_ydata()[0] == 10
    assert ax.get_ylabel() == "E [µm]" and ax.get_xlabel() == "date of the test"
    lo, hi = ax.get_xlim()
    assert lo <= mdates.date2num(d[0]) and hi >= mdates.date2num(tr.crossing)


def test_trend_figure_of_tests_on_one_date_spans_years_not_a_century():
    """Every test on one date: the axis stays around that date (the workbench once drew 0-100
    years)."""
    d = [dt.datetime(2026, 3, 1)] * 3
    fig = trend_figure(fit_trend("E", d, [5.0, 5.2, 5.1], "um"))
    lo, hi = fig.axes[0].get_xlim()
    assert 0 < hi - lo <= 5 * 366
