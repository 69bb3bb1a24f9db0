"""Export and import of the history as a portable archive.

The archive is a ZIP file holding ``history.jsonl`` (one JSON object a line: the machine, the
axis, the test's fields, its parameters and compensation tables, and the name of its raw file)
and ``raw/<sha256>-<filename>``, the files as they came. Import evaluates each raw file again
and stores it in its own transaction, skipping files already stored (SHA-256), so an
interrupted import is simply run again.
"""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

from axiscal.errors import DataFormatError

__all__ = ["FORMAT", "export_history", "import_history"]

FORMAT = "axiscal.history/1"


def export_history(store, path, machine: str | None = None) -> int:
    """Write the history (or one machine's) to the ZIP archive ``path``; returns the count."""
    import os
    import tempfile

    p = Path(path)
    tests = store.tests(machine=machine)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", dir=p.parent or ".")
    os.close(fd)
    try:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            lines = [json.dumps({"format": FORMAT, "tests": len(tests)})]
            for summary in reversed(tests):                       # oldest first
                t = store.get(summary.id)
                raw_name = f"raw/{t.sha256}-{Path(summary.filename).name}"
                z.writestr(raw_name, t.raw)
                lines.append(json.dumps({
                    "machine": summary.machine, "axis": summary.axis, "kind": summary.kind,
                    "tested_at": summary.tested_at.isoformat(), "date_known": summary.date_known,
                    "filename": summary.filename, "sha256": t.sha256, "raw": raw_name,
                    "instrument": t.instrument, "operator": t.operator, "note": summary.note,
                    "parameters": {k: list(v) for k, v in summary.parameters.items()},
                    "tables": [list(x) for x in t.tables]}))
            z.writestr("history.jsonl", "\n".join(lines) + "\n")
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return len(tests)


def import_history(store, path, progress=None) -> tuple[int, int]:
    """Store every test of the archive ``path``; returns (added, already stored)."""
    import hashlib

    p = Path(path)
    try:
        z = zipfile.ZipFile(p)
    except (zipfile.BadZipFile, OSError) as exc:
        raise DataFormatError(f"not an axiscal history archive ({exc})", str(p)) from None
    added = dup = 0
    with z:
        try:
            lines = z.read("history.jsonl").decode("utf-8").splitlines()
        except KeyError:
            raise DataFormatError("no history.jsonl inside: not an axiscal history archive",
                                  str(p)) from None
        head = json.loads(lines[0]) if lines else {}
        if head.get("format") != FORMAT:
            raise DataFormatError(f"format {head.get('format')!r}; expected {FORMAT}", str(p))
        for n, line in enumerate(lines[1:], start=2):
            try:
                rec = json.loads(line)
                raw = z.read(rec["raw"])
            except (ValueError, KeyError) as exc:
                raise DataFormatError(f"entry {n - 1} is damaged ({exc})", str(p), n) from None
            if hashlib.sha256(raw).hexdigest() != rec.get("sha256"):
                raise DataFormatError(f"entry {n - 1} ({rec.get('filename')}): the raw file does "
                                      "not match its SHA-256", str(p), n)
            r = store.add(raw, rec["filename"], machine=rec["machine"], axis=rec["axis"],
                          kind=rec["kind"], instrument=rec.get("instrument", ""),
                          operator=rec.get("operator", ""), note=rec.get("note", ""),
                          date=rec["tested_at"] if rec.get("date_known", True) else None,
                          tables=tuple(tuple(x) for x in rec.get("tables", [])))
            dup += r.duplicate
            added += not r.duplicate
            if progress:
                progress(n - 1, len(lines) - 1)
    return added, dup
