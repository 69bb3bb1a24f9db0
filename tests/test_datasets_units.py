"""The vocabulary: units and the positioning dataset's validation."""

import math

import numpy as np
import pytest

from axiscal import units
from axiscal.datasets import Direction, Environment, Metadata, PositioningDataset
from axiscal.errors import InputError, UnitError


def test_unit_conversions():
    """1° = 3600″; 1 arcsec = 4.8481 µrad (π/648000); 1 in = 25.4 mm exactly."""
    assert units.convert(1, "deg", "arcsec") == pytest.approx(3600)
    assert units.ARCSEC == pytest.approx(math.pi / 648000)
    assert units.convert(1, "in", "mm") == pytest.approx(25.4)
    assert units.canonical("µm") == "um" and units.canonical("Arcseconds") == "arcsec"
    np.testing.assert_allclose(units.to_si([1, 2], "mm"), [1e-3, 2e-3])
    with pytest.raises(UnitError, match="cannot convert 'mm'"):
        units.convert(1, "mm", "deg")
    with pytest.raises(UnitError, match="angle unit where a length unit"):
        units.factor("deg", "length")


def test_dataset_validation_names_the_problem():
    ok = dict(targets=[0, 1, 2], up=[[0, 1]] * 3, down=[[0, 1]] * 3)
    with pytest.raises(InputError, match="strictly increasing: 1 is followed by 1"):
        PositioningDataset.from_arrays("linear", [0, 1, 1], ok["up"], ok["down"])
    with pytest.raises(InputError, match="2 rows but there are 3 target"):
        PositioningDataset.from_arrays("linear", ok["targets"], [[0, 1]] * 2, ok["down"])
    with pytest.raises(InputError, match="not a angle unit|not a angle"):
        PositioningDataset.from_arrays("rotary", ok["targets"], ok["up"], ok["down"], "mm", "arcsec")
    with pytest.raises(InputError, match="every reading of direction up is missing"):
        PositioningDataset.from_arrays("linear", ok["targets"], [[np.nan]] * 3)
    with pytest.raises(InputError, match="axis kind 'spiral'"):
        PositioningDataset.from_arrays("spiral", **ok)
    with pytest.raises(InputError, match="humidity = 120"):
        Environment(humidity=120)


def test_dataset_is_frozen():
    ds = PositioningDataset.from_arrays("linear", [0, 1], [[1, 2], [3, 4]])
    with pytest.raises(ValueError):
        ds.up[0, 0] = 5
    with pytest.raises(AttributeError):
        ds.targets = np.array([0, 2])  # type: ignore[misc]


def test_directions_and_metadata():
    assert Direction.parse("Fwd") is Direction.UP and Direction.parse("bwd") is Direction.DOWN
    with pytest.raises(InputError):
        Direction.parse("left")
    with pytest.raises(InputError, match="unknown metadata field"):
        Metadata.from_dict({"machin": "x"})
    ds = PositioningDataset.from_arrays("rotary", [0, 90], [[1, 2], [3, 4]])
    assert "rotary axis, unidirectional" in str(ds)
    assert ds.with_metadata(machine="TT").metadata.machine == "TT"


def test_absurd_magnitudes_are_refused_before_they_overflow():
    """Review finding: deviations near 1e308 made ISO 230-2 statistics overflow to inf."""
    with pytest.raises(InputError, match="beyond"):
        PositioningDataset.from_arrays("linear", [0, 1], [[1e300, 2], [3, 4]])
    with pytest.raises(InputError, match="targets hold a value beyond"):
        PositioningDataset.from_arrays("linear", [0, 1e200], [[1, 2], [3, 4]])
