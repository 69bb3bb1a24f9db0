"""A machine controller with low-bandwidth sine/cosine encoder inputs (Siemens 840D-like).

What Renishaw, Laser scale axis referencing needs of the controller:

* **Inputs.** It reads the compensator's sine and cosine, interpolates them by the arctangent
  and counts whole periods (:meth:`Controller.decode`), N counts per period. Its inputs have a
  limited bandwidth: a signal frequency above ``max_input_frequency`` is an alarm
  (:meth:`Controller.frequency_alarms`), never a silent miscount. The frequency monitor averages
  the count rate over a gate time, as a hardware frequency counter does; a burst shorter than
  the gate (the rephasing stage at high homing speed lasts about 10 µs) hides in that average,
  so the edge rate is checked too (:meth:`Controller.edge_frequency`): the signal's frequency
  over the shortest interval between output edges that spans one signal period.
* **Homing.** It zeroes the axis at the first position where the reference mark is active and
  sine = cosine (phase 45°), :meth:`Controller.find_home`.
* **Twin axes.** After both axes of a gantry are homed it compares their positions with a skew
  limit (:meth:`Controller.check_skew`): within the limit it deskews by moving X2 relative to X1
  until ``p1 - p2`` equals the offset parameter; beyond it, an alarm.

All counts are integers; positions are ``count * count_size``.

Examples
--------
>>> import numpy as np
>>> from axiscal.instruments.compensator import synthesise
>>> ctl = Controller(counts_per_period=256)
>>> m = np.array([250, 255, 260, 300, 420])
>>> s, c = synthesise(m, 256)
>>> (ctl.decode(s, c) - ctl.decode(s, c)[0]).tolist()
[0, 5, 10, 50, 170]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError

__all__ = ["Controller", "ControllerAlarm", "HomeLatch", "SkewCheck"]


@dataclass(frozen=True)
class ControllerAlarm:
    """An alarm raised by the controller.

    Attributes
    ----------
    kind : str
        ``"input frequency"`` or ``"skew limit"``.
    message : str
    index : int
        Sample at which it was raised (-1 if not tied to a sample).
    value : float
        The offending value (the highest frequency seen, Hz, or the skew, counts).
    limit : float
    """

    kind: str
    message: str
    index: int
    value: float
    limit: float

    def __str__(self) -> str:
        return f"ALARM ({self.kind}): {self.message}"


@dataclass(frozen=True)
class HomeLatch:
    """Where the controller zeroed the axis.

    Attributes
    ----------
    count : int
        Controller count at the home position Z (becomes position 0).
    index : int
        First sample at which the axis had reached Z.
    """

    count: int
    index: int


@dataclass(frozen=True)
class SkewCheck:
    """The controller's skew check after both axes of a gantry are homed.

    Attributes
    ----------
    skew : int
        p1 - p2 in output counts (X1 position minus X2 position, each relative to its home).
    limit : int
        The configured skew limit.
    alarm : bool
        True if |skew| > limit: the controller stops and does not synchronise.
    deskew_move : int
        Counts X2 moves (relative to X1) to bring the skew to the offset parameter; 0 on alarm.
    """

    skew: int
    limit: int
    alarm: bool
    deskew_move: int


@dataclass(frozen=True)
class Controller:
    """The controller's encoder inputs, homing and twin-axis parameters.

    Attributes
    ----------
    counts_per_period : int
        N: counts the controller makes of one sine/cosine period (256 in the paper).
    count_size : float, metres
        Length of one count (period / N).
    max_input_frequency : float, Hz
        Highest sine/cosine frequency the inputs accept.
    frequency_gate : float, seconds
        Gate time of the frequency monitor.
    skew_limit : int, counts
        Largest |p1 - p2| of a gantry accepted before synchronisation.
    offset : int, counts
        Twin-axis offset parameter: the p1 - p2 that deskew leaves (trims squareness for a real
        offset between the two reference marks).
    """

    counts_per_period: int = 256
    count_size: float = 20e-6 / 256
    max_input_frequency: float = 100e3
    frequency_gate: float = 100e-6
    skew_limit: int = 300
    offset: int = 0

    def __post_init__(self) -> None:
        n = self.counts_per_period
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 8 or n % 8:
            raise InputError(f"controller counts_per_period = {n!r} must be a multiple of 8")
        if not self.count_size > 0:
            raise InputError(f"count_size = {self.count_size!r} m must be positive")
        if not self.max_input_frequency > 0:
            raise InputError(f"max_input_frequency = {self.max_input_frequency!r} Hz must be "
                             "positive")
        if not self.frequency_gate > 0:
            raise InputError(f"frequency_gate = {self.frequency_gate!r} s must be positive")
        if int(self.skew_limit) < 0:
            raise InputError(f"skew_limit = {self.skew_limit!r} counts must be >= 0")

    # -- inputs ------------------------------------------------------------------------------
    def decode(self, sine, cosine) -> np.ndarray:
        """Interpolate sine/cosine by the arctangent and count periods: controller counts.

        The first sample's count is its phase (0..N-1), so counts are congruent to the
        compensator's count modulo N. Between two samples the phase must move by less than half a
        period (the sampling condition the frequency monitor guards).
        """
        n = self.counts_per_period
        s = np.asarray(sine, dtype=float)
        c = np.asarray(cosine, dtype=float)
        if s.shape != c.shape or s.ndim != 1 or s.size == 0:
            raise InputError("sine and cosine must be non-empty 1-D arrays of the same length")
        idx = np.mod(np.rint(np.arctan2(s, c) * (n / (2.0 * np.pi))).astype(np.int64), n)
        step = np.mod(np.diff(idx) + n // 2, n) - n // 2
        return idx[0] + np.concatenate(([0], np.cumsum(step)))

    def input_frequency(self, counts, times) -> np.ndarray:
        """Signal frequency per sample as the monitor measures it: counts moved over the gate
        time ending at the sample, divided by N and by the gate time (Hz)."""
        m = np.asarray(counts, dtype=np.int64)
        t = np.asarray(times, dtype=float)
        if m.shape != t.shape:
            raise InputError("counts and times must have the same length")
        start = np.searchsorted(t, t - self.frequency_gate, side="left")
        span = np.maximum(t - t[start], self.frequency_gate)
        # the total path travelled within the gate (both directions count)
        path = np.concatenate(([0], np.cumsum(np.abs(np.diff(m)))))
        return (path - path[start]) / self.counts_per_period / span

    def edge_frequency(self, counts, times) -> np.ndarray:
        """Signal frequency at each sample over the shortest span of edges covering one period.

        An output edge is a change of the count. For every sample at which an edge occurs, the
        latest earlier edge at least N counts of path behind it is found; the frequency is the
        path between the two edges, in periods, over the time between them (Hz). Between two
        edge instants the count advances by exactly the counts of the edges after the first, so
        the estimate is not biased by the staircase (the compensator emits its counts at laser
        count instants, 8.1 output counts at a time for 0.633 µm). NaN where less than one
        period of edges precedes the sample, or no edge occurs at it.

        Parameters
        ----------
        counts : array_like of int
            The signal's count per sample (compensator side).
        times : array_like, seconds

        Returns
        -------
        ndarray, Hz
        """
        m = np.asarray(counts, dtype=np.int64)
        t = np.asarray(times, dtype=float)
        if m.shape != t.shape or m.ndim != 1:
            raise InputError("counts and times must be 1-D arrays of the same length")
        out = np.full(m.shape, np.nan)
        if m.size < 2:
            return out
        path = np.concatenate(([0], np.cumsum(np.abs(np.diff(m)))))
        edge = np.flatnonzero(np.diff(m) != 0) + 1
        pe, te = path[edge], t[edge]
        n = self.counts_per_period
        j = np.searchsorted(pe, pe - n, side="right") - 1
        ok = (j >= 0) & (te > te[np.maximum(j, 0)])
        jj = j[ok]
        out[edge[ok]] = (pe[ok] - pe[jj]) / n / (te[ok] - te[jj])
        return out

    def frequency_alarms(self, counts, times) -> list[ControllerAlarm]:
        """An alarm if the input frequency exceeds the limit anywhere (empty list if not).

        Either measure over the limit raises it: the gated average of the frequency monitor
        (:meth:`input_frequency`) or the edge rate (:meth:`edge_frequency`), which catches a
        burst shorter than the gate. Raised at the first sample over the limit, reporting the
        true peak: the highest frequency over one signal period (or the gated value when the
        record holds less than one period of edges).
        """
        gated = self.input_frequency(counts, times)
        edges = self.edge_frequency(counts, times)
        over = (gated > self.max_input_frequency) | (edges > self.max_input_frequency)
        if not over.any():
            return []
        k = int(np.argmax(over))
        has_edges = bool(np.isfinite(edges).any())
        peak = float(np.nanmax(edges)) if has_edges else float(gated.max())
        gate_us = self.frequency_gate * 1e6
        return [ControllerAlarm(
            "input frequency",
            f"sine/cosine input at up to {peak / 1e3:.2f} kHz over one signal period (the "
            f"{gate_us:g} µs gated monitor averages {float(gated.max()) / 1e3:.2f} kHz) exceeds "
            f"the controller's {self.max_input_frequency / 1e3:g} kHz, first at t = "
            f"{float(np.asarray(times)[k]):.7f} s; counts from there on are not trusted",
            k, peak, float(self.max_input_frequency))]

    def max_speed(self) -> float:
        """Fastest speed the inputs accept, m/s: max frequency times the period."""
        return self.max_input_frequency * self.counts_per_period * self.count_size

    # -- homing -------------------------------------------------------------------------------
    def find_home(self, counts, reference, direction: int = 1) -> HomeLatch | None:
        """The home count: the first count at phase 45° (sine = cosine > 0) passed while the
        reference mark is active. None if the axis has not got there.

        Parameters
        ----------
        counts : array_like of int
            Decoded controller counts per sample.
        reference : array_like of bool
            Reference mark input per sample.
        direction : {+1, -1}
            Direction of the homing move.
        """
        m = np.asarray(counts, dtype=np.int64)
        ref = np.asarray(reference, dtype=bool)
        if m.shape != ref.shape:
            raise InputError("counts and reference must have the same length")
        d = 1 if direction > 0 else -1
        if not ref.any():
            return None
        kr = int(np.argmax(ref))
        n = self.counts_per_period
        before = int(m[kr - 1]) if kr > 0 else int(m[kr]) - d
        # first count strictly after `before` (in the homing direction) with m ≡ N/8 (mod N)
        z = before + d * (1 + (d * (n // 8 - before - d)) % n)
        run_end = kr + int(np.argmax(~ref[kr:])) if (~ref[kr:]).any() else m.size
        reached = np.flatnonzero(d * m[kr:run_end] >= d * z)
        if reached.size == 0:
            return None
        return HomeLatch(count=int(z), index=kr + int(reached[0]))

    # -- twin axes ----------------------------------------------------------------------------
    def check_skew(self, p1: int, p2: int) -> SkewCheck:
        """Compare the homed positions of X1 and X2 (counts) with the skew limit.

        Returns the skew ``p1 - p2``; if ``|skew| <= skew_limit`` the deskew move of X2 is
        ``skew - offset`` (after it, p1 - p2 = offset), else an alarm and no move.
        """
        skew = int(p1) - int(p2)
        alarm = abs(skew) > int(self.skew_limit)
        return SkewCheck(skew=skew, limit=int(self.skew_limit), alarm=alarm,
                         deskew_move=0 if alarm else skew - int(self.offset))
