"""Table sizes are bounded before anything is allocated (CLI review: --spacing 1e-9 tried to
allocate 1.5 TiB for 2e11 points and died with numpy's MemoryError traceback)."""

import pytest

from axiscal.compensation.squareness import squareness_compensation
from axiscal.compensation.tables import MAX_TABLE_POINTS, table_from_deviations
from axiscal.errors import InputError
from axiscal.standards.iso230_1 import Squareness


def test_tiny_spacing_is_refused_naming_the_count():
    with pytest.raises(InputError, match=r"200000000001 table points; at most 100000"):
        table_from_deviations([0, 200], [1.0, 2.0], spacing=1e-9)


def test_denormal_spacing_is_refused_not_overflowed():
    with pytest.raises(InputError, match="infinitely many table points"):
        table_from_deviations([0, 200], [1.0, 2.0], spacing=5e-324)


def test_modulo_table_count_is_bounded_too():
    with pytest.raises(InputError, match="table points; at most"):
        table_from_deviations([0, 180, 360], [1.0, 2.0, 1.0], spacing=360 / 10**7, modulo=True,
                              axis_kind="rotary", position_unit="deg", correction_unit="arcsec")


def test_the_limit_itself_is_allowed():
    """Exactly MAX_TABLE_POINTS points: 0 … (MAX-1)·spacing."""
    t = table_from_deviations([0, MAX_TABLE_POINTS - 1], [1.0, 2.0], spacing=1.0)
    assert t.n_points == MAX_TABLE_POINTS


def test_squareness_table_count_is_bounded():
    c = squareness_compensation(Squareness(40e-6, ("X", "Z")), aligned_axis="Z")
    with pytest.raises(InputError, match="table points; at most"):
        c.table(0.0, 1.0, 1e-12)
