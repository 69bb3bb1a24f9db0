"""``parse_result_json`` refuses what is not an ISO 230-2 result (CLI review: NaN targets and
unknown units were accepted and reached the controller file)."""

import copy
import json

import pytest

from axiscal.io.results import load_mean_deviations, parse_result_json
from axiscal.errors import DataFormatError

BASE = {"axis_kind": "linear", "target_unit": "mm", "unit": "um",
        "targets": [{"target": 0, "mean_up": 1.0, "mean_down": None},
                    {"target": 100, "mean_up": 2.0, "mean_down": None}]}


def _with(path, value):
    d = copy.deepcopy(BASE)
    *head, last = path
    node = d
    for k in head:
        node = node[k]
    node[last] = value
    return d


def test_a_good_result_is_read():
    r = parse_result_json(BASE)
    assert r.targets.tolist() == [0.0, 100.0]
    assert r.mean_up.tolist() == [1.0, 2.0]
    assert r.target_unit == "mm" and r.deviation_unit == "um"


@pytest.mark.parametrize("path, value, rule", [
    (("targets", 0, "target"), float("nan"), r"targets\[0\].target = nan must be a finite number"),
    (("targets", 1, "target"), float("inf"), r"targets\[1\].target = inf"),
    (("targets", 0, "target"), True, r"targets\[0\].target = True"),
    (("targets", 0, "target"), 10**400, r"targets\[0\].target = 1000"),
    (("targets", 1, "mean_up"), float("-inf"), r"mean_up = -inf must be a finite number or null"),
    (("unit",), "furlong", "unit: unknown unit 'furlong'"),
    (("target_unit",), "parsec", "target_unit: unknown unit 'parsec'"),
    (("unit",), "arcsec", "unit = 'arcsec' is not a length unit"),
    (("target_unit",), "deg", "target_unit = 'deg' is not a length unit"),
])
def test_bad_values_are_refused_by_name(path, value, rule):
    with pytest.raises(DataFormatError, match=rule):
        parse_result_json(_with(path, value))


def test_nan_target_in_a_result_file_is_refused(tmp_path):
    """Python's json reads the non-standard NaN literal; the reader must not pass it on."""
    f = tmp_path / "r.json"
    f.write_text(json.dumps(_with(("targets", 0, "target"), float("nan"))))
    assert "NaN" in f.read_text()
    with pytest.raises(DataFormatError, match="finite"):
        load_mean_deviations(f)


def test_units_come_back_in_their_canonical_names():
    r = parse_result_json(_with(("unit",), "µm"))
    assert r.deviation_unit == "um"
