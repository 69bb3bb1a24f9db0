"""The location errors as LinuxCNC trt kinematics pins (axiscal.compensation.five_axis): the
pins put into LinuxCNC's own forward transform (trtfuncs.c) see the twin's true axis lines, and
re-measuring the twin after the correction shows what pins can and cannot hold."""

from __future__ import annotations

import tomllib
from importlib import resources

import numpy as np
import pytest

from axiscal.api import fiveaxis
from axiscal.compensation.five_axis import trt_correction
from axiscal.errors import InputError


def _config(name, **errors):
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath(name).read_text("utf-8"))
    if errors:
        cfg["location_errors"] = errors
    return cfg


def _lcnc_world(tilt, pins, joint, t, c):
    """LinuxCNC 2.9 src/emc/kinematics/trtfuncs.c, xyzacKinematicsForward /
    xyzbcKinematicsForward (commit 135b0ce5) in matrix form, pins in metres."""
    def rx(a):
        return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])

    def ry(a):
        return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])

    def rz(a):
        return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])

    p = {k: v[1] * 1e-3 for k, v in pins.items()}
    p_c = np.array([p["x-rot-point"], p["y-rot-point"], 0.0])
    if tilt == "A":
        p_t, rot = np.array([0.0, p["y-rot-point"] + p["y-offset"], p["z-offset"]]), rx
    else:
        p_t, rot = np.array([p["x-rot-point"] + p["x-offset"], 0.0, p["z-offset"]]), ry
    return rz(-c) @ (rot(-t) @ (joint - p_t) + p_t - p_c) + p_c


@pytest.mark.parametrize("name, errors", [
    ("fiveaxis_ac.toml", {"E_Y0A": 12.0, "E_Z0A": -18.0, "E_X0C": 20.0, "E_Y0C": -15.0}),
    ("fiveaxis_bc.toml", {"E_X0B": 12.0, "E_Z0B": -18.0, "E_X0C": 20.0, "E_Y0C": -15.0}),
])
def test_the_pins_in_linuxcnc_forward_see_the_true_axis_lines(name, errors):
    """Position errors only, measured without noise: with the new pins LinuxCNC's forward
    transform maps the joints of a table point to that point (within 0.05 µm) at any pose."""
    cfg = _config(name, **errors)
    for s in cfg["setup"]:
        s["noise_um"] = 0.0
    sim = fiveaxis.simulate(cfg, seed=0)
    corr = trt_correction(sim.machine.geometry, sim.result)
    m = sim.machine
    rng = np.random.default_rng(1)
    for _ in range(6):
        t = np.radians(rng.uniform(-90, 0) if m.tilt == "A" else rng.uniform(0, 90))
        c = rng.uniform(-np.pi, np.pi)
        point = rng.uniform(-0.15, 0.15, 3)
        joint = m.to_machine(np.array([t]), np.array([c]), point)[0]   # where the table puts it
        world = _lcnc_world(m.tilt, corr.pins, joint, t, c)
        np.testing.assert_allclose(world, point, atol=0.05e-6)
    assert set(corr.pins) == ({"x-rot-point", "y-rot-point", "y-offset", "z-offset"}
                              if m.tilt == "A" else
                              {"x-rot-point", "y-rot-point", "x-offset", "z-offset"})


def test_verification_on_the_twin_without_tilts_falls_more_than_90_percent(tmp_path):
    cfg = _config("fiveaxis_ac.toml", E_Y0A=12.0, E_Z0A=-18.0, E_A0A=40.0, E_X0C=20.0,
                  E_Y0C=-15.0, E_C0C=50.0)
    comp = fiveaxis.compensate(cfg, _files(cfg, tmp_path), verify=True)
    v = comp.verification
    assert min(v.reduction) > 0.9 and max(v.after) < 3e-6
    assert comp.correction.home_offset["A"] == pytest.approx(40e-6 * 180 / np.pi, rel=0.05)
    assert "setp xyzac-trt-kins.x-rot-point 0.02" in comp.correction.hal()


def test_orientation_errors_no_pin_holds_go_to_the_external_offsets(tmp_path):
    """The example's 25-30 µrad tilts: named as held by no pin, corrected by the external
    offsets (on the twin, to first order); every range falls > 90 % and what is left without
    noise is under 0.5 µm (before the external offsets: 79-88 %, 8 µm left)."""
    cfg = _config("fiveaxis_ac.toml")
    comp = fiveaxis.compensate(cfg, _files(cfg, tmp_path), verify=True)
    assert set(comp.correction.not_held) == {"E_B0A", "E_C0A", "E_B0C"}
    assert comp.correction.not_held["E_B0A"] == pytest.approx(25.0, abs=2.0)
    assert comp.correction.external_offsets["tilt"] == "A"
    assert "external offsets" in comp.correction.hal()
    v = comp.verification
    assert min(v.reduction) > 0.9 and max(v.after_unmodelled) < 0.5e-6, v


@pytest.mark.parametrize("name", ["fiveaxis_ac.toml", "fiveaxis_bc.toml"])
def test_the_hal_component_sends_the_joints_where_the_identified_lines_put_the_point(
        tmp_path, name):
    """axiscal_trtcomp.py (pure Python, run by LinuxCNC) against axiscal's kinematics: the
    pins' kinematics at the commanded point plus the component's offset equal the identified
    lines at the commanded point (T_nom(p + o) = T_act(p)), within 1e-12 m."""
    import importlib.util
    from importlib import resources as res

    from axiscal.compensation.five_axis import corrected_geometry
    from axiscal.physics.rotary_location import table_to_machine

    path = res.files("axiscal.data").joinpath("linuxcnc", "axiscal_trtcomp.py")
    spec = importlib.util.spec_from_file_location("axiscal_trtcomp", str(path))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    cfg = _config(name)
    corr = fiveaxis.compensate(cfg, _files(cfg, tmp_path)).correction
    g = corrected_geometry(fiveaxis.load(cfg)[0].geometry, corr)
    tilted = {n: v * 1e-6 for n, v in corr.not_held.items()}
    comp = mod.TrtMap(corr.external_offsets)
    sign = -1 if g.tilt == "A" else 1
    for p, t, c in (([100.0, -40.0, 80.0], 60.0, 130.0), ([-20.0, 150.0, 5.0], 90.0, -250.0)):
        o = np.array(comp.correction([*p, sign * t, c]))
        a = np.radians([sign * t, c])
        want = table_to_machine(g, tilted, a[0], a[1], np.array(p) * 1e-3)
        got = table_to_machine(g, {}, a[0], a[1], (np.array(p) + o) * 1e-3)
        assert np.abs(o).max() > 1e-3                     # mm: the tilts move the point µm
        np.testing.assert_allclose(got, want, atol=1e-12)


def test_no_pin_for_an_unidentified_position(tmp_path):
    cfg = _config("fiveaxis_ac.toml")
    cfg["setup"] = [{"kind": "probing", "place_mm": [150, 20, 60], "A_deg": [0],
                     "C_deg": [0, 90, 180, 270]}]
    with pytest.raises(InputError, match="E_Y0A, E_Z0A not identified"):
        fiveaxis.compensate(cfg, _files(cfg, tmp_path))


def _files(cfg, folder):
    return list(fiveaxis.simulate(cfg, seed=2, out=folder).files)


@pytest.mark.parametrize("name", ["fiveaxis_ac.toml", "fiveaxis_bc.toml"])
def test_the_sinumerik_chain_is_the_identified_kinematics(tmp_path, name):
    """SINUMERIK Operate Commissioning Manual 10/2015, 7.7 'Swiveling' (kinematics with a rotary
    table): l2 to rotary axis 1, l3 from axis 1 to axis 2, l4 = -(l2 + l3), directions v1, v2.
    The chain p -> l2 + R1(v1, a - CARR24)(l3 + R2(v2, c)(l4 + p)) built from the written
    values equals axiscal's kinematics with the identified errors within 1e-9 mm."""
    from axiscal.compensation.five_axis_sinumerik import swivel_data
    from axiscal.physics.rotary_location import rotate_about_line, table_to_machine

    cfg = _config(name)
    sim = fiveaxis.simulate(cfg, seed=2, out=tmp_path)
    g = sim.machine.geometry
    carr = swivel_data(g, sim.result).values
    v = lambda first: np.array([carr[f"$TC_CARR{first + i}"] for i in range(3)])  # noqa: E731
    l2, v1, v2, l3, l4 = v(4), v(7), v(10), v(15), v(18)
    np.testing.assert_allclose(l2 + l3 + l4, 0.0, atol=1e-12)
    assert carr["$TC_CARR23"] == "P" and carr["$TC_CARR22"] == "C"
    got = {e.name: e.value for e in sim.result.errors}
    t = g.tilt
    errors = {n: got[n] for n in got if "+" not in n}
    errors[f"E_{t}0{t}"] = got[f"E_{t}0{t}+E_{t}0C"]
    p = np.array([[120.0, -35.0, 40.0]])
    for a, c in ((0.0, 0.0), (-70.0, 200.0), (35.0, -95.0)):
        a_rad, c_rad = np.radians(a), np.radians(c)
        inner = rotate_about_line(l4 + p, np.zeros(3), v2, np.array([c_rad]))
        chain = l2 + rotate_about_line(l3 + inner, np.zeros(3), v1,
                                       np.array([a_rad - np.radians(carr["$TC_CARR24"])]))
        want = table_to_machine(g, errors, a_rad, c_rad, p * 1e-3) * 1e3
        np.testing.assert_allclose(chain, want, atol=1e-9)
    assert "$TC_CARR24[1]=" in swivel_data(g, sim.result).program()
