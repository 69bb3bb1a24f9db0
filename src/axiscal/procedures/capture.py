"""A positioning test taken from a continuous record, without a trigger at the targets.

The laser records all the time (a dynamic capture); the machine runs the plan, stopping at each
target for its dwell. The stops are found where the reading stays within a band (``window``)
for at least ``dwell`` seconds after a light smoothing (a 10 ms moving average removes noise and
vibration well above the band's time scale), matched in order to the plan's steps (overrun moves
may or may not show a stop), and averaged over the second half of each stop (the tail of the
settling ringing is out by then, as at the end of a triggered dwell); the deviation at a target is
that mean minus the target (ISO 230-2:2014 §3.1: ``x_ij = P_ij − P_i``), exactly what a triggered
capture would give at the end of the dwell, less the noise of a single reading.

A record that does not fit the plan is refused by saying where: the measurement with no stop
(target, run, direction and the time span it was expected in), or the stop the plan does not
explain (its time and position).

The dynamic view of the same record: velocity and acceleration (central differences of the
smoothed position), the settling time of each stop (from the last moment the speed exceeded 10 %
of the move's peak speed to the start of the stable band), and the vibration spectrum of the
stops (Hann-windowed FFT, amplitude-corrected; Harris, "On the use of windows for harmonic
analysis with the discrete Fourier transform", Proc. IEEE 66 (1978)).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal import units
from axiscal.datasets import Metadata, PositioningDataset
from axiscal.errors import InputError, MeasurementError

__all__ = ["Record", "PlanRows", "Stop", "CaptureResult", "find_stops", "capture_test", "match_stops", "plan_dataset",
           "SMOOTHING_S"]

#: Moving-average length applied before looking for stops, seconds.
SMOOTHING_S = 0.01


@dataclass(frozen=True, eq=False)
class Record:
    """A continuous record: readings at a constant (or given) sample rate, as the readers of
    :mod:`axiscal.io.measured` (CSV) and :mod:`axiscal.io.rtx` give it."""

    times: np.ndarray            # s
    readings: np.ndarray         # m (linear) or rad (rotary)
    kind: str                    # "linear" or "rotary"
    commanded: np.ndarray | None = None
    sample_rate: float = 0.0
    header: dict = field(default_factory=dict)
    unit: str = "mm"
    source: str = "<text>"
    notes: tuple = ()            # what the reader noted (an .rtx count unlike its header)


@dataclass(frozen=True, eq=False)
class PlanRows:
    """A test plan as exported (measure and overrun moves, in order)."""

    kind: np.ndarray
    position: np.ndarray
    direction: np.ndarray
    run: np.ndarray
    target_index: np.ndarray
    dwell: np.ndarray
    target_unit: str
    axis: str
    axis_kind: str
    source: str = "<text>"

    @property
    def targets(self) -> np.ndarray:
        """The distinct targets, ordered by index."""
        m = self.kind == "measure"
        idx = self.target_index[m]
        out = np.empty(int(idx.max()) + 1)
        out[idx] = self.position[m]
        return out


@dataclass(frozen=True)
class Stop:
    """A stable stretch of the record."""

    start: int          # first sample
    end: int            # one past the last sample
    t_start: float      # s
    t_end: float        # s
    mean: float         # reading, SI (m or rad)
    spread: float       # max − min of the smoothed reading over the stop, SI


@dataclass(frozen=True, eq=False)
class CaptureResult:
    """The dataset captured and what was found on the way."""

    dataset: PositioningDataset
    stops: tuple
    assigned: tuple          # (stop index, plan row) for each measurement
    overruns: int
    settling: np.ndarray     # s, per measurement
    spectrum: tuple          # (frequencies Hz, amplitude SI)
    smoothed: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    window: float            # SI (m or rad)
    dwell: float
    sample_rate: float
    applied: str = ""
    warnings: tuple = ()     # what the record's reader noted (an .rtx count unlike its header)

    def summary(self) -> dict:
        f, a = self.spectrum
        k = int(np.argmax(a)) if a.size else 0
        scale = 1e6 if self.dataset.axis_kind.value == "linear" else 1 / units.ARCSEC
        return {"stops": len(self.stops), "measurements": len(self.assigned),
                "overruns": self.overruns, "window_um": self.window * scale,
                "dwell_s": self.dwell, "sample_rate_hz": self.sample_rate,
                "settling_s": {"median": float(np.median(self.settling)),
                               "max": float(np.max(self.settling))},
                "vibration": {"peak_hz": float(f[k]) if a.size else 0.0,
                              "amplitude_um": float(a[k] * scale) if a.size else 0.0},
                "applied": self.applied or None, "warnings": list(self.warnings)}


def find_stops(times, readings, window: float, dwell: float) -> tuple[list, np.ndarray]:
    """The stops of a record: stretches at least ``dwell`` s long within ``window`` (SI).

    Returns the stops and the smoothed readings.
    """
    from scipy.ndimage import maximum_filter1d, minimum_filter1d, uniform_filter1d

    t = np.asarray(times, dtype=float)
    x = np.asarray(readings, dtype=float)
    fs = (t.size - 1) / (t[-1] - t[0])
    m = max(1, int(round(SMOOTHING_S * fs)))
    smooth = uniform_filter1d(x, m, mode="nearest") if m > 1 else x
    k = max(2, int(round(dwell * fs)))
    if k >= x.size:
        raise InputError(f"a stop of {dwell:g} s is longer than the whole record "
                         f"({t[-1] - t[0]:g} s)")
    # forward windows x[i : i + k] (scipy's origin -k//2 moves the window to start at i)
    hi = maximum_filter1d(smooth, k, origin=-(k // 2))
    hi -= minimum_filter1d(smooth, k, origin=-(k // 2))        # the range, in place
    stable = hi <= window
    del hi
    stable[x.size - k + 1:] = False
    edges = np.flatnonzero(np.diff(np.concatenate(([0], stable.view(np.int8), [0]))))
    stops = []
    for a, b in zip(edges[::2], edges[1::2]):            # starts a … b-1 stable
        s, e = int(a), int(b - 1 + k)
        seg = x[(s + e) // 2:e]                     # the settled second half (ringing tail out)
        stops.append(Stop(s, e, float(t[s]), float(t[e - 1]), float(seg.mean()),
                          float(np.ptp(smooth[s:e]))))
    return stops, smooth


def capture_test(record, plan, *, window: float = 1.0, dwell: float | None = None,
                 datum: float | None = None, environment=None, dead_path: float = 0.0
                 ) -> CaptureResult:
    """Find the stops of ``record`` and match them to ``plan`` (see the module docstring).

    Parameters
    ----------
    record : Record
        ``times`` (s) and ``readings`` (m or rad) from the laser's datum.
    plan : PlanRows
        The plan the machine ran.
    window : float, µm (linear) or arcsec (rotary)
    dwell : float, s, optional
        Shortest stop (default 60 % of the plan's measurement dwell).
    datum : float, plan unit, optional
        Where the laser was zeroed (default the first target).
    environment : EnvironmentLog, optional
        Compensate the raw readings for the air and the material (linear axes).
    """
    kind = "rotary" if plan.axis_kind == "rotary" else "linear"
    if record.kind != kind:
        raise InputError(f"the record holds {record.kind} readings, the plan is a {kind} axis")
    dev_unit = "um" if kind == "linear" else "arcsec"
    w = window * units.factor(dev_unit)
    measure_dwell = plan.dwell[plan.kind == "measure"]
    d = dwell if dwell is not None else 0.6 * float(np.min(measure_dwell))
    if not d > 0:
        raise InputError("the plan's dwell is 0 s: give --dwell, the shortest stop in s")
    stops, smooth = find_stops(record.times, record.readings, w, d)
    f = units.factor(plan.target_unit)
    zero = float(plan.targets[0]) if datum is None else float(datum)
    assigned, overruns = _match(stops, plan, zero, f, record.times, smooth, w)
    means = np.array([stops[i].mean for i, _ in assigned])
    applied = ""
    if environment is not None:
        if kind != "linear":
            raise InputError("environment compensation applies to linear readings")
        from axiscal.procedures.environment import compensate_displacements, conditions_at

        mid = np.array([(stops[i].t_start + stops[i].t_end) / 2 for i, _ in assigned])
        cond = conditions_at(mid, environment)
        comp = compensate_displacements(mid, means, conditions=cond, dead_path=dead_path,
                                        normalise_material=cond.material_temperature is not None
                                        and cond.expansion_coefficient is not None)
        means = comp.displacement
        applied = f"environment compensated: {comp.applied}"
    rows = [r for _, r in assigned]
    pos = zero + means / f
    dev = (pos - plan.position[rows]) * f / units.factor(dev_unit)
    warnings = tuple(getattr(record, "notes", ()))
    ds = _dataset(plan, rows, dev, dev_unit, "; ".join((applied, *warnings)).strip("; "))
    vel, acc, settling = _dynamics(record.times, smooth, stops, assigned)
    spectrum = _spectrum(record.times, record.readings, stops)
    return CaptureResult(ds, tuple(stops), tuple(assigned), overruns, settling, spectrum,
                         smooth, vel, acc, w, d, float(record.sample_rate), applied, warnings)


def match_stops(stops, plan, *, factor: float, times, zero: float = 0.0, smooth=None,
                window: float = 0.0):
    """Assign ``stops`` to ``plan``'s rows in order, as :func:`capture_test` does (overrun rows may
    or may not show a stop; a misfit is refused by saying where).

    ``stops[k].mean`` is the stop's reading in SI from ``zero`` (plan unit), ``factor`` the SI
    size of the plan unit; ``times`` (s) date the record's start in messages. Without ``smooth``
    (a record between the stops), two stops in a row at one position are one stop.

    Returns ``[(stop index, plan row), ...]`` for the measurements and the number of overrun
    stops.
    """
    return _match(stops, plan, zero, factor, np.asarray(times, dtype=float),
                  np.zeros(0) if smooth is None else smooth, window)


def plan_dataset(plan, rows, deviations, deviation_unit: str, applied: str = ""
                 ) -> PositioningDataset:
    """The dataset of ``plan`` with ``deviations`` (``deviation_unit``) at its rows ``rows``;
    ``applied`` is added to the notes."""
    return _dataset(plan, rows, deviations, deviation_unit, applied)


def _match(stops, plan, zero, f, times, smooth, window):
    """Assign stops to plan rows in order; refuse a misfit by saying where.

    Two stops at one position with the reading between them never leaving ten windows are one
    stop broken by a disturbance; a real reversal (an overrun) leaves by much more.
    """
    pos = plan.position
    steps = np.abs(np.diff(pos))
    steps = steps[steps > 0]
    tol = 0.25 * float(steps.min()) if steps.size else 1.0
    stop_pos = np.array([zero + s.mean / f for s in stops])
    j, assigned, overruns, last = 0, [], 0, None
    n = pos.size
    for k, p in enumerate(stop_pos):
        if j >= n:
            break                                  # stops after the plan's end: ignored
        if abs(p - pos[j]) <= tol:
            if plan.kind[j] == "measure":
                assigned.append((k, j))
            else:
                overruns += 1
            last, j = (k, j), j + 1
            continue
        if last is not None and last[0] == k - 1 and abs(p - pos[last[1]]) <= tol:
            between = smooth[stops[k - 1].end:stops[k].start]
            if between.size == 0 or np.ptp(np.concatenate(([stops[k].mean], between))) \
                    <= 10 * window:
                continue                           # the same stop, broken by a disturbance
        ahead = next((jj for jj in range(j + 1, min(n, j + 4)) if abs(p - pos[jj]) <= tol),
                     None)
        if ahead is None:
            raise MeasurementError(
                f"a stop at {stops[k].t_start:.3f} s (position {p:.6g} {plan.target_unit}) is "
                f"not in the plan: the next step expected is {_step(plan, j)}")
        missed = [jj for jj in range(j, ahead) if plan.kind[jj] == "measure"]
        if missed:
            t0 = stops[last[0]].t_end if last else times[0]
            raise MeasurementError(
                f"no stop for {_step(plan, missed[0])} between {t0:.3f} and "
                f"{stops[k].t_start:.3f} s (shorter than the dwell, or outside the window?)")
        if plan.kind[ahead] == "measure":
            assigned.append((k, ahead))
        else:
            overruns += 1
        last, j = (k, ahead), ahead + 1
    missing = [jj for jj in range(j, n) if plan.kind[jj] == "measure"]
    if missing:
        raise MeasurementError(f"the record ends before {_step(plan, missing[0])} "
                               f"({len(missing)} measurement(s) have no stop)")
    return assigned, overruns


def _step(plan, j) -> str:
    d = "↑" if plan.direction[j] == "+" else "↓"
    if plan.kind[j] == "measure":
        return (f"target {plan.target_index[j] + 1} ({plan.position[j]:g} {plan.target_unit}) "
                f"run {plan.run[j]} {d}")
    return f"the overrun at {plan.position[j]:g} {plan.target_unit}"


def _dataset(plan, rows, dev, dev_unit, applied) -> PositioningDataset:
    targets = plan.targets
    n_runs = int(plan.run.max())
    up = np.full((targets.size, n_runs), np.nan)
    has_down = np.any((plan.direction == "-") & (plan.kind == "measure"))
    down = np.full((targets.size, n_runs if has_down else 0), np.nan)
    for r, v in zip(rows, dev):
        arr = up if plan.direction[r] == "+" else down
        arr[plan.target_index[r], plan.run[r] - 1] = v
    notes = "captured by axiscal from a continuous record (stops matched to the plan)"
    if applied:
        notes += f"; {applied}"
    return PositioningDataset(plan.axis_kind, targets, up, down, plan.target_unit, dev_unit,
                              Metadata(axis=plan.axis, notes=notes))


def _dynamics(times, smooth, stops, assigned):
    t = np.asarray(times)
    dt = (t[-1] - t[0]) / (t.size - 1)
    uniform = np.allclose(np.diff(t[:1000]), dt, rtol=1e-6)
    step = dt if uniform else t                            # a scalar step needs no temporaries
    vel = np.gradient(smooth, step).astype(np.float32)    # for the view: single precision
    acc = np.gradient(vel, step).astype(np.float32)
    settling = []
    for i, _ in assigned:
        s = stops[i]
        prev_end = stops[i - 1].end if i > 0 else 0
        seg = np.abs(vel[prev_end:s.start])
        if seg.size == 0 or seg.max() == 0:
            settling.append(0.0)
            continue
        fast = np.flatnonzero(seg > 0.1 * seg.max())
        arrival = prev_end + int(fast[-1])
        settling.append(float(t[s.start] - t[arrival]))
    return vel, acc, np.array(settling)


def _spectrum(times, readings, stops, longest: int = 8):
    """Mean Hann-windowed amplitude spectrum of the longest stops (amplitude of a sinusoid)."""
    t = np.asarray(times)
    x = np.asarray(readings)
    chosen = sorted(stops, key=lambda s: s.end - s.start, reverse=True)[:longest]
    if not chosen:
        return np.zeros(0), np.zeros(0)
    n = min(s.end - s.start for s in chosen)
    n = int(2 ** np.floor(np.log2(max(n, 8))))
    fs = (t.size - 1) / (t[-1] - t[0])
    w = np.hanning(n)
    amp = np.zeros(n // 2 + 1)
    for s in chosen:
        seg = x[s.end - n:s.end]
        seg = seg - np.polyval(np.polyfit(np.arange(n), seg, 1), np.arange(n))
        amp += 2 * np.abs(np.fft.rfft(seg * w)) / w.sum()
    amp /= len(chosen)
    freq = np.fft.rfftfreq(n, 1 / fs)
    keep = freq >= 1.0
    return freq[keep], amp[keep]
