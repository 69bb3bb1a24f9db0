"""Tidy CSV for positioning tests.

Format
------
One reading per line with the header ``target,direction,run,deviation``; ``actual`` may stand
instead of ``deviation``, in which case deviation = actual − target (ISO 230-2 §3.1; Yüksel et al., Position accuracy and repeatability calibration of turn tables
eq. 1) and ``actual`` is in the target unit. ``direction`` is ``+``/``-`` (also ``up``/``down``,
``fwd``/``bwd``). Comment lines start with ``#``; a leading comment may declare the units and the
metadata as ``key=value`` pairs::

    # target_unit=mm deviation_unit=um axis=X machine=VMC-800
    target,direction,run,deviation
    0,+,1,0.8
    0,-,1,-1.2

Units given as options stand in for units the file does not declare; an option that disagrees
with the file's declaration is refused, and missing units are an error (a rotary file read as
millimetres, or µm read as mm, would give numbers that look right and are not).
"""

from __future__ import annotations

import io
import math
from array import array
from typing import Callable, Iterable, Iterator

from axiscal import units
from axiscal._parse import MAX_MAGNITUDE, agreed_unit, check_run_number, csv_cells, finite_number
from axiscal.datasets import _DIRECTION_WORDS, AxisKind, Direction, Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError, InputError, MissingFileError

__all__ = ["parse_positioning_csv", "read_positioning_csv", "format_positioning_csv",
           "iter_file_lines"]

_META_KEYS = {"machine", "axis", "operator", "date", "instrument", "notes"}

_CHUNK_BYTES = 1 << 20

#: A line longer than this is not a reading (a binary file, or a file with no line ends).
MAX_LINE_BYTES = 1 << 20

#: The table of runs may be at most this many times the readings (plus a fixed allowance) before
#: the file is refused as mostly missing: run numbers far apart at many targets would otherwise
#: allocate a table of mostly missing readings as large as the product.
_SPARSE_FACTOR = 10
_SPARSE_ALLOWANCE = 1_000_000


def read_positioning_csv(path, target_unit: str | None = None, deviation_unit: str | None = None,
                         axis_kind: str | None = None,
                         progress: Callable[[int, int], None] | None = None) -> PositioningDataset:
    """Read a tidy positioning CSV file, streaming it; see :func:`parse_positioning_csv`.

    The file is read line by line, and the readings are kept in compact arrays, so the memory
    used is proportional to the number of readings, not a multiple of the file. ``progress``, if
    given, is called now and then with ``(bytes read, file size)``.
    """
    return _parse_lines(iter_file_lines(path, progress), target_unit, deviation_unit, axis_kind,
                        str(path))


def iter_file_lines(path, progress: Callable[[int, int], None] | None = None
                    ) -> Iterator[tuple[int, str]]:
    """``(line number, text)`` of every line of a UTF-8 text file, read a line at a time.

    Errors name the file: a missing file, a folder, not UTF-8 (with the byte), a line longer than
    :data:`MAX_LINE_BYTES`.
    """
    from axiscal.io._files import _not_utf8, open_regular_file

    fh, size = open_regular_file(path)
    source = str(path)
    with fh:
        offset = 0          # bytes of the file decoded so far
        lineno = 0
        rest = b""
        while True:
            try:
                chunk = fh.read(_CHUNK_BYTES)
            except OSError as exc:
                raise MissingFileError(path, exc.strerror or str(exc)) from None
            if offset == 0 and not rest and chunk.startswith(b"\xef\xbb\xbf"):
                chunk, offset = chunk[3:], 3
            data = rest + chunk
            if chunk:
                cut = data.rfind(b"\n") + 1      # decode whole lines only
                if cut == 0:
                    cut = data.rfind(b"\r") + 1  # an old Mac file ends its lines with CR
                if cut == 0 and len(data) > MAX_LINE_BYTES:
                    raise DataFormatError(f"line {lineno + 1} is longer than "
                                          f"{MAX_LINE_BYTES // 2**20} MiB; is this a CSV file?",
                                          source)
                data, rest = data[:cut], data[cut:]
            else:
                rest = b""
            if data:
                try:
                    text = data.decode("utf-8")
                except UnicodeDecodeError as exc:
                    raise DataFormatError(_not_utf8(data, exc.start, offset), source) from None
                offset += len(data)
                for line in text.splitlines():
                    lineno += 1
                    yield lineno, line
                if progress is not None:
                    progress(offset, size)
            if not chunk:
                break


def parse_positioning_csv(
    text: str,
    target_unit: str | None = None,
    deviation_unit: str | None = None,
    axis_kind: str | None = None,
    source: str = "<text>",
) -> PositioningDataset:
    """Parse a tidy positioning CSV text into a :class:`PositioningDataset`.

    Raises
    ------
    DataFormatError
        Wrong header, a non-numeric value (with its line number), a bad direction, no data.
    UnitError
        An unknown unit, or units of the wrong dimension.

    Examples
    --------
    >>> ds = parse_positioning_csv('''# target_unit=deg deviation_unit=arcsec
    ... target,direction,run,deviation
    ... 0,+,1,1.0
    ... 0,+,2,1.5
    ... 90,+,1,-0.5
    ... 90,+,2,0.0
    ... ''')
    >>> ds.axis_kind.value, ds.n_targets, ds.bidirectional
    ('rotary', 2, False)
    """
    return _parse_lines(_numbered_lines(text), target_unit, deviation_unit, axis_kind, source)


def _numbered_lines(text: str) -> Iterator[tuple[int, str]]:
    """``enumerate(text.splitlines(), 1)`` without the list of every line (a text of millions
    of readings would hold them all at once)."""
    pos, n, lineno = 0, len(text), 0
    while pos < n:
        end = text.find("\n", pos)
        if end < 0:
            end = n
        chunk = text[pos:end]
        pos = end + 1
        for piece in chunk.splitlines() or [""]:   # "\r", and a lone CR of an old Mac file
            lineno += 1
            yield lineno, piece


def _parse_lines(lines: Iterable[tuple[int, str]], target_unit, deviation_unit, axis_kind,
                 source: str) -> PositioningDataset:
    header_meta: dict[str, str] = {}
    header: tuple[int, str] | None = None
    readings = None
    for lineno, line in lines:
        s = line.strip()
        if not s:
            continue
        if s.startswith("#"):
            for key, value in _parse_comment(s[1:], source, lineno).items():
                if header_meta.get(key, value) != value:   # two files pasted together?
                    raise DataFormatError(f"{key}={value} contradicts {key}={header_meta[key]} "
                                          "declared above", source, lineno)
                if header is None:
                    header_meta[key] = value
            continue
        if header is None:
            header = (lineno, line)
            setup = _setup(header, header_meta, target_unit, deviation_unit, axis_kind, source)
            readings = _Readings(*setup[:3], source)
            continue
        readings.add(lineno, line)
    if header is None:
        raise DataFormatError("no header and no readings (empty file?)", source)
    kind, tu, du = setup[3:]
    return readings.dataset(kind, tu, du, Metadata(**{k: v for k, v in header_meta.items()
                                                      if k in _META_KEYS}))


def _setup(header, header_meta, target_unit, deviation_unit, axis_kind, source):
    """Columns and units from the header line and the leading comment; errors as the file has them."""
    tu = agreed_unit(target_unit, header_meta.get("target_unit"), "target_unit", source)
    du = agreed_unit(deviation_unit, header_meta.get("deviation_unit"), "deviation_unit",
                     source)
    declared_kind = header_meta.get("axis_kind")
    if (axis_kind and declared_kind
            and AxisKind.parse(axis_kind) is not AxisKind.parse(declared_kind)):
        raise DataFormatError(f"the file declares axis_kind={declared_kind} but the option gives "
                              f"{axis_kind}", source)
    kind_text = axis_kind or declared_kind

    header_lineno, header_line = header
    columns = [c.strip().lower() for c in csv_cells(header_line, source, header_lineno)]
    value_col = "deviation" if "deviation" in columns else "actual" if "actual" in columns else None
    needed = ["target", "direction", "run"]
    if value_col is None or any(c not in columns for c in needed):
        raise DataFormatError(
            f"header {header_line.strip()!r} must name the columns target,direction,run,deviation "
            "(or actual instead of deviation)",
            source,
            header_lineno,
        )
    if tu is None:
        raise DataFormatError(
            "no target unit: give --target-unit (mm or deg) or a leading comment "
            "'# target_unit=mm deviation_unit=um'",
            source,
        )
    tu = units.canonical(tu)
    if value_col == "deviation" and du is None:
        raise DataFormatError(
            "no deviation unit: give --deviation-unit (um, mm or arcsec) or a leading comment "
            "'# target_unit=mm deviation_unit=um'",
            source,
        )
    du = units.canonical(du) if du is not None else ("um" if units.dimension(tu) == "length" else "arcsec")
    kind = AxisKind.parse(kind_text) if kind_text else (
        AxisKind.LINEAR if units.dimension(tu) == "length" else AxisKind.ROTARY
    )
    to_dev = units.convert(1.0, tu, du) if value_col == "actual" else None
    return columns, value_col, to_dev, kind, tu, du


#: Direction spellings taken without stripping or case folding (1 for ↑, 0 for ↓); any other goes
#: through Direction.parse.
_FAST_DIRECTION = {spelled: int(d is Direction.UP) for word, d in _DIRECTION_WORDS.items()
                   for spelled in (word, word.upper(), word.capitalize())}


class _Readings:
    """The readings of a positioning CSV, kept in compact arrays as they are read.

    A line of plain cells is converted directly; anything else (quotes, a bad number, a missing
    reading, a bad direction) goes through the checked path, which gives the one-line message
    naming the line, so both paths accept and refuse exactly the same lines.
    """

    def __init__(self, columns: list[str], value_col: str, to_dev: float | None, source: str):
        self.ncols = len(columns)
        self.it, self.idi, self.ir, self.iv = (columns.index(c) for c in
                                               ("target", "direction", "run", value_col))
        self.value_col = value_col
        self.to_dev = to_dev
        self.source = source
        self.where: dict[float, int] = {}   # target -> its number in order of first reading
        self.index = array("i")              # the target number of each reading
        self.values = array("d")
        self.up = bytearray()
        self.runs = array("i")
        self.count = 0          # reading lines, a missing reading included
        self.max_run = 0
        self.max_run_at: tuple[int, str] = (0, "")

    def add(self, lineno: int, line: str) -> None:
        self.count += 1
        parts = line.split(",")
        reading = None
        if len(parts) == self.ncols and '"' not in line and line.isascii() and "_" not in line:
            try:   # the common line: plain cells, converted directly
                t = float(parts[self.it])
                v = float(parts[self.iv])
                r = int(parts[self.ir])
                d = _FAST_DIRECTION[parts[self.idi]]
            except (ValueError, KeyError):
                pass
            else:
                if -MAX_MAGNITUDE <= t <= MAX_MAGNITUDE and -MAX_MAGNITUDE <= v <= MAX_MAGNITUDE \
                        and r >= 1:
                    reading = (t, d, r, v, parts[self.ir])
        if reading is None:
            reading = self._checked(lineno, line)
            if reading is None:
                return   # a missing reading: counted by the dataset as NaN
        t, d, r, v, run_text = reading
        if r > self.max_run:
            self.max_run, self.max_run_at = r, (lineno, run_text)
        if r > 2147483647:   # beyond any file's readings: refused at the end (max_run keeps it)
            r = 2147483647
        i = self.where.get(t)
        if i is None:
            i = self.where[t] = len(self.where)
        self.index.append(i)
        self.values.append((v - t) * self.to_dev if self.to_dev is not None else v)
        self.up.append(d)
        self.runs.append(r)

    def _checked(self, lineno: int, line: str):
        """``(target, up, run, value, run as written)`` of a line the direct conversion did not
        take, or ``None`` for a missing reading; a bad cell raises the one-line error."""
        source = self.source
        row = csv_cells(line, source, lineno)
        if len(row) < self.ncols:
            raise DataFormatError(f"{len(row)} fields where the header has {self.ncols}",
                                  source, lineno)
        target = finite_number(row[self.it], "target", source, lineno)
        try:
            up = Direction.parse(row[self.idi]) is Direction.UP
        except InputError as exc:
            raise DataFormatError(str(exc), source, lineno) from None
        run_text = row[self.ir]
        run_value = finite_number(run_text, "run", source, lineno, limit=math.inf)
        if run_value != int(run_value) or run_value < 1:
            check_run_number(run_value, self.count, source, lineno, run_text)
        raw = row[self.iv].strip()
        if raw == "" or raw.lower() in {"nan", "na", "missing"}:
            if int(run_value) > self.max_run:
                self.max_run, self.max_run_at = int(run_value), (lineno, run_text)
            return None
        value = finite_number(raw, self.value_col, source, lineno)
        return target, int(up), int(run_value), value, run_text

    def dataset(self, kind, tu, du, meta) -> PositioningDataset:
        import numpy as np

        source = self.source
        if self.max_run > self.count:   # a run numbered beyond the readings (checked at the end)
            lineno, text = self.max_run_at
            check_run_number(self.max_run, self.count, source, lineno, text)
        if not self.index:
            raise DataFormatError("the header is there but no readings follow", source)
        first_seen = np.fromiter(self.where, dtype=float, count=len(self.where))
        order = np.argsort(first_seen, kind="stable")
        targets = first_seen[order]
        rank = np.empty(order.size, dtype=np.int32)
        rank[order] = np.arange(order.size, dtype=np.int32)
        index = rank[np.frombuffer(self.index, dtype=np.int32)]
        v = np.frombuffer(self.values, dtype=float)
        up = np.frombuffer(self.up, dtype=np.bool_)
        runs = np.frombuffer(self.runs, dtype=np.int32)
        m = targets.size
        n_readings = v.size
        tables = []
        for mask, direction in ((up, Direction.UP), (~up, Direction.DOWN)):
            n = int(runs[mask].max()) if mask.any() else 0
            if m * n > _SPARSE_FACTOR * n_readings + _SPARSE_ALLOWANCE:
                raise DataFormatError(
                    f"{int(mask.sum())} readings ({direction.value}) spread over {m} targets x "
                    f"{n} runs would leave the table almost all missing; check the target and "
                    "run columns", source)
            table = np.full((m, n), np.nan)
            if n:
                cell = index[mask].astype(np.int64) * n + (runs[mask] - 1)
                counts = np.bincount(cell, minlength=m * n)
                if counts.max() > 1:
                    twice = int(np.argmax(counts > 1))
                    raise DataFormatError(
                        f"two readings for target {targets[twice // n]:g}, direction "
                        f"{direction.value}, run {twice % n + 1}", source)
                table.reshape(-1)[cell] = v[mask]
            tables.append(table)
        try:
            return PositioningDataset.from_arrays(kind, targets, tables[0], tables[1], tu, du,
                                                  meta)
        except DataFormatError:
            raise
        except AxiscalError as exc:
            raise DataFormatError(str(exc), source) from None


def format_positioning_csv(ds: PositioningDataset) -> str:
    """Write a dataset as tidy CSV with a units comment (missing readings are left out)."""
    import shlex   # the writer's only (start-up of the readers)

    buf = io.StringIO()
    meta = {k: getattr(ds.metadata, k) for k in sorted(_META_KEYS) if getattr(ds.metadata, k)}
    head = f"target_unit={ds.target_unit} deviation_unit={ds.deviation_unit} axis_kind={ds.axis_kind.value}"
    for k, v in meta.items():
        head += f" {k}={shlex.quote(v)}"
    buf.write(f"# {head}\n")
    buf.write("target,direction,run,deviation\n")
    for t, d, run, dev in ds.iter_records():
        buf.write(f"{t:.12g},{d},{run},{dev:.12g}\n")
    return buf.getvalue()


def _parse_comment(text: str, source: str, lineno: int) -> dict[str, str]:
    from axiscal._parse import comment_tokens

    out = {}
    for tok in comment_tokens(text, source, lineno):
        if "=" in tok:
            k, v = tok.split("=", 1)
            k = k.strip().lower()
            if k in _META_KEYS or k in {"target_unit", "deviation_unit", "axis_kind"}:
                out[k] = v.strip()
    return out


