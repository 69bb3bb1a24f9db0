"""The kinds of test the history keeps, each read and evaluated by the library's own code.

A file is recognised by its content (or given a kind): a positioning test (tidy CSV, axiscal
JSON or EPICS ecmc; ISO 230-2:2014, linear or rotary, which includes a rotary calibration's
result), a straightness trajectory (ISO 230-1), a ballbar circular test (ISO 230-4), a
multi-point diagonal test of squareness (ISO 230-6), and five motion errors of a rotary axis
(ISO 230-7). :func:`evaluate_file` returns what the store keeps: the evaluation as JSON, its
summary parameters with their units, and the metadata the file declares. Evaluating the same
bytes again gives the same numbers, which is how a stored test is shown again.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field


from axiscal import units
from axiscal._json import jsonable
from axiscal.errors import DataFormatError, InputError

__all__ = ["KINDS", "Evaluated", "detect_kind", "evaluate_file", "jsonable", "result_text"]

KINDS = ("iso230-2", "straightness", "ballbar", "diagonal", "motion")


@dataclass
class Evaluated:
    """A file read and evaluated: what the history stores of it."""

    kind: str
    axis_kind: str
    result: dict
    parameters: dict            # name -> (value, unit)
    dataset_json: str = ""
    machine: str = ""
    axis: str = ""
    date: str = ""
    operator: str = ""
    instrument: str = ""
    environment: dict = field(default_factory=dict)
    dataset: object = None
    evaluation: object = None


def detect_kind(text: str) -> str:
    """The kind of a data file from its content (its header line)."""
    stripped = text.lstrip("\ufeff \t\r\n")
    if stripped.startswith("{"):
        return "iso230-2"
    if "TGT_DATA[" in text or stripped.startswith("HEADER::"):   # ecmc; Renishaw .rtl/.rta
        return "iso230-2"
    for line in stripped.splitlines():
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        head = {c.strip().lower() for c in s.split(",")}
        if {"target", "direction", "run"} <= head:
            return "iso230-2"
        if {"angle", "direction", "deviation"} <= head:
            return "ballbar"
        if {"diagonal", "position", "error"} <= head:
            return "diagonal"
        if {"run", "angle_deg"} <= head:
            return "motion"
        if {"position", "deviation"} <= head:
            return "straightness"
        break
    raise DataFormatError("not a data file the history knows: expected a positioning test, a "
                          "straightness, ballbar, diagonal or five-error CSV, or axiscal JSON")


def evaluate_file(raw: bytes, filename: str, kind: str | None = None) -> Evaluated:
    """Read ``raw`` (the file's bytes) and evaluate it by its standard."""
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataFormatError(f"not UTF-8 text (byte {exc.start})", filename) from None
    k = kind or detect_kind(text)
    if k not in KINDS:
        raise InputError(f"kind {k!r}: one of {', '.join(KINDS)}")
    return _EVALUATORS[k](text, filename)


def _positioning(text: str, filename: str) -> Evaluated:
    from axiscal.io import parse_positioning
    from axiscal.io.json import format_positioning_json
    from axiscal.standards.iso230_2 import evaluate

    ds = parse_positioning(text, filename)
    r = evaluate(ds)
    unit = r.deviation_unit
    params = {n: (getattr(r, n), unit) for n in
              ("A", "A_up", "A_down", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "B",
               "B_mean") if getattr(r, n) is not None and math.isfinite(getattr(r, n))}
    params.update(_other_standards(ds))
    md = ds.metadata
    env = {k: v for k, v in dataclasses.asdict(md.environment).items() if v is not None}
    return Evaluated("iso230-2", ds.axis_kind.value, jsonable(r), params,
                     format_positioning_json(ds), md.machine, md.axis, md.date, md.operator,
                     md.instrument, jsonable(env), ds, r)


def _other_standards(ds) -> dict:
    """The parameters of every other positioning standard axiscal evaluates, named
    ``KEY:NAME`` (``jis-b6192:R``), so compare and trend work for any standard a contract names."""
    from axiscal.standards import positioning_standards as ps

    out = {}
    for std, res in ps.evaluate_all(ds):
        if std.key == "iso230-2:2014" or isinstance(res, str):
            continue
        for name, (value, unit, _) in res.parameters().items():
            if value is not None and math.isfinite(value):
                out[f"{std.key}:{name}"] = (value, unit)
    return out


def _straightness(text: str, filename: str) -> Evaluated:
    from axiscal.io.straightness import parse_straightness
    from axiscal.standards.iso230_1 import straightness

    d = parse_straightness(text, source=filename)
    ls = straightness(d.positions, d.deviations, "least_squares")
    mz = straightness(d.positions, d.deviations, "minimum_zone")
    result = {"axis": d.axis, "direction": d.direction, "n": ls.n,
              "positions_mm": d.positions * 1e3, "deviations_um": d.deviations * 1e6,
              "least_squares": {"straightness_um": ls.deviation * 1e6,
                                "slope_um_per_m": ls.line.slope * 1e6},
              "minimum_zone": {"straightness_um": mz.deviation * 1e6,
                               "slope_um_per_m": mz.line.slope * 1e6}}
    params = {"straightness": (ls.deviation * 1e6, "um"),
              "straightness_min_zone": (mz.deviation * 1e6, "um"),
              "slope": (ls.line.slope * 1e6, "um/m")}
    return Evaluated("straightness", "linear", jsonable(result), params, axis=d.axis,
                     dataset=d, evaluation=ls)


def _ballbar(text: str, filename: str) -> Evaluated:
    from axiscal.io.ballbar import parse_ballbar
    from axiscal.standards.iso230_4 import evaluate_circular

    d = parse_ballbar(text, source=filename)
    r = evaluate_circular(d.runs, d.radius, axes=d.axes)
    res = r.as_dict()
    params = {"squareness": (res["squareness"]["um_per_m"], "um/m"),
              "scale_mismatch": (res["scale_mismatch_um_per_m"], "um/m"),
              "backlash_x": (res["backlash_x_um"], "um"), "backlash_y": (res["backlash_y_um"], "um"),
              "H": (res["H_um"], "um")}
    for key, name in (("G_ccw_um", "G_ccw"), ("G_cw_um", "G_cw")):
        if res.get(key) is not None:
            params[name] = (res[key], "um")
    plane = "".join(d.axes)
    return Evaluated("ballbar", "linear", jsonable(res), params, axis=plane, dataset=d,
                     evaluation=r)


def _diagonal(text: str, filename: str) -> Evaluated:
    from axiscal.io.ballbar import parse_diagonal
    from axiscal.standards.iso230_6 import diagonal_squareness_multipoint

    d = parse_diagonal(text, source=filename)
    r = diagonal_squareness_multipoint(d.length_x, d.length_y, d.positions_d1, d.errors_d1,
                                       d.positions_d2, d.errors_d2)
    res = {"squareness": r.squareness.as_dict(), "length_x_mm": r.length_x * 1e3,
           "length_y_mm": r.length_y * 1e3, "error_d1_um": r.error_d1 * 1e6,
           "error_d2_um": r.error_d2 * 1e6}
    params = {"squareness": (r.squareness.um_per_m, "um/m")}
    return Evaluated("diagonal", "linear", jsonable(res), params, axis="XY", dataset=d,
                     evaluation=r)


def _motion(text: str, filename: str) -> Evaluated:
    from axiscal.io.motion import parse_motion_errors
    from axiscal.standards.iso230_7 import evaluate

    d = parse_motion_errors(text, source=filename)
    r = evaluate(d)
    params = {}
    for m in r.motions:
        scale, unit = (1e6, "um") if m.kind == "length" else (1 / units.ARCSEC, "arcsec")
        key = m.name.replace(" ", "_")
        params[f"{key}_total"] = (m.total * scale, unit)
    res = {"title": d.title, "n_runs": r.n_runs,
           "motions": [{"name": m.name, "kind": m.kind, "total": m.total,
                        "synchronous": m.synchronous, "asynchronous": m.asynchronous}
                       for m in r.motions]}
    return Evaluated("motion", "rotary", jsonable(res), params, dataset=d, evaluation=r)


_EVALUATORS = {"iso230-2": _positioning, "straightness": _straightness, "ballbar": _ballbar,
               "diagonal": _diagonal, "motion": _motion}


def result_text(ev: Evaluated) -> str:
    """The evaluation as the command line prints it (for ``history show``)."""
    r = ev.evaluation
    return str(r) if r is not None else json.dumps(ev.result, indent=2)
