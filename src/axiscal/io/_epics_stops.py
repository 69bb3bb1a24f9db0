"""The dwells of an EPICS log read and matched to a test: the reference where it rests, and the
dwells matched to a plan, to the targets given, or to the targets the setpoint passes through
(the rules are in :mod:`axiscal.io.epics`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from axiscal import units
from axiscal.datasets import PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError

__all__ = ["assemble", "settled_mean"]


def assemble(dwells, position, targets, plan, kind, tu, du, k, meta, notes, source
             ) -> tuple[PositioningDataset, int]:
    """The positioning dataset of ``dwells`` and the number of stops that are not measurements
    (over-travel); ``position(dwell)`` is the reference position of a dwell measured (target
    unit ``tu``; ``k`` converts ``tu`` to the deviation unit ``du``)."""
    if targets is not None and plan is not None:
        raise DataFormatError("give the targets or a plan, not both", source)
    reached = [i for i, d in enumerate(dwells) if d.arrival != 0]
    if not reached:
        raise DataFormatError("the setpoint never steps from one held value to another: no "
                              "approach to measure", source)
    first = dwells[0]
    if first.arrival == 0:
        notes += (f"; the first stop (at {first.value:g} {tu}, not reached by a step in the "
                  "log) is not a measurement")
    try:
        if plan is not None:
            ds, found, others = _by_plan(dwells, reached, position, plan, tu, du, k, source)
        else:
            ds, found, others = _by_targets(dwells, reached, position, targets, kind, tu, du,
                                            k, source)
    except DataFormatError:
        raise
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None
    ds = dataclasses.replace(ds, metadata=dataclasses.replace(meta, notes=notes + found))
    return ds, others


def _by_targets(dwells, reached, position, targets, kind, tu, du, k, source):
    given = targets is not None
    tg = _given(targets, tu, source) if given else _passed_through(dwells, source)
    span = float(tg[-1] - tg[0]) if tg.size > 1 else max(1.0, abs(float(tg[0])))
    tol = 1e-6 * span + 5e-6 * float(np.abs(tg).max())  # camonitor's %g: 6 significant digits
    counts: dict = {}
    records, others = [], 0
    for i in reached:
        d = dwells[i]
        j = int(np.argmin(np.abs(tg - d.value)))
        if abs(d.value - tg[j]) > tol:
            others += 1
            continue
        key = (j, d.arrival)
        counts[key] = run = counts.get(key, 0) + 1
        records.append((float(tg[j]), "+" if d.arrival > 0 else "-", run,
                        (position(d) - tg[j]) * k))
    never = [float(t) for j, t in enumerate(tg) if not any(key[0] == j for key in counts)]
    if never:
        raise DataFormatError(f"target {never[0]:g} {tu} is never reached: no stop of the "
                              "setpoint at it", source)
    ds = PositioningDataset.from_records(kind, records, tu, du, None, source=source)
    how = "the targets given" if given else "the values the setpoint passes through"
    return ds, (f"; {len(dwells)} stops: {len(records)} measurements at {tg.size} targets "
                f"({how}), {others} other stops (over-travel, or not at a target)"), others


def _by_plan(dwells, reached, position, plan, tu, du, k, source):
    from axiscal.procedures.capture import Stop, match_stops, plan_dataset

    if units.canonical(plan.target_unit) != tu:
        raise DataFormatError(f"the plan is in {plan.target_unit}, the log is read in {tu}",
                              source)
    f = units.factor(tu)
    stops = [Stop(n, n, dwells[i].t_start, dwells[i].t_end, dwells[i].value * f, 0.0)
             for n, i in enumerate(reached)]
    assigned, overruns = match_stops(stops, plan, factor=f, times=[dwells[0].t_start])
    rows, dev = [], []
    for n, row in assigned:
        d = dwells[reached[n]]
        if (d.arrival > 0) != (plan.direction[row] == "+"):
            raise DataFormatError(
                f"the plan approaches {plan.position[row]:g} {tu} (run {plan.run[row]}) "
                f"{'upwards' if plan.direction[row] == '+' else 'downwards'}, the setpoint came "
                f"from {'below' if d.arrival > 0 else 'above'} (setpoint line {d.line})", source)
        rows.append(row)
        dev.append((position(d) - plan.position[row]) * k)
    ds = plan_dataset(plan, rows, np.array(dev), du)
    return ds, (f"; {len(dwells)} stops matched to the plan {plan.source}: {len(rows)} "
                f"measurements, {overruns} overrun stops"), overruns


def _given(targets, tu, source) -> np.ndarray:
    try:
        tg = np.asarray([float(t) for t in targets], dtype=float)
    except (TypeError, ValueError):
        raise DataFormatError(f"targets {targets!r}: give numbers", source) from None
    if tg.size == 0 or not np.isfinite(tg).all():
        raise DataFormatError("the targets must be finite numbers, at least one", source)
    tg = np.sort(tg)
    if np.any(np.diff(tg) == 0):
        raise DataFormatError("a target is given twice", source)
    return tg


def _passed_through(dwells, source) -> np.ndarray:
    values = sorted({d.value for d in dwells if d.arrival != 0 and d.arrival == d.departure})
    if not values:
        raise DataFormatError("no stop is passed through (reached and left in one direction), "
                              "so the targets cannot be told from the over-travel: give the "
                              "targets or a plan", source)
    out = [values[0]]
    for v in values[1:]:
        if not math.isclose(v, out[-1], rel_tol=1e-12, abs_tol=1e-12):
            out.append(v)
    return np.array(out)


def settled_mean(ref, d, band: float, settled: float, aims, source: str) -> float:
    """Time-weighted mean of the held reference over the settled stretch of the dwell: of the
    stretches within ``band`` at least ``settled`` s long, the longest of the episode whose
    mean is nearest ``aims[0]`` (the setpoint in the reference's numbers) and nearer it than
    ``aims[1]`` (the setpoint before)."""
    t, v = ref.times, ref.values
    i0 = int(np.searchsorted(t, d.t_start, side="right")) - 1
    i1 = int(np.searchsorted(t, d.t_end, side="left"))
    where = f"the stop at {d.value:g} (setpoint line {d.line})"
    if i0 < 0:
        raise DataFormatError(f"PV {ref.name} has no reading before {where}", source)
    held = v[i0:i1]
    w = np.diff(np.concatenate(([d.t_start], t[i0 + 1:i1], [d.t_end])))
    episodes = _stable_episodes(held, w, band, settled)
    if not episodes:
        if not np.isfinite(held).any():
            raise DataFormatError(f"PV {ref.name} is unknown (disconnected, INVALID or not a "
                                  f"number) throughout {where}", source)
        lost = float(w[~np.isfinite(held)].sum())
        why = (f"it is unknown for {lost:.3g} s of it (disconnected, INVALID or not a number)"
               if lost > 0 else "a wider window or a longer dwell?")
        raise DataFormatError(f"PV {ref.name} never stays within the window for {settled:g} s "
                              f"during {where} ({why})", source)
    means = [(float(np.dot(held[a:b], w[a:b]) / w[a:b].sum()) if w[a:b].sum() > 0
              else float(held[b - 1])) for a, b in episodes]
    here, before = aims
    near = [m for m in means if not abs(m - before) <= abs(m - here)]
    if not near:
        raise DataFormatError(f"PV {ref.name} rests only nearer the setpoint before "
                              f"({d.came_from:g}) during {where} (a wider window?)", source)
    return min(near, key=lambda m: abs(m - here))


def _stable_episodes(values: np.ndarray, weights: np.ndarray, band: float, least: float
                     ) -> list:
    """``[(a, b), ...]``: per episode of rest, the run ``values[a:b]`` (finite, max − min ≤
    ``band``) with the largest sum of ``weights``, which is at least ``least``. Two pointers with
    monotonic queues, one pass; overlapping runs are one episode."""
    from collections import deque

    episodes: list = []
    a, total, open_end = 0, 0.0, -1
    hi, lo = deque(), deque()
    for j, x in enumerate(values):
        if not math.isfinite(x):
            a, total = j + 1, 0.0
            hi.clear()
            lo.clear()
            continue
        while hi and values[hi[-1]] <= x:
            hi.pop()
        hi.append(j)
        while lo and values[lo[-1]] >= x:
            lo.pop()
        lo.append(j)
        total += weights[j]
        while values[hi[0]] - values[lo[0]] > band:
            total -= weights[a]
            a += 1
            while hi[0] < a:
                hi.popleft()
            while lo[0] < a:
                lo.popleft()
        if total >= least:
            if episodes and a < open_end:           # overlaps the episode's last run
                best = episodes[-1]
                if total > best[2]:
                    episodes[-1] = (a, j + 1, total)
            else:
                episodes.append((a, j + 1, total))
            open_end = j + 1
    return [(p, q) for p, q, _ in episodes]
