"""The ballbar budget of G and H (standards/iso230_9_ballbar.py, axiscal's reading of ISO/TR
230-9:2005's general form, JCGM 100:2008 eq. 10): each contributor by hand, the calibrated
length acting on neither figure, the centring not on H, bad inputs refused in one line."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from axiscal.errors import ConfigError
from axiscal.standards.iso230_9_ballbar import ballbar_budget


def test_each_contributor_by_hand():
    """G = 20 µm, H = 4 µm, R = 150 mm, gain 0.1 %, resolution 0.1 µm, α = 1 µm/(m·K) over 1 K,
    centring 0.05 mm: u_GAIN(G) = 0.02/√3, u_RES = √2·0.1/√12, u_THERMAL = 0.15/√3,
    u_CENTRE = 0.05²/300 mm /√3 = 0.00833/√3 µm; U = 2·u_c."""
    r = SimpleNamespace(G_ccw=20e-6, G_cw=None, H=4e-6)
    b = ballbar_budget(r, 0.15, {"gain": 0.1, "resolution": 0.1, "alpha": 1.0,
                                 "delta_t": 1.0, "centring": 0.05})
    res, th = math.sqrt(2) * 0.1 / math.sqrt(12), 0.15 / math.sqrt(3)
    centre = 0.05**2 / 300 * 1e3 / math.sqrt(3)
    assert b.U("G_ccw") == pytest.approx(2 * math.sqrt((0.02 / math.sqrt(3))**2 + res**2
                                                       + th**2 + centre**2), rel=1e-12)
    assert b.U("H") == pytest.approx(2 * math.sqrt((0.004 / math.sqrt(3))**2 + res**2
                                                   + th**2), rel=1e-12)
    assert b.U("G_cw") is None and b.k == 2.0
    assert not [i for i in b.inputs if i.assumed and i.name not in ("calibration_u", "k")]


def test_the_calibrated_length_acts_on_neither_figure():
    r = SimpleNamespace(G_ccw=20e-6, G_cw=18e-6, H=4e-6)
    a, b = ballbar_budget(r, 0.1), ballbar_budget(r, 0.1, {"calibration_u": 5.0})
    assert {p: a.U(p) for p in ("G_ccw", "G_cw", "H")} == \
        {p: b.U(p) for p in ("G_ccw", "G_cw", "H")}
    assert any(c.name == "u_CAL" and c.applies_to == () for c in b.contributors)
    assert any("assumed" in n for n in a.notes)


@pytest.mark.parametrize("table, words", [
    ({"gian": 0.1}, "no such input"),
    ({"gain": -1}, "gain = -1 % is implausible"),
    ({"k": 0}, "k = 0 is implausible"),
    ({"alpha": 11.5e-6}, r"alpha = 1.15e-05 µm/\(m·K\) is implausible"),   # α in 1/K, no unit
    ({"alpha": float("nan")}, "must be a finite number"),
    ({"delta_t": "2 m"}, "delta_t = ")])
def test_bad_inputs_are_refused_in_one_line(table, words):
    with pytest.raises(ConfigError, match=words) as e:
        ballbar_budget(SimpleNamespace(G_ccw=1e-6, G_cw=1e-6, H=1e-6), 0.1, table)
    assert "\n" not in str(e.value)


def test_alpha_is_typed_in_the_unit_every_report_shows():
    """α is typed as 11.5 (µm/(m·K)), as the budget prints it and as ``[uncertainty]
    expansion_coefficient`` is typed (ISO/TR 16015:2003's steel); the same α given as text in
    1/K gives the same U, and the budget's input reads 11.5 µm/(m·K)."""
    r = SimpleNamespace(G_ccw=20e-6, G_cw=18e-6, H=4e-6)
    a = ballbar_budget(r, 0.1, {"alpha": 11.5})
    b = ballbar_budget(r, 0.1, {"alpha": "1.15e-5 1/K"})
    c = ballbar_budget(r, 0.1)
    assert a.U("G_ccw") == pytest.approx(b.U("G_ccw"), rel=1e-12) == c.U("G_ccw")
    alpha = next(i for i in a.inputs if i.name == "alpha")
    assert (alpha.value, alpha.unit) == (11.5, "µm/(m·K)")
    assert any("11.5 µm/(m·K) × 100 mm" in x.basis for x in a.contributors)
