"""Squareness (per method) and five-DOF uncertainty budgets in ISO/TR 230-9 form."""

import math

import pytest

from axiscal.errors import InputError
from axiscal.standards.iso230_9_geometry import (
    SQUARENESS_METHODS,
    five_dof_budget,
    squareness_budget,
)
from axiscal.standards.iso230_6 import diagonal_squareness

ARCSEC_UM_M = math.pi / 648000 * 1e6


def test_optics_method_by_hand():
    """Straightness optics ±0.5 µm/m (k = 2) on each slope, optical square ±0.5 arcsec (k = 2):
    u = √(2·0.25² + (0.25 × 4.848)²) = 1.2628 µm/m; U = 2.526 µm/m."""
    b = squareness_budget("optics")
    expected = 2 * math.sqrt(2 * 0.25**2 + (0.25 * ARCSEC_UM_M) ** 2)
    assert b.U("squareness") == pytest.approx(expected, rel=1e-12)
    assert b.unit == "um/m"


def test_diagonal_sensitivity_matches_iso230_6():
    """The sensitivity of the diagonal budget is that of ISO 230-6 squareness = D0(D1 − D2)/(2XY):
    a 1 µm change of D1 changes the evaluated squareness by exactly u_D1 / u(D1)."""
    x, y = 0.6, 0.8
    sq0 = diagonal_squareness(x, y, 3e-6, -2e-6).squareness.um_per_m
    sq1 = diagonal_squareness(x, y, 4e-6, -2e-6).squareness.um_per_m
    b = squareness_budget("diagonal", length_x=x, length_y=y, laser_ppm=2.0, e_ve=0.0)
    u_d1 = {c.name: c.u for c in b.contributors}["u_D1"]
    u_length = 2.0 * math.hypot(x, y) / 2  # µm of diagonal per the laser, k = 2 removed
    assert abs(sq1 - sq0) == pytest.approx(u_d1 / u_length, rel=1e-9)


@pytest.mark.parametrize(
    "method, field, name, factor",
    [
        ("optics", dict(optics_accuracy=1.0), ("u_OPTICS,X", "u_OPTICS,Y"), 2.0),
        ("optics", dict(square_error=1.0), "u_SQUARE", 2.0),
        ("square", dict(square_error=1.0), "u_SQUARE", 2.0),
        ("square", dict(square_length=1.0), "u_SQUARE", 0.5),
        ("square", dict(probe_accuracy=1.0), "u_PROBE", 2.0),
        ("reversal", dict(reposition=1.0), "u_REPOSITION", 2.0),
        ("ballbar", dict(transducer_accuracy=1.0), "u_TRANSDUCER", 2.0),
        ("ballbar", dict(ballbar_radius=0.3), ("u_TRANSDUCER", "u_CALIBRATION"), 0.5),
        ("ballbar", dict(e_ve=2.0), "u_CALIBRATION", 2.0),
        ("diagonal", dict(laser_ppm=1.0, e_ve=0.0), ("u_D1", "u_D2"), 2.0),
        ("diagonal", dict(diagonal_length_u=20.0, diagonal_d1=5.0), "u_D0", 2.0),
    ],
)
def test_each_contributor_sensitivity(method, field, name, factor):
    """One input changes its own contributor(s) by the factor of the model, and no other."""
    base = dict(e_ve=1.0, slope_fit_x=0.1, slope_fit_y=0.2, diagonal_d1=5.0)
    names = (name,) if isinstance(name, str) else name
    if "e_ve" in field and "e_ve" not in names and method == "diagonal":
        base["e_ve"] = 0.0
    u0 = {c.name: c.u for c in squareness_budget(method, **base).contributors}
    u1 = {c.name: c.u for c in squareness_budget(method, **{**base, **field}).contributors}
    for n in u0:
        assert u1[n] == pytest.approx(u0[n] * (factor if n in names else 1.0), rel=1e-12), n


def test_reversal_does_not_carry_the_square_error():
    """Reversing the square cancels its own error (Chapman, Calibration of machine squareness)."""
    a = squareness_budget("reversal", square_error=0.5).U("squareness")
    b = squareness_budget("reversal", square_error=50.0).U("squareness")
    assert a == b < squareness_budget("square", square_error=50.0).U("squareness")
    assert set(SQUARENESS_METHODS) == {"optics", "square", "reversal", "ballbar", "diagonal"}


def test_five_dof_budget_by_hand_and_crosstalk():
    """εz: resolution 0.26 arcsec (Optics Express 2018 §3), 1 % of a 10 arcsec range, crosstalk
    ±0.3 arcsec, drift σ 0.05 arcsec: U = 2·√(0.0751² + 0.1² + 0.1732² + 0.05²)."""
    b = five_dof_budget(
        {"ez": 0.26, "dy": 0.04}, {"ez": 10.0, "dy": 2.0}, crosstalk={"ez": 0.6}, drift={"ez": 0.05}
    )
    expected = 2 * math.sqrt(
        (0.26 / (2 * math.sqrt(3))) ** 2 + 0.1**2 + (0.3 / math.sqrt(3)) ** 2 + 0.05**2
    )
    assert b["ez"].U("ez") == pytest.approx(expected, rel=1e-12)
    assert b["dy"].unit == "um" and b["ez"].unit == "arcsec"
    assert b["dy"].U("dy") == pytest.approx(
        2 * math.hypot(0.04 / (2 * math.sqrt(3)), 0.02), rel=1e-12
    )


def test_bad_inputs():
    with pytest.raises(InputError, match="squareness method"):
        squareness_budget("laser")
    with pytest.raises(InputError):
        squareness_budget("square", square_length=0)
    with pytest.raises(InputError, match="channel"):
        five_dof_budget({"ez3": 1}, {})


def test_diagonal_budget_is_the_method_budget_with_its_inputs_shown():
    """ISO 230-6:2002 §4 (squareness = D0 (D1 − D2)/(2XY)): a 600 × 800 mm test, D0 = 1 m.
    diagonal_budget gives the ``diagonal`` budget of the measured travels and errors; the
    configuration's inputs sit under the measured ones; every input is listed, the defaults
    marked assumed with their rule, and said in words in the notes."""
    from axiscal.errors import ConfigError
    from axiscal.standards.iso230_6 import diagonal_squareness
    from axiscal.standards.iso230_9_geometry import diagonal_budget

    r = diagonal_squareness(0.6, 0.8, 20e-6, 5e-6)
    b = diagonal_budget(r, {"laser_ppm": 1.0, "length_x": 9.0})       # a travel is measured
    by_hand = squareness_budget("diagonal", length_x=0.6, length_y=0.8, laser_ppm=1.0,
                                diagonal_d1=20.0, diagonal_d2=5.0)
    assert b.U("squareness") == pytest.approx(by_hand.U("squareness"), rel=1e-12)
    # u_D = 1 ppm/2 × 1 m = 0.5 µm, × D0/(2XY) = 1/0.96 per m; u_D0 = 15 µm/0.96 m² × 10 µm
    assert b.rows("squareness")[0][1] == pytest.approx(0.5 / 0.96, rel=1e-12)
    assert b.rows("squareness")[2][1] == pytest.approx(15 / 0.96 * 1e-6 * 10, rel=1e-12)
    inputs = {i.name: i for i in b.inputs}
    assert inputs["length_x"].value == 0.6 and not inputs["length_x"].assumed
    assert inputs["laser_ppm"].rule == "" and not inputs["laser_ppm"].assumed   # given
    assert inputs["e_ve"].assumed and inputs["diagonal_length_u"].assumed
    assert [n.split(" (")[0] for n in b.notes] == [
        "assumed: environmental variation error E_VE 0 µm",
        "assumed: standard uncertainty of the diagonal length D0 10 µm"]
    with pytest.raises(ConfigError, match="probe: no such input"):
        diagonal_budget(r, {"probe": 1.0})
    with pytest.raises(ConfigError, match="laser_ppm = 'a lot': write a number, then its unit"):
        diagonal_budget(r, {"laser_ppm": "a lot"})
