"""Decision rules of ISO 14253-1:2017 §5 and simple acceptance (ILAC-G8:2019 §4.2.1)."""

import pytest

from axiscal.errors import InputError
from axiscal.standards.iso14253_1 import Outcome, Rule, decide, overall

C, N, Z = Outcome.CONFORMS, Outcome.NONCONFORMS, Outcome.ZONE

# Tolerance zone [-10, 10], U = 1: acceptance zone [-9, 9], rejection outside [-11, 11].
# Each limit is approached from both sides and at the boundary (ISO 14253-1:2017 §5.2-5.4).
TWO_SIDED = [
    (0.0, C, C),
    (8.99, C, C),
    (9.0, C, C),
    (9.01, Z, C),
    (9.99, Z, C),
    (10.0, Z, C),
    (10.01, Z, N),
    (10.99, Z, N),
    (11.0, Z, N),
    (11.01, N, N),
    (20.0, N, N),
    (-8.99, C, C),
    (-9.0, C, C),
    (-9.01, Z, C),
    (-10.0, Z, C),
    (-10.01, Z, N),
    (-11.0, Z, N),
    (-11.01, N, N),
    (-20.0, N, N),
]


@pytest.mark.parametrize("y, guarded, simple", TWO_SIDED)
def test_truth_table_two_sided(y, guarded, simple):
    assert decide("x", y, 1.0, 10.0, -10.0).outcome is guarded
    assert decide("x", y, 1.0, 10.0, -10.0, rule="simple").outcome is simple


@pytest.mark.parametrize(
    "y, guarded, simple",
    [
        (0.0, C, C),
        (7.4, C, C),
        (7.5, C, C),
        (7.6, Z, C),
        (10.0, Z, C),
        (10.1, Z, N),
        (12.5, Z, N),
        (12.6, N, N),
    ],
)
def test_truth_table_one_sided(y, guarded, simple):
    """A one-sided tolerance (E ≤ 10 µm, U = 2.5 µm): only the upper limit is checked."""
    d = decide("E", y, 2.5, 10.0)
    assert d.outcome is guarded
    assert decide("E", y, 2.5, 10.0, rule=Rule.SIMPLE).outcome is simple
    assert d.passed == {C: True, N: False, Z: None}[guarded]


def test_uncertainty_larger_than_half_the_zone_never_proves_conformance():
    """U > T/2 of a zone [0, T]: no value can be proven conforming (ISO 14253-1 §5.2)."""
    assert all(decide("x", y / 10, 6.0, 10.0, 0.0).outcome is not C for y in range(0, 101))


def test_not_applicable_and_overall():
    assert decide("A_down", None, 1.0, 5.0).outcome is None
    ds = [decide("E", 1, 1, 10), decide("R", 4, 1, 5)]
    assert overall(ds) is C
    assert overall(ds + [decide("B", 5.5, 1, 5)]) is Z
    assert overall(ds + [decide("B", 5.5, 1, 5), decide("A", 20, 1, 10)]) is N
    assert overall([decide("A_down", None, 1.0, 5.0)]) is None


@pytest.mark.parametrize(
    "kw",
    [
        dict(U=-1),
        dict(U=float("nan")),
        dict(upper=float("inf")),
        dict(lower=20.0),
        dict(rule="guard"),
    ],
)
def test_bad_input_refused(kw):
    args = dict(parameter="E", value=1.0, U=1.0, upper=10.0, lower=None, rule="iso14253-1") | kw
    with pytest.raises(InputError):
        decide(**args)
