"""The kinds of test the history keeps, each read and evaluated by the library's own code.

A file is recognised by its content (or given a kind): a positioning test (tidy CSV, axiscal
JSON or EPICS ecmc; ISO 230-2:2014, linear or rotary, which includes a rotary calibration's
result), a straightness trajectory (ISO 230-1), a ballbar circular test (the full diagnosis
with its ISO 230-4 figures, :func:`evaluate_ballbar`), a multi-point diagonal test of squareness
(ISO 230-6), five motion errors of a rotary axis (ISO 230-7), and a five-axis kinematics test
(a sphere probed at many rotary poses or an R-test, with the machine's nominal geometry in the
file: the location errors of ISO 230-1 / ISO 230-7 Clause 3 identified from it,
:func:`axiscal.api.fiveaxis.identify`'s one call), and an ISO 230-3:2020 thermal test's log
(ETVE, spindle, linear axis, rotary table: :func:`axiscal.standards.iso230_3.evaluate_thermal`,
the call of ``axiscal thermal evaluate``), a five-axis ballbar test (a rotary axis, or both,
moving with the linear axes; ISO 10791-6:2014 as :mod:`axiscal.standards.iso10791_6` reads it:
the range with U of ``axiscal fiveaxis ballbar evaluate``), and a volumetric test: a volumetric configuration
holding its 21 errors inline, mapped by ISO/TR 16907:2015 with the body diagonals of ISO
230-6:2002 (the call of ``axiscal volumetric map``), and a squareness test from two straightness
trajectories (ISO 230-1:2012 §3.6.7: one TOML file holding both and the options,
:mod:`axiscal.io.biaxial`, the call of ``axiscal squareness biaxial``).
:func:`evaluate_file` returns
what the store keeps: the evaluation as JSON, its summary parameters with their units, and the
metadata the file declares. Evaluating the same bytes again gives the same numbers, which is how
a stored test is shown again; and they are the numbers of the command a user runs on the file
(``ballbar analyze``, ``straightness``, ``evaluate``...), which tests/store/test_paths_agree.py
checks for every kind.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
from dataclasses import dataclass, field


from axiscal import units
from axiscal._json import jsonable
from axiscal.errors import DataFormatError, InputError

__all__ = ["KINDS", "Evaluated", "ballbar_parameters", "detect_kind", "evaluate_ballbar",
           "evaluate_file", "jsonable", "other_standards", "result_text", "positioning_record",
           "with_uncertainty", "inputs_from_config", "budget_of", "UNCERTAINTY_TABLE",
           "drift_check_record", "drift_check_from_readings", "with_drift_check",
           "IdentificationBudget", "ThermalBudget", "volumetric_record"]

#: The configuration table holding each kind's uncertainty inputs (ISO 230-2:2014 Annex A;
#: ISO/TR 230-9 for squareness and, axiscal's reading of it, the other kinds'); a kind not named
#: here takes no inputs from a table (a five-axis identification's, a thermal test's and a
#: five-axis ballbar test's budgets come from their data: :func:`budget_of`).
UNCERTAINTY_TABLE = {"iso230-2": "uncertainty", "diagonal": "squareness_uncertainty",
                     "ballbar": "ballbar_uncertainty", "motion": "motion_uncertainty",
                     "squareness": "squareness_uncertainty",   # two straightness profiles
                     "volumetric": "volumetric_uncertainty",
                     "straightness": "straightness_uncertainty"}

KINDS = ("iso230-2", "straightness", "ballbar", "diagonal", "motion", "fiveaxis", "thermal",
         "volumetric", "fiveaxis-ballbar", "squareness")


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
    #: A positioning test by every other positioning standard (:func:`other_standards`), the
    #: table its page shows; None for other kinds.
    standards: dict | None = None
    #: The uncertainty budget (:func:`with_uncertainty`; None: the kind has none, or it was
    #: not asked for), the inputs it was made with, and ISO 14253-1 decisions made with it.
    budget: object = None
    inputs: dict = field(default_factory=dict)
    verdicts: tuple = ()
    #: The drift check stored with a positioning test (:func:`drift_check_record`), or None.
    drift_check: dict | None = None

    @property
    def quantities(self) -> dict:
        """Every result as a :class:`~axiscal.standards.quantities.Quantity` (value, U, k,
        unit, verdict): the one shape of every path."""
        from axiscal.standards.quantities import make_quantities

        return make_quantities(self.parameters, self.budget, self.verdicts)

    def stored_result(self) -> dict:
        """The evaluation as the history stores it: the kind's result object with the
        ``quantities`` block (schema version), the uncertainty inputs and the budget."""
        from axiscal.standards.quantities import quantities_json

        out = {**self.result, **quantities_json(self.quantities),
               "uncertainty_inputs": jsonable(self.inputs)}
        if self.budget is not None:
            out["uncertainty_budget"] = jsonable(self.budget.to_json())
        if self.drift_check is not None:
            out["drift_check"] = jsonable(self.drift_check)
        return out


def drift_check_record(raw: bytes, filename: str) -> dict:
    """A drift check (ISO 230-2:2014 Annex A.5) as the history keeps it beside its positioning
    test: the file's name and SHA-256, its readings (the test's deviation unit, file order) and
    E_VE, their range (:func:`~axiscal.standards.iso230_9_inputs.environmental_variation`).
    The one place a drift check becomes an E_VE: ``iso230-2 --drift-check``, the history and
    the workbench take it from here.

    Examples
    --------
    >>> r = drift_check_record(b"reading\\n0.1\\n0.4\\n-0.2\\n", "dc.csv")
    >>> round(r["e_ve"], 6), r["samples"], r["standard"]
    (0.6, 3, 'ISO 230-2:2014 Annex A.5')
    """
    import hashlib

    from axiscal.io._files import _not_utf8
    from axiscal.io.drift import parse_drift_check
    from axiscal.standards.iso230_9_inputs import environmental_variation

    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataFormatError(_not_utf8(raw, exc.start), str(filename)) from None
    readings = parse_drift_check(text, source=filename)
    return {"standard": "ISO 230-2:2014 Annex A.5", "filename": str(filename)[:300],
            "sha256": hashlib.sha256(raw).hexdigest(), "samples": int(readings.size),
            "readings": [float(v) for v in readings],
            "e_ve": float(environmental_variation(readings)), "e_ve_source": "drift check"}


def drift_check_from_readings(kept: dict) -> dict:
    """The drift check a stored record keeps (``result["drift_check"]``: its file's name and
    SHA-256 and its readings, :func:`drift_check_record`) made again from its readings, where
    the file itself was not kept (``iso230-2 --drift-check --history`` keeps the readings):
    E_VE their range again (:func:`~axiscal.standards.iso230_9_inputs.
    environmental_variation`), as :func:`drift_check_record` makes it. An archive brings it.

    Raises
    ------
    InputError
        Not a name, a SHA-256 and at least 2 finite readings (the count stated if one is).

    Examples
    --------
    >>> r = drift_check_from_readings({"filename": "dc.csv", "sha256": "0" * 64,
    ...                                "readings": [0.1, 0.4, -0.2]})
    >>> round(r["e_ve"], 6), r["samples"]
    (0.6, 3)
    """
    import numpy as np

    from axiscal._parse import MAX_MAGNITUDE
    from axiscal.standards.iso230_9_inputs import environmental_variation

    readings = kept.get("readings")
    if not (isinstance(readings, list) and len(readings) >= 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            and abs(v) <= MAX_MAGNITUDE for v in readings)):
        raise InputError("the drift check's readings are not a list of at least 2 finite "
                         f"numbers within ±{MAX_MAGNITUDE:g}")
    name, sha = kept.get("filename"), kept.get("sha256")
    if not (isinstance(name, str) and name.strip() and isinstance(sha, str) and len(sha) == 64):
        raise InputError("the drift check has no file name or SHA-256")
    if kept.get("samples", len(readings)) != len(readings):
        raise InputError(f"the drift check states {kept.get('samples')!r:.20} readings and "
                         f"holds {len(readings)}")
    values = np.asarray(readings, dtype=float)
    return {"standard": "ISO 230-2:2014 Annex A.5", "filename": name[:300], "sha256": sha,
            "samples": int(values.size), "readings": [float(v) for v in values],
            "e_ve": float(environmental_variation(values)), "e_ve_source": "drift check"}


def with_drift_check(ev: Evaluated, inputs: dict, record: dict,
                     declared: dict | None = None) -> tuple[Evaluated, dict]:
    """``ev`` with its drift check kept, and the uncertainty ``inputs`` with E_VE measured by
    it (``e_ve_source = 'drift check'``; over a configuration's declared E_VE). ``declared``:
    the inputs the user gave for this test; an E_VE among them as well is refused (given
    twice). Only a positioning test (ISO 230-2) has a drift check."""
    if ev.kind != "iso230-2":
        raise InputError(f"a drift check (ISO 230-2:2014 Annex A.5) goes with a positioning "
                         f"test; this file is a {ev.kind} test")
    if declared and "e_ve" in declared:
        raise InputError("E_VE is given twice: by the drift check (--drift-check) and by the "
                         "uncertainty input e_ve (--uncertainty e_ve); give one")
    unit = getattr(ev.evaluation, "deviation_unit", "")
    kept = {**record, "unit": unit}
    return (dataclasses.replace(ev, drift_check=kept),
            {**inputs, "e_ve": record["e_ve"], "e_ve_source": "drift check"})


def inputs_from_config(kind: str, cfg: dict, dataset=None) -> dict:
    """The uncertainty inputs of a ``kind`` of test from a configuration (the user's with a
    job's tables on top): its table of :data:`UNCERTAINTY_TABLE`, and for a linear positioning
    test whose file holds no material temperature, the one the job's ``[conditions]`` states,
    so a certificate and its budget agree. The one place inputs are resolved."""
    table = dict(cfg.get(UNCERTAINTY_TABLE.get(kind, ""), None) or {})
    if kind == "iso230-2" and dataset is not None:
        mat = cfg.get("conditions", {}).get("material_temperature")
        if (mat is not None and "material_temperature" not in table
                and dataset.axis_kind.value == "linear"
                and not dataset.metadata.environment.material_temperature):
            table["material_temperature"] = mat
    return table


def with_uncertainty(ev: Evaluated, inputs: dict | None) -> Evaluated:
    """``ev`` with its uncertainty budget made from ``inputs`` (absent ones assumed and said):
    ISO 230-2:2014 Annex A for a positioning test
    (:func:`~axiscal.standards.iso230_9.positioning_budget`), ISO/TR 230-9 for a diagonal
    squareness test (:func:`~axiscal.standards.iso230_9_geometry.diagonal_budget`), G and H
    of a ballbar test (:func:`~axiscal.standards.iso230_9_ballbar.ballbar_budget`), a
    straightness test's (:func:`~axiscal.standards.iso230_9_straightness.straightness_budget`), the ISO
    230-7 values of a five-motion-error test
    (:func:`~axiscal.standards.iso230_7_uncertainty.motion_budget`), a squareness
    from two straightness profiles (ISO/TR 230-9, its one evaluation made again with these
    inputs, since its result states U), a five-axis
    identification's and a thermal test's own, a volumetric map's figures
    (:func:`~axiscal.standards.iso230_9_volumetric.volumetric_budget`); the other kinds keep none. Every path that shows a U (command, history, workbench, report,
    certificate, API) takes it from here."""
    inputs = dict(inputs or {})
    if ev.kind == "squareness":     # its --json holds U: the one evaluation, with these inputs
        return dataclasses.replace(_squareness_record(ev.dataset, inputs), inputs=inputs)
    return dataclasses.replace(ev, budget=budget_of(ev.kind, ev.dataset, ev.evaluation, inputs),
                               inputs=inputs)


def budget_of(kind: str, dataset, evaluation, inputs: dict):
    """The uncertainty budget of a ``kind`` of test from its inputs (None: the kind has none):
    the one call behind :func:`with_uncertainty` and the certificate's budget."""
    if kind == "iso230-2":
        from axiscal.standards.iso230_9 import positioning_budget

        return positioning_budget(dataset, evaluation, inputs)
    if kind == "diagonal":
        from axiscal.standards.iso230_9_geometry import diagonal_budget

        return diagonal_budget(evaluation, inputs)
    if kind == "ballbar":
        from axiscal.standards.iso230_9_ballbar import ballbar_budget

        return ballbar_budget(evaluation, dataset.radius, inputs)
    if kind == "motion":
        from axiscal.standards.iso230_7_uncertainty import motion_budget

        return motion_budget(evaluation, inputs)
    if kind == "straightness":
        from axiscal.standards.iso230_9_straightness import straightness_budget

        return straightness_budget(dataset.positions, dataset.deviations, inputs)
    if kind == "fiveaxis":
        return IdentificationBudget(evaluation)
    if kind == "thermal":
        return ThermalBudget(evaluation, log=dataset)
    if kind == "fiveaxis-ballbar":      # the range's own budget, made by its one evaluation
        return evaluation.budget
    if kind == "squareness":            # ISO/TR 230-9, made by its one evaluation (biaxial)
        return dataset.evaluate(inputs).budget
    if kind == "volumetric":            # the map's figures from the 21 errors' U
        from axiscal.standards.iso230_9_volumetric import volumetric_budget

        cfg = dataset.parts["config"]
        return volumetric_budget(cfg.errors, evaluation, dataset.parts["diagonals"], inputs,
                                 getattr(cfg, "uncertainty", {}))
    return None


_VOLUMETRIC = re.compile(r"^[ \t]*\[machine\][ \t]*(#.*)?$", re.M)
_ERRORS = re.compile(r"^[ \t]*\[errors\][ \t]*(#.*)?$", re.M)
_BIAXIAL = re.compile(r"^[ \t]*\[biaxial\][ \t]*(#.*)?$", re.M)
_FIRST = re.compile(r"^[ \t]*\[first\][ \t]*(#.*)?$", re.M)


def detect_kind(text: str) -> str:
    """The kind of a data file from its content (its header line)."""
    stripped = text.lstrip("\ufeff \t\r\n")
    if stripped.startswith("{"):
        return "iso230-2"
    if _VOLUMETRIC.search(text) and _ERRORS.search(text):    # a TOML [machine] and [errors]
        return "volumetric"
    if _BIAXIAL.search(text) and _FIRST.search(text):        # a TOML [biaxial] and [first]
        return "squareness"
    if "TGT_DATA[" in text or stripped.startswith("HEADER::"):   # ecmc; Renishaw .rtl/.rta
        return "iso230-2"
    from axiscal.io.epics import looks_like_camonitor

    if looks_like_camonitor(stripped):         # an EPICS camonitor log of two PVs
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
        if "pose" in head and "c_deg" in head:
            return "fiveaxis-ballbar" if "deviation_um" in head else "fiveaxis"
        if {"position", "deviation"} <= head:
            return "straightness"
        if s.split(",")[0].strip().lower() == "time_s" and "reading" not in head:
            return "thermal"        # an ISO 230-3 log (a drift check is time_s,reading)
        break
    raise DataFormatError("not a data file the history knows: expected a positioning test, a "
                          "straightness, ballbar, diagonal, five-error, five-axis probing, "
                          "R-test, five-axis ballbar or ISO 230-3 thermal log CSV, axiscal "
                          "JSON, a volumetric configuration (TOML) with its errors inline, "
                          "or a squareness test from two straightness trajectories (TOML, "
                          "squareness biaxial --inline)")


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

    ds = parse_positioning(text, filename)
    return dataclasses.replace(positioning_record(ds), dataset_json=format_positioning_json(ds))


def positioning_record(ds, result=None, others: bool = True) -> Evaluated:
    """A positioning dataset evaluated by ISO 230-2:2014 (``result``: its evaluation already
    made, e.g. with the full turn merged) and, with ``others``, by every other positioning
    standard (``KEY:NAME`` parameters; the history's record has them, ``axiscal iso230-2``
    does not evaluate them)."""
    from axiscal.standards.iso230_2 import evaluate

    r = evaluate(ds) if result is None else result
    unit = r.deviation_unit
    params = {n: (getattr(r, n), unit) for n in
              ("A", "A_up", "A_down", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "B",
               "B_mean") if getattr(r, n) is not None and math.isfinite(getattr(r, n))}
    standards = None
    if others:
        more, standards = other_standards(ds)
        params.update(more)
    md = ds.metadata
    env = {k: v for k, v in dataclasses.asdict(md.environment).items() if v is not None}
    return Evaluated("iso230-2", ds.axis_kind.value, jsonable(r), params, "", md.machine, md.axis, md.date, md.operator,
                     md.instrument, jsonable(env), ds, r, standards)


def other_standards(ds) -> tuple[dict, dict]:
    """Every other positioning standard axiscal evaluates, from one evaluation of each:

    - the parameters, named ``KEY:NAME`` (``jis-b6192:R``), so compare and trend work for any
      standard a contract names;
    - the table a test's page shows: ``rows`` (standard, parameter, value, meaning; a parameter
      not evaluated has value None and its reason) and ``unpublished`` (the standards with no
      public definitions).
    """
    from axiscal.standards import positioning_standards as ps

    out, rows, unpublished = {}, [], []
    for std, res in ps.evaluate_all(ds):
        if std.key == "iso230-2:2014":
            continue
        if isinstance(res, str):  # no public definitions, or this test cannot form them
            if std.available:
                rows.append((std.title, "—", None, res))
            else:
                unpublished.append(std.title)
            continue
        rows += [row[:4] for row in ps.table_rows(std, res)]
        for name, (value, unit, _) in res.parameters().items():
            if value is not None and math.isfinite(value):
                out[f"{std.key}:{name}"] = (value, unit)
    return out, {"rows": rows, "unpublished": unpublished}


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

    d = parse_ballbar(text, source=filename)
    r = evaluate_ballbar(d)
    res = {"plane": "".join(d.axes), **r.as_dict()}
    return Evaluated("ballbar", "linear", jsonable(res), ballbar_parameters(r),
                     axis=res["plane"], dataset=d, evaluation=r)


def evaluate_ballbar(data, *, feed: float | None = None, axes: tuple[str, str] | None = None,
                     datum: str = ""):
    """The one evaluation of a ballbar test, whichever path it takes (``ballbar analyze``,
    ``squareness circular``, ``history add`` and ``show``, the workbench, archive import).

    Both directions: the full diagnosis
    (:func:`~axiscal.standards.ballbar_diagnosis.diagnose`), which holds the ISO 230-4:2005
    figures and what their simpler fit folds together. One direction: the diagnosis cannot
    separate backlash from squareness, so the ISO 230-4 evaluation
    (:func:`~axiscal.standards.iso230_4.evaluate_circular`) with its warning.

    Parameters
    ----------
    data : axiscal.io.ballbar.BallbarData
    feed : float or None, m/s
        Overrides the file's feed.
    axes : (str, str) or None
        Overrides the file's plane.
    datum : str
        Datum axis of the ISO 230-1 squareness sign.

    Returns
    -------
    BallbarDiagnosis or CircularResult
    """
    from axiscal.standards.ballbar_diagnosis import diagnose
    from axiscal.standards.iso230_4 import evaluate_circular

    axes = axes or data.axes
    if {r.direction for r in data.runs} == {"ccw", "cw"}:
        return diagnose(data.runs, data.radius, feed=data.feed if feed is None else feed,
                        axes=axes, datum=datum)
    return evaluate_circular(data.runs, data.radius, axes=axes, datum=datum)


#: Units of the diagnosis's JSON keys, by suffix (the store writes um, not µm).
_SUFFIX_UNITS = (("_um_per_m", "um/m"), ("_um", "um"), ("_ms", "ms"), ("_mm", "mm"),
                 ("_hz", "Hz"))


def ballbar_parameters(r) -> dict:
    """A ballbar evaluation's summary parameters (name -> (value, unit)) for compare and trend:
    every diagnosed term by its JSON key without the unit, G and H of ISO 230-4:2005, and the
    ISO 230-4 fit's own squareness, scale mismatch and backlash as ``iso230-4:NAME``."""
    circ = getattr(r, "circular", r)
    c = circ.as_dict()
    params = {"H": (c["H_um"], "um"), "G_ccw": (c["G_ccw_um"], "um"),
              "G_cw": (c["G_cw_um"], "um")}
    simple = {"squareness": (c["squareness"]["um_per_m"], "um/m"),
              "scale_mismatch": (c["scale_mismatch_um_per_m"], "um/m"),
              "backlash_x": (c["backlash_x_um"], "um"), "backlash_y": (c["backlash_y_um"], "um")}
    if circ is r:                       # one direction: the ISO 230-4 figures are the result
        params.update(simple)
    else:
        params.update({f"iso230-4:{k}": v for k, v in simple.items()})
        for key, value in r.values.items():
            suffix, unit = next(((s, u) for s, u in _SUFFIX_UNITS if key.endswith(s)))
            name = key[:-len(suffix)]
            params[key if name in params else name] = (value, unit)   # vibration, vibration_hz
        params["residual_rms"] = (r.residual_rms * 1e6, "um")
    return {k: (float(v), u) for k, (v, u) in params.items()
            if v is not None and math.isfinite(v)}


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
    from axiscal.standards.iso230_7_uncertainty import motion_parameters

    d = parse_motion_errors(text, source=filename)
    r = evaluate(d)
    params = motion_parameters(r)   # as ``axiscal motion analyze --json`` writes them: one answer
    res = {"title": d.title, "n_runs": r.n_runs,
           "motions": [{"name": m.name, "kind": m.kind, "total": m.total,
                        "synchronous": m.synchronous, "asynchronous": m.asynchronous}
                       for m in r.motions]}
    return Evaluated("motion", "rotary", jsonable(res), params, dataset=d, evaluation=r)


@dataclass(frozen=True)
class IdentificationBudget:
    """The uncertainty of a five-axis identification in the shape the quantities read
    (:func:`~axiscal.standards.quantities.make_quantities`): ``U(name)`` in µm or µrad, ``k``,
    ``to_json()``: each error's standard uncertainty by input (JCGM 100:2008 5.1.3: the
    residual, the probe's offset, the R-test's gains and directions) as the identification
    gives it (:attr:`~axiscal.standards.location_errors.LocationError.components`)."""

    result: object
    method: str = "least squares, JCGM 100:2008 5.1.3"

    @property
    def k(self) -> float:
        return self.result.errors[0].k if self.result.errors else 2.0

    def U(self, name: str) -> float | None:
        return next((e.U_display for e in self.result.errors if e.name == name), None)

    def U_text(self, name: str) -> str:
        U = self.U(name)
        return "—" if U is None else f"{U:.3f}"

    def to_json(self) -> dict:
        return {"method": self.method, "k": self.k,
                "u_components": {e.name: {k: v * 1e6 for k, v in e.components.items()}
                                 for e in self.result.errors}}


def _fiveaxis(text: str, filename: str) -> Evaluated:
    """A probing or R-test CSV that states its machine's nominal geometry (``#
    tilt_position_mm``, ``# c_position_mm``): the location errors by
    :func:`~axiscal.standards.location_errors.identify_location_errors`, as ``axiscal fiveaxis
    identify`` gives them with that geometry (the axes' travel is not in the file and not
    checked here)."""
    from axiscal.io.five_axis import parse_five_axis, parse_five_axis_geometry
    from axiscal.standards.location_errors import identify_location_errors

    geometry = parse_five_axis_geometry(text, filename)
    if geometry is None:
        raise DataFormatError("a five-axis test kept in the history states its machine's "
                              "nominal geometry: add '# tilt_position_mm = ..' and '# "
                              "c_position_mm = ..' (mm) before the header", filename)
    rec = parse_five_axis(text, source=filename)
    try:
        r = identify_location_errors(geometry, [rec.setup()])
    except InputError as exc:
        raise InputError(f"{filename}: {exc}") from None
    params = {e.name: (e.value_display, "urad" if e.unit == "µrad" else "um")
              for e in r.errors}
    params["residual_rms"] = (r.residual_rms * 1e6, "um")
    res = {**r.to_dict(), "tilt_axis": geometry.tilt, "kind_of_test": rec.kind,
           "label": rec.label, "convention": r.plan.convention,
           "tilt_position_mm": [v * 1e3 for v in geometry.tilt_position],
           "c_position_mm": [v * 1e3 for v in geometry.c_position]}
    return Evaluated("fiveaxis", "rotary", jsonable(res), params, axis=f"{geometry.tilt}C",
                     instrument="touch probe" if rec.kind == "probing" else "R-test",
                     dataset=rec, evaluation=r)


def _fiveaxis_ballbar(text: str, filename: str) -> Evaluated:
    """A five-axis ballbar CSV (:mod:`axiscal.io.five_axis_ballbar`): the range of its readings
    with U by the record's one evaluation
    (:meth:`~axiscal.procedures.five_axis_ballbar.BallbarRecord.evaluate`, the call of
    ``axiscal fiveaxis ballbar evaluate``); the stored result is that command's ``--json``
    set-up (:meth:`~axiscal.procedures.five_axis_ballbar.BallbarRecord.result_dict`), the
    range (µm) its parameter, with the range's own budget (k = 2)."""
    from axiscal.io.five_axis_ballbar import parse_ballbar

    rec = parse_ballbar(text, source=filename)
    try:
        r = rec.evaluate()
    except InputError as exc:
        raise InputError(f"{filename}: {exc}") from None
    return Evaluated("fiveaxis-ballbar", "rotary", jsonable(rec.result_dict(r)),
                     {"range": (r.range * 1e6, "um")}, axis=f"{rec.tilt}C",
                     instrument="ballbar", dataset=rec, evaluation=r)


#: The store's unit names of the ISO 230-3 figures' display units (ASCII, as the store writes).
_THERMAL_UNITS = {"µm": "um", "µrad": "urad", "K": "K", "µm/m": "um/m", "h": "h"}


@dataclass(frozen=True)
class ThermalBudget:
    """The U of an ISO 230-3 test's figures in the shape the quantities read
    (:func:`~axiscal.standards.quantities.make_quantities`): ``U(name)`` in the figure's display
    unit (the number of ``thermal evaluate --json``) and ``k`` = 2, as
    :mod:`axiscal.standards.iso230_3` gives them (the sensors' noise from
    their sample-to-sample steps; an extreme's bias added; sensor calibration not included)."""

    result: object
    method: str = ("ISO 230-3:2020 figures: reading noise from sample-to-sample steps, u = "
                   "sqrt(2) sigma, an extreme's bias added; sensor calibration not included")
    k: float = 2.0
    #: The log the figures came from (:class:`~axiscal.standards.iso230_3_data.ThermalLog`):
    #: each channel's reading noise σ, the budget's inputs (None: not listed).
    log: object = None

    def U(self, name: str) -> float | None:
        """U of figure ``name`` as ``thermal evaluate --json`` writes it (None: no such figure)."""
        return next((f["U"] for f in self.result.to_dict()["figures"] if f["name"] == name),
                    None)

    def U_text(self, name: str) -> str:
        U = self.U(name)
        return "—" if U is None else f"{U:.3f}"

    def to_json(self) -> dict:
        """``method``, ``k`` and ``inputs``: each channel's reading noise σ (µm, or °C for a
        temperature sensor) by :func:`~axiscal.standards.iso230_3_data.noise_sigma`, the
        one estimate the figures' U are made from."""
        out = {"method": self.method, "k": self.k}
        if self.log is not None:
            from axiscal.standards.iso230_3_data import noise_sigma

            rule = "measured: the channel's sample-to-sample steps (robust)"
            out["inputs"] = {
                **{f"sigma_{c}": {"label": f"reading noise σ of {c}", "unit": "µm",
                                  "value": noise_sigma(v) * 1e6, "assumed": False, "rule": rule}
                   for c, v in self.log.displacements.items()},
                **{f"sigma_{c}": {"label": f"reading noise σ of {c}", "unit": "°C",
                                  "value": noise_sigma(v), "assumed": False, "rule": rule}
                   for c, v in self.log.temperatures.items()}}
        return out


def _thermal(text: str, filename: str) -> Evaluated:
    """An ISO 230-3:2020 thermal test's log (:mod:`axiscal.io.thermal`): its figures by
    :func:`~axiscal.standards.iso230_3.evaluate_thermal`, the one call of ``axiscal thermal
    evaluate``; the stored result is that command's ``--json`` object (``to_dict()``), each
    figure a parameter in its display unit."""
    from axiscal.io.thermal import parse_thermal_log
    from axiscal.standards.iso230_3 import evaluate_thermal

    log = parse_thermal_log(text, source=filename)
    r = evaluate_thermal(log)
    d = r.to_dict()
    params = {f["name"]: (f["value"], _THERMAL_UNITS[f["unit"]]) for f in d["figures"]}
    return Evaluated("thermal", "rotary" if log.test == "rotary" else "linear",
                     jsonable(d), params, axis=log.axis or "",
                     dataset=log, evaluation=r)


def _volumetric(text: str, filename: str) -> Evaluated:
    """A volumetric configuration holding its 21 errors inline (:mod:`axiscal.io.volumetric`,
    ``base=None``): the map on the command's default 11³ grid and the body diagonals by
    :func:`axiscal.io.simulation_results.volumetric_map`, the one call of ``axiscal volumetric
    map``; the stored result is that command's ``--json`` object, the figures (largest |E|,
    each axis's range, each diagonal's range, in µm) its parameters. The evaluation is the
    ``VolumetricMap``, the dataset the command's run (its ``parts``: the configuration, the
    body diagonals, a simulation's truth), from which its figure and report are drawn."""
    from axiscal.io.simulation_results import volumetric_map
    from axiscal.io.volumetric import parse_volumetric_config

    return volumetric_record(volumetric_map(parse_volumetric_config(text, filename, base=None),
                                            VOLUMETRIC_GRID))


def volumetric_record(run) -> Evaluated:
    """A volumetric map's run (:func:`axiscal.io.simulation_results.volumetric_map`) as the
    record the history keeps of it (:func:`_volumetric`), with no budget yet
    (:func:`with_uncertainty` adds it): the one shape of ``volumetric map --json`` and of the
    stored test."""
    cfg, d = run.parts["config"], run.json
    params = {"largest": (d["largest_um"], "um"),
              **{f"range_{a}": (v, "um") for a, v in d["range_um"].items()},
              **{f"diagonal_{g['name']}": (g["range_um"], "um") for g in d["diagonals"]}}
    return Evaluated("volumetric", "linear", jsonable(d), params, machine=cfg.name, axis="XYZ",
                     dataset=run, evaluation=run.record)


def _squareness(text: str, filename: str) -> Evaluated:
    """A squareness test from two straightness trajectories (:mod:`axiscal.io.biaxial`, written
    by ``axiscal squareness biaxial --inline``): the squareness by
    :meth:`~axiscal.io.biaxial.BiaxialTest.evaluate`, the one call of ``squareness biaxial``
    (ISO 230-1:2012 §3.6.7; U by ISO/TR 230-9); the stored result is that command's ``--json``
    object, the squareness (µm/m) its parameter. Evaluated here with the budget's inputs all
    assumed; :func:`with_uncertainty` evaluates it again with the test's inputs."""
    from axiscal.io.biaxial import parse_biaxial_test

    return _squareness_record(parse_biaxial_test(text, filename), {})


def _squareness_record(test, inputs: dict) -> Evaluated:
    """The record of a :class:`~axiscal.io.biaxial.BiaxialTest` evaluated with ``inputs``."""
    b = test.evaluate(inputs)
    sq = b.result.squareness
    return Evaluated("squareness", "linear", jsonable(b.summary),
                     {"squareness": (sq.um_per_m, "um/m")}, machine=test.machine,
                     axis="".join(sq.axes), dataset=test, evaluation=b, budget=b.budget)


#: Grid points per axis of a stored volumetric test's map (``volumetric map``'s default).
VOLUMETRIC_GRID = 11


_EVALUATORS = {"iso230-2": _positioning, "straightness": _straightness, "ballbar": _ballbar,
               "diagonal": _diagonal, "motion": _motion, "fiveaxis": _fiveaxis,
               "thermal": _thermal, "volumetric": _volumetric,
               "fiveaxis-ballbar": _fiveaxis_ballbar, "squareness": _squareness}


def result_text(ev: Evaluated) -> str:
    """The evaluation as the command line prints it (for ``history show``)."""
    r = ev.evaluation
    return str(r) if r is not None else json.dumps(ev.result, indent=2)
