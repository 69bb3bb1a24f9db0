"""The evaluation, figure, report and notebook view of one test of any kind (public API).

:func:`positioning_evaluation` and :func:`ballbar_evaluation` give the fields of
:class:`axiscal.api.Evaluation` (the ``--json`` built by :mod:`axiscal.io.results`);
:func:`evaluation_figure` and :func:`write_evaluation_report` its ``plot()`` and ``report()``.

:func:`kind_figure` draws what the kind's command draws with ``--plot`` (``ballbar analyze``,
``straightness``, ``squareness diagonal --file``, ``motion analyze``); :func:`notebook_html` is
the ``_repr_html_`` of :class:`axiscal.api.Evaluation`: its scalar results, then its figure.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

__all__ = ["FIGURES", "kind_figure", "notebook_html", "positioning_evaluation",
           "ballbar_evaluation", "evaluation_figure", "write_evaluation_report", "KIND_STANDARD",
           "kind_of_file", "evaluated_file", "RECORD_KEYS", "uncertainty_tables"]

#: The key of ISO 230-2:2014, the standard of a positioning test unless another is named.
ISO230_2 = "iso230-2:2014"
#: The standard of each kind of test file (:func:`axiscal.store.kinds.detect_kind`).
KIND_STANDARD = {"iso230-2": ISO230_2, "straightness": "iso230-1", "ballbar": "iso230-4",
                 "diagonal": "iso230-6", "motion": "iso230-7", "fiveaxis": "iso230-7:location",
                 "thermal": "iso230-3", "volumetric": "iso-tr-16907",
                 "fiveaxis-ballbar": "iso10791-6"}
KIND_STANDARD["squareness"] = "iso230-1"      # squareness from two straightness profiles


#: The title of the report of each kind of test other than positioning.
REPORT_TITLES = {"straightness": "Straightness (ISO 230-1)",
                 "diagonal": "Diagonal squareness (ISO 230-6)",
                 "motion": "Error motions of a rotary axis (ISO 230-7)",
                 "ballbar": "Circular test (ISO 230-4)",
                 "thermal": "Thermal effects (ISO 230-3)",
                 "fiveaxis": "Five-axis location errors (ISO 230-1 / ISO 230-7)",
                 "volumetric": "Volumetric accuracy",
                 "fiveaxis-ballbar": "Five-axis ballbar test (ISO 10791-6 as axiscal reads it)"}
REPORT_TITLES["squareness"] = "Squareness from two straightness profiles (ISO 230-1)"


def kind_of_file(path: Any) -> str:
    """The kind of test a data file holds, told by its content (as the history does); a
    Renishaw export in UTF-16 or a Windows code page is a positioning test, as
    :func:`axiscal.io.read_positioning` reads it."""
    from axiscal.errors import DataFormatError
    from axiscal.io import read_text
    from axiscal.store.kinds import detect_kind

    try:
        return detect_kind(read_text(path))
    except DataFormatError:
        from axiscal.io import detect
        from axiscal.io._files import read_bytes
        from axiscal.io.renishaw import decode

        try:
            if detect.looks_like_renishaw(decode(read_bytes(path), None, str(path))[0]):
                return "iso230-2"
        except DataFormatError:
            pass
        raise


def evaluated_file(path: Any, kind: str) -> Any:
    """A data file of ``kind`` evaluated as the history evaluates it (one evaluation per kind)."""
    from axiscal.store.kinds import evaluate_file

    return evaluate_file(Path(path).read_bytes(), Path(path).name, kind)


def kind_figure(kind: str, dataset: Any, result: Any) -> Any:
    """The matplotlib Figure of a ``ballbar``, ``straightness``, ``diagonal`` or ``motion``
    evaluation (:data:`FIGURES`)."""
    return FIGURES[kind](dataset, result)


def _ballbar_figure(data: Any, r: Any) -> Any:
    """Both directions: the diagnosis's polar plot and ranked terms; one: the ISO 230-4 plot."""
    if hasattr(r, "circular"):
        from axiscal.report.ballbar_plots import diagnosis_figure

        return diagnosis_figure(data.runs, r)
    from axiscal.report.squareness_plots import ballbar_figure

    return ballbar_figure(data.runs, r)


def _straightness_figure(data: Any, r: Any) -> Any:
    from axiscal.report.squareness_plots import straightness_figure

    return straightness_figure(data, r)


def _diagonal_figure(data: Any, r: Any) -> Any:
    from axiscal.report.squareness_plots import diagonal_figure

    return diagonal_figure(data, r)


def _motion_figure(data: Any, r: Any) -> Any:
    from axiscal.report.motion_plots import polar_figure

    return polar_figure(r)


#: The figure of each kind other than a positioning test: the one its command's --plot draws.
def _thermal_figure(log: Any, r: Any) -> Any:
    """``axiscal thermal evaluate --plot``'s figure: drifts and temperatures over time."""
    from axiscal.report.thermal_plots import plot_thermal

    return plot_thermal(log)


def _volumetric_figure(run: Any, vmap: Any) -> Any:
    """``axiscal volumetric map --plot``'s figure: the grid magnified and the |E| slices."""
    from axiscal.report.volumetric_plots import volumetric_figure

    return volumetric_figure(vmap, f"Volumetric error map — {run.parts['config'].name}")


def _fiveaxis_ballbar_figure(record: Any, r: Any) -> Any:
    """A five-axis ballbar set-up's readings along its path with the range and U."""
    from axiscal.report.five_axis_plots import ballbar_path_figure

    return ballbar_path_figure(record, r)


def _squareness_figure(test: Any, b: Any) -> Any:
    """``axiscal squareness biaxial --plot``'s figure: both trajectories with their lines."""
    from axiscal.report.squareness_plots import biaxial_figure

    return biaxial_figure(test.one, test.two, b.result, test.title)


FIGURES = {"ballbar": _ballbar_figure, "straightness": _straightness_figure,
           "diagonal": _diagonal_figure, "motion": _motion_figure, "thermal": _thermal_figure,
           "volumetric": _volumetric_figure, "fiveaxis-ballbar": _fiveaxis_ballbar_figure}
FIGURES["squareness"] = _squareness_figure


#: A kind of test in words, as the reports head it.
KIND_WORDS = {"iso230-2": "Positioning test", "positioning": "Positioning test",
              "standards": "Positioning test", "ballbar": "Ballbar test",
              "straightness": "Straightness", "diagonal": "Squareness by diagonals",
              "motion": "Motion errors of a rotary axis",
              "thermal": "Thermal test (ISO 230-3)",
              "volumetric": "Volumetric accuracy (ISO/TR 16907)",
              "fiveaxis-ballbar": "Five-axis ballbar test (ISO 10791-6)"}
KIND_WORDS["squareness"] = "Squareness from two straightness profiles"


def notebook_html(kind: str, standard: str, d: dict, fig: Any, quantities: Any = None) -> str:
    """A notebook's view: the quantities with their U and verdict (or, for a simulation, the
    scalar results), labelled and to the decimals of the reports (:mod:`axiscal.report.labels`),
    then the figure (SVG)."""
    from html import escape

    from axiscal.report.html import figure_svg
    from axiscal.report.labels import fmt, quantity
    from axiscal.standards.positioning_standards import STANDARDS
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    rows = []
    if quantities:
        rows.append("<tr><th>quantity</th><th>value</th><th>U</th><th>k</th><th>verdict</th></tr>")
        for q in quantities.values():
            name, u = quantity(q.name, q.unit)
            head = f"{q.symbol if q.symbol != q.name else name} [{u}]" if u else name
            rows.append(f"<tr><th>{escape(head)}</th><td>{escape(fmt(q.value, u))}</td>"
                        f"<td>{escape(format_uncertainty(q.U))}</td>"
                        f"<td>{'' if q.k is None else f'{q.k:g}'}</td>"
                        f"<td>{escape(q.verdict or '')}</td></tr>")
        for k, v in d.items():          # what the test is: machine, axis, runs ...
            if (k in quantities or k in ("unit", "schema_version")
                    or not isinstance(v, (int, str)) or isinstance(v, bool)):
                continue
            name, _ = quantity(str(k))
            rows.append(f"<tr><th>{escape(name)}</th><td colspan='4'>{escape(fmt(v))}</td></tr>")
    else:
        unit = d.get("unit") if isinstance(d.get("unit"), str) else None
        for k, v in d.items():
            if k == "unit" or not (isinstance(v, (int, float, str)) or v is None):
                continue
            # the result's unit belongs to its deviations, not to counts, flags and texts
            own = unit if isinstance(v, float) or v is None else None
            name, u = quantity(str(k), own)
            head = f"{name} [{u}]" if u else name
            rows.append(f"<tr><th>{escape(head)}</th><td>{escape(fmt(v, u))}</td></tr>")
    title = STANDARDS[standard].title if standard in STANDARDS else standard
    what = KIND_WORDS.get(kind, kind.replace("-", " ").capitalize())
    warns = "".join(f"<li>{escape(str(w))}</li>" for w in d.get("warnings") or ())
    return (f"<div><p><b>{escape(what)}</b> by {escape(title)}</p>"
            f"<table>{''.join(rows)}</table>{f'<ul>{warns}</ul>' if warns else ''}"
            f"{figure_svg(fig)}</div>")


def evaluation_text(ev: Any) -> str:
    """``str()`` of an :class:`axiscal.api.Evaluation`: an ISO 230-2:2014 result by its
    symbols with each U (k) and verdict beside its value, then its warnings; another kind as
    its command prints it, then the quantities that have a U."""
    qs = ev.quantities
    if ev.kind == "iso230-2" and ev.standard == ISO230_2:
        from axiscal import units

        head, *rest = str(ev.result).splitlines()
        lines = [head]
        for name in ev.result.parameters():
            q = qs.get(name)
            if q is None:
                continue
            pad = " " * (3 - len(q.symbol.replace("\u0304", "")))
            if q.value is None:
                lines.append(f"  {q.symbol}{pad}= n/a")
                continue
            text = f"  {q.symbol}{pad}= {q.value:8.2f} {units.display(q.unit)}"
            if q.U is not None:
                from axiscal.standards.uncertainty_reporting import format_uncertainty

                text += f"   U = {format_uncertainty(q.U)} {units.display(q.unit)} (k = {q.k:g})"
            if q.verdict:
                text += f"   {q.verdict}"
            lines.append(text)
        lines += [w for w in rest if w.startswith("  warning:")]
        return "\n".join(lines)
    text = str(ev.result)
    with_u = [str(q) for q in qs.values() if q.U is not None]
    return text + ("\n" + "\n".join(with_u) if with_u else "")


def positioning_evaluation(ds: Any, key: str, tolerances: dict, rule: str | None,
                           uncertainty: dict, *, form: str = "iso230-2", job: Any = None,
                           drift_check: Any = None, full_turn: str = "separate") -> dict:
    """The fields of :class:`axiscal.api.Evaluation` of a positioning test by the standard
    ``key`` of :data:`axiscal.standards.positioning_standards.STANDARDS` (or ``all``): in the
    ``standards`` form as ``axiscal evaluate --standard KEY --json``, in the ``iso230-2`` form
    (ISO 230-2:2014 only) as ``axiscal iso230-2 --json``."""
    from axiscal.errors import InputError

    if key not in (ISO230_2, "all"):   # ISO 230-2:2014 is known without importing the others
        from axiscal.standards import positioning_standards as ps

        if key not in ps.STANDARDS:
            raise InputError(f"standard {key!r}: one of {', '.join(ps.STANDARDS)} or all")
    if form == "iso230-2":
        if key != ISO230_2:
            raise InputError(f"form iso230-2 is the object of 'axiscal iso230-2', ISO 230-2:2014's"
                             f"; {key} gives the standards form")
        return _iso230_2(ds, tolerances, rule, uncertainty, job, drift_check, full_turn)
    if job is not None or drift_check is not None or full_turn != "separate":
        raise InputError("job, drift_check and full_turn are those of 'axiscal iso230-2': "
                         "ISO 230-2:2014 in the iso230-2 form")
    if key == "all" and tolerances:
        raise InputError("tolerances need one standard (parameter names differ between them)")
    return _by_standards(ds, key, tolerances, rule, uncertainty or None)


def _in_file_unit(ds: Any, results: Any) -> dict | None:
    """Each standard's parameters in the deviation unit, in a ``.rta`` file's own µrad
    (:func:`axiscal.io.rta_unit.file_unit_block`); None for any other dataset."""
    from axiscal.io.rta_unit import file_unit_block

    blocks = {std.key: file_unit_block(ds.metadata.notes, {
        name: v for name, (v, u, _) in res.parameters().items() if u == ds.deviation_unit})
        for std, res in results if not isinstance(res, str)}
    if not blocks or None in blocks.values():
        return None
    return {"deviation_unit": "urad", "source": "the .rta file's unit",
            "standards": {k: b["parameters"] for k, b in blocks.items()}}


def _by_standards(ds: Any, key: str, tolerances: dict, rule: str | None, table: Any) -> dict:
    """As ``axiscal evaluate --standard KEY --json``: each standard's parameters, the decisions
    and, where they have a U (ISO 230-2:2014 only), its Annex A budget."""
    import math

    from axiscal.errors import InputError
    from axiscal.io.results import standard_json, verdicts_json
    from axiscal.standards import positioning_standards as ps

    results = (ps.evaluate_all(ds) if key == "all"
               else ((ps.STANDARDS[key], ps.evaluate(key, ds)),))
    first = results[0][1]
    record = None
    if key == ISO230_2:   # its own result and Annex A budget: the figure and the report's
        from axiscal.store.kinds import positioning_record, with_uncertainty

        record = with_uncertainty(positioning_record(ds, others=False), table)
    verdicts: tuple = ()
    if tolerances:
        if isinstance(first, str):
            raise InputError(f"tolerances: {key} was not evaluated: {first}")
        verdicts = tuple(ps.check_tolerances(key, ds, first, tolerances, rule, table,
                                             budget=record and record.budget))
    d = {"unit": ds.deviation_unit, "target_unit": ds.target_unit,
         "standards": [standard_json(std, res) for std, res in results]}
    in_file = _in_file_unit(ds, results)
    if in_file is not None:     # a .rta: shown in arcsec, the file's µrad kept (issue 42)
        d["in_file_unit"] = in_file
    if verdicts:
        from axiscal.standards.iso14253_1 import unprovable

        d.update(verdicts_json(verdicts))
        d["warnings"] = unprovable(verdicts, {"um": "µm"}.get(ds.deviation_unit,
                                                             ds.deviation_unit))
    result, budget = first, None
    if record is not None:
        result, budget = record.evaluation, record.budget
        quantities = replace(record, verdicts=verdicts).quantities
        if any(not math.isnan(v.U) for v in verdicts):
            d["uncertainty_budget"] = budget.to_json([v.parameter for v in verdicts])
    else:
        quantities = _standards_quantities(results, verdicts)
    from axiscal.standards.quantities import quantities_json

    d.update(quantities_json(quantities), uncertainty_inputs=dict(table or {}))
    return dict(kind="iso230-2", standard=key, dataset=ds, result=result, _json=d,
                _budget=budget, _verdicts=verdicts, _results=tuple(results),
                _quantities=quantities)


def _standards_quantities(results: Any, verdicts: tuple) -> dict:
    """The quantities of positioning standards other than ISO 230-2:2014 (no published budget
    gives their U): one standard's by its names, ``all`` as ``KEY:NAME``."""
    import math

    from axiscal.standards.quantities import make_quantities

    params = {}
    for std, res in results:
        if isinstance(res, str):
            continue
        for name, (v, u, _) in res.parameters().items():
            if v is not None and math.isfinite(v):
                params[name if len(results) == 1 else f"{std.key}:{name}"] = (v, u)
    return make_quantities(params, None, verdicts)


def _iso230_2(ds: Any, tolerances: dict, rule: str | None, uncertainty: dict, job: Any,
              drift_check: Any, full_turn: str) -> dict:
    """As ``axiscal iso230-2 FILE --json``: the user configuration, the job file over it, then
    E_VE measured by a drift check (ISO 230-2:2014 Annex A.5) and the uncertainty inputs."""
    from axiscal.report.issue import decisions_for, load_config
    from axiscal.standards.iso230_2 import check_tolerances
    from axiscal.standards.iso230_2 import evaluate as iso_evaluate
    from axiscal.store.kinds import inputs_from_config, positioning_record, with_uncertainty

    result = iso_evaluate(ds, full_turn=full_turn)  # type: ignore[arg-type]
    if isinstance(job, dict):   # a job's tables already read (axiscal.api: a dict job)
        from axiscal.io.user_config import merge

        cfg = merge(load_config(None), job)
    else:
        cfg = load_config(None if job is None else Path(job))
    if uncertainty or drift_check is not None:
        table = dict(cfg.get("uncertainty") or {})
        if drift_check is not None:
            table.update(_drift_e_ve(drift_check, uncertainty))
        cfg = {**cfg, "uncertainty": {**table, **uncertainty}}
    check_tolerances(result, {**cfg.get("tolerance", {}), **tolerances})
    record = with_uncertainty(positioning_record(ds, result, others=False),
                              inputs_from_config("iso230-2", cfg, ds))
    verdicts, _, _ = decisions_for(result.parameters(), record.budget, tolerances, cfg, rule)
    return record_fields(replace(record, verdicts=tuple(verdicts)), _config=cfg)


def record_fields(record: Any, **extra: Any) -> dict:
    """The fields of :class:`axiscal.api.Evaluation` of one test's record
    (:class:`axiscal.store.kinds.Evaluated` with its budget): the one way an evaluation is
    made from a record, for :func:`axiscal.evaluate`, ``History.evaluation`` and the commands.
    A positioning test's ``to_dict()`` is the object of ``axiscal iso230-2 --json``; every
    kind's carries the ``quantities`` block (:mod:`axiscal.standards.quantities`)."""
    from axiscal._json import jsonable
    from axiscal.standards.quantities import quantities_json

    quantities = record.quantities
    if record.kind == "iso230-2":   # by ISO 230-2:2014: the history's KEY:NAME of the others
        from axiscal.io.results import result_json   # are left to ``evaluate --standard all``

        quantities = {k: q for k, q in quantities.items() if ":" not in k}
        ds = record.dataset
        d = {**result_json(record.evaluation, record.verdicts, record.budget),
             "machine": ds.metadata.machine, "axis": ds.metadata.axis, "notes": ds.metadata.notes}
        from axiscal.io.rta_unit import file_unit_block

        block = file_unit_block(ds.metadata.notes, record.evaluation.parameters())
        if block is not None:       # a .rta: shown in arcsec, the file's µrad kept (issue 42)
            d["in_file_unit"] = block
    else:
        d = dict(record.result)
        if record.budget is not None:
            d["uncertainty_budget"] = jsonable(record.budget.to_json())
    d.update(quantities_json(quantities), uncertainty_inputs=jsonable(record.inputs))
    fields = dict(kind=record.kind, standard=KIND_STANDARD[record.kind], dataset=record.dataset,
                  result=record.evaluation, _json=d, _budget=record.budget,
                  _verdicts=tuple(record.verdicts), _quantities=quantities,
                  _config={"uncertainty": dict(record.inputs)})
    fields.update(extra)
    return fields


def _drift_e_ve(drift_check: Any, uncertainty: dict) -> dict:
    """E_VE, the range of a drift check's readings (ISO 230-2:2014 Annex A.5), as inputs."""
    from axiscal.errors import InputError
    from axiscal.io._files import read_bytes
    from axiscal.store.kinds import drift_check_record

    if "e_ve" in uncertainty:
        raise InputError("E_VE is given twice: by the drift check (--drift-check) and by the "
                         "uncertainty input e_ve (--uncertainty e_ve); give one")
    rec = drift_check_record(read_bytes(drift_check), str(drift_check))
    return {"e_ve": rec["e_ve"], "e_ve_source": rec["e_ve_source"]}


def ballbar_evaluation(data: Any, *, feed: float | None = None,
                       plane: str | None = None, uncertainty: dict | None = None) -> dict:
    """The fields of :class:`axiscal.api.Evaluation` of a ballbar dataset evaluated in memory
    (ISO 230-4:2005 and the diagnosis; ``feed`` mm/min and ``plane`` over the file's, as
    ``axiscal ballbar analyze --feed --plane``), with the budget of G and H made from
    ``uncertainty`` (the ``[ballbar_uncertainty]`` inputs) by the one
    :func:`~axiscal.store.kinds.with_uncertainty`; the other kinds are evaluated from their
    file."""
    from axiscal.errors import InputError
    from axiscal.io.ballbar import BallbarData
    from axiscal._json import jsonable
    from axiscal.store.kinds import (Evaluated, ballbar_parameters, evaluate_ballbar,
                                     with_uncertainty)

    if not isinstance(data, BallbarData):
        raise InputError(f"evaluate: give the file's path for a {type(data).__name__} "
                         "(a positioning or ballbar dataset is evaluated in memory)")
    if feed is not None and not feed > 0:
        raise InputError(f"feed (--feed) {feed:g}: must be a positive feed in mm/min")
    axes = data.axes
    if plane is not None:
        if plane.upper() not in ("XY", "YZ", "ZX"):
            raise InputError(f"plane (--plane) {plane!r}: choose XY, YZ or ZX")
        axes = (plane.upper()[0], plane.upper()[1])
    r = evaluate_ballbar(data, feed=None if feed is None else feed / 6e4, axes=axes)
    res = jsonable({"plane": "".join(axes), **r.as_dict()})
    return record_fields(with_uncertainty(Evaluated(
        "ballbar", "linear", res, ballbar_parameters(r), axis=res["plane"], dataset=data,
        evaluation=r), uncertainty))


def evaluation_figure(ev: Any) -> Any:
    """The figure of an :class:`axiscal.api.Evaluation`, as its command's ``--plot`` draws it."""
    from axiscal.errors import InputError

    if ev.kind == "iso230-2":
        from axiscal.report import plots

        if ev.standard == ISO230_2:
            return plots.iso230_2_figure(ev.result, ev.dataset)
        fig = (plots.standards_figure(ev.dataset, ev._results) if ev.standard == "all"
               else plots.standard_figure(ev.dataset, *ev._results[0]))
        if fig is None:
            raise InputError("plot: no standard evaluates this test, so there is no figure")
        return fig
    return kind_figure(ev.kind, ev.dataset, ev.result)


def write_evaluation_report(ev: Any, path: Path, title: str | None = None) -> Path:
    """Write the HTML report of an :class:`axiscal.api.Evaluation`, as the command's
    ``--report``; returns the path."""
    from axiscal.report.html import positioning_report, standards_report, write_result_report

    if ev.kind == "iso230-2" and ev.standard == ISO230_2:
        from axiscal.report.uncertainty import add_uncertainty

        rep = positioning_report(ev.dataset, ev.result, verdicts=ev._verdicts)
        add_uncertainty(rep, ev._budget, ev._verdicts,
                        [p for p, v in ev.result.parameters().items() if v is not None])
        return rep.write(path)
    if ev.kind == "iso230-2":
        what = ("every positioning standard" if ev.standard == "all"
                else ev._results[0][0].title)
        return standards_report(ev.dataset, ev._results, title or f"Positioning test by {what}",
                                ev._verdicts).write(path)
    if ev.kind == "ballbar" and hasattr(ev.result, "circular"):
        from axiscal.report.ballbar_plots import write_diagnosis_report

        kw = {} if title is None else {"title": title}
        return write_diagnosis_report(path, ev.dataset.runs, ev.result, **kw)
    if ev.kind == "thermal":        # ``axiscal thermal evaluate --report``'s report
        from axiscal.report.thermal_plots import thermal_report

        rep = thermal_report(ev.dataset, ev.result)
        if title is not None:
            rep.title = title
        return rep.write(path)
    if ev.kind == "volumetric":     # ``axiscal volumetric map --report``'s report
        from axiscal.report.volumetric_plots import volumetric_report

        run = ev.dataset
        cfg = run.parts["config"]
        rep = volumetric_report(ev.result, run.parts["diagonals"], cfg.errors, name=cfg.name,
                                truth=run.parts["truth"], budget=ev.budget)
        if title is not None:
            rep.title = title
        return rep.write(path)
    if ev.kind == "squareness":     # ``axiscal squareness biaxial --report``'s report
        from axiscal.report.squareness_plots import write_biaxial_report

        t = ev.dataset
        return write_biaxial_report(path, t.one, t.two, ev.result,
                                    title or f"{t.one.source}, {t.two.source}", t.config,
                                    t.orientation)
    if ev.kind == "fiveaxis":       # ``axiscal fiveaxis identify --report``'s report
        from axiscal.physics.rotary_location import Geometry
        from axiscal.report.five_axis_plots import location_report

        d = ev._json                # the stored record states the nominal geometry it used
        geometry = Geometry(d["tilt_axis"], tuple(v * 1e-3 for v in d["tilt_position_mm"]),
                            tuple(v * 1e-3 for v in d["c_position_mm"]))
        rep = location_report(geometry, ev.result, name=ev.dataset.label or "five-axis test")
        if title is not None:
            rep.title = title
        return rep.write(path)
    if ev.kind == "fiveaxis-ballbar":   # ``axiscal fiveaxis ballbar evaluate --report``'s
        from axiscal.report.five_axis_ballbar import ballbar_report

        return ballbar_report([(ev.dataset, ev.result)], title=title or
                              f"{REPORT_TITLES[ev.kind]} — {ev.result.label}").write(path)
    title = title or REPORT_TITLES[ev.kind]
    if ev.kind == "straightness":   # ``axiscal straightness --report``'s tables of U
        shown = {k: v for k, v in ev._json.items() if k not in RECORD_KEYS}
        return write_result_report(path, title, shown, tables=uncertainty_tables(ev._json),
                                   figure=evaluation_figure(ev))
    return write_result_report(path, title, ev._json, figure=evaluation_figure(ev))


#: The keys of a record's JSON that hold its U (:func:`record_fields`), which a report shows as
#: :func:`uncertainty_tables`, not as raw values.
RECORD_KEYS = ("schema_version", "quantities", "uncertainty_budget", "uncertainty_inputs")


def uncertainty_tables(d: dict) -> list:
    """A report's tables of a record's U (``d``: its JSON, :func:`record_fields`, with an
    ISO/TR 230-9 budget listing its inputs): each figure with U and k, and the budget's inputs
    in words, each measured, given or assumed with its rule, as ``(caption, headers, rows)``
    of :func:`axiscal.report.html.write_result_report`. ``axiscal straightness --report`` and
    a stored straightness test's report show these."""
    from axiscal.report.labels import quantity
    from axiscal.standards.uncertainty_reporting import format_value
    from axiscal.units import display

    b = d["uncertainty_budget"]
    figures = [(quantity(n)[0], format_value(q["value"], q["U"]), b["U_display"][n],
                f"{q['k']:g}", display(q["unit"])) for n, q in d["quantities"].items()
               if q.get("U") is not None]
    inputs = [(i["label"], f"{i['value']:g} {i['unit']}".strip(),
               "assumed" if i["assumed"] else "measured" if i["rule"].startswith("measured")
               else "given", i["rule"].removeprefix("measured: ")) for i in b["inputs"].values()]
    return [(f"Expanded uncertainty ({b['method']})", ["figure", "value", "U", "k", "unit"],
             figures),
            ("Inputs of the uncertainty budget (set in the user configuration's table of the "
             "kind's uncertainty inputs)", ["input", "value", "", "rule or source"], inputs)]
