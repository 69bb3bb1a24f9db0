"""Renishaw laser-system ASCII exports: ``.rtl`` (linear) and ``.rta`` (angular) positioning tests.

Layout
------
Plain text in named sections, each opened by a line ``NAME::`` and the file closed by ``EOF::``;
Renishaw's software writes CRLF line ends (the C# writer below writes ``\\r\\n``, the Chinese web
reader below says "纯文本 CRLF")::

    HEADER::
    File type  : rtl                      (rta for an angular test)
    Owner      : Linear
    Version no : V20.02.02

    TARGET DATA::
    Filetype  : ISO
    Target-count: 5
    Targets :
    0 100 200 300 400                     (five a line)
    Flags: 0 0 2 0

    USER-TEXT::
    Machine: VMC 800
    Serial No: 1234
    Date: 2016-12-12 10:46:00
    By: JS
    Axis: X
    Location: Bay 3
    TITLE: X axis after service

    RUNS::
    Run-count: 4

    DEVIATIONS::
    Run Target Data:
    1   1      0.8                        (run, target number, deviation)
    ...

    ENVIRONMENT::
    Air temp   : 20.337280 20.384956 0    (start, end, a flag not interpreted)
    Air press  : 99.039005 99.049346 1
    Air humid  : 46.954897 46.893887
    Mat temp 1 : 20.203292 20.321342 0
    Mat temp 2 : -10.000000 -10.000000 0
    Exp coeff  : 8.000000 8.000000 0
    Date Time  : "10:46 Dec 12 2016" "11:01 Dec 12 2016"

    EOF::

Sources (public programs that read or write these files; layout learned from them, no code copied)
--------------------------------------------------------------------------------------------------
1. A C# WPF measuring program (namespace ``AAM``, ``MainViewModel.SaveDatatoFile``; in the public
   code index as file id 1695960937, repository not resolvable through the index, licence not
   seen) *writes* ``.rtl``: the section names and order, ``File type : rtl``, ``Owner : Linear``,
   targets five a line, ``Flags: 0 0 2 0`` for a bidirectional and ``Flags: 0 1 2 0`` for a
   unidirectional test, ``Run-count`` = 2 × runs, deviation lines ``run  target  value``
   with odd runs over targets 1…m and even runs over m…1, the deviation
   ``(laser reading − target) × 1000`` with targets in mm (so µm, actual minus target), and for a
   unidirectional test an even run of zeros after each measured run. Its ENVIRONMENT block names
   the records (``Air temp``, ``Air Press``, ``Air Humid``, ``Mat temp 1…3``, ``Env factor``,
   ``Exp coeff``, ``Date Time``, ``Final Data``).
2. Paolico/AxisCorection (Java, ``src/main/java/model/RtlParser.java`` and ``RtlEnvironment.java``,
   commit b06d718c496c478b4a918d53fb6d26c6f749219c, 2019; no licence file) *reads* ``.rtl``: every
   section, ``Target-count``/``Flags``/``Run-count``, run-target-value lines, odd runs forward and
   even runs backward ("tam"/"zpět"), and its comments quote a real file's ENVIRONMENT lines (the
   values shown above: air pressure 99.04, material sensors 2 and 3 at exactly −10.000000).
3. A C++ MFC dialog (``CDialogParameters::OnBnClickedParseRtl``, index id 29642958385) *reads*
   ``.rtl`` for a scale controller: targets in mm ("mm为单位"), deviations in µm
   ("um 为单位的偏差值"), ``Target-count`` and ``Run-count`` before the data, targets on
   (m/5)+1 lines.
4. A JavaScript compensation view (index id 68574318152) *reads* ``.rtl``: CRLF text, targets
   "may be wrapped over several lines", positions in mm.
5. "Read Laser Plot 5.3" (Python/PyQt, index id 5760434055) *reads* ``.rta``: targets in degrees,
   and it multiplies each deviation by 180/π·3600/1000 = 0.2063 to get arcseconds, i.e. the file's
   angular deviations are in **µrad**; an ``EQUIPMENT::`` section follows DEVIATIONS.
6. A laser-cutter controller's file list (index id 69478548917) names "``*.rtl; *.ren; *.pos;
   *.csv`` (Renishaw laser-interferometer exports)" as its inputs.

Readings chosen where the sources are silent or could be read two ways
----------------------------------------------------------------------
* **Units.** ``.rtl``: targets mm, deviations µm (sources 1, 3, 4). ``.rta``: targets degrees,
  deviations µrad (source 5 only; no source says arcseconds). The dataset keeps the file's units
  (so nothing is rounded); ``deviation_unit=`` converts. **Inch** files: no public source shows
  one, so a file declaring any unit (a ``...unit...:`` line) other than mm/degrees is refused.
* **Sign.** Source 1 writes laser reading − target: the ISO 230-2:2014 §2.13 deviation (actual
  minus target; Yüksel et al., Position accuracy and repeatability calibration of turn tables
  eq. 1). No sign is flipped.
* **Directions.** ``Flags: 0 0 2 0`` (bidirectional): odd run 2j−1 is run j of the first
  direction, even run 2j run j of the other. The first direction is + (ISO 230-2 ↑) when the
  targets are listed increasing, − when decreasing (runs go over the targets in listed order);
  targets listed in any other order are refused. ``Flags: 0 1 2 0`` (unidirectional): the odd
  runs are the measured runs, the even runs must hold only zeros (source 1's placeholders) or the
  file is refused. Any other ``Flags`` (a **pilgrim** test's order among them: no source shows
  how Renishaw numbers its runs) is refused, as is a file with no ``Flags`` line.
* **Environment.** Each record's start and end values are averaged (the mean is what the
  dataset's conditions hold; the third field is not interpreted). Air pressure is in kPa (99.04
  in source 2 is a plausible air pressure only in kPa) and stored in Pa; ``Exp coeff`` in
  ppm/°C (8.0 in source 2) stored in 1/K; a material sensor reading exactly −10.000000 at start
  and end is a sensor not fitted (source 2): left out of the conditions, and said so in the
  notes. ``Date`` in USER-TEXT is the test date when it is an ISO 8601 date (as source 1 writes
  it); otherwise ENVIRONMENT's first ``Date Time`` (``"10:46 Dec 12 2016"`` in source 2's real
  file) is used when there is one.
* **Metadata.** Machine → machine, Axis → axis, By → operator, TITLE → notes (with
  ``Serial No`` and ``Location`` appended when present). The format has no instrument field.

A damaged file (no ``EOF::``, a count that contradicts the data, a missing run or target, a
value that is not a number, a run or target outside the declared counts) is refused in one line.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from datetime import datetime
from decimal import Decimal, InvalidOperation

import numpy as np

from axiscal import units
from axiscal._parse import finite_number, strict_int
from axiscal.datasets import AxisKind, Environment, Metadata, PositioningDataset
from axiscal.io.rta_unit import RTA_CONVERTED, file_unit_block  # noqa: F401  (kept here too)
from axiscal.errors import AxiscalError, DataFormatError, InputError
from axiscal.io.detect import looks_like_renishaw

__all__ = ["decode", "encode", "CODE_PAGES", "RTA_CONVERTED", "file_unit_block",
           "looks_like_renishaw", "parse_renishaw", "read_renishaw", "parse_rtl", "read_rtl",
           "parse_rta", "read_rta", "format_renishaw", "format_rtl", "format_rta"]

#: File type -> (axis kind, target unit, deviation unit, HEADER Owner written).
FILE_TYPES = {
    "rtl": (AxisKind.LINEAR, "mm", "um", "Linear"),
    "rta": (AxisKind.ROTARY, "deg", "urad", "Angular"),
}
#: The HEADER version string source 1 writes (so that Renishaw's software takes the file).
VERSION_WRITTEN = "V20.02.02"
FLAGS_BIDIRECTIONAL = ("0", "0", "2", "0")
FLAGS_UNIDIRECTIONAL = ("0", "1", "2", "0")
#: A material sensor reading exactly this at start and end is not fitted (source 2).
NO_SENSOR = -10.0
_SECTION = re.compile(r"^([A-Z][A-Z0-9 \-]*)::$")
_REQUIRED = ("HEADER", "TARGET DATA", "RUNS", "DEVIATIONS")
_TARGETS_PER_LINE = 5


#: Windows code pages a Renishaw export may be written in (``encoding=``); 1252 by default.
CODE_PAGES = ("cp1252", "cp1250", "cp1251", "cp1253", "cp1254", "cp1257", "cp932", "cp936")


def decode(data: bytes, encoding: str | None = None, source: str = "<bytes>") -> tuple[str, str]:
    """The text of a Renishaw export and the encoding it was read in.

    Renishaw's software runs on Windows and writes the ANSI code page of the PC: a German "ä"
    in the USER-TEXT is the byte 0xE4 (Windows-1252). Read: UTF-8 (with or without a BOM),
    UTF-16 with its BOM, else ``encoding`` (one of :data:`CODE_PAGES`, default Windows-1252).
    The numbers are ASCII in every one of them.
    """
    if encoding is not None:
        enc = _code_page(encoding)
        try:
            return data.decode(enc), _name(enc)
        except UnicodeDecodeError as exc:
            raise DataFormatError(f"not {_name(enc)} text (byte {exc.start})", source) from None
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16"), "utf-16"
        except UnicodeDecodeError as exc:
            raise DataFormatError(f"not UTF-16 text (byte {exc.start})", source) from None
    try:
        return data.decode("utf-8-sig"), "utf-8"
    except UnicodeDecodeError:
        if b"\x00" in data[:4096]:
            raise DataFormatError("not a text file (it holds NUL bytes)", source) from None
        return data.decode("cp1252", errors="replace"), "windows-1252"


def encode(text: str, encoding: str | None = None) -> bytes:
    """The bytes of a Renishaw export written in ``encoding`` (one of :data:`CODE_PAGES`,
    ``utf-8`` (the default) or ``utf-16``, written with its BOM), as Renishaw's Windows software
    writes the PC's code page; :func:`decode` reads them back. A character the code page cannot
    hold is refused naming it (nothing is replaced)."""
    enc = _code_page(encoding) if encoding is not None else "utf-8-sig"
    enc = "utf-8" if enc == "utf-8-sig" else enc
    try:
        return text.encode(enc)
    except UnicodeEncodeError as exc:
        raise InputError(f"encoding {encoding!r}: {text[exc.start]!r} (in "
                         f"{text[max(0, exc.start - 20):exc.start + 20]!r}) is not in "
                         f"{_name(enc)}; write it in utf-8 or a code page that holds it") from None


def _code_page(encoding: str) -> str:
    """The codec of a name :func:`decode` and :func:`encode` accept; others refused."""
    enc = str(encoding).lower().replace("windows-", "cp").replace("-", "")
    if enc not in CODE_PAGES and enc not in ("utf8", "utf16"):
        raise InputError(f"encoding {encoding!r}: one of utf-8, utf-16, "
                         f"{', '.join(CODE_PAGES)}")
    return {"utf8": "utf-8-sig", "utf16": "utf-16"}.get(enc, enc)


def _name(enc: str) -> str:
    return {"utf-8-sig": "utf-8"}.get(enc, enc.replace("cp", "windows-") if enc.startswith("cp12")
                                      else enc)


def read_renishaw(path, encoding: str | None = None, **kwargs) -> PositioningDataset:
    """Read a ``.rtl`` or ``.rta`` file in UTF-8, UTF-16 (BOM) or a Windows code page
    (:func:`decode`; the encoding used is said in the dataset's notes); see
    :func:`parse_renishaw`."""
    from axiscal.io._files import read_bytes

    text, used = decode(read_bytes(path), encoding, str(path))
    return parse_renishaw(text, source=str(path), encoding=used, **kwargs)


def read_rtl(path, **kwargs) -> PositioningDataset:
    """Read a linear ``.rtl`` file (an angular one is refused)."""
    return read_renishaw(path, expect="rtl", **kwargs)


def read_rta(path, **kwargs) -> PositioningDataset:
    """Read an angular ``.rta`` file (a linear one is refused)."""
    return read_renishaw(path, expect="rta", **kwargs)


def parse_rtl(text: str, **kwargs) -> PositioningDataset:
    """Parse a linear ``.rtl`` export; see :func:`parse_renishaw`."""
    return parse_renishaw(text, expect="rtl", **kwargs)


def parse_rta(text: str, **kwargs) -> PositioningDataset:
    """Parse an angular ``.rta`` export; see :func:`parse_renishaw`."""
    return parse_renishaw(text, expect="rta", **kwargs)


def parse_renishaw(text: str, source: str = "<text>", target_unit: str | None = None,
                   deviation_unit: str | None = None, axis_kind: str | None = None,
                   expect: str | None = None, encoding: str = "") -> PositioningDataset:
    """Parse a Renishaw ``.rtl``/``.rta`` export into a :class:`PositioningDataset`.

    Parameters
    ----------
    text : str
        The file's content (CRLF or LF line ends).
    target_unit : str, optional
        Refused unless it is the file's own (mm for ``.rtl``, deg for ``.rta``).
    deviation_unit : str, optional
        Convert the deviations to this unit (default: µm for ``.rtl``, the file's own; arcsec
        for ``.rta``, converted from the file's µrad and said in the notes, as every rotary
        result of axiscal is in arcseconds).
    axis_kind : {"linear", "rotary"}, optional
        Refused unless it matches the file type.
    expect : {"rtl", "rta"}, optional
        Refuse a file of the other type.
    encoding : str, optional
        The encoding the text was read in (:func:`decode`); anything but UTF-8 is said in the
        dataset's notes.

    Examples
    --------
    >>> ds = PositioningDataset.from_arrays("linear", [0, 100], [[1.5], [-0.5]], [[2.0], [0.5]])
    >>> parse_renishaw(format_renishaw(ds)).equals(ds)
    True
    """
    sections = _sections(text, source)
    head = _fields(sections["HEADER"], source)
    ftype = _file_type(head, source, expect)
    kind, tu, du, _owner = FILE_TYPES[ftype]
    _check_options(ftype, kind, tu, target_unit, axis_kind, source)
    for name in ("HEADER", "TARGET DATA", "USER-TEXT"):
        _refuse_units(sections.get(name, []), tu, ftype, source)
    targets, flags = _targets(sections["TARGET DATA"], source)
    n_runs = _run_count(sections["RUNS"], source)
    values = _deviations(sections["DEVIATIONS"], len(targets), n_runs, source)
    records = _records(targets, values, flags, n_runs, source)
    env, env_date, unfitted = _environment(sections.get("ENVIRONMENT", []), source)
    meta = _metadata(_fields(sections.get("USER-TEXT", []), source), env, env_date, unfitted)
    if encoding and encoding != "utf-8":
        said = f"read as {encoding} text (a Windows export in the PC's code page)"
        meta = replace(meta, notes=f"{meta.notes} | {said}" if meta.notes else said)
    try:
        ds = PositioningDataset.from_records(kind, records, tu, du, meta, source=source)
    except DataFormatError:
        raise
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None
    if deviation_unit is None and ftype == "rta":
        said = RTA_CONVERTED
        ds = ds.with_deviation_unit("arcsec")
        return replace(ds, metadata=replace(ds.metadata, notes=f"{ds.metadata.notes} | {said}"
                                            if ds.metadata.notes else said))
    return ds.with_deviation_unit(units.canonical(deviation_unit)) if deviation_unit else ds


# -- reading ----------------------------------------------------------------------------------
def _sections(text: str, source: str) -> dict[str, list[tuple[int, str]]]:
    """The lines of each section, by name; refuses text outside sections and a missing EOF."""
    out: dict[str, list[tuple[int, str]]] = {}
    current = None
    ended = False
    for n, raw in enumerate(text.lstrip("\ufeff").splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if ended:
            raise DataFormatError(f"text after EOF:: ({line[:40]!r})", source, n)
        m = _SECTION.match(line)
        if m:
            current = " ".join(m.group(1).split())
            if current == "EOF":
                ended = True
            elif current in out:
                raise DataFormatError(f"section {current}:: appears twice", source, n)
            else:
                out[current] = []
            continue
        if current is None:
            raise DataFormatError("a Renishaw export opens with HEADER::", source, n)
        out[current].append((n, line))
    missing = [s for s in _REQUIRED if s not in out]
    if missing:
        raise DataFormatError(f"missing section(s) {', '.join(s + '::' for s in missing)}: the "
                              "file is truncated or not a Renishaw export", source)
    if not ended:
        raise DataFormatError("no EOF:: line: the file is truncated", source)
    return out


def _fields(lines, source: str) -> dict[str, tuple[int, str]]:
    """``Key : value`` lines of a section, keyed by the lower-case key with single spaces."""
    out: dict[str, tuple[int, str]] = {}
    for n, line in lines:
        if ":" not in line:
            continue
        key, value = line.split(":", 1)
        k = " ".join(key.lower().split())
        if k in out:
            raise DataFormatError(f"{key.strip()!r} is given twice", source, n)
        out[k] = (n, value.strip())
    return out


def _file_type(head: dict, source: str, expect: str | None) -> str:
    n, value = head.get("file type", (None, ""))
    ftype = value.lower()
    if ftype not in FILE_TYPES:
        raise DataFormatError(f"HEADER File type {value!r}: axiscal reads rtl (linear) and rta "
                              "(angular)", source, n)
    if expect is not None and ftype != expect:
        raise DataFormatError(f"a .{ftype} file where a .{expect} file was expected", source, n)
    return ftype


def _check_options(ftype, kind, tu, target_unit, axis_kind, source) -> None:
    if target_unit and units.canonical(target_unit) != tu:
        raise DataFormatError(f"a .{ftype} file's targets are in {tu}; drop --target-unit "
                              f"{target_unit}", source)
    if axis_kind and AxisKind.parse(axis_kind) is not kind:
        raise DataFormatError(f"a .{ftype} file holds a {kind.value} axis, not {axis_kind}",
                              source)


def _refuse_units(lines, tu: str, ftype: str, source: str) -> None:
    """No public source shows an inch (or any other unit) declaration: refuse one."""
    for n, line in lines:
        key, _, value = line.partition(":")
        if "unit" in key.lower() and value.strip().lower() not in (tu, "degree", "degrees"):
            raise DataFormatError(f"{line!r}: no public source shows how a .{ftype} file in other "
                                  f"units than {tu} is laid out (inch files are not read)",
                                  source, n)


def _targets(lines, source: str) -> tuple[list[float], tuple[str, ...]]:
    """Target positions (in listed order) and the Flags fields, counts checked."""
    fields = _fields([(n, ln) for n, ln in lines if not _is_number_line(ln)], source)
    if "filetype" in fields and fields["filetype"][1].upper() != "ISO":
        n, v = fields["filetype"]
        raise DataFormatError(f"TARGET DATA Filetype {v!r}: only ISO is established by public "
                              "sources", source, n)
    declared = _count(fields, "target-count", "TARGET DATA", source)
    targets = [finite_number(tok, "target", source, n)
               for n, ln in lines if _is_number_line(ln) for tok in ln.split()]
    if len(targets) != declared:
        raise DataFormatError(f"Target-count: {declared} but {len(targets)} targets are listed",
                              source)
    if "flags" not in fields:
        raise DataFormatError("no Flags: line in TARGET DATA; the runs' directions cannot be told",
                              source)
    n, value = fields["flags"]
    flags = tuple(value.split())
    if flags not in (FLAGS_BIDIRECTIONAL, FLAGS_UNIDIRECTIONAL):
        raise DataFormatError(f"Flags: {value}: public sources establish only 0 0 2 0 "
                              "(bidirectional) and 0 1 2 0 (unidirectional); pilgrim and other "
                              "run orders are not read", source, n)
    return targets, flags


def _is_number_line(line: str) -> bool:
    return bool(line) and (line[0].isdigit() or line[0] in "+-.")


def _count(fields: dict, key: str, section: str, source: str) -> int:
    if key not in fields:
        raise DataFormatError(f"no {key.capitalize()}: line in {section}", source)
    n, value = fields[key]
    try:
        count = strict_int(value)
    except ValueError:
        raise DataFormatError(f"{key.capitalize()}: {value!r} is not a whole number", source,
                              n) from None
    if count < 1:
        raise DataFormatError(f"{key.capitalize()}: {count} (at least 1)", source, n)
    return count


def _run_count(lines, source: str) -> int:
    return _count(_fields(lines, source), "run-count", "RUNS", source)


def _deviations(lines, m: int, n_runs: int, source: str) -> dict[tuple[int, int], float]:
    """Every (run, target number) -> deviation; each must be given exactly once."""
    values: dict[tuple[int, int], float] = {}
    for n, line in lines:
        if not _is_number_line(line):
            if line.replace(" ", "").lower() == "runtargetdata:":
                continue
            raise DataFormatError(f"{line[:40]!r} in DEVIATIONS: expected run, target number "
                                  "and deviation", source, n)
        cells = line.split()
        if len(cells) != 3:
            raise DataFormatError(f"{line!r}: expected run, target number and deviation", source, n)
        run, target = (_index(c, what, limit, source, n) for c, what, limit in
                       ((cells[0], "run", n_runs), (cells[1], "target number", m)))
        if (run, target) in values:
            raise DataFormatError(f"run {run} at target {target} is given twice", source, n)
        values[(run, target)] = finite_number(cells[2], "deviation", source, n)
    for run in range(1, n_runs + 1):
        have = sum((run, t) in values for t in range(1, m + 1))
        if have != m:
            raise DataFormatError(f"run {run} has {have} of the {m} targets (Run-count: {n_runs}, "
                                  f"Target-count: {m})", source)
    return values


def _index(text: str, what: str, limit: int, source: str, line: int) -> int:
    try:
        i = strict_int(text)
    except ValueError:
        raise DataFormatError(f"{what} {text!r} is not a whole number", source, line) from None
    if not 1 <= i <= limit:
        raise DataFormatError(f"{what} {i} is outside 1…{limit} (the declared count)", source,
                              line)
    return i


def _records(targets, values, flags, n_runs, source):
    """(target, direction, run, deviation) records by the chosen reading of Flags."""
    steps = np.diff(targets)
    if np.all(steps > 0):
        first, second = "+", "-"
    elif np.all(steps < 0):
        first, second = "-", "+"
    else:
        raise DataFormatError("targets are listed neither increasing nor decreasing; the runs' "
                              "directions cannot be told", source)
    if n_runs % 2:
        pair = "out and back" if flags == FLAGS_BIDIRECTIONAL else "measured run and zero run"
        raise DataFormatError(f"Run-count: {n_runs} is odd; the runs come in pairs ({pair})",
                              source)
    records = []
    for (run, i), dev in values.items():
        j = (run + 1) // 2
        if run % 2:
            records.append((targets[i - 1], first, j, dev))
        elif flags == FLAGS_BIDIRECTIONAL:
            records.append((targets[i - 1], second, j, dev))
        elif dev != 0.0:
            raise DataFormatError(f"unidirectional (Flags: 0 1 2 0) but even run {run} holds "
                                  f"{dev:g} at target {i}; only zeros are established there",
                                  source)
    return records


def _environment(lines, source: str) -> tuple[Environment, str, list[int]]:
    """The dataset's conditions from the ENVIRONMENT records, the first Date Time and the
    material sensors left out as not fitted."""
    f = _fields(lines, source)
    vals = {}
    for key, scale in (("air temp", "1"), ("air press", "1000"), ("air humid", "1"),
                       ("exp coeff", "0.000001")):
        if key in f:
            vals[key] = _mean(f[key], scale, source)
    mats, unfitted = [], []
    for i in (1, 2, 3):
        if f"mat temp {i}" in f:
            n, value = f[f"mat temp {i}"]
            nums = [finite_number(t, f"Mat temp {i}", source, n) for t in value.split()[:2]]
            if nums and all(v == NO_SENSOR for v in nums):
                unfitted.append(i)
                continue
            mats.append(_mean((n, value), "1", source))
    try:
        env = Environment(air_temperature=vals.get("air temp"), material_temperature=tuple(mats),
                          pressure=vals.get("air press"), humidity=vals.get("air humid"),
                          expansion_coefficient=vals.get("exp coeff"))
    except AxiscalError as exc:
        raise DataFormatError(f"ENVIRONMENT: {exc}", source) from None
    return env, _env_date(f.get("date time")), unfitted


def _mean(entry: tuple[int, str], scale: str, source: str) -> float:
    """Mean of a record's start and end (or its one value) times ``scale``, exactly in decimal."""
    n, value = entry
    tokens = value.split()[:2]
    if not tokens:
        raise DataFormatError("an ENVIRONMENT record without a value", source, n)
    for t in tokens:
        finite_number(t, "ENVIRONMENT value", source, n)
    try:
        total = sum((Decimal(t) for t in tokens), Decimal(0))
    except InvalidOperation:
        raise DataFormatError(f"ENVIRONMENT value {value!r} is not a number", source, n) from None
    return float(total / len(tokens) * Decimal(scale))


def _env_date(entry) -> str:
    """ENVIRONMENT ``Date Time : "10:46 Dec 12 2016" ...`` -> ``2016-12-12 10:46``."""
    if entry is None:
        return ""
    quoted = re.findall(r'"([^"]*)"', entry[1])
    if not quoted:
        return ""
    try:
        return datetime.strptime(quoted[0].strip(), "%H:%M %b %d %Y").strftime("%Y-%m-%d %H:%M")
    except ValueError:
        return quoted[0].strip()


def _metadata(user: dict, env: Environment, env_date: str, unfitted=()) -> Metadata:
    def get(key: str) -> str:
        return user.get(key, (None, ""))[1]

    notes = get("title")
    extra = [f"{label}: {get(key)}" for key, label in (("serial no", "Serial No"),
                                                       ("location", "Location")) if get(key)]
    if unfitted:
        extra.append(f"Mat temp {', '.join(map(str, unfitted))}: {NO_SENSOR:g} (no sensor, "
                     "left out)")
    if extra:
        notes = " | ".join([notes] + extra if notes else extra)
    date = get("date")
    if env_date and not _is_iso_date(date):
        date = env_date
    return Metadata(machine=get("machine"), axis=get("axis"), operator=get("by"),
                    date=date, notes=notes, environment=env)


def _is_iso_date(text: str) -> bool:
    try:
        datetime.fromisoformat(text.strip())
    except ValueError:
        return False
    return True


# -- writing ----------------------------------------------------------------------------------
def format_rtl(ds: PositioningDataset) -> str:
    """Write a linear dataset as a ``.rtl`` export (see :func:`format_renishaw`)."""
    if ds.axis_kind is not AxisKind.LINEAR:
        raise InputError("a .rtl file holds a linear axis; write a rotary one as .rta")
    return format_renishaw(ds)


def format_rta(ds: PositioningDataset) -> str:
    """Write a rotary dataset as a ``.rta`` export (see :func:`format_renishaw`)."""
    if ds.axis_kind is not AxisKind.ROTARY:
        raise InputError("a .rta file holds a rotary axis; write a linear one as .rtl")
    return format_renishaw(ds)


def format_renishaw(ds: PositioningDataset) -> str:
    """A dataset as the Renishaw export of its kind (``.rtl`` linear, ``.rta`` rotary), CRLF.

    Targets in mm (deg), deviations in µm (µrad), every number written so it reads back exactly;
    :func:`parse_renishaw` gives the same dataset back (the format has no instrument field).
    Refused: missing readings (the format has none), unequal run counts in the two directions,
    more than three material sensors, a line break in a metadata field.
    """
    ftype = "rtl" if ds.axis_kind is AxisKind.LINEAR else "rta"
    _kind, tu, du, owner = FILE_TYPES[ftype]
    _check_writable(ds, ftype)
    t = units.convert(ds.targets, ds.target_unit, tu)
    up, down = (units.convert(a, ds.deviation_unit, du) for a in (ds.up, ds.down))
    if ds.bidirectional:
        order, first, second, flags = t, up, down, FLAGS_BIDIRECTIONAL
    else:
        first = up if up.shape[1] else down
        order = t if up.shape[1] else t[::-1]
        first = first if up.shape[1] else first[::-1]
        second, flags = np.zeros_like(first), FLAGS_UNIDIRECTIONAL
    m, n = first.shape
    lines = ["HEADER::", f"File type  : {ftype}", f"Owner      : {owner}",
             f"Version no : {VERSION_WRITTEN}", "", "TARGET DATA::", "Filetype  : ISO",
             f"Target-count: {m}", "Targets :"]
    lines += [" ".join(_num(v) for v in order[k:k + _TARGETS_PER_LINE])
              for k in range(0, m, _TARGETS_PER_LINE)]
    lines += [f"Flags: {' '.join(flags)}", ""] + _user_text(ds.metadata)
    lines += ["RUNS::", f"Run-count: {2 * n}", "", "DEVIATIONS::", "Run Target Data:"]
    for j in range(n):
        lines += [f"{2 * j + 1}   {i + 1}      {_num(first[i, j])}" for i in range(m)]
        lines += [f"{2 * j + 2}   {i + 1}      {_num(second[i, j])}" for i in range(m - 1, -1, -1)]
    lines += [""] + _environment_lines(ds.metadata.environment) + ["EOF::", ""]
    return "\r\n".join(lines)


def _check_writable(ds: PositioningDataset, ftype: str) -> None:
    if ds.missing_count:
        raise InputError(f"{ds.missing_count} missing reading(s): a .{ftype} file holds every "
                         "run at every target")
    if ds.bidirectional and ds.up.shape[1] != ds.down.shape[1]:
        raise InputError(f"{ds.up.shape[1]} runs up but {ds.down.shape[1]} down: a .{ftype} "
                         "file pairs each run out with a run back")
    md = ds.metadata
    for name in ("machine", "axis", "operator", "date", "notes"):
        if "\n" in getattr(md, name) or "\r" in getattr(md, name):
            raise InputError(f"metadata {name} holds a line break; a .{ftype} USER-TEXT line "
                             "cannot")
    mats = md.environment.material_temperature
    if len(mats) > 3:
        raise InputError(f"{len(mats)} material sensors; a .{ftype} file has Mat temp 1…3")
    if NO_SENSOR in mats:
        raise InputError(f"a material temperature of exactly {NO_SENSOR:g} °C reads back as "
                         "'no sensor' in a Renishaw file")


def _user_text(md: Metadata) -> list[str]:
    return ["USER-TEXT::", f"Machine: {md.machine}", "Serial No: ", f"Date: {md.date}",
            f"By: {md.operator}", f"Axis: {md.axis}", "Location: ", f"TITLE: {md.notes}", ""]


def _environment_lines(env: Environment) -> list[str]:
    rows = [("Air temp   ", env.air_temperature, 0), ("Air press  ", env.pressure, 3),
            ("Air humid  ", env.humidity, 0)]
    rows += [(f"Mat temp {i + 1} ", v, 0) for i, v in enumerate(env.material_temperature)]
    rows.append(("Exp coeff  ", env.expansion_coefficient, -6))
    out = [f"{name}: {_shifted(v, shift)} {_shifted(v, shift)} 0"
           for name, v, shift in rows if v is not None]
    return ["ENVIRONMENT::"] + out + [""] if out else []


def _shifted(value: float, shift: int) -> str:
    """``value`` divided by 10**shift in exact decimal (Pa -> kPa, 1/K -> ppm/K)."""
    return format(Decimal(repr(float(value))).scaleb(-shift), "f") if shift else repr(float(value))


def _num(v: float) -> str:
    """Shortest text that reads back as the same float (``-0.0`` as ``0.0``)."""
    v = float(v) + 0.0
    if not math.isfinite(v):
        raise InputError(f"value {v!r} cannot be written")
    return repr(v)
