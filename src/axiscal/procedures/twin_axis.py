"""Referencing of a twin axis (gantry) with compensated laser feedback (Renishaw, Laser scale axis referencing).

Two linked axes, X1 and X2, each with its own laser scale, compensator and reference switch. The
sequence of the paper:

1. X1 is master and homes; X2 tracks X1's movement *as the controller sees it*. During X1's
   stage 2 the controller sees 256 + v1 counts while X1 moves 256, so X2 moves v1 counts more
   than X1.
2. The roles reverse: X2 homes as master, X1 tracks, and X1 moves v2 counts more than X2 during
   X2's stage 2.
3. The controller compares ``skew = p1 - p2`` (each position relative to its home) with the skew
   limit: beyond it an alarm; within it, deskew by moving X2 relative to X1 until
   ``p1 - p2`` equals the offset parameter.

The simulation is in output counts (integers, exact), the servo of each axis holding its
controller count on the commanded value. The skew the controller sees before synchronisation is

    p1 - p2 = s0 + (switch_2 - switch_1) + d (v2 - v1)

(s0 the real skew X1 - X2 before homing, d the homing direction): the homing adds d (v2 - v1),
never more than ±(N - 1) counts, the paper's ±256 for N = 256. In length that is just under one
signal period whatever N: (N − 1)·period/N (255 × 78.125 nm = 19.92 µm, 127 × 156.25 nm =
19.84 µm at 20 µm); fewer counts per period reduce the skew in counts, not in micrometres. A
compensator rephases at the first hit of its own switch, whether its axis is master or slave at
the time.

Examples
--------
>>> g = TwinAxis(switch_1=1000, switch_2=1000)
>>> r = simulate_twin_homing(g, power_up_phase_1=0, power_up_phase_2=100)
>>> r.virtual_1, r.virtual_2, r.skew_check.skew
(248, 148, -100)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.compensator import SineOutput, reference_virtual
from axiscal.instruments.controller import Controller, SkewCheck

__all__ = ["TwinAxis", "TwinHomingResult", "simulate_twin_homing", "required_skew_limit",
           "phase_for_virtual", "worst_case_runs"]


@dataclass(frozen=True)
class TwinAxis:
    """A gantry's two axes in output counts.

    Attributes
    ----------
    output : SineOutput
        The compensators' output format (both the same).
    controller : Controller
        Skew limit and offset parameter.
    switch_1, switch_2 : int
        Real output count (machine coordinate) at which each reference switch trips.
    start_1, start_2 : int
        Real output counts of X1 and X2 when homing starts (start_1 - start_2 is the skew the
        gantry had before homing).
    direction : {+1, -1}
        Homing direction.
    """

    output: SineOutput = field(default_factory=SineOutput)
    controller: Controller = field(default_factory=Controller)
    switch_1: int = 1000
    switch_2: int = 1000
    start_1: int = 0
    start_2: int = 0
    direction: int = 1

    def __post_init__(self) -> None:
        if self.controller.counts_per_period != self.output.counts_per_period:
            raise InputError("the controller and the compensators differ in counts per period")
        d = self.direction
        if d not in (1, -1):
            raise InputError(f"direction {d!r} must be +1 or -1")
        for i, (s, x) in enumerate(((self.switch_1, self.start_1),
                                    (self.switch_2, self.start_2)), start=1):
            if d * (s - x) <= 0:
                raise InputError(f"X{i} starts at count {x}, not before its switch at {s} in the "
                                 "homing direction")

    @property
    def reference_offset(self) -> int:
        """switch_2 - switch_1: the offset parameter that makes the deskewed gantry square."""
        return int(self.switch_2 - self.switch_1)


@dataclass(frozen=True, eq=False)
class TwinHomingResult:
    """The twin-axis homing sequence, step by step.

    Attributes
    ----------
    gantry : TwinAxis
    virtual_1, virtual_2 : int
        Virtual movement of each compensator's rephasing, counts.
    real_1, real_2 : ndarray of int64
        Real output counts of X1 and X2 at each command step (homing X1, then X2; then deskew).
    phase : ndarray of int8
        1 while X1 homes as master, 2 while X2 homes, 3 for the deskew move.
    home_1, home_2 : int
        Real counts at which X1 and X2 were zeroed.
    skew_check : SkewCheck
        The controller's check of p1 - p2 before synchronisation.
    skew_after : int or None
        p1 - p2 after deskew (the offset parameter), None on alarm.
    """

    gantry: TwinAxis
    virtual_1: int
    virtual_2: int
    real_1: np.ndarray
    real_2: np.ndarray
    phase: np.ndarray
    home_1: int
    home_2: int
    skew_check: SkewCheck
    skew_after: int | None

    @property
    def real_skew(self) -> np.ndarray:
        """Real skew X1 - X2 at each step relative to the skew before homing, counts."""
        s0 = self.gantry.start_1 - self.gantry.start_2
        return (self.real_1 - self.real_2) - s0

    @property
    def homing_skew(self) -> np.ndarray:
        """Real skew added by the homing sequence, before synchronisation, counts."""
        return self.real_skew[self.phase < 3]

    @property
    def alarm(self) -> bool:
        return self.skew_check.alarm

    def to_dict(self) -> dict[str, Any]:
        """Plain-data summary (the ``axiscal scale gantry --json`` object)."""
        hs = self.homing_skew
        return {
            "counts_per_period": self.gantry.output.counts_per_period,
            "count_size_nm": self.gantry.output.count_size * 1e9,
            "virtual_1": self.virtual_1,
            "virtual_2": self.virtual_2,
            "homing_skew_min": int(hs.min()),
            "homing_skew_max": int(hs.max()),
            "skew_before_sync": self.skew_check.skew,
            "skew_limit": self.skew_check.limit,
            "alarm": self.alarm,
            "deskew_move": self.skew_check.deskew_move,
            "skew_after_sync": self.skew_after,
            "offset": int(self.gantry.controller.offset),
            "required_skew_limit": required_skew_limit(self.gantry),
            "homing_skew_bound_um": (self.gantry.output.counts_per_period - 1)
            * self.gantry.output.count_size * 1e6,
        }

    def __str__(self) -> str:
        g = self.gantry
        q = g.output.count_size * 1e6
        hs = self.homing_skew
        lines = [
            f"Twin-axis homing, {g.output.counts_per_period} counts of {q * 1e3:.3f} nm per period",
            f"  X1 rephased by {self.virtual_1} counts, X2 by {self.virtual_2}: real skew during "
            f"homing {int(hs.min())} to {int(hs.max())} counts ({hs.min() * q:.2f} to "
            f"{hs.max() * q:.2f} µm)",
            f"  skew before synchronisation p1 - p2 = {self.skew_check.skew} counts "
            f"({self.skew_check.skew * q:.2f} µm); limit {self.skew_check.limit}",
        ]
        if self.alarm:
            lines.append(f"  ALARM (skew limit): |{self.skew_check.skew}| > {self.skew_check.limit}"
                         "; not synchronised")
        else:
            lines.append(f"  deskew: X2 moved {self.skew_check.deskew_move} counts; p1 - p2 = "
                         f"{self.skew_after} (offset parameter)")
        lines.append(f"  skew limit this configuration needs, switch scatter aside: at least "
                     f"{required_skew_limit(g)} counts")
        n = g.output.counts_per_period
        lines.append(f"  the homing skew d(v2 - v1) is bounded by one signal period: ±{n - 1} "
                     f"counts = ±{(n - 1) * q:.2f} µm of the {g.output.period * 1e6:g} µm period; "
                     "fewer counts per period lower it in counts, not in µm")
        return "\n".join(lines)


def required_skew_limit(gantry: TwinAxis, switch_spread: int = 0) -> int:
    """Smallest skew limit that never raises an alarm for this gantry, counts.

    The skew before synchronisation is ``p1 - p2 = s0 - (switch_1 - switch_2) + (v2 - v1)`` with
    s0 = start_1 - start_2 and v1, v2 in 0..N-1, so its magnitude is at most
    ``|s0 - (switch_1 - switch_2)| + N - 1``; ``switch_spread`` adds the switches' combined
    repeatability (counts).
    """
    n = gantry.output.counts_per_period
    s0 = gantry.start_1 - gantry.start_2
    base = abs(s0 + gantry.reference_offset)
    return int(base + n - 1 + abs(int(switch_spread)))


def simulate_twin_homing(gantry: TwinAxis, power_up_phase_1: int = 0, power_up_phase_2: int = 0,
                         switch_error_1: int = 0, switch_error_2: int = 0) -> TwinHomingResult:
    """Home X1 then X2 with locked slaves, check the skew and deskew.

    Parameters
    ----------
    gantry : TwinAxis
    power_up_phase_1, power_up_phase_2 : int
        Phase of each compensator's outputs at power-up, counts (0..N-1): with the switch
        positions they fix the virtual movements v1 and v2.
    switch_error_1, switch_error_2 : int
        Repeatability error of each switch this time, counts.

    Returns
    -------
    TwinHomingResult
    """
    g = gantry
    n = g.output.counts_per_period
    d = g.direction
    ax1 = _Axis(g.start_1, g.switch_1 + switch_error_1, int(power_up_phase_1) % n, n, d)
    ax2 = _Axis(g.start_2, g.switch_2 + switch_error_2, int(power_up_phase_2) % n, n, d)
    steps1, steps2, phases = [], [], []

    # 1: X1 master to its home; X2 follows the command
    _locked_move(ax1, ax2, ax1.m_z, steps1, steps2, phases, 1)
    home_1 = ax1.o
    # 2: X2 master; if its home is behind (passed while it was slave), back off first
    if d * (ax2.cmd - ax2.m_z) > 0:
        _locked_move(ax2, ax1, ax2.m_z - d * n, steps2, steps1, phases, 2)
    _locked_move(ax2, ax1, ax2.m_z, steps2, steps1, phases, 2)
    home_2 = ax2.o
    p1 = ax1.m_now - ax1.m_z
    p2 = ax2.m_now - ax2.m_z
    check = g.controller.check_skew(p1, p2)
    skew_after = None
    if not check.alarm:
        # 3: deskew, X2 alone (both compensators are phased: m = o + constant)
        ax2.o += check.deskew_move
        ax2.cmd += check.deskew_move
        steps1.append(ax1.o)
        steps2.append(ax2.o)
        phases.append(3)
        skew_after = (ax1.m_now - ax1.m_z) - (ax2.m_now - ax2.m_z)
    return TwinHomingResult(
        gantry=g, virtual_1=ax1.v, virtual_2=ax2.v,
        real_1=np.concatenate([np.atleast_1d(np.asarray(s, dtype=np.int64)) for s in steps1]),
        real_2=np.concatenate([np.atleast_1d(np.asarray(s, dtype=np.int64)) for s in steps2]),
        phase=np.concatenate([np.full(np.size(s), p, dtype=np.int8)
                              for s, p in zip(steps1, phases)]),
        home_1=int(home_1), home_2=int(home_2), skew_check=check, skew_after=skew_after)


def phase_for_virtual(switch: int, virtual: int, counts_per_period: int, direction: int = 1) -> int:
    """The power-up phase (0..N-1) that makes a compensator whose switch trips at real count
    ``switch`` rephase by ``virtual`` counts."""
    n = int(counts_per_period)
    for phi in range(n):
        if reference_virtual(int(switch) + phi, n, direction) == int(virtual) % n:
            return phi
    raise InputError(f"no power-up phase gives a virtual movement of {virtual}")  # pragma: no cover


def worst_case_runs(gantry: TwinAxis) -> tuple[TwinHomingResult, TwinHomingResult]:
    """The two extreme runs: X1 rephased by N-1 and X2 by 0 counts, and the reverse."""
    n = gantry.output.counts_per_period
    runs = []
    for v1, v2 in ((n - 1, 0), (0, n - 1)):
        runs.append(simulate_twin_homing(
            gantry, phase_for_virtual(gantry.switch_1, v1, n, gantry.direction),
            phase_for_virtual(gantry.switch_2, v2, n, gantry.direction)))
    return runs[0], runs[1]


class _Axis:
    """One axis in output counts: real count o, and the compensator's map o -> m."""

    def __init__(self, start: int, switch: int, phase: int, n: int, d: int):
        self.o = int(start)
        self.s = int(switch)
        self.phi = phase
        self.n = n
        self.d = d
        self.v = reference_virtual(self.s + phase, n, d)
        self.m_z = self.s + phase + d * (5 * n // 4 + self.v)
        self.done = False  # stage 2 complete (latched)
        self.cmd = int(self.m_of(np.array([self.o]))[0])  # the controller's command for it

    def m_of(self, o: np.ndarray) -> np.ndarray:
        """Controller count for real counts o, moving on from the present state."""
        if self.done:
            return o + self.phi + self.d * self.v
        u = self.d * (o - self.s)
        extra = np.where(u >= self.n, self.v, (self.v * np.clip(u, 0, self.n)) // self.n)
        return o + self.phi + self.d * extra

    @property
    def m_now(self) -> int:
        return int(self.m_of(np.array([self.o]))[0])

    def follow(self, targets: np.ndarray) -> np.ndarray:
        """Real counts the servo reaches for commanded controller counts (monotone sweep):
        the last real count whose controller count has not passed the target."""
        d = self.d
        lo = min(self.o, int(np.min(targets)) - self.phi - self.n) - 2 * self.n
        hi = max(self.o, int(np.max(targets)) - self.phi + self.n) + 2 * self.n
        table_o = np.arange(lo, hi + 1, dtype=np.int64)
        table_m = d * self.m_of(table_o)
        if d < 0:
            table_o, table_m = table_o[::-1], table_m[::-1]
        k = np.searchsorted(table_m, d * np.asarray(targets, dtype=np.int64), side="right") - 1
        reached = table_o[np.clip(k, 0, table_o.size - 1)]
        return reached

    def settle(self, o_path: np.ndarray) -> None:
        """Take the last real count of a path and latch stage 2 if it was completed."""
        if o_path.size:
            if np.any(self.d * (o_path - self.s) >= self.n):
                self.done = True
            self.o = int(o_path[-1])


def _locked_move(master: _Axis, slave: _Axis, target: int, steps_m: list, steps_s: list,
                 phases: list, phase: int) -> None:
    """Command the master's controller count to ``target`` one count at a time; the slave's
    command follows the same increments. Each servo holds the last real count whose controller
    count has not passed its command (where a virtual count makes the controller count skip the
    command, the axis waits one count short of it)."""
    m0 = master.cmd
    step = 1 if target >= m0 else -1
    cmd = np.arange(m0 + step, target + step, step, dtype=np.int64)
    if cmd.size == 0:
        return
    s_cmd = slave.cmd + (cmd - m0)
    o_master = master.follow(cmd)
    o_slave = slave.follow(s_cmd)
    master.settle(o_master)
    slave.settle(o_slave)
    master.cmd = int(cmd[-1])
    slave.cmd = int(s_cmd[-1])
    steps_m.append(o_master)
    steps_s.append(o_slave)
    phases.append(phase)
