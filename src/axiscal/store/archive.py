"""Export and import of the history as a portable archive.

The archive is a ZIP file holding ``history.jsonl`` (one JSON object a line: first the header,
``{"format": "axiscal.history/3", "tests": N, "audit": A, "certificates": C, "laboratory": L,
"drift_checks": D}``, then one record a test: the machine, the axis, the test's fields, why it
was withdrawn ("" if it counts), its parameters and compensation tables, the drift check its
record was made with, and the name of its raw file), ``raw/<sha256>-<filename>``, the files as
they came, and the records kept beside them (ISO/IEC 17025:2017 §7.5, §8.4): ``audit.jsonl``
(the audit trail of the corrections), ``certificates.jsonl`` and ``certificates/<sha256>`` (the
certificate register and its issued documents), :mod:`axiscal.store.archive_records`;
``laboratory.jsonl`` (the laboratory kept in the history) and ``drift_checks.jsonl`` with
``drift_checks/<sha256>`` (the drift checks kept beside their tests, files as uploaded),
:mod:`axiscal.store.archive_laboratory`. An archive of ``axiscal.history/2`` (before the
laboratory and the drift checks) or ``/1`` (before the audit trail and the register) imports
as before, without what it does not carry; one of a newer format (``/4`` …) is refused in one
line naming the update it needs.

Export writes a temporary file beside the archive and renames it into place, so a full disk or
an error leaves no partial archive; the archive gets the mode a plain write gives (0666 less the
umask, 0644 usually), not the temporary file's 0600.

Import is all or nothing. The archive is distrusted and checked whole before the first row:

* its ZIP directory: at most :data:`MAX_ENTRIES` entries, none declared larger than
  :data:`MAX_ENTRY_BYTES`, all together at most :data:`MAX_TOTAL_BYTES`, none over 1 MiB
  expanding more than :data:`MAX_RATIO` times its compressed size, no encrypted entry, and the
  compressed sizes adding up to no more than the file (entries that overlap, how a zip bomb
  makes gigabytes of a few megabytes, add up to more);
* every entry read through a bounded reader that stops at its declared size, whatever the
  header says (:func:`_read_entry`);
* ``history.jsonl``: UTF-8, its header with the format and the count of records, every record a
  JSON object with every field present and of its type, every table ``[controller, filename,
  text]``, every raw file present and matching its SHA-256;
* every raw file not stored before evaluated again (one that no longer evaluates refuses the
  archive);
* ``audit.jsonl``, ``certificates.jsonl``, ``laboratory.jsonl`` and ``drift_checks.jsonl``:
  the counts the header announces, every entry of its fields and types, every test it names in
  the archive, every document and drift-check file present and matching its SHA-256, every
  drift check giving the E_VE it states.

Then every test is stored in one transaction (:meth:`~axiscal.store.history.Store.add_all`),
with the withdrawals, the audit trail, the certificates, the laboratory and the drift checks in
the same transaction: a damaged archive, an error, a certificate number the register gave
another document, another laboratory kept in the history (the rules for the laboratory and the
drift checks: :mod:`axiscal.store.archive_laboratory`), or a killed process leaves the
database exactly as it was; files already stored (same SHA-256), audit entries, certificates
and drift checks already kept are counted, not stored again, so an import can be run again.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import zipfile
from pathlib import Path

from axiscal.errors import AxiscalError, DataFormatError, InputError, one_line

__all__ = ["FORMAT", "export_history", "import_history", "Imported", "KEPT", "MAX_ENTRIES", "MAX_ENTRY_BYTES",
           "MAX_TOTAL_BYTES", "MAX_RATIO"]

FORMAT = "axiscal.history/3"
#: The formats an import reads (/1: before the audit trail and the register were carried; /2:
#: before the laboratory and the drift checks were).
FORMATS = ("axiscal.history/1", "axiscal.history/2", FORMAT)
_FORMAT = re.compile(r"axiscal\.history/([0-9]{1,9})")
#: At most this many entries in an archive's ZIP directory.
MAX_ENTRIES = 200_000
#: No entry larger than a file axiscal reads (``axiscal.io._files.MAX_TEXT_BYTES``, 256 MiB).
MAX_ENTRY_BYTES = 256 * 2**20
#: All entries together, uncompressed.
MAX_TOTAL_BYTES = 2**30
#: An entry over 1 MiB may expand at most this many times its compressed size (measurement
#: files deflate 2-10 times; a zip bomb's entries about 1000 times).
MAX_RATIO = 100
_RATIO_FROM = 2**20
_SHA256 = re.compile(r"[0-9a-f]{64}")
#: The fields of a record: type and default (None: required).
_FIELDS = {"machine": (str, None), "axis": (str, None), "kind": (str, None),
           "tested_at": (str, None), "filename": (str, None), "sha256": (str, None),
           "raw": (str, None), "date_known": (bool, True), "instrument": (str, ""),
           "operator": (str, ""), "note": (str, ""), "parameters": (dict, {}),
           "tables": (list, []), "withdrawn": (str, ""), "uncertainty_inputs": (dict, {}),
           "quantities": (dict, {}), "schema_version": (int, 0), "drift_check": (dict, {})}


def export_history(store, path, machine: str | None = None) -> int:
    """Write the history (or one machine's) to the ZIP archive ``path``, with its audit trail and
    certificates (:mod:`axiscal.store.archive_records`); returns the count of tests."""
    import tempfile

    from axiscal.io._files import _mode_for

    p = Path(path)
    tests = store.tests(machine=machine)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", dir=p.parent or ".")
    except OSError as exc:
        raise InputError(f"cannot write {p}: {exc.strerror or exc}") from None
    os.close(fd)
    try:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            _write(z, store, tests, machine)
        os.chmod(tmp, _mode_for(p))
        os.replace(tmp, p)
    except BaseException as exc:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(exc, OSError):                     # a full disk, a file-size limit ...
            raise InputError(f"cannot write {p}: {exc.strerror or exc}; no archive was "
                             "left") from None
        raise
    return len(tests)


def _write(z: zipfile.ZipFile, store, tests, machine) -> None:
    """The tests' records and raw files, then the audit trail and the certificates."""
    from axiscal.store.archive_laboratory import DRIFT_CHECKS, LABORATORY, export_laboratory
    from axiscal.store.archive_records import AUDIT, CERTIFICATES, export_records

    lines, shas = [], {}
    for summary in reversed(tests):                       # oldest first
        t = store.get(summary.id)
        shas[summary.id] = t.sha256
        raw_name = f"raw/{t.sha256}-{Path(summary.filename).name}"
        z.writestr(raw_name, t.raw)
        lines.append(json.dumps({
            "machine": summary.machine, "axis": summary.axis, "kind": summary.kind,
            "tested_at": summary.tested_at.isoformat(), "date_known": summary.date_known,
            "filename": summary.filename, "sha256": t.sha256, "raw": raw_name,
            "instrument": t.instrument, "operator": t.operator, "note": summary.note,
            "withdrawn": summary.withdrawn,
            "parameters": {k: list(v) for k, v in summary.parameters.items()},
            # the record's U: its inputs (import makes the same budget) and its quantities
            "uncertainty_inputs": t.result.get("uncertainty_inputs", {}),
            "schema_version": t.result.get("schema_version", 0),
            "quantities": t.result.get("quantities", {}),
            # the drift check the record was made with (its readings, where no file was kept)
            "drift_check": t.result.get("drift_check") or {},
            "tables": [list(x) for x in t.tables]}))
    audit, certs = export_records(store, shas, machine)
    lab, checks = export_laboratory(store, shas)
    head = {"format": FORMAT, "tests": len(tests), "audit": len(audit),
            "certificates": len(certs), "laboratory": len(lab), "drift_checks": len(checks)}
    z.writestr("history.jsonl", "\n".join([json.dumps(head)] + lines) + "\n")
    z.writestr(AUDIT, "".join(json.dumps(e, ensure_ascii=False) + "\n" for e in audit))
    written = set()
    for entry, doc in certs:
        if entry["document"] not in written:
            z.writestr(entry["document"], doc)
            written.add(entry["document"])
    z.writestr(CERTIFICATES, "".join(json.dumps(e, ensure_ascii=False) + "\n"
                                     for e, _ in certs))
    z.writestr(LABORATORY, "".join(json.dumps(e, ensure_ascii=False) + "\n" for e in lab))
    for entry, raw in checks:
        if entry["file"] not in written:
            z.writestr(entry["file"], raw)
            written.add(entry["file"])
    z.writestr(DRIFT_CHECKS, "".join(json.dumps(e, ensure_ascii=False) + "\n"
                                     for e, _ in checks))


class Imported(tuple):
    """What an import brought: ``(added, already stored)`` tests, as a pair, with the records
    kept beside them that came in (each not kept before): ``audit`` entries, ``laboratory``
    (1 when the archive's laboratory was taken), ``drift_checks`` (drift-check files),
    ``certificates`` (register entries) and ``documents`` (their issued documents, distinct).
    ``str()`` says it all in one line (``history import``, the workbench's upload)."""

    def __new__(cls, added: int, duplicates: int, **kept: int):
        self = super().__new__(cls, (added, duplicates))
        self.kept = {k: int(kept.get(k, 0)) for k in KEPT}
        return self

    added = property(lambda self: self[0])
    duplicates = property(lambda self: self[1])

    def to_dict(self) -> dict:
        """``added``, ``duplicates`` and each of :data:`KEPT` (``history import --json``)."""
        return {"added": self[0], "duplicates": self[1], **self.kept}

    def text(self, source) -> str:
        """``imported N tests from SOURCE (M already stored); A audit entries, ...``"""
        words = {"audit": "audit entries", "laboratory": "laboratory record",
                 "drift_checks": "drift-check files", "certificates": "certificates",
                 "documents": "issued documents"}
        return (f"imported {self[0]} tests from {source} ({self[1]} already stored); "
                + ", ".join(f"{self.kept[k]} {w}" for k, w in words.items()))


#: The records kept beside the tests an import counts (:class:`Imported`).
KEPT = ("audit", "laboratory", "drift_checks", "certificates", "documents")


def import_history(store, path, progress=None) -> Imported:
    """Store every test of the archive ``path`` with its audit trail, certificates, laboratory
    and drift checks, all or nothing; returns (added, already stored) with the counts of the
    records that came in beside them (:class:`Imported`).

    ``progress(done, total)`` is called as the records are checked and evaluated.
    """
    from axiscal.store import archive_laboratory
    from axiscal.store.archive_records import restore

    p = Path(path)
    try:
        z = zipfile.ZipFile(p)
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        raise DataFormatError(f"not an axiscal history archive ({one_line(str(exc))})",
                              str(p)) from None
    with z:
        _check_directory(z, p)
        head, records = _records(_jsonl_text(z, p, "history.jsonl"), p)
        names = set(z.namelist())
        for n, rec in records:
            if rec["raw"] not in names:
                raise DataFormatError(f"history.jsonl line {n} ({rec['filename']}): its raw file "
                                      f"{rec['raw']} is missing from the archive; nothing was "
                                      "imported", str(p))
        kept = _kept_records(z, p, head, {rec["sha256"]: rec["kind"] for _, rec in records})
        audit, certs, lab, checks = kept
        known = store.stored([rec["sha256"] for _, rec in records])
        items = []
        for k, (n, rec) in enumerate(records, start=1):
            if rec["sha256"] not in known:
                items.append(_prepared(z, p, n, rec, checks))
            if progress:
                progress(k, len(records))
    by_sha = {rec["sha256"]: rec for _, rec in records}
    new = {i.sha256 for i in items}

    kept: dict = {}

    def then(s, _results):          # run again with the transaction if it is retried
        kept["laboratory"], kept["drift_checks"] = archive_laboratory.restore(s, lab, checks,
                                                                              new, p)
        kept["audit"], kept["certificates"], kept["documents"] = restore(s, by_sha, new, audit,
                                                                         certs, p)

    results = (store.add_all(items, then=then) if items or audit or certs or lab or checks
               else [])
    added = sum(not r.duplicate for r in results)
    return Imported(added, len(records) - added, **kept)


#: The records kept beside the tests: (entry, key of its count in the header), by format.
def _kept_names() -> dict[str, tuple[tuple[str, str], ...]]:
    from axiscal.store.archive_laboratory import DRIFT_CHECKS, LABORATORY
    from axiscal.store.archive_records import AUDIT, CERTIFICATES

    two = ((AUDIT, "audit"), (CERTIFICATES, "certificates"))
    return {FORMATS[0]: (), FORMATS[1]: two,
            FORMAT: two + ((LABORATORY, "laboratory"), (DRIFT_CHECKS, "drift_checks"))}


def _kept_records(z: zipfile.ZipFile, p: Path, head: dict, tests: dict[str, str]
                  ) -> tuple[list, list, dict | None, list]:
    """The audit entries, certificates, laboratory and drift checks an archive carries (by its
    format: none in /1, no laboratory and drift checks in /2), each checked whole; ``tests``:
    the kind of each test of the archive by its SHA-256."""
    from axiscal.store.archive_laboratory import check_drift_checks, check_laboratory
    from axiscal.store.archive_records import check_audit, check_certificates

    parts = []
    for name, key in _kept_names()[head["format"]]:
        if name not in z.namelist():
            raise DataFormatError(f"no {name} inside: the archive is truncated or altered",
                                  str(p))
        lines = [(n, _json_object(line, n, p, "an entry", name)) for n, line in
                 enumerate(_jsonl_text(z, p, name).splitlines(), start=1) if line.strip()]
        if head.get(key) != len(lines):
            raise DataFormatError(f"history.jsonl announces {repr(head.get(key))[:40]} {key} "
                                  "entries and "
                                  f"{name} holds {len(lines)}: the archive is truncated or "
                                  "altered", str(p))
        parts.append(lines)
    parts += [[]] * (4 - len(parts))

    def read(n):
        return _read_entry(z, p, n)

    return (check_audit(parts[0], set(tests), p),
            check_certificates(parts[1], set(tests), read, p),
            check_laboratory(parts[2], p), check_drift_checks(parts[3], tests, read, p))


# -- checking ----------------------------------------------------------------------------------
def _check_directory(z: zipfile.ZipFile, p: Path) -> None:
    """Refuse, from the ZIP directory alone, an archive that would expand beyond the bounds."""
    infos = z.infolist()
    if len(infos) > MAX_ENTRIES:
        raise DataFormatError(f"{len(infos)} entries; an archive holds at most {MAX_ENTRIES}",
                              str(p))
    total = packed = 0
    for i in infos:
        if i.flag_bits & 0x1:
            raise DataFormatError(f"entry {i.filename[:80]!r} is encrypted", str(p))
        if i.file_size > MAX_ENTRY_BYTES:
            raise DataFormatError(f"entry {i.filename[:80]!r} expands to {i.file_size} bytes; "
                                  f"at most {MAX_ENTRY_BYTES // 2**20} MiB each", str(p))
        if i.file_size > _RATIO_FROM and i.file_size > MAX_RATIO * max(i.compress_size, 1):
            raise DataFormatError(f"entry {i.filename[:80]!r} expands {i.file_size} bytes from "
                                  f"{i.compress_size}, more than {MAX_RATIO} times: refused "
                                  "as a zip bomb", str(p))
        total += i.file_size
        packed += i.compress_size
    if total > MAX_TOTAL_BYTES:
        raise DataFormatError(f"the entries expand to {total} bytes; an archive holds at most "
                              f"{MAX_TOTAL_BYTES // 2**20} MiB", str(p))
    if packed > p.stat().st_size:
        raise DataFormatError(f"the entries' compressed sizes add up to {packed} bytes, more "
                              f"than the file's {p.stat().st_size}: entries overlap (a zip "
                              "bomb's trick); refused", str(p))


def _read_entry(z: zipfile.ZipFile, p: Path, name: str) -> bytes:
    """An entry's bytes, read in pieces and stopped past its declared size (and the bound)."""
    info = z.getinfo(name)
    limit = min(info.file_size, MAX_ENTRY_BYTES)
    parts, size = [], 0
    try:
        with z.open(info) as f:
            while chunk := f.read(2**20):
                size += len(chunk)
                if size > limit:
                    raise DataFormatError(f"entry {name[:80]!r} expands beyond its declared "
                                          f"{info.file_size} bytes; refused", str(p))
                parts.append(chunk)
    except (zipfile.BadZipFile, OSError, EOFError, ValueError, NotImplementedError) as exc:
        if isinstance(exc, AxiscalError):
            raise
        raise DataFormatError(f"entry {name[:80]!r} is damaged ({one_line(str(exc))})",
                              str(p)) from None
    except Exception as exc:                     # zlib.error and the like: damaged data
        raise DataFormatError(f"entry {name[:80]!r} is damaged ({type(exc).__name__}: "
                              f"{one_line(str(exc))[:120]})", str(p)) from None
    return b"".join(parts)


def _jsonl_text(z: zipfile.ZipFile, p: Path, name: str) -> str:
    try:
        data = _read_entry(z, p, name)
    except KeyError:
        raise DataFormatError(f"no {name} inside: not an axiscal history archive",
                              str(p)) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise DataFormatError(f"{name} is not UTF-8 text (byte {exc.start} is "
                              f"0x{data[exc.start]:02X})", str(p)) from None


def _records(text: str, p: Path) -> tuple[dict, list[tuple[int, dict]]]:
    """The header and (line number, record) of every record, each checked; the header first."""
    lines = [(n, line) for n, line in enumerate(text.splitlines(), start=1) if line.strip()]
    if not lines:
        raise DataFormatError("history.jsonl is empty: not an axiscal history archive", str(p))
    head = _json_object(lines[0][1], lines[0][0], p, "the archive's header")
    found = _FORMAT.fullmatch(str(head.get("format")))
    if found and int(found.group(1)) > int(FORMAT.rsplit("/", 1)[1]):
        raise DataFormatError(f"format {head['format']} was written by a newer axiscal than "
                              f"this one, which reads {FORMATS[0]} … {FORMAT}; update axiscal "
                              "to import it; nothing was imported", str(p))
    if head.get("format") not in FORMATS:
        raise DataFormatError(f"history.jsonl line {lines[0][0]}: format "
                              f"{str(head.get('format'))[:60]!r}; expected "
                              f"{' or '.join(FORMATS)}", str(p))
    out = [(n, _record(_json_object(line, n, p, "a test record"), n, p)) for n, line in lines[1:]]
    count = head.get("tests")
    if "tests" in head and (isinstance(count, bool) or not isinstance(count, int)):
        raise DataFormatError(f"history.jsonl line {lines[0][0]}: 'tests' is a JSON "
                              f"{type(count).__name__}, not a whole number; the count of "
                              "tests checks that the archive is whole", str(p))
    if isinstance(count, int) and count != len(out):
        raise DataFormatError(f"history.jsonl announces {count} tests and holds {len(out)}: "
                              "the archive is truncated or altered", str(p))
    return head, out


def _json_object(line: str, n: int, p: Path, what: str, name: str = "history.jsonl") -> dict:
    try:
        value = json.loads(line)
    except RecursionError:
        raise DataFormatError(f"{name} line {n}: JSON nested too deeply to be {what}",
                              str(p)) from None
    except ValueError as exc:
        raise DataFormatError(f"{name} line {n} is not JSON ({one_line(str(exc))[:80]})",
                              str(p)) from None
    if not isinstance(value, dict):
        raise DataFormatError(f"{name} line {n}: a JSON {type(value).__name__}, not "
                              f"{what} (a JSON object)", str(p))
    return value


def _record(rec: dict, n: int, p: Path) -> dict:
    """The record with every field present and of its type (defaults filled in)."""
    out = {}
    for key, (typ, default) in _FIELDS.items():
        if key not in rec and default is None:
            raise DataFormatError(f"history.jsonl line {n}: the record has no {key!r}", str(p))
        value = rec.get(key, default)
        if not isinstance(value, typ):
            raise DataFormatError(f"history.jsonl line {n}: {key!r} is a JSON "
                                  f"{type(value).__name__}, not a {typ.__name__}", str(p))
        out[key] = value
    for key in ("machine", "axis", "kind", "filename"):
        if not out[key].strip():
            raise DataFormatError(f"history.jsonl line {n}: {key!r} is empty", str(p))
    if not _SHA256.fullmatch(out["sha256"]):
        raise DataFormatError(f"history.jsonl line {n}: 'sha256' is not 64 hexadecimal digits",
                              str(p))
    for k, table in enumerate(out["tables"]):
        if not (isinstance(table, list) and len(table) == 3
                and all(isinstance(x, str) for x in table)):
            size = len(table) if isinstance(table, list) else type(table).__name__
            raise DataFormatError(f"history.jsonl line {n}: tables[{k}] is {size!r}; a table is "
                                  "[controller, filename, text], three strings", str(p))
    return out


def _prepared(z: zipfile.ZipFile, p: Path, n: int, rec: dict, checks: list):
    """The record's raw file read, checked against its SHA-256 and evaluated again, with the
    newest of its drift checks the archive carries (or, where no file was kept, the one its
    record holds: :func:`axiscal.store.kinds.drift_check_from_readings`) as the record was."""
    from axiscal.store.history import prepare

    raw = _read_entry(z, p, rec["raw"])
    if hashlib.sha256(raw).hexdigest() != rec["sha256"]:
        raise DataFormatError(f"history.jsonl line {n} ({rec['filename'][:80]}): the raw file "
                              "does not match its SHA-256; nothing was imported", str(p))
    files = [(data, e["filename"]) for e, data in checks if e["test"] == rec["sha256"]]
    inputs, drift = rec["uncertainty_inputs"], {}
    if files:
        drift = {"drift_check": files[-1]}
    elif rec["drift_check"]:
        drift = {"kept_drift_check": rec["drift_check"]}
    if drift:           # E_VE is the drift check's again, not given twice
        inputs = {k: v for k, v in inputs.items() if k not in ("e_ve", "e_ve_source")}
    try:
        return prepare(raw, rec["filename"], machine=rec["machine"], axis=rec["axis"],
                       kind=rec["kind"], instrument=rec["instrument"],
                       operator=rec["operator"], note=rec["note"],
                       date=rec["tested_at"] if rec["date_known"] else None,
                       tables=tuple(tuple(x) for x in rec["tables"]),
                       uncertainty=inputs, **drift)
    except AxiscalError as exc:
        raise DataFormatError(f"history.jsonl line {n} ({rec['filename'][:80]}): "
                              f"{one_line(str(exc))}; nothing was imported", str(p)) from None
