"""Thermal logs as CSV (axiscal.io.thermal): round trip and strict refusals, one line each."""

import numpy as np
import pytest

from axiscal.errors import DataFormatError
from axiscal.io.drift import parse_drift_check
from axiscal.io.thermal import format_drift_check, format_thermal_log, parse_thermal_log
from axiscal.machines.thermal_config import parse_thermal_config
from axiscal.procedures.thermal import plan_thermal, simulate_drift_check, simulate_thermal
from axiscal.standards.iso230_3 import evaluate_thermal

CONFIG = "src/axiscal/data/thermal_vmc.toml"


@pytest.fixture(scope="module")
def twin():
    return parse_thermal_config(open(CONFIG).read(), CONFIG)


@pytest.fixture(scope="module")
def spindle_text(twin):
    sim = simulate_thermal(twin, plan_thermal(twin, "spindle"), np.random.default_rng(2))
    return sim, format_thermal_log(sim.log)


@pytest.mark.parametrize("test", ["etve", "spindle", "linear"])
def test_round_trip_keeps_every_figure(twin, test):
    """Written at 0.1 nm and 0.1 mK, read back: every figure within 1 nm (1 nrad for tilts)."""
    sim = simulate_thermal(twin, plan_thermal(twin, test), np.random.default_rng(1))
    back = parse_thermal_log(format_thermal_log(sim.log), "t.csv")
    a, b = evaluate_thermal(sim.log), evaluate_thermal(back)
    assert back.targets == pytest.approx(sim.log.targets) if sim.log.targets else True
    for f in a.figures:
        assert b[f.name].value == pytest.approx(f.value, abs=2e-9 if f.kind != "temperature" else 2e-4)


def _edit(text, fn):
    lines = text.splitlines()
    head = [i for i, l in enumerate(lines) if l.startswith("time_s")][0]
    fn(lines, head)
    return "\n".join(lines) + "\n"


def _set_cell(lines, row, col, value):
    cells = lines[row].split(",")
    cells[col] = value
    lines[row] = ",".join(cells)


@pytest.mark.parametrize("name, edit, words", [
    ("gap", lambda L, h: L.__delitem__(slice(h + 50, h + 70)), "a gap of"),
    ("backwards", lambda L, h: _set_cell(L, h + 30, 0, "100"), "time goes backwards"),
    ("stuck", lambda L, h: [_set_cell(L, h + i, 1, "20.1234") for i in range(10, 90)],
     "the sensor is stuck"),
    ("jump", lambda L, h: [_set_cell(L, h + i, 6, str(float(L[h + i].split(",")[6]) + 40))
                           for i in range(100, len(L) - h)], "the sensor jumps"),
    ("short", lambda L, h: L.__delitem__(slice(h + 200, None)), "needs at least 4 h"),
    ("not a number", lambda L, h: _set_cell(L, h + 5, 2, "abc"), "is not a number"),
    ("row length", lambda L, h: L.__setitem__(h + 5, L[h + 5] + ",1"), "cells; the header"),
    ("column", lambda L, h: L.__setitem__(h, L[h].replace("X2", "W")), "column 'W'"),
    ("header key", lambda L, h: L.insert(1, "# colour = red"), "unknown header key"),
])
def test_bad_logs_are_one_line_each(spindle_text, name, edit, words):
    _, text = spindle_text
    with pytest.raises(DataFormatError) as e:
        parse_thermal_log(_edit(text, edit), "bad.csv")
    assert words in str(e.value), str(e.value)
    assert "\n" not in str(e.value) and str(e.value).startswith("bad.csv")


def _convert_temperatures(text, fn, declare=None):
    out = []
    for line in text.splitlines():
        if line.startswith("# temperature_unit"):
            if declare:
                out.append(f"# temperature_unit = {declare}")
            continue
        out.append(line)
    head = [i for i, l in enumerate(out) if l.startswith("time_s")][0]
    cols = [i for i, c in enumerate(out[head].split(",")) if c.startswith("T_")]
    for i in range(head + 1, len(out)):
        cells = out[i].split(",")
        for c in cols:
            cells[c] = f"{fn(float(cells[c])):.4f}"
        out[i] = ",".join(cells)
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("unit, fn, hint", [
    ("F", lambda c: c * 9 / 5 + 32, "look like °F"),
    ("K", lambda c: c + 273.15, "look like kelvin"),
])
def test_fahrenheit_and_kelvin_refused_unless_declared(spindle_text, unit, fn, hint):
    sim, text = spindle_text
    with pytest.raises(DataFormatError, match=hint):
        parse_thermal_log(_convert_temperatures(text, fn), "t.csv")
    log = parse_thermal_log(_convert_temperatures(text, fn, declare=unit), "t.csv")
    for name, v in sim.log.temperatures.items():
        np.testing.assert_allclose(log.temperatures[name], v, atol=1e-3)


def test_drift_check_file_is_what_iso230_2_reads(twin):
    dc = simulate_drift_check(twin, plan_thermal(twin, "drift-check"), np.random.default_rng(0))
    readings = parse_drift_check(format_drift_check(dc.time, dc.readings))
    np.testing.assert_allclose(readings, dc.readings * 1e6, atol=1e-4)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from axiscal.errors import AxiscalError  # noqa: E402

_HEAD = "# test = etve\ntime_s,T_room,X\n"


@settings(max_examples=60, deadline=None)
@given(st.text(max_size=400), st.booleans())
def test_arbitrary_text_raises_only_axiscal_errors(text, with_head):
    """CONVENTIONS habit 9: the parser never raises anything but an AxiscalError."""
    try:
        parse_thermal_log((_HEAD if with_head else "") + text, "h.csv")
    except AxiscalError:
        pass


@settings(max_examples=20, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=32), min_size=3,
                max_size=40))
def test_arbitrary_numbers_raise_only_axiscal_errors(values):
    rows = "\n".join(f"{60 * i},{v},{v}" for i, v in enumerate(values))
    try:
        parse_thermal_log(_HEAD + rows, "h.csv")
    except AxiscalError:
        pass
