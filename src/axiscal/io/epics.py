"""EPICS ``camonitor`` logs: a positioning test from the raw monitor stream of a setpoint and a
reference PV.

The layout (EPICS Base, ``modules/ca/src/tools/tool_lib.c``, ``print_time_val_sts``, and the
``camonitor`` manual page, "Timestamps", "Arrays")
--------------------------------------------------------------------------------------------
One line per value update::

    IOC:m1-PosSet                  2023-05-04 12:34:56.789012 15
    IOC:m1-PosAct                  2023-05-04 12:34:57.000112 14.99987 LOLO MAJOR
    IOC:wave 2023-05-04 12:34:57.100000 3 1 2 3

* the PV name (padded to 30 characters for a scalar), a blank;
* the server time stamp ``%Y-%m-%d %H:%M:%S.%06f`` (the default, ``-ts``), ``<undefined>`` for a
  record never processed (a zero stamp), the client stamp in parentheses (``-tc``), or both;
  with ``-tr`` (relative), ``-ti`` (incremental) or ``-tI`` (incremental by channel) a PV's
  first line carries the absolute stamp and the later ones a signed offset in seconds
  (``%+12.6f``); ``-tn`` prints none;
* the value; an array prints its element count, then the elements;
* the alarm status and severity (``LOLO MAJOR``) when not ``NO_ALARM``;
* ``*** disconnected``, ``*** Not connected (PV not found)``, ``*** no read access`` ... when the
  channel is lost.

What real logs add, as seen in the public logs of ESS/PSI ecmc tests (A. Sandström,
github.com/anderssandstrom/ecmc_target_muts_logger, ``b02/x/rawdata/x_230_2.log``: a setpoint
``X-PosCmd``, a reference ``ILD_DownSample`` and five more PVs interleaved, 56 341 lines): each
PV's first line is its *current* value with the time it was last processed, so it can be older
than the lines before it; between PVs the lines are not in time order; within one PV they are.
Those logs carry no licence, so none is copied into this repository; the tests build logs of the
same layout.

How a test is taken from a log
------------------------------
The setpoint holds a value while the axis stands at a target: a *dwell* is a stretch of at
least ``dwell`` seconds (default 1 s) over which the setpoint keeps one value (a trajectory
setpoint that ramps updates every cycle, so its ramps are not dwells). The axis may still be
travelling when the setpoint has jumped (the real log above: a 5 mm step at 0.2 mm/s arrives 1.3 s
before the next step), and may be moved away by another command before the setpoint changes
again, so the settled part of a dwell is read from the reference itself: the stretches of the
dwell over which the reference stays within a band of ``window`` (default 1 µm, or 1 arcsec; as
:mod:`axiscal.procedures.capture` finds a stop) for at least ``settled`` s (default 0.5 s) are
the episodes of rest, and the longest stretch of the episode nearest the setpoint (and nearer
it than the setpoint before) is the settled part: an axis that starts late still rests at the
previous target at the dwell's start. The reading is the time-weighted mean of the reference
over it, each value held until the next update: Channel Access posts a monitor only when the
value changes by more than the record's deadband (EPICS Record Reference Manual, fields
MDEL/ADEL), so a steady reading may not repeat. An update with severity ``INVALID``, a NaN or a
lost channel makes the reference unknown until its next update (a gap no stretch crosses).

The approach direction of a dwell is the sign of the move that reached it, from the previous
dwell (the previous stop, or the over-travel), never from a sample of a ramp between them: a
trajectory setpoint ramps, and its last sample before a stop lies a fraction of a step short
of it (issue 42); the log's first dwell was not reached by a move in the log and is not a
measurement. The setpoint "before" that the settled reference must be nearer the stop than is
that previous dwell too, so axis errors of hundreds of µm read as they do with a setpoint that
jumps. The deviation is the reference minus the target (ISO 230-2:2014 clause 3,
eq. (1): ``x_ij = P_ij − P_i``); ``reference_scale`` and ``reference_offset`` turn a raw reference into
a position first (ecmc's ``REF_GR`` and ``REF_OFF``, ``ecmcGetISO230DataFromCAFile.bash``).

The dwells are matched to the test three ways:

* a plan (``axiscal plan ... --csv``): in order, as
  :func:`axiscal.procedures.capture.capture_test` matches stops (overrun rows may show a dwell);
  the plan's direction must agree with the step;
* targets given: a dwell at a target (within 1e-6 of the targets' span, plus the 5e-6 relative
  rounding of camonitor's default ``%g``) is a measurement in the direction of its step, any
  other dwell an overrun; the run is the count of earlier visits of that target in that
  direction (run j of ISO 230-2:2014 clause 3); the deviation is taken from the target given;
* neither: the targets are the values of the dwells the setpoint passes *through* (reached and
  left in the same direction); a dwell where the setpoint turns back is the over-travel of the
  linear test cycle (ISO 230-2:2014 §5.3 and its figures) unless its value is one of those
  targets. A test with no over-travel (the last target is its turning point) needs the targets.

The defaults (dwell, window, settled, unit when not given: mm, scale 1 and offset 0) are
written into the dataset's notes, which the commands print beside the result and the
certificate states under its assumptions.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from datetime import datetime

import numpy as np

from axiscal import units
from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError
from axiscal.io.detect import CLOCK as _CLOCK
from axiscal.io.detect import DATE as _DATE
from axiscal.io.detect import NOTES_START, looks_like_camonitor
from axiscal.io.detect import OFFSET as _OFFSET

__all__ = ["NOTES_START", "PvSeries", "CamonitorLog", "Dwell", "EpicsCapture",
           "looks_like_camonitor", "parse_camonitor", "read_camonitor", "find_dwells",
           "capture_epics", "parse_epics", "read_epics"]

_STAMP = rf"(?:{_DATE}|{_CLOCK}|<undefined>|{_OFFSET})"
_LINE = re.compile(rf"^(?P<name>\S+)\s+(?:(?P<server>{_STAMP})\s*)?"
                   rf"(?:\((?P<client>{_STAMP})\)\s*)?(?P<rest>.*)$")
_OFFSET_RE, _DATE_RE = re.compile(_OFFSET), re.compile(_DATE)
_SEVERITIES = {"NO_ALARM", "MINOR", "MAJOR", "INVALID"}
#: ``offsets``: how a signed offset after a PV's first line is read (camonitor -tr, -ti, -tI).
OFFSETS = ("relative", "incremental", "by-channel")


@dataclass(frozen=True, eq=False)
class PvSeries:
    """The updates of one PV: times (s from the log's first absolute stamp), values (NaN where the
    value is unknown: a lost channel, an INVALID severity, a non-number), the file's lines."""

    name: str
    times: np.ndarray
    values: np.ndarray
    lines: np.ndarray
    elements: int          # the largest element count seen (1 for a scalar)
    alarms: int            # updates with a MINOR or MAJOR severity
    invalid: int           # updates whose value is unknown (INVALID, NaN, lost channel)
    undefined: int         # updates stamped <undefined> (not used: no time)
    text: bool             # some update is not a number (an enum string ...)


@dataclass(frozen=True, eq=False)
class CamonitorLog:
    """A camonitor log: its PVs by name, in order of first appearance."""

    pvs: dict
    start: str             # the first absolute stamp, as written ("" if none)
    end: float             # the latest time in the log, s
    source: str = "<text>"

    def series(self, name: str) -> PvSeries:
        """The PV ``name``, or a one-line refusal naming the PVs the log holds."""
        if name not in self.pvs:
            raise DataFormatError(f"PV {name!r} is not in the log (it holds "
                                  f"{_names(self.pvs)})", self.source)
        return self.pvs[name]


@dataclass(frozen=True)
class Dwell:
    """A stretch over which the setpoint holds ``value``."""

    value: float
    t_start: float         # s
    t_end: float           # s
    arrival: int           # +1 reached from below, -1 from above, 0 not reached in the log
    departure: int         # +1 left upwards, -1 downwards, 0 the log ends in it
    line: int              # the setpoint's line that starts it
    came_from: float = math.nan   # the setpoint's value before it


def read_camonitor(path, offsets: str = "relative") -> CamonitorLog:
    """Read a camonitor log; see :func:`parse_camonitor`."""
    from axiscal.io._files import read_text

    return parse_camonitor(read_text(path), str(path), offsets)


def parse_camonitor(text: str, source: str = "<text>", offsets: str = "relative"
                    ) -> CamonitorLog:
    """Parse a camonitor log (module docstring) into one :class:`PvSeries` per PV.

    Parameters
    ----------
    text : str
    source : str
        Named in errors.
    offsets : {"relative", "incremental", "by-channel"}
        How the signed offsets of ``camonitor -tr``, ``-ti`` or ``-tI`` are read (the text
        alone cannot tell them apart); absolute stamps need no choice.

    Examples
    --------
    >>> log = parse_camonitor('''IOC:sp 2023-05-04 12:00:00.000000 15
    ... IOC:rb 2023-05-04 12:00:00.500000 15.002 HIHI MAJOR
    ... IOC:sp 2023-05-04 12:00:10.000000 25''')
    >>> log.series("IOC:sp").values.tolist(), log.series("IOC:rb").times.tolist()
    ([15.0, 25.0], [0.5])
    """
    if offsets not in OFFSETS:
        raise DataFormatError(f"offsets {offsets!r}: use one of {', '.join(OFFSETS)}", source)
    state = _State(offsets, source)
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if line and not line.startswith("#"):
            state.take(line, lineno)
    if not state.pvs:
        raise DataFormatError("no camonitor lines ('PV time stamp value')", source)
    pvs = {name: d.series(name) for name, d in state.pvs.items()}
    end = max((float(s.times.max()) for s in pvs.values() if s.times.size), default=math.nan)
    return CamonitorLog(pvs, state.start_text, end, source)


def find_dwells(series: PvSeries, end: float, dwell: float = 1.0) -> list:
    """The dwells of a setpoint: stretches of at least ``dwell`` s holding one value.

    ``end`` (s) closes the last stretch (the log's last time). Equal consecutive values are one
    stretch; an unknown value (NaN) ends a stretch and starts none.
    """
    t, v = series.times, series.values
    starts = [i for i in range(t.size) if i == 0 or not _same(v[i], v[i - 1])]
    stretches = []
    for k, i in enumerate(starts):
        t1 = t[starts[k + 1]] if k + 1 < len(starts) else end
        stretches.append((i, float(t[i]), float(t1)))
    known = [float(v[i]) if math.isfinite(v[i]) else None for i, _, _ in stretches]
    held = [known[k] is not None and t1 - t0 >= dwell for k, (_, t0, t1) in enumerate(stretches)]
    # where the axis came from and goes to: the previous (next) *stop*, not the last (first)
    # sample of a ramp between stops (issue 42); a value before the first stop counts as one
    before, last = [], None
    for k, x in enumerate(known):
        before.append(last)
        if x is not None and (held[k] or last is None):
            last = x
    after, nxt = [None] * len(known), None
    for k in range(len(known) - 1, -1, -1):
        after[k] = nxt
        if known[k] is not None and (held[k] or nxt is None):
            nxt = known[k]
    out = []
    for k, (i, t0, t1) in enumerate(stretches):
        if not held[k]:
            continue
        out.append(Dwell(known[k], t0, t1, _sign(known[k], before[k]), _sign(after[k], known[k]),
                         int(series.lines[i]), math.nan if before[k] is None else before[k]))
    return out


def read_epics(path, **kwargs) -> PositioningDataset:
    """Read a positioning test from a camonitor log; see :func:`parse_epics`."""
    from axiscal.io._files import read_text

    return parse_epics(read_text(path), source=str(path), **kwargs)


@dataclass(frozen=True, eq=False)
class EpicsCapture:
    """A test taken from a camonitor log and what was found on the way."""

    dataset: PositioningDataset
    setpoint_pv: str
    reference_pv: str
    stops: int             # dwells of the setpoint
    measurements: int
    other_stops: int       # over-travel (or a plan's overrun rows)


def parse_epics(text: str, *args, **kwargs) -> PositioningDataset:
    """The positioning dataset of :func:`capture_epics` (same parameters)."""
    return capture_epics(text, *args, **kwargs).dataset


def capture_epics(text: str, setpoint_pv: str | None = None, reference_pv: str | None = None,
                targets=None, plan=None, *, target_unit: str | None = None,
                deviation_unit: str | None = None, axis_kind: str | None = None,
                dwell: float = 1.0, window: float = 1.0, settled: float = 0.5,
                reference_scale: float = 1.0,
                reference_offset: float = 0.0, offsets: str = "relative",
                source: str = "<text>") -> EpicsCapture:
    """A positioning test from a camonitor log (module docstring).

    Parameters
    ----------
    text : str
    setpoint_pv, reference_pv : str, optional
        The PVs; found when the log holds exactly two PVs (the one with fewer updates is the
        setpoint), else required.
    targets : sequence of float, target unit, optional
    plan : PlanRows, optional
        The plan the axis ran (its unit is the target unit).
    target_unit : str, optional
        Unit of setpoint and reference (default mm; the log carries none).
    deviation_unit : str, optional
        Default µm (length) or arcsec (angle).
    dwell : float, s
        Shortest stretch of one setpoint value that is a stop.
    window : float, deviation unit (µm or arcsec by default)
        Band the reference stays within over a dwell's settled part.
    settled : float, s
        Shortest settled part of a measured dwell.
    reference_scale, reference_offset : float
        ``position = scale × reference + offset`` (target unit).

    Returns
    -------
    EpicsCapture
        The dataset (its ``metadata.notes`` say what was found and which defaults were used)
        and the counts of stops.
    """
    from axiscal.io._epics_stops import assemble, settled_mean

    log = parse_camonitor(text, source, offsets)
    sp_name, ref_name = _choose_pvs(log, setpoint_pv, reference_pv)
    sp, ref = log.series(sp_name), log.series(ref_name)
    for s in (sp, ref):
        _check_usable(s, source)
    _check_options(dwell, window, settled, reference_scale, reference_offset, source)
    tu, du, k, kind = _units(target_unit, deviation_unit, axis_kind, plan, source)
    dwells = find_dwells(sp, log.end, dwell)
    if not dwells:
        raise DataFormatError(f"the setpoint {sp_name} never holds a value for {dwell:g} s: "
                              "no steps to measure at (give a shorter dwell?)", source)
    band = window / k / abs(reference_scale)      # in the reference's own numbers

    def position(d: Dwell) -> float:       # only the dwells measured need a reference
        aims = [(x - reference_offset) / reference_scale for x in (d.value, d.came_from)]
        return (settled_mean(ref, d, band, settled, aims, source) * reference_scale
                + reference_offset)

    said = (f"{NOTES_START}: setpoint {sp_name}, reference {ref_name}; unit {tu}"
            + ("" if target_unit or plan is not None else " (assumed: the log carries none)")
            + f"; dwell ≥ {dwell:g} s; reference averaged where it rests within {window:g} "
            f"{ {'um': 'µm'}.get(du, du)} for ≥ {settled:g} s in each dwell")
    if reference_scale != 1.0 or reference_offset != 0.0:
        said += f"; position = {reference_scale:.12g} × reference + {reference_offset:.12g}"
    meta = Metadata(instrument=ref_name, axis=sp_name, date=log.start.split(" ")[0])
    ds, others = assemble(dwells, position, targets, plan, kind, tu, du, k, meta,
                          said + _alarm_note(ref), source)
    n = int(np.isfinite(ds.up).sum() + np.isfinite(ds.down).sum())
    return EpicsCapture(ds, sp_name, ref_name, len(dwells), n, others)


def _units(target_unit, deviation_unit, axis_kind, plan, source):
    """Target unit, deviation unit, the factor between them and the axis kind."""
    unit_text = target_unit or (plan.target_unit if plan is not None else None) or "mm"
    try:
        tu = units.canonical(unit_text)
        dim = units.dimension(tu)
        du = units.canonical(deviation_unit) if deviation_unit else (
            "um" if dim == "length" else "arcsec")
        k = units.convert(1.0, tu, du)
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None
    kind = AxisKind.parse(axis_kind) if axis_kind else (
        AxisKind.LINEAR if dim == "length" else AxisKind.ROTARY)
    return tu, du, k, kind


# -- the log's lines ---------------------------------------------------------------------------
class _Pv:
    """One PV's updates while the log is read."""

    def __init__(self):
        self.t, self.v, self.lines = [], [], []
        self.elements, self.alarms, self.invalid, self.undefined = 1, 0, 0, 0
        self.text = False
        self.first_abs = None      # the absolute time of its first stamped line
        self.last = None           # its last time (for -tI)

    def series(self, name: str) -> PvSeries:
        return PvSeries(name, np.array(self.t, dtype=float), np.array(self.v, dtype=float),
                        np.array(self.lines, dtype=int), self.elements, self.alarms,
                        self.invalid, self.undefined, self.text)


class _State:
    """The reading of a log: the PVs so far and the clock."""

    def __init__(self, offsets: str, source: str):
        self.offsets, self.source = offsets, source
        self.pvs: dict[str, _Pv] = {}
        self.origin = None          # datetime of the first absolute stamp (whole seconds)
        self.origin_frac = 0.0      # its fraction of a second
        self.start_text = ""
        self.first_server = None    # s: camonitor's tsFirst (the -tr reference)
        self.previous = None        # s: the previous update's time (the -ti reference)
        self.day = 0.0              # s added to a clock-only stamp after midnight
        self.seconds: dict = {}     # whole-second text -> datetime

    def take(self, line: str, lineno: int) -> None:
        m = _LINE.match(line)
        if m is None:
            raise DataFormatError(f"not a camonitor line: {line[:60]!r}", self.source, lineno)
        name, rest = m.group("name"), m.group("rest")
        pv = self.pvs.setdefault(name, _Pv())
        stamp = m.group("server") or m.group("client")
        if stamp and _OFFSET_RE.fullmatch(stamp) and pv.first_abs is None:
            rest, stamp = f"{stamp} {rest}".strip(), None    # a value: -tn has no stamps
        if "***" in rest:                     # a lost channel: unknown from then on
            if stamp:
                self._add(pv, self._time(pv, stamp, lineno), math.nan, lineno, invalid=True)
            else:
                pv.invalid += 1
            return
        if stamp is None:
            raise DataFormatError("a line without a time stamp (camonitor -tn?): the stops "
                                  "cannot be timed; record with time stamps", self.source,
                                  lineno)
        if stamp == "<undefined>":
            pv.undefined += 1
            return
        t = self._time(pv, stamp, lineno)
        value, invalid = self._value(pv, rest, lineno)
        self._add(pv, t, value, lineno, invalid)

    def _add(self, pv, t, value, lineno, invalid=False):
        pv.t.append(t)
        pv.v.append(value)
        pv.lines.append(lineno)
        pv.invalid += bool(invalid)
        if math.isfinite(t):
            pv.last = self.previous = t

    def _time(self, pv: _Pv, stamp: str, lineno: int) -> float:
        if _OFFSET_RE.fullmatch(stamp):
            ref = {"relative": self.first_server, "incremental": self.previous,
                   "by-channel": pv.last}[self.offsets]
            if ref is None:
                raise DataFormatError(f"offset {stamp} s before any absolute time stamp",
                                      self.source, lineno)
            return ref + float(stamp)
        t = self._absolute(stamp, lineno)
        if pv.first_abs is None:
            pv.first_abs = t
        if self.first_server is None:
            self.first_server = t
        return t

    def _absolute(self, stamp: str, lineno: int) -> float:
        dated = _DATE_RE.fullmatch(stamp) is not None
        whole, _, frac = stamp.replace("T", " ").partition(".")
        when = self.seconds.get(whole)             # many updates share a second: parse it once
        if when is None:
            try:
                when = datetime.strptime(whole, "%Y-%m-%d %H:%M:%S" if dated else "%H:%M:%S")
            except ValueError:
                raise DataFormatError(f"time stamp {stamp!r} is not a date and time",
                                      self.source, lineno) from None
            self.seconds[whole] = when
        seconds = float(f"0.{frac}") if frac else 0.0
        if self.origin is None:
            self.origin, self.start_text, self.origin_frac = when, stamp, seconds
        if dated != (self.origin.year != 1900):
            raise DataFormatError(f"time stamp {stamp!r}: the log mixes stamps with and without "
                                  "a date", self.source, lineno)
        t = ((when - self.origin).total_seconds() + (seconds - self.origin_frac)
             + (0.0 if dated else self.day))
        if not dated and self.previous is not None and t < self.previous - 43200:
            self.day += 86400.0                 # a clock-only stamp passed midnight
            t += 86400.0
        return t

    def _value(self, pv: _Pv, rest: str, lineno: int):
        tokens = rest.split()
        invalid = False
        if len(tokens) >= 2 and tokens[-1] in _SEVERITIES:
            invalid = tokens[-1] == "INVALID"
            pv.alarms += tokens[-1] in ("MINOR", "MAJOR")
            tokens = tokens[:-2]
        if not tokens:
            raise DataFormatError("a line with a time stamp but no value", self.source, lineno)
        if len(tokens) > 1 and tokens[0].isdigit() and int(tokens[0]) == len(tokens) - 1:
            pv.elements = max(pv.elements, len(tokens) - 1)
            tokens = tokens[1:2]               # an array: its first element is kept
        value = _number(tokens[0]) if len(tokens) == 1 else None
        if value is None:
            pv.text = True
            return math.nan, True
        return (math.nan if invalid or not math.isfinite(value) else value,
                invalid or not math.isfinite(value))


def _number(token: str):
    try:
        return float(token)
    except ValueError:
        pass
    try:
        return float(int(token, 0))            # camonitor -0x, -0o, -0b
    except ValueError:
        return None


# -- choosing and checking the PVs -------------------------------------------------------------
def _choose_pvs(log: CamonitorLog, setpoint: str | None, reference: str | None):
    if setpoint and reference:
        if setpoint == reference:
            raise DataFormatError(f"the setpoint and the reference are the same PV {setpoint!r}",
                                  log.source)
        return setpoint, reference
    names = list(log.pvs)
    if len(names) == 2:
        if setpoint or reference:
            given = setpoint or reference
            log.series(given)
            other = names[1] if names[0] == given else names[0]
            return (given, other) if setpoint else (other, given)
        a, b = (log.pvs[n] for n in names)
        return (a.name, b.name) if a.times.size <= b.times.size else (b.name, a.name)
    missing = " and ".join(o for o, v in (("--setpoint-pv", setpoint),
                                          ("--reference-pv", reference)) if not v)
    raise DataFormatError(f"the log holds {len(names)} PVs ({_names(log.pvs)}); name the "
                          f"setpoint and the reference ({missing})", log.source)


def _check_usable(s: PvSeries, source: str) -> None:
    if s.elements > 1:
        raise DataFormatError(f"PV {s.name} holds arrays of {s.elements} elements; a setpoint "
                              "or reference is one number", source)
    if s.text and not np.isfinite(s.values).any():
        raise DataFormatError(f"PV {s.name} holds text, not numbers", source)
    if not np.isfinite(s.values).any():
        raise DataFormatError(f"PV {s.name} has no valid value in the log", source)
    back = np.flatnonzero(np.diff(s.times) < 0)
    if back.size:
        i = int(back[0])
        raise DataFormatError(f"the time of PV {s.name} goes back ({s.times[i]:.6f} s then "
                              f"{s.times[i + 1]:.6f} s from the first stamp)", source,
                              int(s.lines[i + 1]))


def _check_options(dwell, window, settled, scale, offset, source) -> None:
    if not (math.isfinite(dwell) and 0 < dwell <= 86400):
        raise DataFormatError(f"dwell {dwell:g} s: give more than 0, at most 86400 s", source)
    if not (math.isfinite(window) and 0 < window <= 1e6):
        raise DataFormatError(f"rest window {window:g}: give a band wider than 0, at most 1e6 "
                              "(µm or arcsec)",
                              source)
    if not (math.isfinite(settled) and 0 <= settled <= 3600):
        raise DataFormatError(f"settled {settled:g} s: give 0 … 3600 s", source)
    if not (math.isfinite(scale) and scale != 0 and abs(scale) <= 1e6
            and math.isfinite(offset) and abs(offset) <= 1e9):
        raise DataFormatError(f"reference scale {scale:g} and offset {offset:g}: a non-zero "
                              "scale within ±1e6 and an offset within ±1e9", source)


def _alarm_note(ref: PvSeries) -> str:
    parts = []
    if ref.alarms:
        parts.append(f"{ref.alarms} reference update(s) in MINOR/MAJOR alarm (values kept)")
    if ref.undefined:
        parts.append(f"{ref.undefined} update(s) stamped <undefined> (no time: not used)")
    return "".join(f"; {p}" for p in parts)


def _names(pvs: dict) -> str:
    names = list(pvs)
    shown = ", ".join(names[:8])
    return shown + (f" and {len(names) - 8} more" if len(names) > 8 else "")


def _same(a: float, b: float) -> bool:
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b))


def _sign(a, b) -> int:
    """+1 if ``a > b``, -1 if ``a < b``, 0 if equal or either is missing."""
    if a is None or b is None or _same(a, b):
        return 0
    return 1 if a > b else -1
