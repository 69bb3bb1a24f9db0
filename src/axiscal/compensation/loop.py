"""Measure, compensate, re-measure: the loop of Yüksel et al., Position accuracy and repeatability calibration of turn tables's last paragraph on a simulated machine.

"If results are not satisfying, a correction can be implemented electronically by the help of
obtained deviations for each steps ... After all corrections, all test procedure shall be
repeated." (Yüksel et al., Position accuracy and repeatability calibration of turn tables). :func:`run_compensation_loop`:

1. runs the configured ISO 230-2 test on the simulated axis and evaluates it;
2. builds a table (:func:`~axiscal.compensation.tables.table_from_result`), writes it in the
   controller's format and *parses the file back* — the machine gets what the file says;
3. repeats the same test on the axis seen through the controller
   (:class:`~axiscal.compensation.apply.CompensatedAxis`), with the same random stream
   continuing, and evaluates it again.

What remains after compensation is explained by two terms, both reported:

* ``spacing_residual``: E of the compensated axis *without noise* when its table is built from
  the noise-free deviations at the same targets and spacing — the error the table's points and
  the test's targets cannot follow (interpolation between them, a unidirectional table's
  reversal) plus the controller's rounding;
* the repeatability: each correction comes from a mean of n readings and each re-measured mean
  is one too, so two independent means of standard deviation σ/√n meet at each end of the range
  of E; ``budget_E = spacing_residual + 2·3·√2·σ/√n + resolution`` (±3σ of a difference of two
  means at both ends), with σ the standard deviation of one reading (axis repeatability and the
  instrument's noise together).

Configuration: the ``[axis]``, ``[test]``, ``[meta]`` tables of ``axiscal simulate`` plus::

    [compensation]
    controller = "siemens-840d"   # siemens-840d, fanuc, heidenhain, linuxcnc, csv
    spacing = 10.0                # mm or deg
    bidirectional = true
    resolution = 0.1              # µm or arcsec (corrections are rounded to it)
    extrapolation = "hold"        # or "linear"
    options = { machine_axis = "X1" }   # passed to the controller's writer
"""

from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, replace

import numpy as np

from axiscal import units
from axiscal.compensation.apply import CompensatedAxis
from axiscal.compensation.controllers import check_options
from axiscal.compensation.controllers import controller as controller_module
from axiscal.compensation.tables import CompensationTable, table_from_deviations, table_from_result
from axiscal.datasets import AxisKind
from axiscal.errors import ConfigError, InputError
from axiscal.standards.iso230_2 import PARAMETER_NAMES

__all__ = ["CompensationLoopResult", "run_compensation_loop", "loop_settings"]

_KEYS = {"controller", "spacing", "bidirectional", "resolution", "extrapolation", "options"}


@dataclass(frozen=True, eq=False)
class CompensationLoopResult:
    """Before and after of one compensation loop (values in the test's deviation unit).

    Attributes
    ----------
    before, after : Iso230_2Result
        Evaluation of the test on the bare axis and on the compensated axis.
    table : CompensationTable
        The table the controller applied (parsed back from its file).
    controller_file : ControllerFile
        The file as written.
    truth_before, truth_after : dict of str to float
        E, M, B (and their directional forms) without noise, bare and compensated.
    spacing_residual : float
        E left by a noise-free table at the same targets and spacing (see the module docstring).
    sigma : float
        Standard deviation of one reading (repeatability and instrument), deviation unit.
    n_runs : int
    budget_E : float
        What E after compensation may be, given ``spacing_residual`` and ``sigma``.
    between_targets_E : float
        E of the compensated axis without noise over a dense grid (ten points per table
        interval), not only at the targets: what the table leaves where nobody measured.
    sign : float
        +1 as the convention says; −1 for the wrong-sign demonstration.
    before_data, after_data : PositioningDataset
        The readings of the two tests (what a history keeps).
    """

    before: object
    after: object
    table: CompensationTable
    controller_file: object
    truth_before: dict
    truth_after: dict
    spacing_residual: float
    sigma: float
    n_runs: int
    budget_E: float
    between_targets_E: float
    sign: float = 1.0
    before_data: object = None
    after_data: object = None

    @property
    def unit(self) -> str:
        """Deviation unit of every figure."""
        return self.before.deviation_unit

    @property
    def reduction(self) -> float:
        """Fraction by which E fell: 1 − E_after / E_before (negative if it grew)."""
        return 1.0 - self.after.E_up / self.before.E_up if self.before.E is None \
            else 1.0 - self.after.E / self.before.E

    def rows(self) -> list[tuple[str, float | None, float | None]]:
        """(parameter, before, after) for A … B̄."""
        b, a = self.before.parameters(), self.after.parameters()
        return [(k, b[k], a[k]) for k in PARAMETER_NAMES]

    def __str__(self) -> str:
        u = self.unit
        lines = [f"Compensation loop ({self.controller_file.controller}, sign {self.sign:+g}): "
                 f"{self.table.n_points} points every {self.table.spacing:g} "
                 f"{self.table.position_unit}"]
        for k, b, a in self.rows():
            fb = "n/a" if b is None else f"{b:.3g}"
            fa = "n/a" if a is None else f"{a:.3g}"
            lines.append(f"  {k:<7} before {fb:>8}  after {fa:>8} {u}")
        lines.append(f"  E fell by {100 * self.reduction:.1f} %; budget for E after: "
                     f"{self.budget_E:.3g} {u} (spacing {self.spacing_residual:.3g} + "
                     f"repeatability σ = {self.sigma:.3g} over {self.n_runs} runs); "
                     f"between the targets E would be {self.between_targets_E:.3g} {u} without noise")
        return "\n".join(lines)


#: The tables of a compensation-loop configuration.
_TABLES = {"axis", "test", "meta", "compensation"}


def loop_settings(config: dict) -> dict:
    """Validate the ``[compensation]`` table (and the names of all tables) and fill defaults."""
    from axiscal._schema import refuse_unknown

    refuse_unknown(config, _TABLES)
    refuse_unknown(config.get("compensation", {}), _KEYS, "[compensation]")
    c = dict(config.get("compensation", {}))
    if "spacing" not in c:
        raise ConfigError("[compensation] needs spacing (mm or deg between table points)")
    out = dict(controller=str(c.get("controller", "csv")), spacing=c["spacing"],
               bidirectional=c.get("bidirectional", True), resolution=c.get("resolution", 0.1),
               extrapolation=str(c.get("extrapolation", "hold")), options=c.get("options", {}))
    for k in ("spacing", "resolution"):
        v = out[k]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
            raise ConfigError(f"[compensation] {k} = {v!r} must be a number >= 0")
    if not isinstance(out["bidirectional"], bool):
        raise ConfigError(f"[compensation] bidirectional = {out['bidirectional']!r} must be true or false")
    if not isinstance(out["options"], dict):
        raise ConfigError("[compensation] options must be a table")
    return out


def run_compensation_loop(config: dict, seed: int = 1, sign: float = 1.0, machine=None,
                          **overrides) -> CompensationLoopResult:
    """Run measure → compensate → re-measure on the configured simulated axis.

    Parameters
    ----------
    config : dict
        Parsed TOML: ``[axis]``, ``[test]``, optional ``[meta]`` and ``[compensation]``.
    seed : int
        Seed of the one random stream both tests draw from.
    sign : float
        +1 (the convention) or −1 (apply every correction with the wrong sign).
    machine : optional
        A real controller to measure through instead of the simulation (``machine.measure(plan,
        axis, rng, measurement_sigma, controller_file)``, the file None for the bare axis), e.g.
        :class:`axiscal.compensation.on_controller.OnLinuxCNC`; the truth figures stay those of
        the simulated axis and of the table read back.
    **overrides
        Replace ``[compensation]`` keys (``controller=``, ``spacing=`` …).

    Returns
    -------
    CompensationLoopResult
    """
    from axiscal.machines.config import axis_from_config
    from axiscal.procedures.positioning import plan_from_config, simulate_positioning_test
    from axiscal.standards.iso230_2 import evaluate

    cfg = dict(config)
    cfg["compensation"] = {**config.get("compensation", {}), **overrides}
    s = loop_settings(cfg)
    from axiscal._schema import refuse_unknown

    refuse_unknown(config, {"axis", "test", "meta", "compensation"})
    if "axis" not in config:
        raise ConfigError("the configuration has no [axis] table")
    axis = axis_from_config(config["axis"])
    kind = AxisKind.LINEAR if hasattr(axis, "systematic_deviation") else AxisKind.ROTARY
    from axiscal.machines.config import check_test_types

    check_test_types(config.get("test", {}))   # a value of the wrong type, named
    test = dict(config.get("test", {}))
    msigma = float(test.pop("measurement_sigma", 0.0))
    plan = plan_from_config(test, kind, axis.name)
    rng = np.random.default_rng(seed)
    ds0 = (simulate_positioning_test(plan, axis, rng, measurement_sigma=msigma) if machine is None
           else machine.measure(plan, axis, rng, msigma, None))
    before = evaluate(ds0)
    mod = controller_module(s["controller"])
    travel = _travel(axis, plan.target_unit)
    try:
        table = table_from_result(before, float(s["spacing"]), bidirectional=s["bidirectional"],
                                  resolution=float(s["resolution"]), extrapolation=s["extrapolation"],
                                  axis=axis.name)
    except InputError as exc:
        raise ConfigError(f"[compensation]: {exc}") from None
    try:
        options = check_options(mod.write, s["options"], f"[compensation] {mod.NAME}")
    except InputError as exc:
        raise ConfigError(str(exc)) from None
    cf = mod.write(table, travel, **options)
    applied = _read_back(mod, cf, s["options"])
    comp = CompensatedAxis(axis, applied, sign=sign)
    ds1 = (simulate_positioning_test(plan, comp, rng, measurement_sigma=msigma) if machine is None
           else machine.measure(plan, axis, rng, msigma, cf))
    after = evaluate(ds1)
    du = ds0.deviation_unit
    ideal = _ideal_table(plan, axis, du, table, s)
    residual = _truth(plan, CompensatedAxis(axis, ideal), du)["E"]
    sigma = math.hypot(axis.repeatability_sigma / units.factor(du), msigma)
    resolution = max(float(s["resolution"]), applied.resolution)
    budget = residual + 6.0 * math.sqrt(2.0) * sigma / math.sqrt(plan.runs) + resolution
    dense = np.linspace(applied.start, applied.end, 10 * (applied.n_points - 1) + 1)
    dense = dense[(dense >= plan.targets[0]) & (dense <= plan.targets[-1])]
    between = _truth(replace(plan, targets=dense), comp, du)["E"]
    return CompensationLoopResult(before, after, applied, cf, _truth(plan, axis, du),
                                  _truth(plan, comp, du), residual, sigma, plan.runs, budget,
                                  between, sign, ds0, ds1)


# -- helpers ---------------------------------------------------------------------------------
def _travel(axis, unit):
    if axis.travel is None:
        return None
    k = units.factor(unit)
    return (axis.travel[0] / k, axis.travel[1] / k)


def _read_back(mod, cf, options) -> CompensationTable:
    """Parse the written file with what the format itself does not carry."""
    t = cf.table
    given = dict(axis_kind=t.axis_kind, axis=t.axis, correction_unit=t.correction_unit,
                 reference_position=t.reference_position, **options)
    accepted = inspect.signature(mod.parse).parameters
    parsed = mod.parse(cf.text, **{k: v for k, v in given.items() if k in accepted})
    return replace(parsed, axis=t.axis, reference_index=t.reference_index)


def _systematic(axis, x, d):
    fn = getattr(axis, "systematic_deviation", None) or axis.systematic_error
    return np.asarray(fn(x, d))


def _truth(plan, axis, du) -> dict:
    """E, E↑, E↓, M, B of the systematic deviation at the targets (no noise), in ``du``."""
    x = plan.targets * units.factor(plan.target_unit)
    k = 1.0 / units.factor(du)
    up = _systematic(axis, x, 1) * k
    down = _systematic(axis, x, -1) * k
    both = np.concatenate([up, down])
    return dict(E=float(np.ptp(both)), E_up=float(np.ptp(up)), E_down=float(np.ptp(down)),
                M=float(np.ptp(0.5 * (up + down))), B=float(np.max(np.abs(up - down))))


def _ideal_table(plan, axis, du, table, s) -> CompensationTable:
    """The table the same settings give from noise-free deviations at the targets."""
    x = plan.targets * units.factor(plan.target_unit)
    k = 1.0 / units.factor(du)
    up, down = _systematic(axis, x, 1) * k, _systematic(axis, x, -1) * k
    if not s["bidirectional"]:
        up = down = 0.5 * (up + down)
    return table_from_deviations(
        plan.targets, up, down if s["bidirectional"] else None, spacing=table.spacing,
        start=table.start, end=table.end, extrapolation=s["extrapolation"], modulo=table.modulo,
        axis_kind=table.axis_kind, position_unit=table.position_unit, correction_unit=du)
