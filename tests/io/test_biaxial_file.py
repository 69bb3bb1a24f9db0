"""The squareness test file (:mod:`axiscal.io.biaxial`): any text, a mutated file included,
is read or refused with an :class:`~axiscal.errors.AxiscalError`, never another exception
(CONVENTIONS habit 9); what is written is read back to the same doubles."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.biaxial import biaxial_test, format_biaxial_test, parse_biaxial_test
from axiscal.io.straightness import StraightnessData

_P = np.array([0.0, 0.1, 0.2])
GOOD = format_biaxial_test(biaxial_test(
    StraightnessData(_P, np.array([0.0, 1e-6, 3e-7]), "X", "Y", source="x.csv"),
    StraightnessData(_P, np.array([0.0, -2e-6, -4e-6]), "Y", "X", source="y.csv")))


def _read(text: str) -> None:
    try:
        parse_biaxial_test(text, "fuzz.toml")
    except AxiscalError:
        pass


@settings(max_examples=60, deadline=None)
@given(st.integers(0, len(GOOD) - 1), st.integers(0, 40), st.text(max_size=20))
def test_a_mutated_file_is_read_or_refused_by_an_axiscal_error(at, cut, insert):
    _read(GOOD[:at] + insert + GOOD[at + cut:])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(allow_nan=False, allow_infinity=False, min_value=-1e6,
                          max_value=1e6), min_size=2, max_size=30))
def test_written_readings_read_back_to_the_same_doubles(values):
    """Any finite doubles (positions at least two apart) round-trip bit for bit."""
    pos = np.arange(len(values), dtype=float) * 0.1
    dev = np.array(values)
    t = parse_biaxial_test(format_biaxial_test(biaxial_test(
        StraightnessData(pos, dev, "X", "Y"), StraightnessData(pos, -dev, "Y", "X"))))
    assert t.one.deviations.tobytes() == dev.tobytes()
    assert t.two.deviations.tobytes() == (-dev).tobytes()
    assert t.one.positions.tobytes() == pos.tobytes()
