"""Configuration files take a value with its unit (issue 37): a number of a TOML key declared
with a unit (:class:`axiscal._schema.Num`) may be written as text with another unit, read by
pint into the declared one and then checked against the same range."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from axiscal.errors import ConfigError
from axiscal.io.scale_config import parse_scale_config

ROOT = Path(__file__).resolve().parents[2]
SINGLE = ROOT / "examples" / "scale_single.toml"


def _with(text: str, table: str, key: str, value: str) -> str:
    """``text`` with ``key`` of ``[table]`` set to ``value`` (TOML)."""
    block = re.search(rf"^\[{table}\][^\[]*", text, re.MULTILINE)
    assert block, table
    assert re.search(rf"^{key}\s*=", block.group(0), re.MULTILINE), key
    new = re.sub(rf"^{key}\s*=.*$", f"{key} = {value}", block.group(0), count=1,
                 flags=re.MULTILINE)
    return text.replace(block.group(0), new)


@pytest.mark.parametrize("table, key, number, text", [
    ("air", "temperature", "20.6", '"293.75 K"'),            # °C: an absolute temperature
    ("air", "pressure", "100750", '"1007.5 hPa"'),
    ("air", "temperature_rate", "0.002", '"0.12 degC/min"'),  # K/s: a difference per time
    ("laser", "dead_path_mm", "50.0", '"5 cm"'),
    ("switch", "repeatability_um", "0.5", '"500 nm"'),
])
def test_a_value_with_its_unit_equals_the_number(table, key, number, text):
    """The example's value as a number and the same value written with another unit parse to
    the same configuration (the real example examples/scale_single.toml)."""
    base = SINGLE.read_text("utf-8")
    by_number = parse_scale_config(_with(base, table, key, number), "s.toml")
    by_text = parse_scale_config(_with(base, table, key, text), "s.toml")
    assert by_text[table][key] == pytest.approx(by_number[table][key], rel=1e-12)


def test_a_unit_of_another_kind_or_out_of_range_is_refused():
    base = SINGLE.read_text("utf-8")
    with pytest.raises(ConfigError, match=r"temperature = '20 mm': mm cannot be converted"):
        parse_scale_config(_with(base, "air", "temperature", '"20 mm"'), "s.toml")
    with pytest.raises(ConfigError, match=r"temperature = '500 K' must be at most 100 °C"):
        parse_scale_config(_with(base, "air", "temperature", '"500 K"'), "s.toml")
    with pytest.raises(ConfigError, match=r"temperature = 'warm' must be a number in °C"):
        parse_scale_config(_with(base, "air", "temperature", '"warm"'), "s.toml")
