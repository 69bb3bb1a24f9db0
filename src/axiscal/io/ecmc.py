"""ISO 230-2 input files of the EPICS ecmc motion-control framework.

Format (as written by ecmc's ISO 230-2 data-collection scripts)
----------------------------------------------------------------
Plain ``KEY=value`` lines; ``#`` starts a comment. ``REF_PV`` (the reference system's PV) is kept
as the dataset's ``instrument`` and ``TGT_SET_PV`` (the setpoint's) as its ``axis``: the
uncertainty budget takes the reference's kind from the PV's name (``…-Enc01-PosAct``, an
encoder's actual position: :func:`axiscal.standards.iso230_9_inputs.reference_kind`) and shows it
as taken from the file. Other keys (``TEST_PV``, ``DEC`` ...) are ignored::

    UNIT=mm
    CYCLES=5
    POSITIONS=5
    TGT_DATA[1]=15.00000
    REF_DATA_FWD[1,1]=15.00161
    REF_DATA_BWD[1,1]=15.00172

``TGT_DATA[i]`` is the target position i (1-based), ``REF_DATA_FWD[i,j]`` and
``REF_DATA_BWD[i,j]`` the reference system's *actual* position at target i in cycle j in the
forward (positive) and backward (negative) direction. The deviation is actual minus target
(ISO 230-2 §3.1, Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 1), converted to µm for a length ``UNIT`` and to arcseconds for an
angle ``UNIT`` (or to ``deviation_unit`` if given). Declared ``CYCLES``/``POSITIONS`` are checked
against the data: a mismatch is reported, never silently padded.
"""

from __future__ import annotations

import math
import re

from axiscal import units
from axiscal._parse import agreed_unit, check_run_number, finite_number
from axiscal.datasets import AxisKind, Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError
from axiscal.io.detect import looks_like_ecmc

__all__ = ["looks_like_ecmc", "parse_ecmc", "read_ecmc", "format_ecmc"]

_INDEXED = re.compile(r"^(TGT_DATA|REF_DATA_FWD|REF_DATA_BWD)\[\s*(\d+)\s*(?:,\s*(\d+)\s*)?\]$")


def read_ecmc(path, **kwargs) -> PositioningDataset:
    """Read an ecmc ISO 230-2 file; see :func:`parse_ecmc`."""
    from axiscal.io._files import read_text

    return parse_ecmc(read_text(path), source=str(path), **kwargs)


def parse_ecmc(
    text: str,
    target_unit: str | None = None,
    deviation_unit: str | None = None,
    axis_kind: str | None = None,
    source: str = "<text>",
) -> PositioningDataset:
    """Parse an ecmc ISO 230-2 input file into a :class:`PositioningDataset`.

    Examples
    --------
    >>> ds = parse_ecmc('''UNIT=mm
    ... TGT_DATA[1]=10
    ... TGT_DATA[2]=20
    ... REF_DATA_FWD[1,1]=10.001
    ... REF_DATA_FWD[2,1]=20.002
    ... REF_DATA_FWD[1,2]=10.002
    ... REF_DATA_FWD[2,2]=20.001''')
    >>> ds.up.round(6).tolist()
    [[1.0, 2.0], [2.0, 1.0]]
    """
    scalars, targets, ref = _entries(text, source)

    unit_text = agreed_unit(target_unit, scalars.get("UNIT"), "UNIT", source) or "mm"
    tu = units.canonical(unit_text)
    dim = units.dimension(tu)
    du = units.canonical(deviation_unit) if deviation_unit else ("um" if dim == "length" else "arcsec")
    kind = AxisKind.parse(axis_kind) if axis_kind else (
        AxisKind.LINEAR if dim == "length" else AxisKind.ROTARY)
    k = units.convert(1.0, tu, du)

    ids = sorted(targets)
    for d in ref.values():
        for (i, _j) in d:
            if i not in targets:
                raise DataFormatError(f"reference data for position {i}, which has no TGT_DATA[{i}]",
                                      source)
    _check_declared(scalars, "POSITIONS", len(ids), source)
    cycles = max((j for d in ref.values() for (_i, j) in d), default=0)
    _check_declared(scalars, "CYCLES", cycles, source)
    check_run_number(cycles, sum(len(d) for d in ref.values()), source, what="cycle")

    records = []
    for dname, sign in (("FWD", "+"), ("BWD", "-")):
        for (i, j), actual in ref[dname].items():
            records.append((targets[i], sign, j, (actual - targets[i]) * k))
    if len(set(targets.values())) != len(targets):
        raise DataFormatError("two TGT_DATA entries have the same target position", source)
    meta = Metadata(instrument=scalars.get("REF_PV", ""), axis=scalars.get("TGT_SET_PV", ""))
    try:
        return PositioningDataset.from_records(kind, records, tu, du, meta, source=source)
    except DataFormatError:
        raise
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None


def _entries(text: str, source: str) -> tuple[dict, dict, dict]:
    """The file's ``KEY=value`` lines: (scalars by upper-case key, TGT_DATA by position index,
    REF_DATA by direction ``FWD``/``BWD`` and (position, cycle)); a line that is none of them,
    a repeated index or no data at all is a :class:`DataFormatError` naming the line."""
    scalars: dict[str, str] = {}
    targets: dict[int, float] = {}
    ref: dict[str, dict[tuple[int, int], float]] = {"FWD": {}, "BWD": {}}
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if "=" not in line:
            raise DataFormatError(f"expected KEY=value, got {line!r}", source, lineno)
        key, value = (s.strip() for s in line.split("=", 1))
        m = _INDEXED.match(key)
        if not m:
            scalars[key.upper()] = value
            continue
        name, i, j = m.group(1), int(m.group(2)), m.group(3)
        number = finite_number(value, key, source, lineno)
        if name == "TGT_DATA":
            if j is not None:
                raise DataFormatError(f"{key} takes one index", source, lineno)
            if i in targets:
                raise DataFormatError(f"{key} is given twice", source, lineno)
            targets[i] = number
        else:
            if j is None:
                raise DataFormatError(f"{key} needs two indices [position,cycle]", source, lineno)
            d = ref[name[-3:]]
            if (i, int(j)) in d:
                raise DataFormatError(f"{key} is given twice", source, lineno)
            d[(i, int(j))] = number
    if not targets:
        raise DataFormatError("no TGT_DATA[i]= lines", source)
    if not ref["FWD"] and not ref["BWD"]:
        raise DataFormatError("no REF_DATA_FWD[i,j]= or REF_DATA_BWD[i,j]= lines", source)
    return scalars, targets, ref


def format_ecmc(ds: PositioningDataset) -> str:
    """Write a dataset in the ecmc format (actual = target + deviation, in the target unit)."""
    k = units.convert(1.0, ds.deviation_unit, ds.target_unit)
    lines = [f"UNIT={ds.target_unit}", f"CYCLES={ds.n_runs}", f"POSITIONS={ds.n_targets}"]
    for i, t in enumerate(ds.targets, start=1):
        lines.append(f"TGT_DATA[{i}]={t:.12g}")
    for name, arr in (("REF_DATA_FWD", ds.up), ("REF_DATA_BWD", ds.down)):
        for j in range(arr.shape[1]):
            for i, t in enumerate(ds.targets):
                if not math.isnan(arr[i, j]):
                    lines.append(f"{name}[{i + 1},{j + 1}]={t + arr[i, j] * k:.15g}")
    return "\n".join(lines) + "\n"




def _check_declared(scalars: dict[str, str], key: str, found: int, source: str) -> None:
    if key not in scalars:
        return
    try:
        declared = int(scalars[key])
    except ValueError:
        raise DataFormatError(f"{key}={scalars[key]!r} is not a whole number", source) from None
    if declared != found:
        raise DataFormatError(f"{key}={declared} is declared but the data hold {found}", source)
