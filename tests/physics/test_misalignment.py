"""Seed 000 equation 1: its terms, the exact geometry behind it, the Figure 22 trade-off."""


import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.laser import SimulatedAngularInterferometer
from axiscal.physics import misalignment as mis
from axiscal.units import ARCSEC, DEG

TURN = np.radians(np.arange(0.0, 360.0, 2.5))


def _exact_error(alpha, beta, omega, eta, theta=TURN):
    """Angle the exact 3-D geometry reads (counter-rotation exact), relative to θ = 0."""
    laser = SimulatedAngularInterferometer(beam_tilt=beta)
    u, c = mis.reflector_pose(theta, -theta, alpha, eta, omega)
    dl = laser.path_difference(u, c)
    read = np.arcsin(dl / laser.spacing)
    return read - read[0]


@pytest.mark.parametrize("eta", [0.0, 0.7, -2.0])
def test_exact_geometry_reproduces_equation_1_figure_14_case(eta):
    """Seed 000 Figure 14: α = 0.62, β = 1.23, ω = 2.26 mrad substituted into equation 1. The
    reflector pose and beam geometry, with no formula of the seed in them, read the same error
    (relative to the datum) to well below 0.001 arcsec."""
    a, b, w = 0.62e-3, 1.23e-3, 2.26e-3
    exact = _exact_error(a, b, w, eta)
    eq1 = mis.misalignment_error(TURN, a, b, w, eta)
    eq1 = eq1 - eq1[0]
    assert np.max(np.abs(exact - eq1)) / ARCSEC < 1e-3
    assert np.max(np.abs(eq1)) / ARCSEC > 0.3          # the effect itself is not negligible
    # each term separately: amplitudes α²/4, αβ, αω
    terms = mis.misalignment_terms(TURN, a, b, w, eta)
    assert np.max(np.abs(terms.quadratic)) == pytest.approx(a * a / 4, rel=1e-3)
    assert np.max(np.abs(terms.alpha_beta)) == pytest.approx(a * b, rel=1e-3)
    assert np.max(np.abs(terms.alpha_omega)) == pytest.approx(a * w, rel=1e-3)
    assert np.allclose(terms.total, terms.quadratic + terms.alpha_beta + terms.alpha_omega)


def test_exact_geometry_large_alpha_keeps_the_quarter_amplitude():
    """Seed 000: wobble gives α²·sin 2θ/2, the counter-rotation's yaw takes α²·sin 2θ/4 back: the
    net amplitude is α²/4 (about 1 arcsec at α = 0.25°, Figure 11)."""
    a = 0.25 * DEG
    exact = _exact_error(a, 0.0, 0.0, 0.0)
    assert np.max(np.abs(exact)) / ARCSEC == pytest.approx(a * a / 4 / ARCSEC, rel=0.01)
    assert a * a / 4 / ARCSEC == pytest.approx(0.98, abs=0.01)


def test_peak_and_half_range_of_figure_14_case():
    """Peak of eq. 1 over a turn for the Figure 14 case, against a brute-force maximum."""
    a, b, w = 0.62e-3, 1.23e-3, 2.26e-3
    dense = np.linspace(0, 2 * np.pi, 200_001)
    brute = np.max(np.abs(mis.misalignment_error(dense, a, b, w)))
    assert mis.peak_error(a, b, w) == pytest.approx(brute, rel=1e-6)
    # η only shifts the phase (seed 000 note under eq. 1)
    assert np.max(np.abs(mis.misalignment_error(dense, a, b, w, 1.3))) == pytest.approx(brute, rel=1e-6)
    assert mis.peak_error(a, b, w) / ARCSEC == pytest.approx(0.346, abs=0.001)
    assert mis.half_range(a, b, w) <= mis.peak_error(a, b, w)


def test_recommended_alignment_keeps_eq1_well_below_one_arcsec():
    """Seed 000: TIR < 0.04 mm at 50 mm (0.025°) keeps total α within 0.05°; with β < 1 mrad and
    ω within 2.5 mrad the misalignment error uses about half of the ±1 arcsec specification, even
    with every misalignment at its limit."""
    alpha = 0.05 * DEG
    assert 0.4 < mis.peak_error(alpha, 1e-3, 2.5e-3) / ARCSEC < 0.6


def test_tradeoff_table_against_seed_figure_22():
    """Seed 000 Figure 22. Our table (0.8 arcsec base + eq. 1 peak at ω = 2.5 mrad) agrees within
    0.35 arcsec for α <= 2 mrad; for larger α the seed's table grows faster (it adds contributions
    it does not list), so ours is lower there, never higher by more than 0.35 arcsec."""
    fig = mis.SEED000_FIGURE22
    tab = mis.tradeoff_table(np.array(fig["alpha_mrad"]) * 1e-3, np.array(fig["beta_mrad"]) * 1e-3)
    ours = np.array(tab.rows())
    seed = np.array(fig["accuracy_arcsec"])
    small = np.array(fig["alpha_mrad"]) <= 2.0
    assert np.max(np.abs(ours[:, small] - seed[:, small])) < 0.35
    assert np.all(ours - seed < 0.35)
    assert np.all(seed[:, -1] - ours[:, -1] > 1.0)                # the unexplained growth at α = 5
    assert np.all(np.diff(ours, axis=0) > 0) and np.all(np.diff(ours, axis=1) > 0)
    assert "β\\α" in str(tab)


def test_max_alpha_answers_the_setup_question():
    """The answer reaches the wanted accuracy by the more cautious estimate, and is never
    looser than equation 1 alone (0.8 arcsec + peak) would allow."""
    a = mis.max_alpha(1.0 * ARCSEC, 1e-3)
    assert mis.expected_accuracy(a, 1e-3).value == pytest.approx(1.0 * ARCSEC, rel=1e-6)
    assert 0.8 * ARCSEC + mis.peak_error(a, 1e-3, 2.5e-3) <= 1.0 * ARCSEC
    assert mis.max_alpha(0.5 * ARCSEC, 1e-3) == 0.0           # the base alone exceeds it
    assert mis.max_alpha(2.0 * ARCSEC, 1e-3) > a


def test_large_misalignment_refused():
    with pytest.raises(InputError, match="small misalignment"):
        mis.misalignment_error(0.0, 0.5, 0.0, 0.0)


def _figure22():
    fig = mis.SEED000_FIGURE22
    a, b = np.meshgrid(np.array(fig["alpha_mrad"]) * 1e-3, np.array(fig["beta_mrad"]) * 1e-3)
    return a, b, np.array(fig["accuracy_arcsec"])


def test_expected_accuracy_is_never_below_the_published_table():
    """Issue 21 / seed 000 Figure 22 (Renishaw, Interferometric calibration of rotary axes): the
    accuracy the budget states for each (α, β) of the published table, at ω = 2.5 mrad, is not
    lower than the table's value beyond the fit's 0.1 arcsec (the table is printed to 0.1).
    Equation 1 alone gives 4.72 against the table's 7.6 at α = 5, β = 1 mrad."""
    a, b, seed = _figure22()
    est = [[mis.expected_accuracy(ai, bi) for ai, bi in zip(ra, rb)] for ra, rb in zip(a, b)]
    value = np.array([[e.value for e in row] for row in est]) / ARCSEC
    assert np.all(value >= seed - 0.11)
    e = est[0][-1]                                               # α = 5, β = 1 mrad
    assert e.equation1 / ARCSEC == pytest.approx(4.72, abs=0.01) and e.source == "figure22_model"
    assert e.value / ARCSEC == pytest.approx(7.6, abs=0.1)


def test_figure22_fit_is_the_least_squares_fit_of_the_table():
    """FIGURE22_FIT is refitted here from the published 30 values (scipy least squares on
    c0 + RSS(a·α²/4, b·αβ, c·αω), ω = 2.5 mrad) and reproduces them within 0.11 arcsec."""
    from scipy.optimize import least_squares

    a, b, seed = _figure22()
    w = 2.5e-3

    def model(p):
        c0, ka, kb, kc = p
        return c0 + np.sqrt((ka * a**2 / 4) ** 2 + (kb * a * b) ** 2 + (kc * a * w) ** 2) / ARCSEC

    fit = least_squares(lambda p: (model(p) - seed).ravel(), [0.8, 1.0, 1.0, 1.0]).x
    f = mis.FIGURE22_FIT
    assert [f["c0_arcsec"], f["a"], f["b"], f["c"]] == pytest.approx(list(fit), rel=1e-3)
    ours = np.array([[mis.figure22_model(ai, bi) for ai, bi in zip(ra, rb)]
                     for ra, rb in zip(a, b)]) / ARCSEC
    assert np.max(np.abs(ours - seed)) < 0.11


def test_max_alpha_follows_the_published_table_where_it_is_more_cautious():
    """Figure 22: at β = 1 mrad, α = 4 mrad is estimated at ±5.4 arcsec. Asked for ±5.4, the
    budget must not allow more than about 4 mrad; equation 1 alone (0.8 + peak) allows 5.6."""
    a = mis.max_alpha(5.4 * ARCSEC, 1e-3)
    assert 3.9e-3 < a < 4.1e-3
    assert 0.8 * ARCSEC + mis.peak_error(5.6e-3, 1e-3, 2.5e-3) < 5.4 * ARCSEC


def test_datum_relative_error_of_the_figure_14_case():
    """Seed 000 Figure 14 (α = 0.62, β = 1.23, ω = 2.26 mrad): eq. 1 peaks at 0.346 arcsec, but a
    reading relative to the 0° datum carries E(θ) − E(0): 0.60 arcsec at η = 0 on a 10° grid,
    and max E − min E = 0.66 arcsec at the worst η. The estimate states both."""
    e = mis.expected_accuracy(0.62e-3, 1.23e-3, 2.26e-3)
    grid = np.radians(np.arange(0.0, 361.0, 10.0))
    err = mis.misalignment_error(grid, 0.62e-3, 1.23e-3, 2.26e-3, 0.0)
    assert np.max(np.abs(err - err[0])) / ARCSEC == pytest.approx(0.60, abs=0.005)
    th = np.linspace(0, 2 * np.pi, 3601)
    worst = max(np.max(np.abs((x := mis.misalignment_error(th, 0.62e-3, 1.23e-3, 2.26e-3, eta))
                              - x[0])) for eta in np.radians(np.arange(0.0, 360.0, 1.0)))
    assert e.peak / ARCSEC == pytest.approx(0.346, abs=0.001)
    assert e.datum_relative == pytest.approx(worst, rel=1e-3)
    assert e.datum_relative / e.peak > 1.7
