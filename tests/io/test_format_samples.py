"""The file-format page's samples are written by axiscal's writers and read back by its readers."""

import pytest

from axiscal.io.format_samples import COLUMNS, SAMPLES, sample
from axiscal.io.formats import FORMATS

NAMES = {f.name for f in FORMATS}


def test_every_sample_and_column_text_names_a_registered_format():
    assert set(SAMPLES) <= NAMES and set(COLUMNS) <= NAMES
    assert sample("no such format") is None


@pytest.mark.parametrize("name", ["Tidy positioning CSV (ISO 230-2 readings)",
                                  "axiscal positioning JSON", "EPICS ecmc ISO 230-2 file",
                                  "Renishaw linear positioning export (HEADER:: … EOF::)"])
def test_positioning_samples_read_back_to_the_same_test(name):
    """A sample read by :func:`axiscal.io.parse_positioning` gives the three targets and the
    readings it was written from (µm; the ecmc file holds positions, 0.1 nm steps)."""
    import numpy as np

    from axiscal.io import parse_positioning
    from axiscal.io.format_samples import _dataset

    ds, ref = parse_positioning(sample(name), name), _dataset()
    assert np.allclose(ds.targets, ref.targets)
    assert np.allclose(ds.up, ref.up, atol=1e-3) and np.allclose(ds.down, ref.down, atol=1e-3)


def test_straightness_sample_reads_back():
    from axiscal.io.straightness import parse_straightness

    d = parse_straightness(sample("Straightness trajectory"), source="sample")
    assert d.positions.size == 3 and d.deviations[1] == pytest.approx(1.5e-6)


def test_squareness_test_sample_reads_back():
    """The sample's readings come back as the doubles written (``axiscal.io.biaxial``)."""
    from axiscal.io.biaxial import parse_biaxial_test

    t = parse_biaxial_test(sample("Squareness test from two straightness trajectories"))
    assert t.one.deviations.tolist() == [0.0, 1.5e-6, 0.8e-6] and t.two.axis == "Y"
    assert t.machine == "VMC-800" and t.config == "L"
