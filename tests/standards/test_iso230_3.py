"""ISO 230-3:2020 evaluations: the figures' equations on the thermal twin, and the log checks.

The truth test of every figure (within its U at about 95 %, counted over 200 seeds against a
binomial bound) is ``test_iso230_3_coverage.py``; here the equations themselves (tilts from the
sensor pairs, growth from the two targets, a speed programme held, the rotary test's figures
those of the spindle test's equations) and the refusals."""

import dataclasses

import numpy as np
import pytest

from axiscal.errors import DataFormatError, InputError
from axiscal.machines.thermal_config import parse_thermal_config
from axiscal.procedures.thermal import plan_thermal, simulate_drift_check, simulate_thermal
from axiscal.standards.iso230_3 import e_ve_from_etve, evaluate_thermal
from axiscal.standards.iso230_3_data import ThermalLog, check_log

CONFIG = "src/axiscal/data/thermal_vmc.toml"


@pytest.fixture(scope="module")
def twin():
    return parse_thermal_config(open(CONFIG).read(), CONFIG)


def test_spindle_tilts_come_from_the_sensor_pairs(twin):
    """The tilt figures are the twin's A and B (rad), recovered from X1−X2 and Y2−Y1 over l:
    with noiseless sensors they agree to rounding."""
    quiet = dataclasses.replace(twin, displacement_noise=0.0)
    sim = simulate_thermal(quiet, plan_thermal(quiet, "spindle"), np.random.default_rng(0))
    r = evaluate_thermal(sim.log)
    for k in ("A", "B", "X", "Y", "Z"):
        assert r[f"delta_{k}_end_run"].value == pytest.approx(sim.truth[f"delta_{k}_end_run"],
                                                              abs=1e-12)
    assert abs(sim.truth["delta_A_max_run"]) > 1e-6      # the head tilts by µrad


def test_linear_growth_is_the_difference_of_the_two_targets(twin):
    sim = simulate_thermal(twin, plan_thermal(twin, "linear"), np.random.default_rng(3))
    r = evaluate_thermal(sim.log)
    d = sim.log.displacements
    end = int(np.flatnonzero(sim.log.running)[-1])
    g = (d["P2"][end] - d["P2"][0]) - (d["P1"][end] - d["P1"][0])
    assert r["delta_G_end_run"].value == pytest.approx(g)
    span = sim.log.targets[1] - sim.log.targets[0]
    assert r["growth_per_length_max_run"].value == pytest.approx(r["delta_G_max_run"].value / span)


def test_e_ve_from_etve_is_the_range_in_the_window(twin):
    sim = simulate_thermal(twin, plan_thermal(twin, "etve"), np.random.default_rng(4))
    x = sim.log.displacements["X"]
    m = (sim.log.time >= 3600) & (sim.log.time <= 3 * 3600)
    assert e_ve_from_etve(sim.log, "X", 3600.0, 7200.0) == pytest.approx(np.ptp(x[m]))
    with pytest.raises(InputError, match="outside the log"):
        e_ve_from_etve(sim.log, "X", 23 * 3600.0, 7200.0)


def test_simulated_drift_check_range_is_its_e_ve(twin):
    """The drift check's noiseless range is the machine's drift at the set-up plus the
    instrument's: with 1 µm/h of instrument drift over 2 h the range grows by about 2 µm."""
    plan = plan_thermal(twin, "drift-check", duration=7200.0)
    still = simulate_drift_check(twin, plan, np.random.default_rng(5))
    drifting = simulate_drift_check(
        twin, dataclasses.replace(plan, instrument_drift=1e-6 / 3600), np.random.default_rng(5))
    assert np.ptp(still.readings) == pytest.approx(still.true_e_ve, abs=0.8e-6)
    assert drifting.true_e_ve - still.true_e_ve == pytest.approx(2e-6, abs=0.5e-6)


def _log(**changes):
    t = np.arange(0, 13 * 3600 + 1, 60.0)
    rng = np.random.default_rng(0)
    base = dict(test="etve", time=t,
                temperatures={"T_room": 20 + 0.3 * np.sin(t / 8000) + rng.normal(0, 0.01, t.size)},
                displacements={"X": 1e-6 * np.sin(t / 9000) + rng.normal(0, 1e-7, t.size)})
    base.update(changes)
    return ThermalLog(**base)


def test_a_good_log_passes():
    assert check_log(_log()).test == "etve"


@pytest.mark.parametrize("change, words", [
    ("backwards", "time goes backwards"),
    ("gap", "a gap of"),
    ("stuck", "the sensor is stuck"),
    ("jump", "the sensor jumps"),
    ("short", "needs at least 12 h"),
    ("nan", "not a finite number"),
])
def test_bad_logs_are_refused_with_one_line(change, words):
    log = _log()
    t = log.time.copy()
    temp = log.temperatures["T_room"].copy()
    if change == "backwards":
        t[100] = t[98]
        log = dataclasses.replace(log, time=t)
    elif change == "gap":
        t[200:] += 1800
        log = dataclasses.replace(log, time=t)
    elif change == "stuck":
        temp[300:370] = temp[300]
        log = dataclasses.replace(log, temperatures={"T_room": temp})
    elif change == "jump":
        temp[400:] += 2.0
        log = dataclasses.replace(log, temperatures={"T_room": temp})
    elif change == "short":
        n = 6 * 60
        log = dataclasses.replace(log, time=t[:n], temperatures={"T_room": temp[:n]},
                                  displacements={"X": log.displacements["X"][:n]})
    else:
        temp[50] = np.nan
        log = dataclasses.replace(log, temperatures={"T_room": temp})
    with pytest.raises(DataFormatError) as e:
        check_log(log)
    assert words in str(e.value) and "\n" not in str(e.value)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@pytest.fixture(scope="module")
def spindle_log(twin):
    return simulate_thermal(twin, plan_thermal(twin, "spindle"), np.random.default_rng(11)).log


@settings(max_examples=25, deadline=None)
@given(offset=st.floats(-1e-3, 1e-3), flip=st.booleans())
def test_drift_figures_ignore_each_sensors_zero_and_flip_with_the_sign(spindle_log, offset, flip):
    """CONVENTIONS habit 9: a constant added to every reading of a sensor (its zero) leaves every
    drift figure unchanged; negating every displacement negates every drift figure and keeps its
    U (ISO 230-3 figures are changes from the first reading)."""
    base = evaluate_thermal(spindle_log)
    s = -1.0 if flip else 1.0
    moved = dataclasses.replace(spindle_log, displacements={
        k: s * v + offset * (i + 1) for i, (k, v) in enumerate(spindle_log.displacements.items())})
    other = evaluate_thermal(moved)
    for f in base.figures:
        if f.kind in ("length", "angle"):
            assert other[f.name].value == pytest.approx(s * f.value, abs=1e-12)
            assert other[f.name].uncertainty == pytest.approx(f.uncertainty, rel=1e-9, abs=1e-15)


def test_a_speed_programme_is_held_step_by_step(twin):
    """Steps of 25 %, 50 % and 100 % speed for 30 min each, repeated through the 4 h run: the
    spindle node follows the steps (its figures against the truth:
    ``test_iso230_3_coverage.py``, case "spindle programme")."""
    from axiscal.procedures.thermal import _speeds

    plan = plan_thermal(twin, "spindle", programme=((0.25, 1800.0), (0.5, 1800.0), (1.0, 1800.0)))
    u = _speeds(plan)
    t = plan.times
    assert u[t == 0][0] == 0.25 and u[t == 1800][0] == 0.5 and u[t == 3600 + 1740][0] == 1.0
    assert u[t == 5400][0] == 0.25                              # the programme repeats


ROTARY = "src/axiscal/data/thermal_rotary_table.toml"


def test_rotary_table_test_is_clause_8_with_the_spindle_tests_equations():
    """ISO 230-3:2020 Clause 8 (a rotary table turning) on the twin of thermal_rotary_table.toml:
    the result names Clause 8 and the figures are those of the spindle test's equations
    (Clause 6) on the artefact's five sensors (against the truth: ``test_iso230_3_coverage.py``,
    case "rotary")."""
    from axiscal.standards.iso230_3 import evaluate_spindle

    twin = parse_thermal_config(open(ROTARY).read(), ROTARY)
    sim = simulate_thermal(twin, plan_thermal(twin, "rotary"), np.random.default_rng(1))
    result = evaluate_thermal(sim.log)
    assert result.clause == "ISO 230-3:2020 Clause 8" and result.test == "rotary"
    as_spindle = evaluate_spindle(dataclasses.replace(sim.log, test="spindle"))
    assert [f.value for f in as_spindle.figures] == [f.value for f in result.figures]


def test_rotary_test_needs_a_twin_with_a_rotary_table(twin):
    with pytest.raises(InputError, match="needs a twin with a rotary table"):
        plan_thermal(twin, "rotary")
