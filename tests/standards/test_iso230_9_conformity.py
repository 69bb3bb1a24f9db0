"""Uncertainty a laboratory can defend (issue 38), in the one budget function
:func:`axiscal.standards.iso230_9.positioning_budget`: the laboratory's CMC as a floor, the
sampling uncertainty of the runs in U of R and B (JCGM 100:2008 Annex E.4.3) with the narrow
Annex A U stated beside it, the reference's resolution from the data, the verdict decided with
the U printed, and one ``[uncertainty]`` table for linear and rotary tests."""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.ecmc import read_ecmc
from axiscal.standards.iso14253_1 import decide_all
from axiscal.standards.iso230_2 import evaluate
from axiscal.standards.iso230_9 import Contributor, combine, positioning_budget

ESS = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"


@pytest.fixture(scope="module")
def ess():
    ds = read_ecmc(ESS)
    return ds, evaluate(ds)


def test_ess_r_from_one_reading_is_not_conformance_proven(ess):
    """tests/data/ecmc/mcu1025_fat_sat_ISO230.dat (ESS MCU1025): R = R↑ = 204.76 µm at target
    15 mm, where one run reads +93.18 µm and the four others about −21 µm. Annex A's U(R) holds
    the reading and E_VE only (under 1 µm); s from 5 readings is known to 1/√8 = 35 %
    (JCGM 100:2008 Table E.1), so u(R) = 4·s/√8 = 72.4 µm and U(R) = 150 µm as printed: R ≤ 210
    µm is in the uncertainty zone, never 'conformance proven'."""
    ds, r = ess
    assert r.R == pytest.approx(204.76, abs=0.005)
    readings = ds.up[0]
    s = np.std(readings, ddof=1)                       # independent of the evaluation
    assert 4 * s == pytest.approx(r.R, rel=1e-12)
    b = positioning_budget(ds, r, {"e_ve": 1.0})
    u_sampling = dict(b.rows("R"))["u_SAMPLING (R)"]
    assert u_sampling == pytest.approx(4 * s / math.sqrt(8), rel=1e-12)
    assert b.narrow["R"] < 1.0 and b.U_text("R") == "150" and b.stated("R") == 150.0
    (d,) = decide_all(r.parameters(), b, {"R": 210.0})
    assert d.outcome.value == "uncertainty zone"
    assert any("printed is the wider one" in n and "R: Annex A 0.59, printed 150" in n
               for n in b.notes)


def test_sampling_uncertainty_of_b_is_that_of_the_means(ess):
    """B = max |x̄↑ − x̄↓|: u(B_i) = √(s↑²/n↑ + s↓²/n↓) at the target giving B (JCGM 100:2008
    §4.2.3), recomputed here from the readings."""
    ds, r = ess
    i = int(np.argmax(np.abs(ds.up.mean(axis=1) - ds.down.mean(axis=1))))
    want = math.sqrt(np.var(ds.up[i], ddof=1) / 5 + np.var(ds.down[i], ddof=1) / 5)
    b = positioning_budget(ds, r, {"e_ve": 1.0})
    assert dict(b.rows("B"))["u_SAMPLING (B)"] == pytest.approx(want, rel=1e-12)
    assert b.U("B") > b.narrow["B"]
    assert "u_SAMPLING (R)" not in dict(b.rows("E"))          # E, A, M keep Annex A's U


def test_resolution_of_the_reference_from_the_data(ess):
    """The ESS file's encoder steps by 0.20365 µm (readings at one target differ by whole
    multiples of it); the budget takes that, not 1 nm, and says so; a declared value wins."""
    ds, r = ess
    b = positioning_budget(ds, r, {"e_ve": 1.0})
    res = {i.name: i for i in b.inputs}["resolution"]
    assert res.value == pytest.approx(0.20365, abs=5e-5) and not res.assumed
    assert "taken from the data" in res.rule
    assert dict(b.rows("E"))["u_RESOLUTION"] == pytest.approx(res.value / (2 * math.sqrt(3)))
    declared = positioning_budget(ds, r, {"e_ve": 1.0, "resolution": 0.01})
    assert {i.name: i for i in declared.inputs}["resolution"].value == 0.01


def test_a_laser_like_record_keeps_the_default_resolution():
    """Continuous readings (a simulated laser) show no step: the default 1 nm stays, assumed."""
    from axiscal.procedures.positioning import simulate_from_config

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    b = positioning_budget(sim.dataset, sim.result, {"e_ve": 1.0})
    res = {i.name: i for i in b.inputs}["resolution"]
    assert res.value == 0.001 and res.assumed


def test_u_is_never_below_the_cmc_and_says_so(ess):
    """Issue 38: R = 5.81 µm was certified with U = 0.00058 µm. With the laboratory's CMC
    (E 2.0 µm, R 1.0 µm for linear axes) U is never below it, R↑/R↓ take R's and the notes say
    which parameters were raised; without a CMC the budget says none was declared."""
    from axiscal.datasets import PositioningDataset

    rng = np.random.default_rng(3)
    ds = PositioningDataset.from_arrays("linear", np.linspace(0, 500, 6),
                                        1e-4 * rng.normal(size=(6, 5)),
                                        1e-4 * rng.normal(size=(6, 5)), "mm", "um")
    r = evaluate(ds)
    bare = positioning_budget(ds, r, {"e_ve": 0.0001})
    assert bare.U("R") < 0.01 and any("no CMC declared for a linear axis" in n
                                      for n in bare.notes)
    b = positioning_budget(ds, r, {"e_ve": 0.0001, "linear": {"cmc": {"E": 2.0, "R": 1.0}},
                                   "rotary": {"cmc": {"E": 9.0}}})
    assert b.U("R") == b.U("R_up") == b.U("R_down") == 1.0 and b.U("E") >= 2.0
    assert {"R", "R_up", "R_down"} <= set(b.floored) and "A" not in b.cmc
    assert any("never stated (ILAC-P14:09/2020 §5.4)" in n for n in b.notes)
    assert b.to_json()["cmc"]["R"] == 1.0
    with pytest.raises(AxiscalError, match="cmc 'Q': not an ISO 230-2 parameter"):
        positioning_budget(ds, r, {"linear": {"cmc": {"Q": 1.0}}})
    with pytest.raises(AxiscalError, match="give the CMC per kind of axis"):
        positioning_budget(ds, r, {"cmc": {"E": 1.0}})


def test_verdict_uses_the_u_printed():
    """Issue 38: E = 74.77 µm, U = 0.655 µm printed as 0.66 (two digits, rounded up), tolerance
    75.428 µm: 74.77 + 0.655 ≤ 75.428 would pass, 74.77 + 0.66 does not; the decision uses
    the printed U, so the certificate's own numbers give its verdict."""
    b = combine([Contributor("u", "x", 0.3275, "normal", "", "", ("E",))], "um")
    assert b.U("E") == pytest.approx(0.655) and b.U_text("E") == "0.66"
    (d,) = decide_all({"E": 74.77}, b, {"E": 75.428})
    assert d.U == 0.66 and d.outcome.value == "uncertainty zone"
    assert b.value_text("E", 74.7682) == "74.77"


def test_one_configuration_serves_a_rotary_test():
    """Issue 38: a rotary run failed with "unknown key [uncertainty] laser_accuracy_ppm". The
    linear-only keys are ignored for a rotary axis and named; [uncertainty.rotary] values win
    over common ones; a key of neither budget is still refused."""
    from axiscal.procedures.positioning import simulate_from_config

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_rotary.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    table = {"laser_accuracy_ppm": 0.4, "beam_offset": 0.1, "e_ve": 0.5,
             "rotary": {"e_ve": 0.3, "cmc": {"E": 1.5}}}
    b = positioning_budget(sim.dataset, sim.result, table)
    assert {i.name: i.value for i in b.inputs}["e_ve"] == 0.3
    assert any("laser_accuracy_ppm, beam_offset: not an input of a rotary axis's budget"
               in n for n in b.notes)
    assert b.U("E") >= 1.5
    with pytest.raises(AxiscalError, match="laser_acuracy_ppm"):
        positioning_budget(sim.dataset, sim.result, {"laser_acuracy_ppm": 0.4})
