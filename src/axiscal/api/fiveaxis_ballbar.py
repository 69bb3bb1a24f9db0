"""Ballbar tests of the rotary axes in the public API: ``axiscal.fiveaxis.ballbar.plan |
simulate | evaluate`` (ISO 10791-6:2014 kinematic tests as :mod:`axiscal.standards.iso10791_6`
reads them)::

    import axiscal

    planned = axiscal.fiveaxis.ballbar.plan("fiveaxis_ac.toml")    # what each set-up sees
    sim = axiscal.fiveaxis.ballbar.simulate("fiveaxis_ac.toml", seed=1, out="bb")
    done = axiscal.fiveaxis.ballbar.evaluate(["bb/1_ballbar.csv"])
    done.results[0].range, done.results[0].U                   # metres
    done.to_dict()                                             # the keys of ``--json``

``axiscal fiveaxis ballbar plan | simulate | evaluate`` call these same functions. The set-ups
are the configuration's ``[[ballbar]]`` tables (:mod:`axiscal.procedures.five_axis_ballbar`);
the files are described in :mod:`axiscal.io.five_axis_ballbar`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import InputError

TYPE_CHECKING = False   # as typing.TYPE_CHECKING, without importing typing
if TYPE_CHECKING:   # pragma: no cover - for type checkers
    from axiscal.machines.five_axis import FiveAxisMachine

__all__ = ["plan", "simulate", "evaluate", "report", "BallbarPlanned", "BallbarSimulated",
           "BallbarEvaluated"]


@dataclass(frozen=True, eq=False)
class BallbarPlanned:
    """The set-ups (``setups``, BallbarSetUp) of ``machine`` and, per set-up, the range
    sensitivity to each location error (``names``; ``sensitivity`` (S, P): µm per µm or per
    µrad, :func:`~axiscal.standards.iso10791_6.range_sensitivity`)."""

    machine: FiveAxisMachine
    setups: tuple
    names: tuple
    sensitivity: np.ndarray

    def blind(self, i: int) -> list[str]:
        """The errors set-up ``i`` cannot see (range sensitivity below BLIND)."""
        from axiscal.standards.iso10791_6 import BLIND

        return [n for n, v in zip(self.names, self.sensitivity[i]) if v < BLIND]

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis ballbar plan``."""
        from axiscal.physics.rotary_location import is_angle

        return {"machine": self.machine.name, "tilt_axis": self.machine.tilt,
                "units": {n: "µm/µrad" if is_angle(n) else "µm/µm" for n in self.names},
                "setups": [_setup_dict(s) | {
                    "sensitivity": dict(zip(self.names, self.sensitivity[i].round(6).tolist())),
                    "blind": self.blind(i)} for i, s in enumerate(self.setups)]}

    def __str__(self) -> str:
        from axiscal.physics.rotary_location import is_angle

        lines = [f"{self.machine.name}: {len(self.setups)} ballbar set-ups"]
        for i, s in enumerate(self.setups, 1):
            lines.append(f"  {i}. {s.label}: {s.kind}, {s.swept} swept, {s.direction} bar "
                         f"{s.length * 1e3:g} mm, {s.points} points")
        lines.append("range sensitivity (µm of range per µm, or per µrad, of each error alone; "
                     "'—' blind):")
        lines.append("  " + f"{'error':<10}" + "".join(f"{i:>8}" for i in
                                                       range(1, len(self.setups) + 1)))
        from axiscal.standards.iso10791_6 import BLIND

        for j, n in enumerate(self.names):
            cells = "".join(f"{v:8.3f}" if v >= BLIND else f"{'—':>8}"
                            for v in self.sensitivity[:, j])
            lines.append(f"  {n:<10}{cells}  {'µm/µrad' if is_angle(n) else 'µm/µm'}")
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class BallbarEvaluated:
    """Records (BallbarRecord) and their figures (``results``, BallbarRange), one per file."""

    records: tuple
    results: tuple
    files: tuple = ()

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis ballbar evaluate``."""
        return {"setups": [rec.result_dict(r) for rec, r in zip(self.records, self.results)],
                "files": [str(f) for f in self.files]}

    def __str__(self) -> str:
        return "\n".join(str(r) for r in self.results)


@dataclass(frozen=True, eq=False)
class BallbarSimulated(BallbarEvaluated):
    """A simulated run on the twin: ``true_range`` (m, per set-up: the twin's reading range
    without noise, the truth shown only in simulation) beside the evaluation."""

    true_range: tuple = ()

    def to_dict(self) -> dict:
        """The ``--json`` object of ``axiscal fiveaxis ballbar simulate``: that of ``evaluate``
        with ``true_range_um`` and ``deviation_um`` (range − true) per set-up."""
        out = super().to_dict()
        for s, t in zip(out["setups"], self.true_range):
            s["true_range_um"] = t * 1e6
            s["deviation_um"] = s["range_um"] - t * 1e6
        return out

    def __str__(self) -> str:
        lines = [str(r) for r in self.results]
        lines.append("simulation truth (the twin without noise):")
        lines += [f"  {r.label}: true range {t * 1e6:.2f} µm, measured − true "
                  f"{(r.range - t) * 1e6:+.2f} µm" for r, t in zip(self.results, self.true_range)]
        return "\n".join(lines)


def plan(config) -> BallbarPlanned:
    """The configuration's ``[[ballbar]]`` set-ups and what each can see (range sensitivity to
    the ten location errors and the linear axes' three squareness errors)."""
    from axiscal.physics.rotary_location import SQUARENESS
    from axiscal.standards.iso10791_6 import range_sensitivity, reading_sensitivity

    machine, setups = _load(config)
    names = machine.geometry.names + SQUARENESS
    sens = np.array([range_sensitivity(reading_sensitivity(
        machine.geometry, s.tilt_angle, s.c_angle, s.spindle_ball, s.bar, names))
        for s in setups])
    return BallbarPlanned(machine, setups, names, sens)


def simulate(config, seed: int = 1, out=None) -> BallbarSimulated:
    """Run the set-ups on the twin with the simulated ballbar, evaluate each, and (with
    ``out``, a folder) write one CSV per set-up (``1_ballbar.csv`` ...)."""
    from dataclasses import replace

    from axiscal.api._fiveaxis_common import check_seed
    from axiscal.procedures.five_axis_ballbar import measure_ballbar

    machine, setups = _load(config)
    records = measure_ballbar(machine, setups, np.random.default_rng(check_seed(seed)))
    quiet = [replace(s, ballbar=replace(s.ballbar, noise=0.0)) for s in setups]
    truth = tuple(float(np.ptp(r.deviation)) for r in measure_ballbar(machine, quiet))
    results = tuple(r.evaluate() for r in records)
    files: tuple = ()
    if out is not None:
        files = _write(Path(out), records)
    return BallbarSimulated(records, results, files, truth)


def evaluate(files) -> BallbarEvaluated:
    """The range of each ballbar file with its uncertainty
    (:func:`~axiscal.standards.iso10791_6.evaluate_ballbar`)."""
    from axiscal.io.five_axis_ballbar import read_ballbar

    files = list(files)
    if not files:
        raise InputError("give at least one ballbar file")
    records = tuple(read_ballbar(f) for f in files)
    results = []
    for f, r in zip(files, records):
        try:
            results.append(r.evaluate())
        except InputError as exc:
            raise InputError(f"{f}: {exc}") from None
    return BallbarEvaluated(records, tuple(results), tuple(files))


def report(done: BallbarEvaluated, path, tolerance: float | None = None,
           rule: str | None = None) -> Path:
    """Write the report of evaluated set-ups (``axiscal fiveaxis ballbar evaluate --report``):
    :func:`axiscal.report.five_axis_ballbar.ballbar_report`, the report the history writes of
    a stored test; HTML (``.html``) or PDF (``.pdf``); ``tolerance`` (µm) bounds each range.
    Returns the path."""
    from axiscal.report.evaluations import REPORT_TITLES
    from axiscal.report.five_axis_ballbar import ballbar_report

    labels = ", ".join(r.label for r in done.results)
    rep = ballbar_report(zip(done.records, done.results), tolerance=tolerance, rule=rule,
                         title=f"{REPORT_TITLES['fiveaxis-ballbar']} — {labels}",
                         metadata={"files": ", ".join(Path(f).name for f in done.files)})
    return Path(rep.write(path))


def _load(config):
    from axiscal.api._fiveaxis_common import config_dict
    from axiscal.machines.five_axis import five_axis_from_config
    from axiscal.procedures.five_axis_ballbar import ballbar_plan_from_config

    cfg = config_dict(config)
    machine = five_axis_from_config(cfg)
    return machine, ballbar_plan_from_config(cfg, machine)


def _write(folder: Path, records) -> tuple:
    from axiscal.io._files import write_bytes_atomic
    from axiscal.io.five_axis_ballbar import format_ballbar

    texts = [(folder / f"{i}_ballbar.csv", format_ballbar(r)) for i, r in enumerate(records, 1)]
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot make the folder {folder}: {exc.strerror or exc}") from None
    return tuple(write_bytes_atomic(f, t.encode("utf-8")) for f, t in texts)


def _setup_dict(s) -> dict:
    ends = np.degrees([[s.tilt_angle[0], s.c_angle[0]], [s.tilt_angle[-1], s.c_angle[-1]]])
    return {"label": s.label, "kind": s.kind, "swept": s.swept, "direction": s.direction,
            "points": s.points, "pivot_mm": (s.pivot * 1e3).round(6).tolist(),
            "bar": s.bar.round(9).tolist(), "length_mm": s.length * 1e3,
            "spindle_ball_mm": (s.spindle_ball * 1e3).round(6).tolist(),
            "start_deg": ends[0].round(6).tolist(), "end_deg": ends[1].round(6).tolist()}
