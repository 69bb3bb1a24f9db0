"""CONVENTIONS habit 9 for every reader: on any text, a parser returns or raises an AxiscalError.

The existing properties feed raw ``st.text()``, which almost never gets past a header; these feed
text built like the files (a real header or a real file, then lines of tricky cells: NaN, inf,
1e308, huge run numbers, quotes, empty cells, unicode) so the checks behind the header run too.
TOML configurations get every known key with values of every TOML type. The controller-table
parsers get real written files with lines cut, repeated and their numbers replaced.
"""

import json
import math
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.compensation.controllers import CONTROLLERS, controller
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import AxiscalError
from axiscal.io.ballbar import parse_ballbar, parse_diagonal
from axiscal.io.csv import parse_positioning_csv
from axiscal.io.ecmc import parse_ecmc
from axiscal.io.json import parse_positioning_json
from axiscal.io.motion import parse_motion_config, parse_motion_errors
from axiscal.io.scale_config import (_SCHEMA, axis_from_config, homing_from_config,
                                     parse_scale_config, twin_axis_from_config)
from axiscal.io.straightness import parse_straightness
from axiscal.machines.config import axis_from_config as machine_axis
from axiscal.procedures.rotary_config import rotary_config_from_dict

SETTINGS = settings(max_examples=150, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

CELLS = st.one_of(
    st.sampled_from(["0", "1", "-1", "2.5", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf",
                     "", " ", "x", "1e300", "+", "-", "ccw", "cw", "D1", "D2", "up", "fwd",
                     '"', '"1"', "1,2", "0x10", "١", "½", "1_000", "--1"]),
    st.integers(-10**20, 10**20).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.text(max_size=6),
)


def rows(width):
    return st.lists(st.lists(CELLS, min_size=0, max_size=width + 1).map(",".join), max_size=25)


def _only_axiscal_errors(parse, text, *args, **kwargs):
    try:
        return parse(text, *args, **kwargs)
    except AxiscalError:
        return None


def tidy(header, comment=""):
    return rows(len(header.split(","))).map(lambda r: comment + header + "\n" + "\n".join(r) + "\n")


@SETTINGS
@given(tidy("target,direction,run,deviation", "# target_unit=mm deviation_unit=um\n"))
def test_positioning_csv(text):
    _only_axiscal_errors(parse_positioning_csv, text)
    _only_axiscal_errors(parse_positioning_csv, text.replace("deviation", "actual"))


KEYS = st.sampled_from(["TGT_DATA[1]", "TGT_DATA[2]", "TGT_DATA[3]", "REF_DATA_FWD[1,1]",
                        "REF_DATA_FWD[2,2]", "REF_DATA_BWD[3,1]", "REF_DATA_FWD[1,99999999999]",
                        "TGT_DATA[1,2]", "REF_DATA_BWD[2]", "UNIT", "CYCLES", "POSITIONS", "x"])


@SETTINGS
@given(st.lists(st.tuples(KEYS, CELLS), max_size=30))
def test_ecmc(pairs):
    _only_axiscal_errors(parse_ecmc, "\n".join(f"{k}={v}" for k, v in pairs))


JSON_VALUES = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-10**30, 10**30), st.floats(), st.text(max_size=5)),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=5), inner, max_size=3)),
    max_leaves=12)


@SETTINGS
@given(st.fixed_dictionaries({}, optional={
    "format": st.sampled_from(["axiscal.positioning/1", "x"]), "axis_kind": st.sampled_from(["linear", "rotary", 5]),
    "target_unit": st.sampled_from(["mm", "deg", "x", None]), "deviation_unit": st.sampled_from(["um", "arcsec", 3]),
    "targets": JSON_VALUES, "up": JSON_VALUES, "down": JSON_VALUES, "metadata": JSON_VALUES}))
def test_positioning_json(d):
    d.setdefault("format", "axiscal.positioning/1")
    _only_axiscal_errors(parse_positioning_json, json.dumps(d))


@SETTINGS
@given(tidy("position,deviation", "# position_unit=mm deviation_unit=um axis=X direction=Y\n"))
def test_straightness(text):
    _only_axiscal_errors(parse_straightness, text)


@SETTINGS
@given(tidy("angle,direction,deviation", "# radius_mm=150 deviation_unit=um plane=XY\n"),
       st.sampled_from(["radius_mm=150", "radius_mm=nan", "radius_mm=0", "radius_mm=x", "plane=XQ",
                        "deviation_unit=deg"]))
def test_ballbar(text, meta):
    _only_axiscal_errors(parse_ballbar, text.replace("radius_mm=150", meta))


@SETTINGS
@given(tidy("diagonal,position,error", "# length_x_mm=600 length_y_mm=800 position_unit=mm error_unit=um\n"),
       st.sampled_from(["length_x_mm=600", "length_x_mm=-1", "length_x_mm=inf", "length_x_mm=",
                        "position_unit=um"]))
def test_diagonal(text, meta):
    _only_axiscal_errors(parse_diagonal, text.replace("length_x_mm=600", meta))


@SETTINGS
@given(tidy("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um", "# title: t\n"))
def test_motion_errors(text):
    _only_axiscal_errors(parse_motion_errors, text)


# -- TOML configurations -----------------------------------------------------------------------
TOML_SCALARS = st.one_of(st.booleans(), st.integers(-10**6, 10**6), st.sampled_from([0, -1, 10**12, 2**63 - 1]),
                         st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=5))
TOML_VALUES = st.one_of(TOML_SCALARS, st.lists(TOML_SCALARS, max_size=4),
                        st.lists(st.lists(TOML_SCALARS, max_size=3), max_size=3))


def toml_value(v):
    """TOML text of a value (floats as TOML writes them: nan, inf, -inf)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    return "[" + ", ".join(toml_value(x) for x in v) + "]"


def toml_text(tables):
    out = []
    for name, table in tables.items():
        out.append(f"[[{name}]]" if name == "move" else f"[{name}]")
        out += [f"{k} = {toml_value(v)}" for k, v in table.items()]
    return "\n".join(out) + "\n"


def section(keys):
    return st.dictionaries(st.sampled_from(sorted(keys)), TOML_VALUES, max_size=len(keys))


@SETTINGS
@given(st.fixed_dictionaries({}, optional={name: section(keys) for name, keys in _SCHEMA.items()}))
def test_scale_config_and_builders(tables):
    text = toml_text(tables)
    try:
        tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return
    cfg = _only_axiscal_errors(parse_scale_config, text)
    if cfg is None:
        return
    axis = _only_axiscal_errors(axis_from_config, cfg)
    if axis is not None:
        _only_axiscal_errors(homing_from_config, cfg, axis)
    _only_axiscal_errors(twin_axis_from_config, cfg)


LINEAR_KEYS = {"name", "kind", "travel_mm", "scale_error_ppm", "bend_um", "backlash_um",
               "repeatability_um", "thermal_ppm_per_hour"}
ROTARY_KEYS = {"name", "kind", "travel_deg", "backlash_arcsec", "repeatability_arcsec",
               "drift_arcsec_per_hour"}
SUBTABLES = st.fixed_dictionaries({}, optional={
    "irregular": st.dictionaries(st.sampled_from(["rms_um", "rms_arcsec", "seed", "orders", "x"]), TOML_VALUES, max_size=3),
    "periodic": st.lists(st.dictionaries(st.sampled_from(["amplitude_um", "period_mm", "phase_deg"]), TOML_VALUES), max_size=2),
    "harmonics": st.lists(st.dictionaries(st.sampled_from(["order", "amplitude_arcsec", "phase_deg"]), TOML_VALUES), max_size=2),
})


@SETTINGS
@given(section(LINEAR_KEYS | ROTARY_KEYS), SUBTABLES, st.sampled_from(["linear", "rotary"]))
def test_machine_axis_config(table, sub, kind):
    """The [axis] table of machines.config, as load_toml gives it (sub-tables added as parsed)."""
    try:
        doc = tomllib.loads(toml_text({"axis": {**table, "kind": kind}}))
    except tomllib.TOMLDecodeError:
        return
    _only_axiscal_errors(machine_axis, {**doc["axis"], **sub})


ROTARY_TABLES = {
    "setup": {"mount_tilt_mrad", "beam_tilt_mrad", "reflector_height_mm", "tir_radius_mm",
              "lateral_offset_mm", "counter_rotation", "dial_noise_mm", "laser_distance_m"},
    "laser": {"spacing_mm", "nominal_spacing_mm", "noise_arcsec", "resolution_arcsec", "max_angle_deg"},
    "calibrator": {"graduation_error_rms_arcsec", "read_heads", "error_map", "seed", "map_points",
                   "eccentricity_um", "servo_arcsec"},
    "offaxis": {"radius_mm", "phase_deg", "alignment_angles_deg", "yaw_sign", "linear_axis",
                "yaw_period_mm", "yaw_profile_direction_sign", "feed_mm_min"},
    "meta": {"machine", "operator", "x"},
    "test": {"travel_deg", "step_deg", "runs", "speed_deg_s", "overrun", "dwell_s", "cycle",
             "bidirectional", "n_targets"},
}


@SETTINGS
@given(st.fixed_dictionaries({"axis": st.just({"kind": "rotary"})},
                             optional={n: section(k) for n, k in ROTARY_TABLES.items()}),
       st.one_of(st.none(), TOML_SCALARS))
def test_rotary_calibration_config(tables, seed):
    text = ("" if seed is None else f"seed = {toml_value(seed)}\n") + toml_text(tables)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return
    if isinstance(doc.get("calibrator", {}).get("map_points"), int) and doc["calibrator"]["map_points"] > 10**5:
        doc["calibrator"]["map_points"] = 10**5   # a large map is valid, only slow
    _only_axiscal_errors(rotary_config_from_dict, doc)


MOTION_TABLES = {
    "machine": {"name", "axis"},
    "test": {"step_deg", "dwell_s", "samples", "runs", "seed", "drift_window", "stability_duration_min"},
    "instrument": {"f1_mm", "h_mm", "psd_resolution_um", "beam_jitter_urad"},
    "mounting": {"realistic", "beam_yaw_arcsec", "ref_eccentricity_um", "detector_rotation_deg"},
    "reference": {"step_arcsec", "encoder_error", "encoder_noise_arcsec"},
    "drift": {"rate_urad_per_h", "wander_urad", "period_min"},
}


@SETTINGS
@given(st.fixed_dictionaries({}, optional={n: section(k) for n, k in MOTION_TABLES.items()}))
def test_motion_config(tables):
    _only_axiscal_errors(parse_motion_config, toml_text(tables))


# -- controller tables (tests only: the parsers are outside this review's area) -----------------
def _table(name):
    t = [0, 100, 200, 300, 400]
    return table_from_deviations(t, [2.0, -1.0, 4.0, 3.0, -2.0], [0.0, -3.0, 2.0, 1.0, -4.0],
                                 spacing=25, resolution=1.0, axis="X")


WRITTEN = {name: controller(name).write(_table(name), **({"detection_unit": 0.0001} if name == "fanuc" else {})).text
           for name in CONTROLLERS}


@pytest.mark.parametrize("name", sorted(CONTROLLERS))
@SETTINGS
@given(data=st.data())
def test_controller_parsers_on_damaged_files(name, data):
    lines = WRITTEN[name].splitlines()
    for _ in range(data.draw(st.integers(1, 4))):
        i = data.draw(st.integers(0, len(lines) - 1))
        how = data.draw(st.sampled_from(["cut", "drop", "repeat", "number", "append"]))
        if how == "cut":
            lines[i] = lines[i][: data.draw(st.integers(0, len(lines[i])))]
        elif how == "drop" and len(lines) > 1:
            del lines[i]
        elif how == "repeat":
            lines.insert(i, lines[i])
        elif how == "number":
            lines[i] = __import__("re").sub(r"[-+]?\d+(\.\d+)?", data.draw(CELLS).replace("\\", ""), lines[i], count=1)
        else:
            lines.append(data.draw(st.text(max_size=20)))
    _only_axiscal_errors(controller(name).parse, "\n".join(lines) + "\n")
