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
           "volumetric_map", "volumetric_compensation", "compensate_environment",
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
    from axiscal.report.evaluations import evaluated_file, kind_of_file

    kind = kind_of_file(path)
    if kind == "iso230-2":
        from axiscal.io import read_positioning

        return read_positioning(path, target_unit=target_unit, deviation_unit=deviation_unit)
    return evaluated_file(path, kind).dataset


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
        from axiscal.report.evaluations import KIND_STANDARD, evaluated_file, kind_of_file

        kind = kind_of_file(data)
        if kind != "iso230-2":
            ev = evaluated_file(data, kind)
            return Evaluation(kind, KIND_STANDARD[kind], ev.dataset, ev.evaluation, ev.result)
        data = read(data)
    if isinstance(data, PositioningDataset):
        from axiscal.report.evaluations import positioning_evaluation

        return Evaluation(**positioning_evaluation(data, standard.strip().lower(),
                                                   dict(tolerances or {}), rule,
                                                   dict(uncertainty or {})))
    from axiscal.report.evaluations import ballbar_evaluation

    return Evaluation(**ballbar_evaluation(data))


def simulate(config: Union[PathLike, Mapping[str, Any]], seed: int | None = None, *,
             kind: str | None = None) -> "Simulation":
    """Simulate an instrument or a machine from its configuration.

    Parameters
    ----------
    config : str, Path or mapping
        A TOML configuration (a positioning test or a rotary calibration also as a dict),
        its kind told by its tables, in this order: ``[calibrator]`` a rotary calibration
        with the reference calibrator (``axiscal rotary simulate``; Renishaw,
        "Interferometric calibration of rotary axes"); ``[gantry]`` twin-axis homing
        (``scale gantry``); ``[laser]``, ``[compensator]``, ``[switch]`` or ``[homing]``
        referencing of one laser-scale axis (``scale home``; Renishaw, "Laser scale axis
        referencing"); ``[instrument]``, ``[mounting]``, ``[reference]``, ``[drift]`` or
        ``[axis.positioning]`` ... the five motion errors of a rotary axis and ISO 230-7:2015
        (``motion simulate``; Optics Express 2018, "Five-DOF motion errors of a rotary
        axis"); otherwise a positioning test by ISO 230-2:2014 (``axiscal simulate``).
    seed : int, optional
        Seed of the simulation; the same seed gives the same readings. Default as the
        commands: 1 for a positioning test, otherwise the configuration's.
    kind : str, optional
        ``positioning``, ``rotary-calibration``, ``scale-homing``, ``gantry-homing`` or
        ``five-dof``, instead of telling it from the tables.

    Returns
    -------
    Simulation
    """
    from axiscal.errors import InputError

    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise InputError(f"seed {seed!r}: a whole number >= 0")
    from axiscal.io import simulation_results as sr

    cfg = _load_config(config)
    kind = kind or sr.simulation_kind(cfg)
    if kind in ("scale-homing", "gantry-homing", "five-dof"):
        if isinstance(config, Mapping):
            raise InputError(f"simulate: a {kind} configuration is read from its TOML file; "
                             "give its path")
        return Simulation(sr.run_configured(kind, config, seed), seed, kind, Path(config).name)
    if kind == "rotary-calibration":
        from axiscal.procedures.rotary_config import run_rotary_config

        return Simulation(run_rotary_config(cfg, seed), seed, "rotary-calibration")
    if kind != "positioning":
        raise InputError(f"kind {kind!r}: one of {', '.join(sr.SIMULATION_KINDS)}")
    from axiscal.procedures.positioning import simulate_from_config

    seed = 1 if seed is None else seed
    return Simulation(simulate_from_config(cfg, seed=seed), seed)


def volumetric_map(config: PathLike, grid: int = 11) -> "Simulation":
    """The volumetric error of a three-axis machine from its 21 measured geometric errors.

    The errors of ISO 230-1:2012 combined by the rigid-body model of ISO/TR 16907:2015 over the
    working volume, and the body diagonals of ISO 230-6:2002 (``axiscal volumetric map --json``;
    a simulated configuration adds ``truth`` and ``mapped_minus_true_um``).

    Parameters
    ----------
    config : str or Path
        The volumetric configuration (TOML; format in the README, "Volumetric configuration").
    grid : int
        Grid points per axis, 2 to 100 (default 11, as the command).

    Returns
    -------
    Simulation
        ``kind`` ``volumetric-map``; ``result`` the ``VolumetricMap``.
    """
    from axiscal.errors import InputError
    from axiscal.io.simulation_results import volumetric_map as run_map
    from axiscal.io.volumetric import read_volumetric_config

    if isinstance(grid, bool) or not isinstance(grid, int) or not 2 <= grid <= 100:
        raise InputError(f"grid {grid!r}: a whole number of points per axis, 2 to 100")
    return Simulation(run_map(read_volumetric_config(config), grid), None, "volumetric-map",
                      Path(config).name)


def volumetric_compensation(config: PathLike, controller: str, *, out: PathLike | None = None,
                            receiving: Mapping[str, str] | None = None, spacing: float = 20.0,
                            verify: bool = False) -> "Simulation":
    """Positioning and cross-axis tables that remove what tables can of a volumetric map.

    As ``axiscal volumetric compensate CONFIG --controller C [--verify] [--out DIR] --json``:
    the tables in the order of Chapman, "Calibration of machine squareness", Appendix II;
    ``verify`` re-measures the simulated machine with them applied (volumetric map and body
    diagonals before and after; a configuration of ``volumetric simulate`` only).

    Parameters
    ----------
    config : str or Path
        The volumetric configuration (TOML).
    controller : str
        ``siemens-840d``, ``heidenhain`` or ``csv`` (LinuxCNC's 3-D correction: the command).
    out : str or Path, optional
        Folder for the tables (created if missing).
    receiving : mapping, optional
        Axis receiving each squareness correction, e.g. ``{"zx": "Z"}`` (default: the axis
        aligned to the spindle).
    spacing : float, mm
        Table spacing (default 20 mm, as the command), under the configuration's.
    verify : bool
        Re-measure the simulated machine with the tables applied.

    Returns
    -------
    Simulation
        ``kind`` ``volumetric-compensation``; ``result`` the ``VolumetricTables``.
    """
    from axiscal.errors import InputError
    from axiscal.io import simulation_results as sr
    from axiscal.io.volumetric import read_volumetric_config

    if controller == "linuxcnc":
        raise InputError("volumetric_compensation: LinuxCNC's 3-D correction is 'axiscal "
                         "volumetric compensate --controller linuxcnc'")
    if out is not None:
        Path(out).mkdir(parents=True, exist_ok=True)
    cfg = read_volumetric_config(config)
    rec = {k.lower(): v for k, v in (receiving or {}).items()}
    tables = sr.volumetric_tables_for(cfg, rec, spacing, verify)
    return Simulation(sr.volumetric_compensation(cfg, tables, controller, verify=verify, out=out),
                      None, "volumetric-compensation", Path(config).name)


def compensate_environment(raw: PathLike, environment: PathLike | None = None, *,
                           out: PathLike | None = None, equation: str = "ciddor",
                           air_only: bool = False, max_gap: float = 300.0,
                           **conditions: float) -> "Simulation":
    """Raw laser readings compensated for the air at each reading's time and referred to 20 °C.

    As ``axiscal compensate-environment RAW --environment ENV --out OUT --json``: the air's
    refractive index by the named equation and the dead path at each reading, the axis referred
    to 20 °C by ISO 1:2016. Evaluate the test with ``axiscal.evaluate(result.dataset)``.

    Parameters
    ----------
    raw : str or Path
        Raw readings (CSV ``time_s,target,direction,run,reading``; :mod:`axiscal.io.measured`).
    environment : str or Path, optional
        The environment log over the test (CSV or JSON).
    out : str or Path, optional
        Write the compensated positioning CSV there (named in ``to_dict()["out"]``).
    equation : str
        ``ciddor`` (default), ``edlen`` or ``birch-downs``.
    air_only : bool
        Compensate the air only, not the material.
    max_gap : float, s
        Longest gap in the log a reading may fall into (default 300 s, as the command).
    **conditions : float
        Instead of the log's: ``air_temperature`` (°C), ``pressure`` (Pa), ``humidity`` (%),
        ``material_temperature`` (°C), ``expansion_ppm`` (ppm/K).

    Returns
    -------
    Simulation
        ``kind`` ``environment``; ``dataset`` the compensated test.
    """
    from axiscal.io.measured import read_environment_log, read_raw_readings
    from axiscal.io.simulation_results import environment_compensation, environment_options

    options = environment_options(conditions)
    raw_data = read_raw_readings(raw)
    log = read_environment_log(environment) if environment is not None else None
    run = environment_compensation(raw_data, log, out=out, equation=equation,
                                   normalise_material=not air_only, max_gap=max_gap, **options)
    return Simulation(run, None, "environment", Path(raw).name)


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
        from axiscal.report.evaluations import evaluation_figure

        return evaluation_figure(self)

    def report(self, path: PathLike) -> Path:
        """Write the HTML report (``.html``) of the evaluation, as ``--report`` (``axiscal
        evaluate``, ``ballbar analyze``) does; returns the path."""
        from axiscal.report.evaluations import write_evaluation_report

        return Path(write_evaluation_report(self, Path(path)))

    def _repr_html_(self) -> str:
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, self.standard, self._json, self.plot())

    def __str__(self) -> str:
        return str(self.result)


@dataclass(frozen=True, eq=False)
class Simulation:
    """A simulated test with the truth it was built from, or a run computed from a
    configuration or raw readings (volumetric map, environmental compensation).

    Attributes
    ----------
    test : object
        The library's record: a positioning ``SimulatedTest`` (``dataset``, ``result``,
        ``truth``), a ``RotaryCalibrationResult`` (``capture``, ``result``, ``truth_result``,
        ``budget`` ...), or for the other kinds an
        :class:`axiscal.io.simulation_results.SimulationRun` (``record``, ``json``, ``parts``).
    seed : int or None
        The seed it ran with (None: the configuration's).
    kind : str
        ``positioning``, ``rotary-calibration``, ``scale-homing``, ``gantry-homing``,
        ``five-dof``, ``volumetric-map`` or ``environment``.
    name : str
        The configuration's (or raw file's) name, in the figure's and the report's titles.
    """

    test: Any
    seed: int | None
    kind: str = "positioning"
    name: str = ""

    @property
    def dataset(self) -> Any:
        """The simulated readings (a PositioningDataset; five-DOF: the MotionErrorData; an
        environmental compensation: the compensated test; scale homing and a volumetric map:
        None)."""
        if self._run:
            return self.test.parts.get("dataset", self.test.parts.get("data"))
        return self.test.capture.dataset if self._rotary else self.test.dataset

    @property
    def result(self) -> Any:
        """Their evaluation: ISO 230-2:2014 (positioning, rotary), ISO 230-7:2015 (five-DOF);
        the library's record for the other kinds (``ReferencingRun``, ``TwinHomingResult``,
        ``VolumetricMap``, ``ReadingCorrections``)."""
        if self._run:
            return self.test.parts.get("result", self.test.record)
        return self.test.result

    @property
    def _rotary(self) -> bool:
        return self.kind == "rotary-calibration"

    @property
    def _run(self) -> bool:
        return self.kind not in ("positioning", "rotary-calibration")

    def to_dict(self) -> dict:
        """The object of the command's ``--json``: ``axiscal simulate`` (the ISO 230-2 keys,
        ``truth``, ``seed``), ``rotary simulate``, ``scale home``, ``scale gantry``, ``motion
        simulate``, ``volumetric map``, ``volumetric compensate`` or
        ``compensate-environment``."""
        from axiscal.io.simulation_results import simulation_dict

        return simulation_dict(self.kind, self.test, self.seed)

    def plot(self) -> "Figure":
        """The figure of the command's ``--plot``: the ISO 230-2 figure with the simulation's
        truth drawn; a rotary calibration's measured error beside the truth and the budget; the
        referencing signals; the gantry's skew; the five errors against angle; the volumetric
        grid and slices; a verified compensation's figures before and after; the air, material
        and corrections over the test."""
        from axiscal.report.simulation_views import any_simulation_figure

        return any_simulation_figure(self.kind, self.test, self.name)

    def report(self, path: PathLike) -> Path:
        """Write the report (HTML, or PDF by extension where the command allows), as the
        command's ``--report``."""
        from axiscal.report.simulation_views import write_any_simulation_report

        return Path(write_any_simulation_report(self.kind, self.test, path, self.name))

    def write_data(self, path: PathLike) -> Path:
        """Write the simulated readings as ``axiscal simulate --data`` does (``.csv`` tidy CSV
        or ``.json``; five-DOF: the ``.csv`` of ``motion simulate --csv``), so they can be read
        back like an instrument's file."""
        from axiscal.io.simulation_results import write_simulated_data

        return write_simulated_data(self.kind, self.dataset, path)

    def _repr_html_(self) -> str:
        from axiscal.io.simulation_results import DOCUMENTS
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, DOCUMENTS.get(self.kind, DEFAULT_STANDARD),
                             self.to_dict(), self.plot())

    def __str__(self) -> str:
        if self.kind == "environment":
            return str(self.test.json["applied"])
        return str(self.test if self._rotary else self.result)


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
def _load_config(config: Union[PathLike, Mapping[str, Any]]) -> dict:
    if isinstance(config, Mapping):
        return dict(config)
    from axiscal.io._files import load_toml

    return load_toml(Path(config))
