"""The laboratory and the drift checks an archive carries (format ``axiscal.history/3``).

A certificate issued from the history is made with the laboratory kept there (its identity,
signatories, instruments, declared E_VE and CMC: ISO/IEC 17025:2017 §7.8.2.1, §6.5; ILAC-P14)
and with the drift check kept beside its positioning test (E_VE measured, ISO 230-2:2014 Annex
A.5): :mod:`axiscal.store.laboratory`. ``axiscal history export`` carries both, so a history
moved to another database by ``history import`` signs off the same way (§7.5.2, §8.4.2):

* ``laboratory.jsonl``: none or one line, ``{"tables": {...}, "updated": ISO time,
  "updated_by": who}``, the tables as the history keeps them (``company``, ``signatory``,
  ``instrument``, ``uncertainty``); its audit trail travels in ``audit.jsonl`` with the rest;
* ``drift_checks.jsonl``: one drift check a line, oldest first (``test``: the SHA-256 of its
  test's file, ``filename``, ``sha256``, ``e_ve``, ``readings``, ``created``, ``by``, ``file``)
  and its file, byte for byte, as ``drift_checks/<sha256>``.

Import checks them whole before the first row (:func:`check_laboratory`,
:func:`check_drift_checks`): fields of their types, texts within the columns and on one line,
numbers finite, a drift check's file present, matching its SHA-256, read again by
:func:`axiscal.store.kinds.drift_check_record` (the one place a drift check becomes E_VE) and
giving the E_VE and the count of readings the archive states, its test in the archive and a
positioning test. Then, in the import's transaction (:func:`restore`), the rules for what the
history imported into holds already:

* **laboratory**: taken when the history keeps none; nothing to do when it keeps the same
  tables; **refused** when it keeps other tables (another laboratory, or this one edited since
  the export): which one signs the certificates is the laboratory's decision, never an
  import's; nothing is imported, and the message names the tables that differ;
* **drift check**: one the history already keeps with its test (same test, same file SHA-256)
  is counted, not kept twice; one for a test this import stores is kept (the test's record is
  made with the newest one's E_VE, :func:`axiscal.store.history.prepare`); one for a test the
  history held before the import is **merged**: kept after the drift checks the history keeps
  of the test, and the test's record made again with its newest drift check's E_VE over the
  inputs it was stored with, as the test's page does
  (:func:`axiscal.store.laboratory.add_drift_check`); the audit entry saying so comes with the
  archive's trail. So a backup refreshed by importing each new export takes the drift checks
  added since.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import math
import re

from axiscal.errors import AxiscalError, DataFormatError

__all__ = ["LABORATORY", "DRIFT_CHECKS", "export_laboratory", "check_laboratory",
           "check_drift_checks", "restore", "drift_check_for"]

LABORATORY, DRIFT_CHECKS = "laboratory.jsonl", "drift_checks.jsonl"
_SHA256 = re.compile(r"[0-9a-f]{64}")
_LAB_FIELDS = {"tables": (dict,), "updated": (str,), "updated_by": (str,)}
_DRIFT_FIELDS = {"test": (str,), "filename": (str,), "sha256": (str,), "e_ve": (float, int),
                 "readings": (int,), "created": (str,), "by": (str,), "file": (str,)}
#: The JSON type of each table the laboratory keeps.
_TABLE_TYPES = {"company": dict, "signatory": list, "instrument": list, "uncertainty": dict}
#: A whole number in the laboratory's tables stays exact as a double (2^53).
_MAX_INT = 2**53
#: The longest text in the laboratory's tables (an address line, a certificate's number).
_MAX_TEXT = 2000
_MAX_DEPTH = 8


# -- export ------------------------------------------------------------------------------------
def export_laboratory(store, shas: dict[int, str]) -> tuple[list[dict], list[tuple[dict, bytes]]]:
    """The laboratory (a list of none or one entry) and the drift checks of the exported tests
    (``shas``: the SHA-256 of each exported test by its id), oldest first, with their files."""
    from sqlalchemy import select

    from axiscal.store.models import DriftCheck, Laboratory

    with store._guard("read"), store._session() as s:
        row = s.get(Laboratory, 1)
        lab = [] if row is None else [{"tables": json.loads(row.tables_json),
                                       "updated": row.updated.isoformat(),
                                       "updated_by": row.updated_by}]
        checks = [({"test": shas[r.test_id], "filename": r.filename, "sha256": r.sha256,
                    "e_ve": r.e_ve, "readings": r.readings, "created": r.created.isoformat(),
                    "by": r.by, "file": f"drift_checks/{r.sha256}"}, r.raw)
                  for r in s.scalars(select(DriftCheck).order_by(DriftCheck.id))
                  if r.test_id in shas]
    return lab, checks


# -- checking (before the first row) -----------------------------------------------------------
def check_laboratory(entries: list[tuple[int, dict]], p) -> dict | None:
    """The archive's laboratory (None if it carries none), every field and table checked."""
    from axiscal.io.user_config import check_instruments
    from axiscal.store.laboratory import LABORATORY_TABLES
    from axiscal.store.models import Laboratory

    if len(entries) > 1:
        raise DataFormatError(f"{LABORATORY} holds {len(entries)} laboratories; a history keeps "
                              "one; nothing was imported", str(p))
    if not entries:
        return None
    n, e = entries[0]
    _fields(e, _LAB_FIELDS, LABORATORY, n, p)
    _when(e["updated"], LABORATORY, n, p)
    where = f"{LABORATORY} line {n}"
    tables = e["tables"]
    unknown = sorted(set(tables) - set(LABORATORY_TABLES))
    if unknown:
        raise DataFormatError(f"{where}: table {', '.join(unknown)[:80]!r} is not one the "
                              f"laboratory keeps ({', '.join(LABORATORY_TABLES)})", str(p))
    for key, value in tables.items():
        if not isinstance(value, _TABLE_TYPES[key]) or isinstance(value, bool):
            raise DataFormatError(f"{where}: {key!r} is a JSON {type(value).__name__}, not a "
                                  f"{_TABLE_TYPES[key].__name__}", str(p))
        if isinstance(value, list) and not all(isinstance(x, dict) for x in value):
            raise DataFormatError(f"{where}: every entry of {key!r} is a table (JSON object)",
                                  str(p))
        _plain(value, where, key, p)
    try:
        _text(e["updated_by"], "updated_by", Laboratory)
        check_instruments(tables, where)
    except AxiscalError as exc:
        raise DataFormatError(f"{where}: {exc}" if where not in str(exc) else str(exc),
                              str(p)) from None
    return e


def check_drift_checks(entries: list[tuple[int, dict]], kinds: dict[str, str], read, p
                       ) -> list[tuple[dict, bytes]]:
    """Every drift check checked, its file read (``read(name)``), matching its SHA-256 and
    giving the E_VE and readings stated; ``kinds``: the kind of each test of the archive by its
    SHA-256."""
    from axiscal.store.kinds import drift_check_record
    from axiscal.store.models import DriftCheck

    out, seen = [], set()
    for n, e in entries:
        _fields(e, _DRIFT_FIELDS, DRIFT_CHECKS, n, p)
        _when(e["created"], DRIFT_CHECKS, n, p)
        where = f"{DRIFT_CHECKS} line {n} (drift check {e['filename'][:80]!r})"
        try:
            _text(e["filename"], "filename", DriftCheck)
            _text(e["by"], "by", DriftCheck)
        except AxiscalError as exc:
            raise DataFormatError(f"{where}: {exc}", str(p)) from None
        if not e["filename"].strip():
            raise DataFormatError(f"{where}: 'filename' is empty", str(p))
        if e["test"] not in kinds:
            raise DataFormatError(f"{where}: its test {e['test'][:64]!r} is not in the archive; "
                                  "nothing was imported", str(p))
        if kinds[e["test"]] != "iso230-2":
            raise DataFormatError(f"{where}: its test is a {kinds[e['test']][:40]} test; a drift "
                                  "check goes with a positioning test (ISO 230-2:2014 Annex "
                                  "A.5); nothing was imported", str(p))
        if (e["test"], e["sha256"]) in seen:
            raise DataFormatError(f"{where}: the same drift check of the same test appears "
                                  "twice", str(p))
        seen.add((e["test"], e["sha256"]))
        if not _SHA256.fullmatch(e["sha256"]) or e["file"] != f"drift_checks/{e['sha256']}":
            raise DataFormatError(f"{where}: 'file' must be drift_checks/<its sha256>", str(p))
        try:
            raw = read(e["file"])
        except KeyError:
            raise DataFormatError(f"{where}: its file {e['file']} is missing from the archive; "
                                  "nothing was imported", str(p)) from None
        if hashlib.sha256(raw).hexdigest() != e["sha256"]:
            raise DataFormatError(f"{where}: the file does not match its SHA-256; nothing was "
                                  "imported", str(p))
        try:
            record = drift_check_record(raw, e["filename"])
        except AxiscalError as exc:
            raise DataFormatError(f"{where}: {exc}; nothing was imported", str(p)) from None
        if (record["e_ve"], record["samples"]) != (e["e_ve"], e["readings"]):
            raise DataFormatError(f"{where}: it states E_VE {e['e_ve']!r:.40} of {e['readings']} "
                                  f"readings; its file gives {record['e_ve']:g} of "
                                  f"{record['samples']}; nothing was imported", str(p))
        out.append((e, raw))
    return out


def drift_check_for(checks: list[tuple[dict, bytes]], test: str, block: dict
                    ) -> tuple[bytes, str] | None:
    """The (bytes, file name) of the drift check of test ``test`` (SHA-256) whose file the
    test's record was made with (``block``: the record's ``drift_check``), if the archive
    carries it."""
    for e, raw in reversed(checks):
        if e["test"] == test and e["sha256"] == block.get("sha256"):
            return raw, e["filename"]
    return None


def _fields(e: dict, fields: dict, name: str, n: int, p) -> None:
    for key, types in fields.items():
        if key not in e:
            raise DataFormatError(f"{name} line {n}: the entry has no {key!r}", str(p))
        v = e[key]
        if isinstance(v, bool) or not isinstance(v, types):
            raise DataFormatError(f"{name} line {n}: {key!r} is a JSON {type(v).__name__}, "
                                  f"not a {types[0].__name__}", str(p))
        if isinstance(v, float) and not math.isfinite(v):
            raise DataFormatError(f"{name} line {n}: {key!r} is {v}, not a finite number",
                                  str(p))
        if isinstance(v, int) and not -_MAX_INT <= v <= _MAX_INT:
            raise DataFormatError(f"{name} line {n}: {key!r} is a number of {len(str(v))} "
                                  "digits; refused", str(p))


def _when(text: str, name: str, n: int, p) -> None:
    """A date and time as the history keeps it: ISO 8601, UTC without an offset."""
    try:
        when = dt.datetime.fromisoformat(text)
    except ValueError:
        raise DataFormatError(f"{name} line {n}: {text[:40]!r} is not a date and time",
                              str(p)) from None
    if when.tzinfo is not None:
        raise DataFormatError(f"{name} line {n}: {text[:40]!r} has an offset; the history "
                              "keeps UTC without one", str(p))


def _text(value: str, field: str, model) -> None:
    from axiscal.store.limits import checked_text

    checked_text(value, field, model, field)


def _plain(value, head: str, path: str, p, depth: int = 0) -> None:
    """Every value of a laboratory table plain JSON the tables can hold: texts of one line (at
    most :data:`_MAX_TEXT` characters), finite numbers, whole numbers exact as a double, at
    most :data:`_MAX_DEPTH` levels; ``path`` names the value (``company.name``)."""
    from axiscal.store.limits import checked_text

    if depth > _MAX_DEPTH:
        raise DataFormatError(f"{head}: {path} is nested more than {_MAX_DEPTH} levels", str(p))
    if isinstance(value, dict):
        for k, v in value.items():
            _plain(k, head, f"{path} (a key)", p, depth + 1)
            _plain(v, head, f"{path}.{k[:40]}", p, depth + 1)
    elif isinstance(value, list):
        for k, v in enumerate(value):
            _plain(v, head, f"{path}[{k}]", p, depth + 1)
    elif isinstance(value, str):
        try:
            checked_text(value, path, limit=_MAX_TEXT)
        except AxiscalError as exc:
            raise DataFormatError(f"{head}: {exc}", str(p)) from None
    elif isinstance(value, float) and not math.isfinite(value):
        raise DataFormatError(f"{head}: {path} is {value}, not a finite number", str(p))
    elif isinstance(value, int) and not isinstance(value, bool) and abs(value) > _MAX_INT:
        raise DataFormatError(f"{head}: {path} is a whole number of {len(str(value))} digits; "
                              "refused", str(p))


# -- restoring (in the import's transaction) ---------------------------------------------------
def restore(s, lab: dict | None, checks: list[tuple[dict, bytes]], new: set[str], p
            ) -> tuple[int, int]:
    """Keep the archive's laboratory and drift checks by the module's rules; returns (1 if the
    laboratory was taken else 0, drift checks added)."""
    return _restore_laboratory(s, lab, p), _restore_drift_checks(s, checks, new, p)


def _restore_laboratory(s, lab: dict | None, p) -> int:
    from axiscal.store.models import Laboratory

    if lab is None:
        return 0
    row = s.get(Laboratory, 1)
    if row is None:
        s.add(Laboratory(id=1, tables_json=json.dumps(lab["tables"]),
                         updated=dt.datetime.fromisoformat(lab["updated"]),
                         updated_by=lab["updated_by"]))
        s.flush()
        return 1
    kept = json.loads(row.tables_json)
    if kept == lab["tables"]:
        return 0
    new = lab["tables"]
    differ = sorted(k for k in set(kept) | set(new) if kept.get(k) != new.get(k))
    code = str((kept.get("company") or {}).get("code", "") or "")[:40]
    raise DataFormatError(f"this history keeps another laboratory{f' ({code})' if code else ''} "
                          f"than the archive's ({', '.join(differ)} differ): which one "
                          "certifies is the laboratory's decision; edit one to match the "
                          "other, or import into an empty history; nothing was imported",
                          str(p))


def _restore_drift_checks(s, checks: list[tuple[dict, bytes]], new: set[str], p) -> int:
    """Add the drift checks not kept; a test held before that gets one has its record made
    again with its newest drift check (:func:`_remade`)."""
    from sqlalchemy import select

    from axiscal.store.models import DriftCheck, Test

    added, before = 0, set()
    for e, raw in checks:
        tid = s.scalar(select(Test.id).where(Test.sha256 == e["test"]))
        if s.scalar(select(DriftCheck.id).where(DriftCheck.test_id == tid,
                                                DriftCheck.sha256 == e["sha256"])) is not None:
            continue
        if e["test"] not in new:
            before.add(tid)
        s.add(DriftCheck(test_id=tid, filename=e["filename"], raw=raw, sha256=e["sha256"],
                         e_ve=float(e["e_ve"]), readings=e["readings"],
                         created=dt.datetime.fromisoformat(e["created"]), by=e["by"]))
        added += 1
    s.flush()
    for tid in sorted(before):
        _remade(s, tid, p)
    s.flush()
    return added


def _remade(s, tid: int, p) -> None:
    """Test ``tid``'s record made again with its newest drift check's E_VE over the inputs it
    was stored with, as :func:`axiscal.store.laboratory.add_drift_check` makes it."""
    from sqlalchemy import select

    from axiscal.store.kinds import drift_check_record, evaluate_file
    from axiscal.store.laboratory import result_with_drift_check
    from axiscal.store.models import DriftCheck, Test

    t = s.get(Test, tid)
    newest = s.scalars(select(DriftCheck).where(DriftCheck.test_id == tid)
                       .order_by(DriftCheck.id.desc()).limit(1)).one()
    inputs = dict(json.loads(t.result_json).get("uncertainty_inputs") or {})
    try:
        t.result_json = result_with_drift_check(
            evaluate_file(t.raw, t.filename, t.kind), inputs,
            drift_check_record(newest.raw, newest.filename))
    except AxiscalError as exc:
        raise DataFormatError(f"drift check {newest.filename[:80]!r} of test {tid} here: {exc}; "
                              "nothing was imported", str(p)) from None
