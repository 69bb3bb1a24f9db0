"""The five-axis ballbar CSV (:mod:`axiscal.io.five_axis_ballbar`): any text gives a record or
one AxiscalError, never another exception (CONVENTIONS, habit 9)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.five_axis_ballbar import parse_ballbar

HEAD = "# length_mm = 100\n# noise_um = 0.2\npose,A_deg,C_deg,X_mm,Y_mm,Z_mm,deviation_um\n"
CELL = st.sampled_from(["1", "2", "3", "0", "-1", "nan", "inf", "", "x", "1e400", "2.5", " "])


@settings(max_examples=150, deadline=None)
@given(st.lists(st.lists(CELL, min_size=0, max_size=9), min_size=0, max_size=6),
       st.text(max_size=80))
def test_a_parser_raises_only_axiscal_errors(rows, junk):
    for text in (HEAD + "\n".join(",".join(r) for r in rows), junk, HEAD + junk):
        try:
            parse_ballbar(text, "fuzz")
        except AxiscalError:
            pass
