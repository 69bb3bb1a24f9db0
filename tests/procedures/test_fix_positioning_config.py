"""Wrong TOML types in a positioning [test] table are named, never coerced (review finding)."""

import pytest

from axiscal.errors import ConfigError
from axiscal.procedures.positioning import simulate_from_config

AXIS = {"kind": "linear", "travel_mm": [0, 800]}


@pytest.mark.parametrize("test, message", [
    ({"length_mm": 800, "runs": "five"}, "runs = 'five' must be a whole number"),
    ({"length_mm": 800, "runs": 2.7}, "runs = 2.7 must be a whole number"),
    ({"length_mm": 800, "bidirectional": "no"}, "bidirectional = 'no' must be true or false"),
    ({"length_mm": "800"}, "length_mm"),
    ({"length_mm": 800, "dwell_s": []}, "dwell_s"),
    ({"length_mm": 800, "measurement_sigma": "x"}, "measurement_sigma"),
    ({"length_mm": 800, "measurement_sigma": -0.1}, "measurement_sigma = -0.1 must be zero or positive"),
])
def test_wrong_types_are_named(test, message):
    with pytest.raises(ConfigError, match=message):
        simulate_from_config({"axis": AXIS, "test": test})
