"""The uncertainty of a volumetric map's figures (standards/iso230_9_volumetric.py): hand-worked
cases of the law of propagation (JCGM 100:2008 §5.1.2 eq. 10, §5.2.2 eq. 13) through the
rigid-body model of ISO/TR 16907:2015, U linear in the inputs' U, a Monte Carlo draw of the
errors each correlation model describes (JCGM 101:2008 §7, as an independent check of the
sensitivity bookkeeping), a configuration's own U of an error used over its class's, and bad
inputs refused in one line."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import ConfigError
from axiscal.standards.iso230_9_volumetric import VOLUMETRIC_INPUTS, volumetric_budget
from axiscal.standards.volumetric import (AXES, ERROR_NAMES, PAIRS, ErrorFunction,
                                          GeometricErrors, KinematicChain, body_diagonals,
                                          map_volume, volumetric_error)

TRAVEL = {"X": (0.0, 0.1), "Y": (0.0, 0.1), "Z": (-0.1, 0.0)}
MIDDLE = [0.05, 0.05, -0.05]
#: U of the positioning errors only (a squareness's U acts even where none is given).
ONLY_U = {"positioning_a": 1.0, "positioning_b": 0.0, "squareness": 0.0}


def _only(functions=None, squareness=None):
    e = GeometricErrors(KinematicChain.parse("X Y | Z"), functions or {}, squareness or {},
                        MIDDLE, [0, 0, 0], TRAVEL)
    return e, map_volume(e, 11), body_diagonals(e)


@pytest.mark.parametrize("correlation, u_pair", [("scale", 0.5 + 0.5),
                                                 ("independent", math.sqrt(0.5**2 + 0.5**2))])
def test_only_exx_by_hand(correlation, u_pair):
    """EXX alone (10 µm over 100 mm), U = 1 µm (a = 1, b = 0, k = 2): u = 0.5 µm at each end of
    X, zero at the reference point (the model's values are relative to it). The range of E_X is
    E_X(100) − E_X(0): scale (r = −1 for the ramp's two sides, eq. 13) u = 0.5 + 0.5; independent
    (r = 0) u = √(0.5² + 0.5²). A body diagonal's range is e_x times it, e_x = 1/√3 (a 100 mm
    cube, ISO 230-6:2002): its ends are its extremes. E_Y and E_Z do not move: no U (a U of 0
    is never stated)."""
    e, m, d = _only({"EXX": ErrorFunction([0.0, 0.1], [0.0, 10e-6])})
    b = volumetric_budget(e, m, d, {**ONLY_U, "correlation": correlation})
    assert b.U("range_X") == pytest.approx(2 * u_pair, rel=1e-9)
    assert b.U("range_Y") is None and b.U("range_Z") is None     # never U = 0
    assert "no U for the range along Y, the range along Z: none of the measured errors acts " \
        "on it" in b.notes
    assert b.U("largest") == pytest.approx(2 * 0.5, rel=1e-9)
    for name in ("PPP", "NPP", "PNP", "PPN"):
        assert b.U(f"diagonal_{name}") == pytest.approx(2 * u_pair / math.sqrt(3), rel=1e-9)
    assert correlation in b.method and any(correlation in n for n in b.notes)
    pos = [c for c in b.contributors if c.name == "u_POS,range_X"]
    assert len(pos) == 1 and "EXX" in pos[0].basis


def test_a_squareness_alone_by_hand():
    """xy = 10 µm/m alone, U = 2 µm/m: E_X = −θ·(y − c_y) (Chapman, "Calibration of machine
    squareness", Appendix I, eq. 2), so the range of E_X over Y 0-100 mm has sensitivity 0.1 m:
    u = 1 µm/m × 0.1 m = 0.1 µm, U = 0.2 µm, in either correlation model (one number)."""
    e, m, d = _only(squareness={"xy": 10e-6})
    for corr in ("scale", "independent"):
        b = volumetric_budget(e, m, d, {"squareness": 2.0, "correlation": corr})
        assert b.U("range_X") == pytest.approx(0.2, rel=1e-9)
        assert b.U("range_Y") is None


def test_the_positioning_length_part_grows_with_distance_from_the_reference():
    """U = a + b·L with L the distance from the reference point: EXX alone, a = 0, b = 10 µm/m;
    both ends 50 mm from it: U = 0.5 µm at each, u = 0.25 µm; scale: u_c = 0.5 µm, U = 1 µm."""
    e, m, d = _only({"EXX": ErrorFunction([0.0, 0.1], [0.0, 10e-6])})
    b = volumetric_budget(e, m, d, {**ONLY_U, "positioning_a": 0.0, "positioning_b": 10.0})
    assert b.U("range_X") == pytest.approx(1.0, rel=1e-9)


def _machine(seed=1):
    """Every one of the 21 errors, random, tabulated at the 11 grid positions of its axis (so a
    draw at those positions is the function the independent model describes), a tool offset
    other than the measured one (the Abbe terms of ISO/TR 16907 act)."""
    rng = np.random.default_rng(seed)
    funcs = {}
    for n in ERROR_NAMES:
        s = np.linspace(*TRAVEL[n[2]], 11)
        funcs[n] = ErrorFunction(s, rng.normal(0, 5e-6, 11))
    ref = [np.linspace(*TRAVEL[a], 11)[5] for a in AXES]
    e = GeometricErrors(KinematicChain.parse("X Y | Z"), funcs,
                        dict(zip(PAIRS, rng.normal(0, 20e-6, 3))), ref, [0, 0, 0], TRAVEL)
    tool = np.array([0.01, 0.0, -0.1])
    return e, map_volume(e, 11, tool_offset=tool), body_diagonals(e, tool_offset=tool), tool


@settings(max_examples=15, deadline=None)
@given(scale=st.floats(0.01, 100.0), corr=st.sampled_from(["scale", "independent"]))
def test_u_is_linear_in_the_inputs(scale, corr):
    """The model is linear and every contribution is a sensitivity times an input's u: every U
    scales with the inputs' U (k fixed)."""
    e, m, d, _ = MACHINE
    base = {k: v[2] for k, v in VOLUMETRIC_INPUTS.items() if k != "k"}
    a = volumetric_budget(e, m, d, {**base, "correlation": corr})
    b = volumetric_budget(e, m, d, {**{k: v * scale for k, v in base.items()},
                                    "correlation": corr})
    assert a.expanded.keys() == b.expanded.keys() and len(a.expanded) == 8
    for p, U in a.expanded.items():
        assert b.U(p) == pytest.approx(U * scale, rel=1e-9), p


MACHINE = _machine()


def _u_of(name, table, distance):
    """u (m or rad) as the module states it: U/2, positioning a + b·L."""
    if name in PAIRS:
        return table["squareness"] * 1e-6 / 2
    if name[1] in "ABC":
        return table["angular"] * 1e-6 / 2
    if name[1] == name[2]:
        return (table["positioning_a"] + table["positioning_b"] * distance) * 1e-6 / 2
    return table["straightness"] * 1e-6 / 2


@pytest.mark.parametrize("correlation", ["scale", "independent"])
def test_a_monte_carlo_draw_of_the_model_agrees(correlation):
    """JCGM 101:2008 §7 as a check of the propagation: draw each error function's error as the
    model describes it (scale: one normal number times a ramp through the reference point, u
    at the farther end; independent: a normal number at each grid position, zero at the
    reference point), map the draw with the model at each figure's own locus (found here, not
    by the module), and compare the spread with u_c: 20000 draws, the standard deviation within
    3 % (its own standard error 0.5 %). The map of a draw is the sum of the model's maps of
    each tabulated value alone (a hat at one grid position, :func:`volumetric_error` of it):
    the model is linear, so this is the model, not a second one."""
    e, m, d, tool = MACHINE
    table = {"positioning_a": 0.4, "positioning_b": 3.0, "straightness": 0.8, "angular": 1.5,
             "squareness": 2.5}
    b = volumetric_budget(e, m, d, {**table, "correlation": correlation})
    grid, c = m.grid, e.reference
    pts, figs = [], {}
    for i, a in enumerate(AXES):
        for f in (np.argmax, np.argmin):
            idx = np.unravel_index(f(m.error[i]), m.error[i].shape)
            pts.append([g[j] for g, j in zip(grid, idx)])
    top = np.unravel_index(np.argmax(m.magnitude), m.magnitude.shape)
    pts.append([g[j] for g, j in zip(grid, top)])
    P = np.array(pts).T
    for i, a in enumerate(AXES):
        w = np.zeros(P.shape)
        w[i, 2 * i:2 * i + 2] = (1.0, -1.0)
        figs[f"range_{a}"] = w
    figs["largest"] = np.zeros(P.shape)
    figs["largest"][:, -1] = m.error[(slice(None),) + top] / m.largest
    rng = np.random.default_rng(7)
    n_draws = 20000
    total = {name: np.zeros(n_draws) for name in figs}
    for n in ERROR_NAMES + PAIRS:
        if n in PAIRS:
            alone = GeometricErrors(e.chain, {}, {n: 1e-6}, c, e.measured_tool_offset, e.travel)
            resp = volumetric_error(alone, *P, tool) / 1e-6            # (3, points) per rad
            draw = rng.normal(size=(n_draws, 1)) * _u_of(n, table, 0)
            for name, w in figs.items():
                total[name] += draw[:, 0] * np.sum(w * resp) * 1e6
            continue
        i = AXES.index(n[2])
        s = np.linspace(*TRAVEL[n[2]], 11)
        far = max(TRAVEL[n[2]][1] - c[i], c[i] - TRAVEL[n[2]][0])
        resp = np.zeros((11, 3, P.shape[1]))
        for k in range(11):                        # the model's map of one value alone
            if np.isclose(s[k], c[i], atol=1e-12):
                continue                           # zero at the reference point
            hat = np.zeros(11)
            hat[k] = 1e-6
            alone = GeometricErrors(e.chain, {n: ErrorFunction(s, hat)}, {}, c,
                                    e.measured_tool_offset, e.travel)
            resp[k] = volumetric_error(alone, *P, tool) / 1e-6
        if correlation == "scale":
            v = rng.normal(size=(n_draws, 1)) * _u_of(n, table, far) * (s - c[i]) / far
        else:
            v = rng.normal(size=(n_draws, 11)) * np.array(
                [_u_of(n, table, abs(x - c[i])) for x in s])
        for name, w in figs.items():
            total[name] += v @ np.einsum("kip,ip->k", resp, w) * 1e6
    for name, values in total.items():
        assert np.std(values) == pytest.approx(b.combined[name], rel=0.03), name


def test_an_error_s_own_u_is_used_over_its_class():
    """A configuration's ``U`` of EXX (here 4 µm, k = 2) replaces the class's a + b·L for EXX:
    the only-EXX range of E_X is then 2·(2 + 2) µm in the scale model; listed as given."""
    e, m, d = _only({"EXX": ErrorFunction([0.0, 0.1], [0.0, 10e-6])})
    b = volumetric_budget(e, m, d, ONLY_U, given={"EXX": 4e-6})
    assert b.U("range_X") == pytest.approx(8.0, rel=1e-9)
    mine = [i for i in b.inputs if i.name == "EXX"]
    assert mine and not mine[0].assumed and mine[0].value == pytest.approx(4.0)


def test_missing_errors_and_assumed_inputs_are_said():
    e, m, d = _only({"EXX": ErrorFunction([0.0, 0.1], [0.0, 10e-6])})
    b = volumetric_budget(e, m, d)
    assert any(n.startswith("not measured, taken as zero") and "ECZ" in n for n in b.notes)
    assert {i.name for i in b.inputs if i.assumed} == set(VOLUMETRIC_INPUTS)
    said = next(n for n in b.notes if n.startswith("assumed"))
    assert "volumetric uncertainty table" in said and "angular error 2 µrad" in said
    assert not [n for n in b.notes if "_" in n], "printed notes carry no configuration key"
    assert all(i.set_with.startswith("[volumetric_uncertainty] ") for i in b.inputs)
    assert any("correlation model: scale" in n for n in b.notes)


@pytest.mark.parametrize("table, words", [({"angualr": 1}, "no such input"),
                                          ({"angular": -1}, "a finite number ≥ 0"),
                                          ({"k": 0}, "a finite number ≥ 0"),
                                          ({"correlation": "full"}, "scale or independent")])
def test_bad_inputs_are_refused_in_one_line(table, words):
    e, m, d = _only()
    with pytest.raises(ConfigError, match=words) as exc:
        volumetric_budget(e, m, d, table)
    assert "\n" not in str(exc.value)
