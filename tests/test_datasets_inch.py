"""An inch read as a millimetre (issue 30): the rule of :func:`axiscal.datasets.inch_signature`,
its messages, and no false alarm on any example or real file under every reader.

The inch is exactly 25.4 mm (International Yard and Pound Agreement, 1959). A machine axis follows
its targets to parts per million (its deviation is actual minus target, ISO 230-2:2014 §3.1); a
ratio of measured to target positions of 25.4 or 1/25.4 is the unit, never the machine.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from axiscal.datasets import INCH_MM, PositioningDataset, inch_reading, inch_signature
from axiscal.errors import AxiscalError, InputError

ROOT = Path(__file__).resolve().parents[1]
#: Every example and real data file of the repository (reference files with their sources).
FILES = sorted(p for d in (ROOT / "examples", ROOT / "tests" / "data") for p in d.rglob("*")
               if p.is_file() and p.suffix.lower() not in (".md", ".toml", ".ini"))
TARGETS = np.linspace(0.0, 0.8, 9)          # m, an 800 mm axis


@pytest.mark.parametrize("ratio, expected", [(25.4, INCH_MM), (1 / 25.4, 1 / INCH_MM)])
def test_the_inch_is_found_in_either_direction(ratio, expected):
    # a machine with 20 µm/m of scale error and 3 µm of noise, its positions scaled by the inch
    rng = np.random.default_rng(1)
    positions = TARGETS * (1 + 20e-6) + rng.normal(0, 3e-6, TARGETS.size)
    assert inch_signature(TARGETS, ratio * positions + 0.004) == expected   # any offset


@pytest.mark.parametrize("positions", [
    TARGETS * (1 + 1e-3),                          # 1 mm/m: far beyond a real scale error
    TARGETS * 0 + 0.1,                             # an axis that does not move at all
    TARGETS * 25.4 * 1.02,                         # 2 % off the inch: not the unit
    TARGETS * 25.4 + 0.5 * (-1.0) ** np.arange(9),  # slope exactly 25.4, far from that line
    TARGETS[::-1].copy(),                          # running backwards
])
def test_no_signature_without_the_inch(positions):
    assert inch_signature(TARGETS, positions) is None


def test_too_few_or_unusable_points_give_no_signature():
    assert inch_signature([0.1], [2.54]) is None
    assert inch_signature([0.1, 0.1], [2.54, 2.54]) is None
    assert inch_signature([0.0, np.nan, 0.2], [0.0, 1.0, np.nan]) is None


@pytest.mark.parametrize("k, tu, mu, text, which, unit", [
    (INCH_MM, "mm", "mm", "the targets look like inches read as mm", "target", "in"),
    (1 / INCH_MM, "mm", "mm", "the laser readings look like inches read as mm", "measured", "in"),
    (INCH_MM, "in", "in", "the laser readings look like mm read as inches", "measured", "mm"),
    (1 / INCH_MM, "in", "in", "the targets look like mm read as inches", "target", "mm"),
    (INCH_MM, "mm", "in", "the targets look like inches read as mm", "target", "in"),
    (INCH_MM, "um", "um", "the targets look like units of 25.4 µm read as µm", "target", None),
])
def test_the_plausible_reading_names_the_declaration_that_reads_the_file_right(
        k, tu, mu, text, which, unit):
    said, w, u = inch_reading(k, tu, mu, "laser readings")
    assert text in said and (w, u) == (which, unit)
    assert ("25.4 ×" if k > 1 else "1/25.4 of") in said


def test_a_dataset_with_the_inch_in_its_deviations_is_refused_in_words():
    t = np.array([0.0, 200.0, 400.0, 600.0, 800.0]) / INCH_MM        # targets written in inches
    dev_um = (t * INCH_MM - t) * 1e3 + np.array([1.0, 2.0, 1.5, 0.5, 0.0])   # mm positions − them
    with pytest.raises(InputError) as exc:
        PositioningDataset.from_arrays("linear", t, np.column_stack([dev_um, dev_um + 0.3]))
    msg = str(exc.value)
    assert "measured positions are 25.4 × the targets" in msg
    assert "the targets look like inches read as mm" in msg and "+24.4 mm per mm" in msg


def test_a_rotary_dataset_is_never_read_for_inches():
    t = np.array([0.0, 90.0, 180.0, 270.0])
    ds = PositioningDataset.from_arrays("rotary", t, (t * 24.4 * 3600)[:, None])
    assert ds.n_targets == 4


def _readers():
    """Every reader of a file that holds targets with measured positions or deviations."""
    from axiscal.io import read_positioning
    from axiscal.io.ecmc import read_ecmc
    from axiscal.io.json import read_positioning_json
    from axiscal.io.measured import read_environment_log, read_raw_readings
    from axiscal.io.renishaw import read_renishaw

    return {"positioning (told by content)": read_positioning,
            "positioning CSV in mm/µm": lambda p: read_positioning(p, "mm", "um"),
            "ecmc": read_ecmc, "axiscal JSON": read_positioning_json, "Renishaw": read_renishaw,
            "raw laser readings": read_raw_readings, "environment log": read_environment_log}


def test_no_example_or_real_file_raises_the_inch_under_any_reader():
    """Every reader over every file of examples/ and tests/data: a file of another kind is
    refused for its format, but none is ever taken for inches, and each positioning, raw and
    environment file reads."""
    read = {}
    for path in FILES:
        for name, reader in _readers().items():
            try:
                reader(path)
            except AxiscalError as exc:
                assert "25.4" not in str(exc) and "inch" not in str(exc), (name, str(exc))
            else:
                read.setdefault(path.name, []).append(name)
    assert "raw laser readings" in read["raw_readings_vmc800_x.csv"]
    assert "environment log" in read["environment_log_vmc800_x.csv"]
    for real in ("mcu1025_fat_sat_ISO230.dat", "sls_fat_sat_ISO230.dat"):   # ecmc, PSI
        assert "ecmc" in read[real]
    for axis in ("X_EXX.csv", "Y_EYY.csv", "Z_EZZ.csv"):                   # volumetric example
        assert "positioning (told by content)" in read[axis]


def test_the_volumetric_example_reads_whole():
    from axiscal.io.volumetric import read_volumetric_config

    assert read_volumetric_config(ROOT / "examples" / "volumetric" / "volumetric.toml")
