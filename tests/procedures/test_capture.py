"""A test taken from a continuous record without a trigger (issue 12): truth tests and misfits."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.measured import Record, parse_plan_csv
from axiscal.machines.config import axis_from_config
from axiscal.procedures.capture import capture_test
from axiscal.procedures.positioning import plan_linear
from axiscal.procedures.record_simulation import RecordSettings, simulate_record
from axiscal.standards.iso230_2 import evaluate

AXIS = {"name": "X", "kind": "linear", "travel_mm": [-10, 810], "scale_error_ppm": 5.0,
        "backlash_um": 2.0, "repeatability_um": 0.3, "periodic": [
            {"amplitude_um": 1.5, "period_mm": 100.0, "phase_deg": 0}]}


def _plan(**kw):
    return parse_plan_csv(plan_linear(800, dwell=2.0, **kw).to_csv())


@pytest.mark.parametrize("rate, runs", [(10.0, 5), (1000.0, 5), (50000.0, 2)])
def test_captured_deviations_equal_the_truth(rate, runs):
    """Truth test: a simulated machine runs an exported plan (trapezoidal moves at 50 mm/s and
    0.5 m/s², 25 Hz settling ringing, 0.05 µm of 120 Hz vibration, 0.05 µm noise); the captured
    deviation at every target equals the machine's settled deviation within 4 σ of a stop's mean
    (noise and vibration over the shortest stop's samples), and the ISO 230-2 evaluation agrees
    within 0.05 µm."""
    plan = _plan(runs=runs)
    st = RecordSettings(sample_rate=rate)
    t, x, truth = simulate_record(plan, axis_from_config(AXIS), np.random.default_rng(3), st)
    res = capture_test(Record(t, x, "linear", None, rate), plan, window=0.5)
    assert len(res.assigned) == plan.targets.size * runs * 2
    n = min(res.stops[k].end - res.stops[k].start for k, _ in res.assigned) // 2
    tol = 4 * np.hypot(st.noise, st.vibration_amplitude / np.sqrt(2)) / np.sqrt(n) * 1e6
    assert np.nanmax(np.abs(res.dataset.up - truth.up)) < tol
    assert np.nanmax(np.abs(res.dataset.down - truth.down)) < tol
    r, rt = evaluate(res.dataset), evaluate(truth)
    for k in ("A", "E", "M", "R", "B"):
        assert getattr(r, k) == pytest.approx(getattr(rt, k), abs=0.05)
    if rate >= 1000:
        s = res.summary()
        assert s["vibration"]["peak_hz"] == pytest.approx(120, abs=2)
        assert s["vibration"]["amplitude_um"] == pytest.approx(0.05, rel=0.2)
        assert 0.1 < s["settling_s"]["median"] < 1.0


@pytest.fixture(scope="module")
def recorded():
    plan = _plan(runs=2)
    t, x, truth = simulate_record(plan, axis_from_config(AXIS), np.random.default_rng(4),
                                  RecordSettings(sample_rate=200.0))
    return plan, t, x


def test_a_missing_stop_is_named(recorded):
    plan, t, x = recorded
    res = capture_test(Record(t, x, "linear", None, 200.0), plan, window=0.5)
    k, row = res.assigned[7]
    s = res.stops[k]
    x2 = x.copy()
    x2[s.start:s.end] += np.linspace(0, 50e-6, s.end - s.start)     # never settles there
    d = "↑" if plan.direction[row] == "+" else "↓"
    with pytest.raises(AxiscalError, match=rf"no stop for target {plan.target_index[row] + 1} "
                                           rf"\(\S+ mm\) run {plan.run[row]} {d}"):
        capture_test(Record(t, x2, "linear", None, 200.0), plan, window=0.5)


def test_an_unexplained_stop_is_named(recorded):
    plan, t, x = recorded
    res = capture_test(Record(t, x, "linear", None, 200.0), plan, window=0.5)
    k, _ = res.assigned[3]
    s, nxt = res.stops[k], res.stops[k + 1]
    x2 = x.copy()
    mid = (s.end + nxt.start) // 2                  # during the next move: a pause 3 mm away
    x2[mid:mid + 600] = x2[mid] + 0.003
    with pytest.raises(AxiscalError, match="is not in the plan"):
        capture_test(Record(t, x2, "linear", None, 200.0), plan, window=0.5)


def test_a_record_that_ends_early_is_named(recorded):
    plan, t, x = recorded
    n = t.size * 2 // 3
    with pytest.raises(AxiscalError, match="the record ends before target"):
        capture_test(Record(t[:n], x[:n], "linear", None, 200.0), plan, window=0.5)


def test_a_record_of_the_wrong_kind_or_too_short(recorded):
    plan, t, x = recorded
    with pytest.raises(AxiscalError, match="rotary readings"):
        capture_test(Record(t, x, "rotary", None, 200.0), plan)
    with pytest.raises(AxiscalError, match="longer than the whole record"):
        capture_test(Record(t[:50], x[:50], "linear", None, 200.0), plan)
