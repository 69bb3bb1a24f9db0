"""The public Python API: the only stable surface of axiscal.

Everything a script or a notebook needs is at the package's top and documented here::

    import axiscal

    ds = axiscal.read("x_axis.csv")     # format told by the content
    ev = axiscal.evaluate(ds)           # ISO 230-2:2014 by default
    ev.to_dict()                        # the keys of ``axiscal iso230-2 --json``
    ev.plot()                           # a matplotlib Figure
    ev.report("x_axis.html")            # the HTML report
    table = axiscal.compensation_table(ev, spacing=10)
    axiscal.write_table(table, "siemens-840d", "x.ini")
    with axiscal.History("sqlite:///history.sqlite") as h:
        h.add("x_axis.csv", machine="VMC-1")

The functions are thin: every number comes from the same library code the command line and the
workbench call (:func:`axiscal.store.kinds.evaluate_file` is the one evaluation per kind of test,
:mod:`axiscal.standards.positioning_standards` the registry of positioning standards, and
:mod:`axiscal.io.results` builds the ``--json`` objects), so a result here equals the command's
``--json`` for the same file. Modules below this one may change between releases; this one
changes only with a note in CHANGELOG.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Union

if TYPE_CHECKING:   # pragma: no cover - typing only
    from matplotlib.figure import Figure

__all__ = ["Evaluation", "Simulation", "History", "read", "evaluate", "simulate",
           "compensation_table", "write_table"]

PathLike = Union[str, Path]

#: The standard :func:`evaluate` applies when none is named.
DEFAULT_STANDARD = "iso230-2:2014"


def read(path: PathLike, *, target_unit: str | None = None,
         deviation_unit: str | None = None) -> Any:
    """Read any data file axiscal knows into its dataset, the format told by its content.

    Parameters
    ----------
    path : str or Path
        A positioning test (tidy CSV, axiscal JSON, Renishaw .rtl/.rta, EPICS ecmc or camonitor
        log), a straightness, ballbar, diagonal or five-error CSV.
    target_unit, deviation_unit : str, optional
        Units of a positioning CSV that does not declare them (mm/deg; um/mm/arcsec).

    Returns
    -------
    PositioningDataset, BallbarData, StraightnessData, DiagonalData or MotionErrorData
        The frozen dataset, in the units its file declares.

    Raises
    ------
    axiscal.errors.DataFormatError
        A file of no kind axiscal knows, or one that does not parse.
    """
    kind = _kind_of(path)
    if kind == "iso230-2":
        from axiscal.io import read_positioning

        return read_positioning(path, target_unit=target_unit, deviation_unit=deviation_unit)
    return _evaluated(path, kind).dataset


def evaluate(data: Any, standard: str = DEFAULT_STANDARD, *,
             tolerances: Mapping[str, float] | None = None,
             rule: str | None = None,
             uncertainty: Mapping[str, float | str] | None = None) -> "Evaluation":
    """Evaluate a dataset (or a data file) by its standard.

    Parameters
    ----------
    data : dataset or str or Path
        What :func:`read` returns, or a path to read.
    standard : str
        For a positioning test, a key of
        :data:`axiscal.standards.positioning_standards.STANDARDS` (default ``iso230-2:2014``)
        or ``all``. The other kinds have one standard each (ISO 230-1 straightness, ISO 230-4
        ballbar diagnosis, ISO 230-6 diagonal squareness, ISO 230-7 motion errors) and ignore it.
    tolerances : mapping of str to float, optional
        Acceptance tolerances by parameter name in the deviation unit (positioning tests only),
        decided by ISO 14253-1:2017 with U of ISO 230-2:2014 Annex A, as ``--tolerance`` does.
    rule : str, optional
        Decision rule, ``iso14253-1`` (default) or ``simple``.
    uncertainty : mapping, optional
        Inputs of the ISO 230-2:2014 Annex A uncertainty budget by name, over the user
        configuration's ``[uncertainty]`` table, as ``--uncertainty NAME=VALUE`` (e.g.
        ``{"e_ve": 0.3}``: the environmental variation error of a drift check, Annex A.5). Every
        input not given is shown as assumed in ``to_dict()["uncertainty_budget"]``.

    Returns
    -------
    Evaluation
    """
    from axiscal.datasets import PositioningDataset

    if isinstance(data, (str, Path)):
        kind = _kind_of(data)
        if kind != "iso230-2":
            ev = _evaluated(data, kind)
            return Evaluation(kind, _KIND_STANDARD[kind], ev.dataset, ev.evaluation, ev.result)
        data = read(data)
    if isinstance(data, PositioningDataset):
        return _positioning(data, standard.strip().lower(), dict(tolerances or {}), rule,
                            dict(uncertainty or {}))
    return _other(data)


def simulate(config: Union[PathLike, Mapping[str, Any]],
             seed: int | None = None) -> "Simulation":
    """Simulate a configured test and evaluate it by ISO 230-2:2014.

    Parameters
    ----------
    config : str, Path or mapping
        A TOML configuration, or the same as a dict: a positioning test of a simulated axis
        (``[axis]``, ``[test]``, ``[meta]``; as ``axiscal simulate``) or, with a
        ``[calibrator]`` table, a rotary-axis calibration with an angular interferometer and a
        counter-rotating reference calibrator (as ``axiscal rotary simulate``; Renishaw,
        "Interferometric calibration of rotary axes").
    seed : int, optional
        Seed of ``numpy.random.default_rng``; the same seed gives the same readings. Default
        as the commands: 1 for a positioning test, the configuration's for a rotary calibration.

    Returns
    -------
    Simulation
    """
    cfg = _load_config(config)
    if "calibrator" in cfg:
        from axiscal.procedures.rotary_config import run_rotary_config

        return Simulation(run_rotary_config(cfg, seed), seed, "rotary-calibration")
    from axiscal.procedures.positioning import simulate_from_config

    seed = 1 if seed is None else seed
    return Simulation(simulate_from_config(cfg, seed=seed), seed)


def compensation_table(source: Any, spacing: float | None = None, *,
                       bidirectional: bool = False, resolution: float = 0.1,
                       start: float | None = None, end: float | None = None,
                       extrapolation: str = "hold", home: float | None = None,
                       axis: str = "") -> Any:
    """A compensation table from the mean deviations of a positioning test.

    Parameters
    ----------
    source : Evaluation, str or Path
        An ISO 230-2:2014 :class:`Evaluation`, a positioning data file, or the JSON
        ``axiscal iso230-2 --json`` printed.
    spacing : float, mm or deg, optional
        Distance between table points (default: the mean target spacing, as the CLI).
    bidirectional : bool
        Separate tables for the two directions.
    resolution : float, um or arcsec
        Corrections rounded to this step (default 0.1, as ``axiscal compensate``).
    start, end, home : float, mm or deg, optional
        First and last table point, reference position (default: the targets' ends, the start).
    extrapolation : {"hold", "linear"}
        Beyond the measured targets.
    axis : str
        Axis name written in the table (default: the file's).

    Returns
    -------
    axiscal.compensation.tables.CompensationTable
    """
    from axiscal.compensation.tables import table_from_result

    if isinstance(source, Evaluation):
        result, file_axis = source.result, getattr(source.dataset.metadata, "axis", "")
    else:
        from axiscal.io.results import load_mean_deviations

        result, file_axis = load_mean_deviations(source)
    if spacing is None:
        t = result.targets
        spacing = float((t[-1] - t[0]) / (len(t) - 1))
    how: Any = extrapolation     # checked by table_from_result: "hold" or "linear"
    return table_from_result(result, spacing, start=start, end=end, bidirectional=bidirectional,
                             resolution=resolution, extrapolation=how, reference=home,
                             axis=axis or file_axis)


def write_table(table: Any, controller: str, path: PathLike | None = None,
                **options: Any) -> Any:
    """Write a compensation table in a controller's format.

    Parameters
    ----------
    table : CompensationTable
        From :func:`compensation_table`.
    controller : str
        ``siemens-840d``, ``fanuc``, ``heidenhain``, ``linuxcnc``, ``csv`` or ``renishaw-ren``.
    path : str or Path, optional
        Where to write the file (its companion files, e.g. Heidenhain's .CMA, go beside it);
        None writes nothing.
    **options
        The writer's format options (``machine_axis``, ``detection_unit`` ...).

    Returns
    -------
    axiscal.compensation.controllers.ControllerFile
        ``text``, ``extra_files``, ``enable`` (what the controller must be told) and ``notes``.
    """
    from axiscal.compensation.controllers import check_options
    from axiscal.compensation.controllers import controller as get_controller

    mod = get_controller(controller)
    cf = mod.write(table, **check_options(mod.write, options, f"option for {mod.NAME}"))
    if path is not None:
        from axiscal.io._files import write_text_atomic

        write_text_atomic(path, cf.text)
        for name, text in cf.extra_files.items():
            write_text_atomic(Path(path).parent / name, text)
    return cf


@dataclass(frozen=True, eq=False)
class Evaluation:
    """A test evaluated by its standard.

    Attributes
    ----------
    kind : str
        ``iso230-2``, ``straightness``, ``ballbar``, ``diagonal`` or ``motion``.
    standard : str
        The standard's key (``iso230-2:2014``, ``all``, ``iso230-4`` ...).
    dataset : object
        The dataset evaluated.
    result : object
        The library's frozen result (e.g. :class:`axiscal.standards.iso230_2.ISO230_2Result`).
    """

    kind: str
    standard: str
    dataset: Any
    result: Any
    _json: dict = field(repr=False)
    _budget: Any = field(default=None, repr=False)
    _verdicts: tuple = field(default=(), repr=False)
    _results: tuple = field(default=(), repr=False)

    def to_dict(self) -> dict:
        """The ``--json`` object of the command for this test (``axiscal iso230-2``,
        ``axiscal evaluate --standard KEY``; the other kinds the history's evaluation, whose
        numbers are the command's: ``ballbar analyze``, ``straightness`` ...)."""
        import json

        return json.loads(json.dumps(self._json))

    def to_dataframe(self) -> Any:
        """The per-target table (positioning) as a pandas DataFrame (pandas is optional)."""
        from axiscal.errors import InputError

        try:
            import pandas as pd
        except ImportError:
            raise InputError("to_dataframe needs pandas: pip install pandas") from None
        if self.kind != "iso230-2" or "targets" not in self._json:
            raise InputError(f"to_dataframe: a {self.kind} evaluation has no per-target table")
        return pd.DataFrame(self._json["targets"])

    def plot(self) -> "Figure":
        """The evaluation's figure (matplotlib), as its command's ``--plot`` draws it."""
        return _figure(self)

    def report(self, path: PathLike) -> Path:
        """Write the HTML report (``.html``) of the evaluation, as ``--report`` (``axiscal
        evaluate``, ``ballbar analyze``) does; returns the path."""
        return Path(_write_report(self, Path(path)))

    def _repr_html_(self) -> str:
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, self.standard, self._json, self.plot())

    def __str__(self) -> str:
        return str(self.result)


@dataclass(frozen=True, eq=False)
class Simulation:
    """A simulated test with the truth it was built from.

    Attributes
    ----------
    test : object
        The library's record: a positioning ``SimulatedTest`` (``dataset``, ``result``,
        ``truth``) or a ``RotaryCalibrationResult`` (``capture``, ``result``,
        ``truth_result``, ``budget`` ...).
    seed : int or None
        The seed it ran with (None: the configuration's).
    kind : str
        ``positioning`` or ``rotary-calibration``.
    """

    test: Any
    seed: int | None
    kind: str = "positioning"

    @property
    def dataset(self) -> Any:
        """The simulated readings (a PositioningDataset)."""
        return self.test.capture.dataset if self._rotary else self.test.dataset

    @property
    def result(self) -> Any:
        """Their ISO 230-2:2014 evaluation."""
        return self.test.result

    @property
    def _rotary(self) -> bool:
        return self.kind == "rotary-calibration"

    def to_dict(self) -> dict:
        """The object of the command's ``--json``: ``axiscal simulate`` (the ISO 230-2 keys,
        ``truth``, ``seed``) or ``axiscal rotary simulate``."""
        import json

        from axiscal._json import jsonable
        from axiscal.io.results import result_json

        if self._rotary:
            return json.loads(json.dumps(jsonable(self.test.summary())))
        d = result_json(self.test.result)
        d.update(truth=self.test.truth, seed=self.seed)
        return json.loads(json.dumps(d))

    def plot(self) -> "Figure":
        """The ISO 230-2 figure with the simulation's truth drawn (a rotary calibration: the
        measured error beside the truth and the budget, as ``rotary simulate --plot``)."""
        if self._rotary:
            from axiscal.report.rotary import rotary_error_figure

            return rotary_error_figure(self.test)
        from axiscal.report.plots import iso230_2_figure

        s = self.test
        truth = (s.plan.targets, 0.5 * (s.truth_up + s.truth_down)
                 if s.plan.bidirectional else s.truth_up)
        return iso230_2_figure(s.result, s.dataset, truth=truth)

    def report(self, path: PathLike) -> Path:
        """Write the simulation report (HTML), as the command's ``--report``."""
        if self._rotary:
            from axiscal.report.rotary import write_rotary_report

            return Path(write_rotary_report(path, self.test))
        from axiscal.report.html import positioning_report

        rep = positioning_report(self.test.dataset, self.test.result)
        rep.simulation = True
        return Path(rep.write(path))

    def write_data(self, path: PathLike) -> Path:
        """Write the simulated readings (``.csv`` tidy CSV or ``.json``), as ``axiscal simulate
        --data`` does, so they can be read back like a laser's file."""
        from axiscal.errors import InputError
        from axiscal.io._files import write_text_atomic

        suffix = Path(path).suffix.lower()
        if suffix == ".json":
            from axiscal.io.json import format_positioning_json as fmt
        elif suffix == ".csv":
            from axiscal.io.csv import format_positioning_csv as fmt
        else:
            raise InputError(f"write_data {path}: give a .csv or .json file")
        write_text_atomic(path, fmt(self.dataset))
        return Path(path)

    def _repr_html_(self) -> str:
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, DEFAULT_STANDARD, self.to_dict(), self.plot())

    def __str__(self) -> str:
        return str(self.test if self._rotary else self.test.result)


class History:
    """The calibration history (:class:`axiscal.store.Store`): SQLite or PostgreSQL by URL.

    Parameters
    ----------
    url : str, optional
        ``sqlite:///path.sqlite`` or ``postgresql+psycopg://...``; default ``AXISCAL_DB``, else
        the user's SQLite file (as ``axiscal history``).
    """

    def __init__(self, url: str | None = None) -> None:
        from axiscal.store import open_store

        self.store = open_store(url)

    def add(self, path: PathLike, **metadata: Any) -> Any:
        """Evaluate and store a data file (``machine=``, ``axis=``, ``operator=`` ...)."""
        p = Path(path)
        return self.store.add(p.read_bytes(), p.name, **metadata)

    def tests(self, machine: str | None = None, axis: str | None = None) -> list:
        """The stored tests, newest first (TestSummary records)."""
        return self.store.tests(machine, axis)

    def machines(self) -> list:
        """The machines with their axes and test counts (MachineSummary records)."""
        return self.store.machines()

    def get(self, test_id: int) -> Any:
        """One stored test (StoredTest: its file, metadata and evaluation)."""
        return self.store.get(test_id)

    def trend(self, machine: str, axis: str, parameter: str,
              tolerance: float | None = None) -> Any:
        """The trend of one parameter of one axis (axiscal.store.analysis.Trend)."""
        from axiscal.store import trend

        return trend(self.store, machine, axis, parameter, tolerance)

    def close(self) -> None:
        self.store.close()

    def __enter__(self) -> "History":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# -- helpers -----------------------------------------------------------------------------------
_KIND_STANDARD = {"iso230-2": DEFAULT_STANDARD, "straightness": "iso230-1", "ballbar": "iso230-4",
                  "diagonal": "iso230-6", "motion": "iso230-7"}


def _kind_of(path: PathLike) -> str:
    from axiscal.io import read_text
    from axiscal.store.kinds import detect_kind

    return detect_kind(read_text(path))


def _evaluated(path: PathLike, kind: str) -> Any:
    from axiscal.store.kinds import evaluate_file

    return evaluate_file(Path(path).read_bytes(), Path(path).name, kind)


def _positioning(ds: Any, key: str, tolerances: dict, rule: str | None,
                 uncertainty: dict) -> Evaluation:
    from axiscal.errors import InputError
    from axiscal.standards import positioning_standards as ps

    if key == DEFAULT_STANDARD:
        return _iso230_2(ds, tolerances, rule, uncertainty)
    if key != "all" and key not in ps.STANDARDS:
        raise InputError(f"standard {key!r}: one of {', '.join(ps.STANDARDS)} or all")
    if key == "all" and tolerances:
        raise InputError("tolerances need one standard (parameter names differ between them)")
    results = (ps.evaluate_all(ds) if key == "all"
               else ((ps.STANDARDS[key], ps.evaluate(key, ds)),))
    first = results[0][1]
    verdicts: tuple = ()
    if tolerances:
        if isinstance(first, str):
            raise InputError(f"tolerances: {key} was not evaluated: {first}")
        verdicts = tuple(ps.check_tolerances(key, ds, first, tolerances, rule,
                                             uncertainty or None))
    from axiscal.io.results import standard_json, verdicts_json

    d = {"unit": ds.deviation_unit, "target_unit": ds.target_unit,
         "standards": [standard_json(std, res) for std, res in results]}
    if verdicts:
        from axiscal.standards.iso14253_1 import unprovable

        d.update(verdicts_json(verdicts))
        d["warnings"] = unprovable(verdicts, {"um": "µm"}.get(ds.deviation_unit,
                                                             ds.deviation_unit))
    return Evaluation("iso230-2", key, ds, results[0][1], d, _verdicts=tuple(verdicts),
                      _results=tuple(results))


def _iso230_2(ds: Any, tolerances: dict, rule: str | None, uncertainty: dict) -> Evaluation:
    """As ``axiscal iso230-2 FILE --json`` (the user configuration's uncertainty inputs)."""
    from axiscal.io.results import result_json
    from axiscal.report.issue import budget_for, decisions_for, load_config
    from axiscal.standards.iso230_2 import check_tolerances
    from axiscal.standards.iso230_2 import evaluate as iso_evaluate

    result = iso_evaluate(ds)
    cfg = load_config(None)
    if uncertainty:
        cfg = {**cfg, "uncertainty": {**(cfg.get("uncertainty") or {}), **uncertainty}}
    check_tolerances(result, {**cfg.get("tolerance", {}), **tolerances})
    budget = budget_for(ds, result, cfg)
    verdicts, _, _ = decisions_for(result.parameters(), budget, tolerances, cfg, rule)
    d = {**result_json(result, verdicts, budget), "machine": ds.metadata.machine,
         "axis": ds.metadata.axis, "notes": ds.metadata.notes}
    return Evaluation("iso230-2", DEFAULT_STANDARD, ds, result, d, budget, tuple(verdicts))


def _other(data: Any) -> Evaluation:
    """A ballbar dataset evaluated in memory; the other kinds are evaluated from their file."""
    from axiscal.errors import InputError
    from axiscal.io.ballbar import BallbarData
    from axiscal.store.kinds import evaluate_ballbar
    from axiscal._json import jsonable

    if not isinstance(data, BallbarData):
        raise InputError(f"evaluate: give the file's path for a {type(data).__name__} "
                         "(a positioning or ballbar dataset is evaluated in memory)")
    r = evaluate_ballbar(data)
    return Evaluation("ballbar", "iso230-4", data, r,
                      jsonable({"plane": "".join(data.axes), **r.as_dict()}))


def _load_config(config: Union[PathLike, Mapping[str, Any]]) -> dict:
    if isinstance(config, Mapping):
        return dict(config)
    from axiscal.io._files import load_toml

    return load_toml(Path(config))


def _figure(ev: Evaluation) -> "Figure":
    from axiscal.errors import InputError

    if ev.kind == "iso230-2":
        from axiscal.report import plots

        if ev.standard == DEFAULT_STANDARD:
            return plots.iso230_2_figure(ev.result, ev.dataset)
        fig = (plots.standards_figure(ev.dataset, ev._results) if ev.standard == "all"
               else plots.standard_figure(ev.dataset, *ev._results[0]))
        if fig is None:
            raise InputError("plot: no standard evaluates this test, so there is no figure")
        return fig
    from axiscal.report.evaluations import kind_figure

    return kind_figure(ev.kind, ev.dataset, ev.result)


def _write_report(ev: Evaluation, path: Path) -> Path:
    from axiscal.report.html import positioning_report, standards_report, write_result_report

    if ev.kind == "iso230-2" and ev.standard == DEFAULT_STANDARD:
        from axiscal.report.uncertainty import add_uncertainty

        rep = positioning_report(ev.dataset, ev.result, verdicts=ev._verdicts)
        add_uncertainty(rep, ev._budget, ev._verdicts,
                        [p for p, v in ev.result.parameters().items() if v is not None])
        return rep.write(path)
    if ev.kind == "iso230-2":
        return standards_report(ev.dataset, ev._results, f"Positioning test by {ev.standard}",
                                ev._verdicts).write(path)
    if ev.kind == "ballbar" and hasattr(ev.result, "circular"):
        from axiscal.report.ballbar_plots import write_diagnosis_report

        return write_diagnosis_report(path, ev.dataset.runs, ev.result)
    title = {"straightness": "Straightness (ISO 230-1)", "diagonal": "Diagonal squareness "
             "(ISO 230-6)", "motion": "Error motions of a rotary axis (ISO 230-7)",
             "ballbar": "Circular test (ISO 230-4)"}[ev.kind]
    return write_result_report(path, title, ev._json, figure=_figure(ev))
