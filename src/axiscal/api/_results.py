"""The records the public API returns: :class:`Evaluation` and :class:`Simulation`.

Each is the library's frozen result with what a notebook wants of it: ``to_dict()`` (the
command's ``--json``), ``plot()`` (a matplotlib Figure), ``report(path)`` and ``_repr_html_``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

if TYPE_CHECKING:   # pragma: no cover - typing only
    from matplotlib.figure import Figure

__all__ = ["Evaluation", "Simulation", "PathLike", "DEFAULT_STANDARD"]

#: The standard :func:`axiscal.evaluate` applies when none is named.
DEFAULT_STANDARD = "iso230-2:2014"

#: A path argument: text or a :class:`pathlib.Path`.
PathLike = Union[str, Path]



@dataclass(frozen=True, eq=False)
class Evaluation:
    """A test evaluated by its standard.

    Attributes
    ----------
    kind : str
        ``iso230-2``, ``straightness``, ``ballbar``, ``diagonal`` or ``motion``.
    standard : str
        The standard's key (``iso230-2:2014``, ``all``, ``iso230-2`` ...).
    dataset : object
        The dataset evaluated.
    result : object
        The library's frozen result (e.g. :class:`axiscal.standards.iso230_2.Iso230_2Result`;
        by another positioning standard its ``StandardResult``).
    quantities : dict of str to Quantity
        Every result with its value, U, k, unit and verdict
        (:class:`axiscal.standards.quantities.Quantity`); also as attributes (``ev.E``,
        ``ev.E.U``) and items (``ev["jis-b6192:R"]``).

    Examples
    --------
    >>> import axiscal
    >>> from axiscal.datasets import PositioningDataset
    >>> ds = PositioningDataset.from_arrays("linear", [0, 100, 200], [[1, 2], [0, 1], [2, 2]],
    ...                                     [[3, 3], [2, 1], [4, 5]], "mm", "um")
    >>> ev = axiscal.evaluate(ds, uncertainty={"e_ve": 0.3})
    >>> ev.E.value, ev.E.unit, ev.E.k
    (4.0, 'um', 2.0)
    >>> ev.E.U == ev.budget.U("E") == ev.to_dict()["quantities"]["E"]["U"]
    True
    """

    kind: str
    standard: str
    dataset: Any
    result: Any
    _json: dict = field(repr=False)
    _budget: Any = field(default=None, repr=False)
    _verdicts: tuple = field(default=(), repr=False)
    _results: tuple = field(default=(), repr=False)
    _config: dict = field(default_factory=dict, repr=False)
    _quantities: dict = field(default_factory=dict, repr=False)

    @property
    def quantities(self) -> dict:
        """Every result as a :class:`~axiscal.standards.quantities.Quantity` (value, U, k,
        unit, verdict), by name: the ``quantities`` of :meth:`to_dict`."""
        return dict(self._quantities)

    def __getattr__(self, name: str) -> Any:
        """A quantity by its name as an attribute (``ev.E``, ``ev.R_up``)."""
        if name.startswith("_"):
            raise AttributeError(name)
        q = self.__dict__.get("_quantities", {}).get(name)
        if q is None:
            raise AttributeError(f"{type(self).__name__} has no attribute or quantity {name!r}"
                                 f"; quantities: {', '.join(self.__dict__.get('_quantities', {}))}")
        return q

    def __getitem__(self, name: str) -> Any:
        """A quantity by its name (``ev["jis-b6192:R"]``)."""
        from axiscal.errors import InputError

        try:
            return self._quantities[name]
        except KeyError:
            raise InputError(f"no quantity {name!r}; quantities: "
                             f"{', '.join(self._quantities)}") from None

    @property
    def budget(self) -> Any:
        """The ISO 230-2:2014 Annex A uncertainty budget
        (:class:`axiscal.standards.iso230_9.UncertaintyBudget`) of a positioning test by ISO
        230-2:2014, else None."""
        return self._budget

    @property
    def verdicts(self) -> tuple:
        """The ISO 14253-1:2017 decisions on the tolerances given (``Decision`` records, in the
        standard's parameter order); empty without tolerances."""
        return self._verdicts

    @property
    def results(self) -> tuple:
        """A positioning test by other standards: ``(Standard, StandardResult or reason)``
        pairs, one per standard evaluated (``all``: every standard); else empty."""
        return self._results

    @property
    def config(self) -> dict:
        """The configuration an ISO 230-2:2014 evaluation used: the user configuration, the
        job file's tables and the uncertainty inputs over them (the certificate's)."""
        return dict(self._config)

    @property
    def conformance_proven(self) -> bool | None:
        """True when conformance is proven for every tolerance given (ISO 14253-1:2017),
        False when it is not for one (non-conformance proven, or the uncertainty zone: the
        commands' exit code 1), None without tolerances."""
        checked = [v for v in self._verdicts if v.value is not None]
        return None if not checked else all(v.passed is True for v in checked)

    def to_dict(self) -> dict:
        """The ``--json`` object of the command for this test (``axiscal iso230-2``,
        ``axiscal evaluate --standard KEY``, ``axiscal ballbar analyze`` without ``file``; the
        other kinds the history's evaluation, whose numbers are the command's:
        ``straightness`` ...)."""
        import json

        return json.loads(json.dumps(self._json))

    def to_dataframe(self, what: str = "parameters") -> Any:
        """A tidy pandas DataFrame (pandas is optional).

        ``what="parameters"`` (default): one row per quantity, indexed by name, with ``symbol``,
        ``value``, ``U``, ``k``, ``unit``, ``verdict`` and ``tolerance``.
        ``what="targets"``: a positioning test's per-target table indexed by ``target``
        (x̄↑, x̄↓, B_i, s, R_i ... ISO 230-2:2014 §3), the units in ``attrs["units"]``.
        """
        from axiscal.errors import InputError

        try:
            import pandas as pd
        except ImportError:
            raise InputError("to_dataframe needs pandas: pip install pandas") from None
        if what == "parameters":
            from axiscal.standards.quantities import quantities_frame

            return quantities_frame(self._quantities)
        if what != "targets":
            raise InputError(f"to_dataframe({what!r}): 'parameters' or 'targets'")
        if self.kind != "iso230-2" or not hasattr(self.result, "target_table"):
            raise InputError(f"to_dataframe: a {self.kind} evaluation by {self.standard} has no "
                             "per-target table")
        df = pd.DataFrame(self.result.target_table()).set_index("target")
        u, tu = self.result.deviation_unit, self.result.target_unit
        df.attrs["units"] = {"target": tu, **{c: ("" if c.startswith("n_") else u)
                                              for c in df.columns}}
        return df

    def plot(self) -> "Figure":
        """The evaluation's figure (matplotlib), as its command's ``--plot`` draws it."""
        from axiscal.report.evaluations import evaluation_figure

        return evaluation_figure(self)

    def report(self, path: PathLike, title: str | None = None) -> Path:
        """Write the HTML report (``.html``) of the evaluation, as ``--report`` (``axiscal
        evaluate``, ``ballbar analyze``) does; returns the path. ``title``: the report's
        heading where the kind has one to choose (other positioning standards, ballbar
        diagnosis; default the standard's words)."""
        from axiscal.report.evaluations import write_evaluation_report

        return Path(write_evaluation_report(self, Path(path), title))

    def _repr_html_(self) -> str:
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, self.standard, self._json, self.plot(),
                             self._quantities)

    def __str__(self) -> str:
        """The result as its command prints it, each quantity with its U where it has one."""
        from axiscal.report.evaluations import evaluation_text

        return evaluation_text(self)

    def __repr__(self) -> str:
        shown = [q for q in self._quantities.values() if q.value is not None][:3]
        more = len(self._quantities) - len(shown)
        return (f"<Evaluation {self.kind} by {self.standard}: "
                f"{'; '.join(map(str, shown)) or 'no quantities'}"
                f"{f' (+{more} more)' if more > 0 else ''}>")


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
        ``five-dof``, ``ballbar``, ``volumetric-map``, ``volumetric-compensation`` or
        ``environment``.
    name : str
        The configuration's (or raw file's) name, in the figure's and the report's titles.
    """

    test: Any
    seed: int | None
    kind: str = "positioning"
    name: str = ""

    @property
    def dataset(self) -> Any:
        """The simulated readings (a PositioningDataset; five-DOF: the MotionErrorData;
        ballbar: the BallbarData; an environmental compensation: the compensated test; scale
        homing and a volumetric map: None)."""
        if self._run:
            return self.test.parts.get("dataset", self.test.parts.get("data"))
        return self.test.capture.dataset if self._rotary else self.test.dataset

    @property
    def result(self) -> Any:
        """Their evaluation: ISO 230-2:2014 (positioning, rotary), ISO 230-7:2015 (five-DOF),
        the ballbar diagnosis with ISO 230-4:2005 (ballbar, as ``ballbar analyze`` of the
        simulated file); the library's record for the other kinds (``ReferencingRun``,
        ``TwinHomingResult``, ``VolumetricMap``, ``VolumetricTables``,
        ``ReadingCorrections``)."""
        if self.kind == "ballbar":
            from axiscal.store.kinds import evaluate_ballbar

            return evaluate_ballbar(self.test.record)
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
        simulate``, ``ballbar simulate``, ``volumetric map``, ``volumetric compensate`` or
        ``compensate-environment``. A volumetric map's carries its figures' U, as the
        history's record of the same file (the user configuration's
        ``[volumetric_uncertainty]``)."""
        if self.kind == "volumetric-map":
            from axiscal.report.simulation_views import volumetric_map_record

            return volumetric_map_record(self.test).stored_result()
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

    def report(self, path: PathLike, uncertainty: dict | None = None) -> Path:
        """Write the report (HTML, or PDF by extension where the command allows), as the
        command's ``--report``; a positioning test's carries its ISO 230-2:2014 Annex A
        uncertainty from ``uncertainty`` (inputs by name; default the user configuration's)."""
        from axiscal.report.simulation_views import write_any_simulation_report

        return Path(write_any_simulation_report(self.kind, self.test, path, self.name,
                                                uncertainty))

    def write_data(self, path: PathLike, encoding: str | None = None) -> Path:
        """Write the simulated readings as ``axiscal simulate --data`` does (``.csv`` tidy CSV,
        ``.json``, or Renishaw ``.rtl``/``.rta``; five-DOF: the ``.csv`` of ``motion simulate
        --csv``; ballbar: the ``.csv`` of ``ballbar simulate --out``), so they can be read
        back like an instrument's file. ``encoding``: the code page of a ``.rtl``/``.rta``
        (``cp1252`` …, as Renishaw's Windows software writes it; refused for other files)."""
        from axiscal.io.simulation_results import write_simulated_data

        return write_simulated_data(self.kind, self.dataset, path, encoding)

    def _repr_html_(self) -> str:
        from axiscal.io.simulation_results import DOCUMENTS
        from axiscal.report.evaluations import notebook_html

        return notebook_html(self.kind, DOCUMENTS.get(self.kind, DEFAULT_STANDARD),
                             self.to_dict(), self.plot())

    def __str__(self) -> str:
        if self.kind == "environment":
            return str(self.test.json["applied"])
        return str(self.test if self._rotary else self.result)
