"""The thermal twin (axiscal.machines.thermal) and its TOML configuration."""

import math

import numpy as np
import pytest

from axiscal.errors import ConfigError, InputError
from axiscal.machines.thermal import Room, ThermalAxis, ThermalNode, ThermalTwin
from axiscal.machines.thermal_config import parse_thermal_config

CONFIG = "src/axiscal/data/thermal_vmc.toml"


def test_first_order_node_follows_its_analytic_step_response():
    """τ dT/dt = T_room + rise·u − T from rest, u = 1: T(t) = 20 + rise (1 − e^(−t/τ))
    (the exact zero-order-hold solution must match at every sample, not only at the end)."""
    tau, rise = 1800.0, 10.0
    twin = ThermalTwin(nodes=(ThermalNode("s", tau, heat="spindle", rise=rise),))
    t = np.arange(0, 7200.0 + 1, 37.0)
    h = twin.run(t, spindle=np.ones(t.size))
    np.testing.assert_allclose(h.nodes["s"], 20 + rise * (1 - np.exp(-t / tau)), atol=1e-9)


def test_structure_maps_temperatures_to_five_displacements_and_the_screw_grows_with_position():
    """d = S (T − 20 °C); e(P) = d_X + (c + α (P − P_fixed)) (T_screw − 20 °C): at 25 °C with
    α = 11.5 ppm/K, c = 0.3 µm/K, d_X = 0.5 µm/K: e(0.8 m) = 2.5 + 1.5 + 46 = 50 µm."""
    room = Room(mean=25.0)
    node = ThermalNode("screw", 60.0, sensitivity=(0.5e-6, 0, 1e-6, 2e-6, 0))
    twin = ThermalTwin(room=room, nodes=(node,),
                       axes=(ThermalAxis("X", (0, 1.0), "screw", 11.5e-6, 0.0, 0.3e-6),))
    h = twin.run(np.arange(0, 601, 60.0))
    np.testing.assert_allclose(h.displacement[-1] * 1e6, [2.5, 0, 5, 10, 0], atol=1e-9)
    e = twin.positioning_error(h, "X", np.array([0.0, 0.8]))[-1] * 1e6
    np.testing.assert_allclose(e, [2.5 + 1.5, 2.5 + 1.5 + 46.0], atol=1e-9)


def test_room_cycle_peaks_at_its_hour():
    room = Room(mean=20.0, amplitude=1.0, period=86400.0, peak_time=15 * 3600.0)
    assert room.temperature(15 * 3600.0) == pytest.approx(21.0)
    assert room.temperature(3 * 3600.0) == pytest.approx(19.0)


def test_sensor_lag_delays_the_reading():
    """A sensor with a lag reads its node through a first-order filter: after one lag time
    constant on a step it shows 1 − 1/e of the step (less than the node)."""
    cfg = """
[[node]]
name = "n"
time_constant_min = 0.001
heat = "spindle"
rise_K = 10
[[sensor]]
name = "T_n"
node = "n"
lag_min = 10
"""
    twin = parse_thermal_config(cfg)
    t = np.arange(0, 1201, 1.0)
    h = twin.run(t, spindle=np.ones(t.size))
    v = twin.read_temperatures(h, None)["T_n"]
    assert v[600] - 20 == pytest.approx(10 * (1 - math.exp(-1)), abs=0.05)


def test_shipped_configuration_reads_and_a_day_runs_fast():
    twin = parse_thermal_config(open(CONFIG).read(), CONFIG)
    assert [n.name for n in twin.nodes] == ["structure", "spindle", "spindle_head", "screw_x"]
    t = np.arange(0, 86400.0 + 1, 10.0)
    h = twin.run(t, spindle=np.full(t.size, 0.5))
    assert h.displacement.shape == (t.size, 5)


@pytest.mark.parametrize("text, words", [
    ("[[node]]\nname='a'\ntime_constant_min=1\nfollows='b'\n", "follows 'b'"),
    ("[[node]]\nname='a'\ntime_constant_min=0\n", "time_constant_min = 0 min must be more than"),
    ("[[node]]\nname='a'\ntime_constant_min=1\nheat='lamp'\n", "heat 'lamp'"),
    ("[[node]]\nname='a'\ntime_constant_min=1\ncolour=3\n", "unknown key [node] colour"),
    ("[[node]]\nname='a'\ntime_constant_min=1\n[[axis]]\nname='X'\ntravel_mm=[5,1]\n"
     "screw_node='a'\n", "travel_mm"),
])
def test_bad_configuration_is_one_clear_error(text, words):
    with pytest.raises(ConfigError) as e:
        parse_thermal_config(text, "t.toml")
    assert words in str(e.value)


def test_loads_outside_zero_to_one_are_refused():
    twin = ThermalTwin(nodes=(ThermalNode("s", 60.0, heat="spindle", rise=1.0),))
    with pytest.raises(InputError, match="between 0 and 1"):
        twin.run(np.arange(3.0), spindle=[0, 2, 0])
