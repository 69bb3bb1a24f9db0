"""ISO 230-2 positioning tests: test plans, and their execution on a simulated axis.

A :class:`TestPlan` is data: the target positions, the number of runs, the cycle (linear or
pilgrim step), the overrun used to approach each target from one direction, and the dwell. Its
:meth:`TestPlan.steps` is the exact sequence of commanded moves, which the simulated procedure
executes and a user can export (:meth:`TestPlan.to_csv`) to drive a real machine.

Target positions (ISO 230-2:2014 §5.2)
--------------------------------------
Linear axes: at least five target positions per metre and at least five in all. They are spaced
``P_i = (i - 1) p + r_i`` where ``p`` is the uniform interval and ``r_i`` a random offset, different
at each target, so that periodic errors (ball-screw pitch, encoder graduation) are not sampled at
the same phase everywhere. The standard does not bound ``r``; this module draws it uniformly in
``±irregularity · p`` (default 0.25, so targets stay ordered and at least p/2 apart) and keeps the
first and last targets at the ends of the travel. The draw comes from ``seed``, so a plan is
reproducible.

Rotary axes: at least 3, 5 or 8 targets for a travel up to 90°, up to 180° and beyond (ISO 230-2
Table 1, Yüksel et al., Position accuracy and repeatability calibration of turn tables Table 1), and the main positions 0°, 90°, 180°, 270° wherever the travel has them.
Over a full turn 360° is a target of its own (Yüksel et al., Position accuracy and repeatability calibration of turn tables Table 3 lists 0° ... 315° and 0°/360°).

Cycles (ISO 230-2:2014 §5.3 and its figures)
--------------------------------------------
``linear``: each run moves through all targets in the positive direction, then back through all in
the negative direction; the direction is reversed beyond the last target by the overrun, and the
first target of each run is approached from ``overrun`` below it (Yüksel et al., Position accuracy and repeatability calibration of turn tables used 5° on a turntable).
``pilgrim``: each target is approached ``runs`` times from below and from above before the axis
moves to the next target (the pilgrim-step cycle), each approach starting from ``overrun`` away.
"""

from __future__ import annotations

import csv as _csv
import io
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from axiscal import units
from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import InputError
from axiscal.standards.iso230_2 import minimum_linear_targets, minimum_rotary_targets

__all__ = [
    "PlanStep",
    "TestPlan",
    "plan_linear",
    "plan_rotary",
    "simulate_positioning_test",
]

#: Most readings in one direction a plan may hold (targets x runs): a simulated move costs about
#: 0.25 ms, and a real test of 20,000 stops is already days of machine time.
MAX_READINGS_PER_DIRECTION = 20_000

Cycle = Literal["linear", "pilgrim"]
_MAIN_POSITIONS_DEG = (0.0, 90.0, 180.0, 270.0, 360.0)


@dataclass(frozen=True)
class PlanStep:
    """One commanded move of a test plan.

    Attributes
    ----------
    seq : int
        Position in the sequence, from 1.
    kind : {"measure", "overrun"}
        A measurement at a target (after the dwell) or a move past a target to reverse.
    position : float
        Commanded position in the plan's ``target_unit``.
    direction : str
        ``+`` or ``-``: the direction of the move that arrives at ``position``.
    run : int
        Run number j (1-based).
    target_index : int
        Index i of the target (0-based) for a measurement, -1 for an overrun move.
    """

    seq: int
    kind: str
    position: float
    direction: str
    run: int
    target_index: int


@dataclass(frozen=True, eq=False)
class TestPlan:
    """An ISO 230-2 positioning test plan (data a simulated or real procedure executes).

    Attributes
    ----------
    axis_kind : AxisKind
    targets : ndarray, ``target_unit``
        Target positions, strictly increasing.
    target_unit : str
        ``mm`` for linear axes, ``deg`` for rotary axes.
    runs : int
        Runs per direction (ISO 230-2 asks for 5).
    cycle : {"linear", "pilgrim"}
    bidirectional : bool
        False measures only in the positive direction.
    overrun : float, ``target_unit``
        Distance past a target from which it is approached, and past the end before reversing.
    dwell : float, seconds
        Time at each target before the reading is taken.
    axis : str
        Axis name, for the exported plan and the dataset.
    """

    __test__ = False  # not a pytest test class, despite the name

    axis_kind: AxisKind
    targets: np.ndarray
    target_unit: str
    runs: int = 5
    cycle: Cycle = "linear"
    bidirectional: bool = True
    overrun: float = 5.0
    dwell: float = 4.0
    axis: str = ""

    def __post_init__(self) -> None:
        kind = AxisKind.parse(self.axis_kind)
        object.__setattr__(self, "axis_kind", kind)
        tu = units.canonical(self.target_unit)
        if units.dimension(tu) != kind.dimension:
            raise InputError(f"target unit {self.target_unit!r} does not suit a {kind.value} axis")
        object.__setattr__(self, "target_unit", tu)
        t = np.array(self.targets, dtype=float)
        if t.ndim != 1 or t.size < 2:
            raise InputError(f"a plan needs at least 2 target positions, got {t.size}")
        if not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise InputError("target positions must be finite and strictly increasing")
        t.flags.writeable = False
        object.__setattr__(self, "targets", t)
        if not isinstance(self.runs, (int, np.integer)) or self.runs < 1:
            raise InputError(f"runs = {self.runs!r} must be a whole number >= 1 (ISO 230-2: 5)")
        if t.size * self.runs > MAX_READINGS_PER_DIRECTION:
            raise InputError(f"{t.size} targets x {self.runs} runs is {t.size * self.runs} readings "
                             f"a direction; a plan holds at most {MAX_READINGS_PER_DIRECTION} "
                             "(ISO 230-2:2014 asks for 5 runs at 5 targets a metre)")
        if self.cycle not in ("linear", "pilgrim"):
            raise InputError(f"cycle {self.cycle!r} is not 'linear' or 'pilgrim'")
        if not (math.isfinite(self.overrun) and self.overrun > 0):
            raise InputError(f"overrun = {self.overrun!r} must be positive (it reverses the axis)")
        if not (math.isfinite(self.dwell) and self.dwell >= 0):
            raise InputError(f"dwell = {self.dwell!r} s must be zero or positive")

    def steps(self) -> tuple[PlanStep, ...]:
        """The commanded sequence of the whole test (see the module docstring for the cycles)."""
        raw = self._linear_steps() if self.cycle == "linear" else self._pilgrim_steps()
        return tuple(PlanStep(k + 1, *s) for k, s in enumerate(raw))

    def _linear_steps(self):
        t, o = self.targets, self.overrun
        out = []
        for j in range(1, self.runs + 1):
            out.append(("overrun", float(t[0] - o), "-", j, -1))
            out.extend(("measure", float(p), "+", j, i) for i, p in enumerate(t))
            if self.bidirectional:
                out.append(("overrun", float(t[-1] + o), "+", j, -1))
                out.extend(("measure", float(t[i]), "-", j, i) for i in range(t.size - 1, -1, -1))
        return out

    def _pilgrim_steps(self):
        o = self.overrun
        out = []
        for i, p in enumerate(self.targets):
            for j in range(1, self.runs + 1):
                out.append(("overrun", float(p - o), "-", j, -1))
                out.append(("measure", float(p), "+", j, i))
                if self.bidirectional:
                    out.append(("overrun", float(p + o), "+", j, -1))
                    out.append(("measure", float(p), "-", j, i))
        return out

    @property
    def n_measurements(self) -> int:
        """Number of readings the plan takes."""
        return self.targets.size * self.runs * (2 if self.bidirectional else 1)

    @property
    def travel(self) -> float:
        """Measured travel in ``target_unit``."""
        return float(self.targets[-1] - self.targets[0])

    def to_csv(self) -> str:
        """The plan as CSV: ``seq,kind,position,direction,run,target_index,dwell_s``.

        A first comment line names the axis, unit, runs and cycle.
        """
        buf = io.StringIO()
        buf.write(f"# axis={self.axis or '-'} axis_kind={self.axis_kind.value} "
                  f"target_unit={self.target_unit} runs={self.runs} cycle={self.cycle} "
                  f"bidirectional={str(self.bidirectional).lower()} overrun={self.overrun:g}\n")
        w = _csv.writer(buf, lineterminator="\n")
        w.writerow(["seq", "kind", "position", "direction", "run", "target_index", "dwell_s"])
        for s in self.steps():
            w.writerow([s.seq, s.kind, f"{s.position:.6f}", s.direction, s.run,
                        s.target_index if s.target_index >= 0 else "",
                        f"{self.dwell:g}" if s.kind == "measure" else "0"])
        return buf.getvalue()

    def __str__(self) -> str:
        shown = self.targets if self.targets.size <= 24 else np.concatenate(
            [self.targets[:10], self.targets[-10:]])
        ts = ", ".join(f"{t:g}" for t in shown)
        if self.targets.size > 24:
            ts = ts.replace(f"{self.targets[9]:g}, ", f"{self.targets[9]:g}, ..., ", 1)
        return (
            f"ISO 230-2 plan for {self.axis or 'the'} {self.axis_kind.value} axis: "
            f"{self.targets.size} targets [{ts}] {self.target_unit}; {self.runs} runs, "
            f"{'bidirectional' if self.bidirectional else 'positive direction only'}, "
            f"{self.cycle} cycle, overrun {self.overrun:g} {self.target_unit}, dwell {self.dwell:g} s; "
            f"{self.n_measurements} readings"
        )


def plan_linear(
    length: float,
    start: float = 0.0,
    n_targets: int | None = None,
    irregularity: float = 0.25,
    seed: int = 0,
    runs: int = 5,
    cycle: Cycle = "linear",
    bidirectional: bool = True,
    overrun: float = 5.0,
    dwell: float = 4.0,
    axis: str = "X",
) -> TestPlan:
    """A plan for a linear axis by ISO 230-2:2014 §5.2 (all lengths in mm).

    Parameters
    ----------
    length : float, mm
        Measurement travel (last target minus first).
    start : float, mm
        First target.
    n_targets : int, optional
        Number of targets; default the standard's minimum (5 per metre, at least 5), and never
        fewer than that minimum.
    irregularity : float
        Largest random offset as a fraction of the uniform interval (0 gives equal spacing; at
        most 0.45 so targets stay ordered).
    seed : int
        Seed of the random offsets (the plan is reproducible).
    runs, cycle, bidirectional, overrun, dwell, axis
        See :class:`TestPlan`; ``overrun`` in mm, ``dwell`` in s.

    Examples
    --------
    >>> p = plan_linear(800, irregularity=0)
    >>> p.targets.tolist()
    [0.0, 200.0, 400.0, 600.0, 800.0]
    """
    if not (math.isfinite(length) and length > 0):
        raise InputError(f"length = {length!r} mm must be positive")
    minimum = minimum_linear_targets(length)
    n = minimum if n_targets is None else int(n_targets)
    if n < minimum:
        raise InputError(
            f"{n} targets over {length:g} mm; ISO 230-2 asks for at least {minimum} "
            "(5 per metre and 5 in all)"
        )
    if not 0 <= irregularity <= 0.45:
        raise InputError(f"irregularity = {irregularity!r} must be between 0 and 0.45")
    irregularity += 0.0   # -0.0 is 0 (numpy's uniform refuses a high of -0.0 below a low of 0)
    p = length / (n - 1)
    r = np.random.default_rng(seed).uniform(-irregularity, irregularity, n) * p
    r[0] = r[-1] = 0.0
    targets = start + np.arange(n) * p + r
    targets = np.round(targets, 3)  # a controller is commanded in µm steps
    return TestPlan(AxisKind.LINEAR, targets, "mm", runs, cycle, bidirectional, overrun, dwell, axis)


def plan_rotary(
    travel: float = 360.0,
    start: float = 0.0,
    step: float | None = None,
    n_targets: int | None = None,
    runs: int = 5,
    cycle: Cycle = "linear",
    bidirectional: bool = True,
    overrun: float = 5.0,
    dwell: float = 4.0,
    axis: str = "C",
) -> TestPlan:
    """A plan for a rotary axis by ISO 230-2:2014 Table 1 (all angles in degrees).

    Targets are evenly spaced by ``step`` (or split the travel into ``n_targets - 1`` intervals;
    default 45°, as Yüksel et al., Position accuracy and repeatability calibration of turn tables), and the main positions 0°, 90°, 180°, 270° (and 360°) are added
    wherever the travel includes them.

    Examples
    --------
    >>> plan_rotary(360).targets.tolist()
    [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0, 360.0]
    >>> plan_rotary(120, start=-60, step=40).targets.tolist()
    [-60.0, -20.0, 0.0, 20.0, 60.0]
    """
    if not (math.isfinite(travel) and travel > 0):
        raise InputError(f"travel = {travel!r} deg must be positive")
    if step is not None and n_targets is not None:
        raise InputError("give either step or n_targets, not both")
    if n_targets is not None:
        if n_targets < 2:
            raise InputError(f"n_targets = {n_targets} must be at least 2")
        grid = start + np.linspace(0.0, travel, int(n_targets))
    else:
        step = 45.0 if step is None else float(step)
        if not (math.isfinite(step) and 0 < step <= travel):
            raise InputError(f"step = {step!r} deg must be positive and not more than the travel")
        k = math.floor(travel / step + 1e-9)
        grid = start + step * np.arange(k + 1)
        if not math.isclose(grid[-1], start + travel, abs_tol=1e-9):
            grid = np.append(grid, start + travel)
    end = start + travel
    main = [m for m in _MAIN_POSITIONS_DEG if start - 1e-9 <= m <= end + 1e-9]
    targets = np.unique(np.round(np.concatenate([grid, main]), 9))
    distinct = np.unique(np.round(np.mod(targets, 360.0), 9) % 360.0).size
    minimum = minimum_rotary_targets(travel)
    if distinct < minimum:
        raise InputError(
            f"{distinct} target positions over {travel:g} deg; ISO 230-2 Table 1 asks for at least "
            f"{minimum}"
        )
    return TestPlan(AxisKind.ROTARY, targets, "deg", runs, cycle, bidirectional, overrun, dwell, axis)


def simulate_positioning_test(
    plan: TestPlan,
    axis,
    rng: np.random.Generator,
    deviation_unit: str | None = None,
    feed: float | None = None,
    measurement_sigma: float = 0.0,
    metadata: Metadata | None = None,
) -> PositioningDataset:
    """Execute a plan on a simulated axis and return the measured dataset.

    The reading at each target is the axis's actual position (from its ``move`` method, with the
    direction of approach, its repeatability noise and the elapsed time for drift) plus an
    instrument noise of ``measurement_sigma``. Time advances by the move at ``feed`` plus the dwell.

    Parameters
    ----------
    plan : TestPlan
    axis : LinearAxis or RotaryAxis
        The simulated machine axis (SI units inside).
    rng : numpy.random.Generator
    deviation_unit : str, optional
        ``um`` (linear) or ``arcsec`` (rotary) by default.
    feed : float, optional
        Speed in plan units per second (default 20 mm/s or 10 deg/s, Yüksel et al., Position accuracy and repeatability calibration of turn tables's table speed).
    measurement_sigma : float
        Standard deviation of the instrument's reading noise, in ``deviation_unit``.
    metadata : Metadata, optional

    Returns
    -------
    PositioningDataset
        In the plan's target unit and ``deviation_unit``.
    """
    kind = plan.axis_kind
    du = deviation_unit or ("um" if kind is AxisKind.LINEAR else "arcsec")
    if units.dimension(du) != kind.dimension:
        raise InputError(f"deviation unit {du!r} does not suit a {kind.value} axis")
    to_si = units.factor(plan.target_unit)
    dev_per_si = 1.0 / units.factor(du)
    feed = feed if feed is not None else (20.0 if kind is AxisKind.LINEAR else 10.0)
    if not feed > 0:
        raise InputError(f"feed = {feed!r} must be positive")
    steps = plan.steps()
    # Check the whole sequence (overrun moves too) against the axis's travel before moving.
    axis.check_in_travel(np.array([s.position for s in steps]) * to_si)
    up = np.full((plan.targets.size, plan.runs), np.nan)
    down = np.full((plan.targets.size, plan.runs if plan.bidirectional else 0), np.nan)
    for t, s, d, actual in execute_plan(plan, axis, rng, feed, to_si):
        dev = (actual - s.position * to_si) * dev_per_si
        if measurement_sigma > 0:
            dev += rng.normal(0.0, measurement_sigma)
        (up if d > 0 else down)[s.target_index, s.run - 1] = dev
    meta = metadata or Metadata(axis=plan.axis or getattr(axis, "name", ""))
    return PositioningDataset(kind, plan.targets, up, down, plan.target_unit, du, meta)


def execute_plan(plan: TestPlan, axis, rng: np.random.Generator, feed: float, to_si: float):
    """Run ``plan`` on a simulated axis: yields ``(time s, step, direction ±1, actual SI)`` at
    each measurement, time advancing by each move at ``feed`` (plan units per second) and the
    dwell."""
    steps = plan.steps()
    t, here = 0.0, float(steps[0].position)
    for s in steps:
        t += abs(s.position - here) / feed
        here = s.position
        if s.kind != "measure":
            continue
        t += plan.dwell
        d = 1 if s.direction == "+" else -1
        yield t, s, d, float(axis.move(s.position * to_si, d, rng, time=t))


# -- configuration-driven simulation and the truth it knows ----------------------------------
@dataclass(frozen=True, eq=False)
class SimulatedTest:
    """A simulated positioning test: the plan, the axis, the dataset, its evaluation and the truth.

    Attributes
    ----------
    plan : TestPlan
    axis : LinearAxis or RotaryAxis
    dataset : PositioningDataset
    result : Iso230_2Result
    truth_up, truth_down : ndarray, ``dataset.deviation_unit``
        Systematic deviation of the axis at each target and direction, without noise (at t = 0).
    truth : dict of str to float
        E, E_up, E_down, M, B and B_mean implied by the injected errors alone, and ``R_expected``,
        the bidirectional repeatability the injected noise implies (4σ + |b|, ISO 230-2 eq. 12
        with s = σ).
    """

    plan: TestPlan
    axis: object
    dataset: PositioningDataset
    result: object
    truth_up: np.ndarray
    truth_down: np.ndarray
    truth: dict


def plan_from_config(test: dict, kind: AxisKind, axis_name: str = "",
                     other_keys: frozenset[str] = frozenset()) -> TestPlan:
    """Build a plan from a ``[test]`` table.

    Linear keys: ``length_mm``, ``start_mm``, ``n_targets``, ``irregularity``, ``seed``;
    rotary keys: ``travel_deg``, ``start_deg``, ``step_deg``, ``n_targets``; both: ``runs``,
    ``cycle``, ``bidirectional``, ``overrun`` (mm or deg), ``dwell_s``. ``other_keys`` are
    read by the caller (accepted here, not used).
    """
    from axiscal.errors import ConfigError
    from axiscal.machines.config import check_test_types

    check_test_types(test)
    common = {"runs", "cycle", "bidirectional", "overrun", "dwell_s", "n_targets"}
    own = ({"length_mm", "start_mm", "irregularity", "seed"} if kind is AxisKind.LINEAR
           else {"travel_deg", "start_deg", "step_deg"})
    from axiscal._schema import refuse_unknown

    refuse_unknown(test, common | own | other_keys, "[test]")
    kw = dict(runs=int(test.get("runs", 5)), cycle=test.get("cycle", "linear"),
              bidirectional=bool(test.get("bidirectional", True)),
              overrun=float(test.get("overrun", 5.0)), dwell=float(test.get("dwell_s", 4.0)),
              axis=axis_name)
    try:
        if kind is AxisKind.LINEAR:
            if "length_mm" not in test:
                raise ConfigError("[test] needs length_mm for a linear axis")
            return plan_linear(float(test["length_mm"]), float(test.get("start_mm", 0.0)),
                               test.get("n_targets"), float(test.get("irregularity", 0.25)),
                               int(test.get("seed", 0)), **kw)
        return plan_rotary(float(test.get("travel_deg", 360.0)), float(test.get("start_deg", 0.0)),
                           test.get("step_deg"), test.get("n_targets"), **kw)
    except ConfigError:
        raise
    except (InputError, TypeError, ValueError) as exc:
        raise ConfigError(f"[test]: {exc}") from None


def simulate_from_config(config: dict, seed: int = 1) -> SimulatedTest:
    """Run the positioning test a configuration describes (``[axis]``, ``[test]``, ``[meta]``).

    ``[test]`` may also hold ``measurement_sigma`` (instrument noise in the deviation unit) —
    read here, not by :func:`plan_from_config`. The random stream is ``default_rng(seed)``.
    """
    from axiscal.errors import ConfigError
    from axiscal.machines.config import axis_from_config
    from axiscal.standards.iso230_2 import evaluate

    from axiscal._schema import refuse_unknown

    refuse_unknown(config, {"axis", "test", "meta"})
    if "axis" not in config:
        raise ConfigError("the configuration has no [axis] table")
    axis = axis_from_config(config["axis"])
    kind = AxisKind.LINEAR if axis.__class__.__name__ == "LinearAxis" else AxisKind.ROTARY
    from axiscal.machines.config import check_test_types

    test = config.get("test", {})
    check_test_types(test)
    sigma = float(test.get("measurement_sigma", 0.0))
    if sigma < 0:
        raise ConfigError(f"[test] measurement_sigma = {sigma!r} must be zero or positive")
    plan = plan_from_config(test, kind, axis.name, frozenset({"measurement_sigma"}))
    try:
        meta = Metadata(**{k: str(v) for k, v in config.get("meta", {}).items()}, axis=axis.name)
    except TypeError as exc:
        raise ConfigError(f"[meta]: {exc}") from None
    ds = simulate_positioning_test(plan, axis, np.random.default_rng(seed),
                                   measurement_sigma=sigma, metadata=meta)
    result = evaluate(ds)
    t_up, t_down, truth = _truth(plan, axis, ds.deviation_unit)
    return SimulatedTest(plan, axis, ds, result, t_up, t_down, truth)


def _truth(plan: TestPlan, axis, deviation_unit: str):
    """Systematic deviations at the targets and the ISO 230-2 figures they imply (no noise).

    The figures come from :func:`axiscal.standards.iso230_2.evaluate` itself, applied to the
    noise-free deviations (two identical runs, so every s is 0): E, E↑, E↓, M, B and B̄ are then
    exactly what the injected errors imply. ``R_expected`` is ISO 230-2 eq. 12 with s = σ:
    4σ + |B_i| at its largest.
    """
    from axiscal.standards.iso230_2 import evaluate

    x = plan.targets * units.factor(plan.target_unit)
    k = 1.0 / units.factor(deviation_unit)
    sys_fn = axis.systematic_deviation if hasattr(axis, "systematic_deviation") else axis.systematic_error
    up = np.asarray(sys_fn(x, 1)) * k
    down = np.asarray(sys_fn(x, -1)) * k if plan.bidirectional else np.full(x.size, np.nan)
    down_runs = np.column_stack([down, down]) if plan.bidirectional else np.empty((x.size, 0))
    ideal = evaluate(PositioningDataset(plan.axis_kind, plan.targets, np.column_stack([up, up]),
                                        down_runs, plan.target_unit, deviation_unit))
    sigma = axis.repeatability_sigma * k
    names = ("E", "E_up", "E_down", "M", "B", "B_mean") if plan.bidirectional else ("E_up",)
    truth = {name: getattr(ideal, name) for name in names}
    truth["R_expected"] = float(4 * sigma + (ideal.B or 0.0))
    return up, down, truth
