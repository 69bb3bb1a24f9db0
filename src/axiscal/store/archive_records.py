"""The records an archive carries beside the tests: the audit trail and the certificate register.

ISO/IEC 17025:2017 §7.5.2 and §8.4.2: technical records, their amendments (who, when, what, why)
and the reports issued are kept and retrievable, so a history moved to another database by
``axiscal history export`` / ``import`` (:mod:`axiscal.store.archive`) keeps them too:

* ``audit.jsonl``: one entry of the audit trail a line, oldest first, as
  :mod:`axiscal.store.corrections` wrote it (``at``, ``by``, ``action``, ``what``, ``reason``,
  ``old``, ``new``) with what it names made portable: the test by its file's SHA-256, the
  machine by its name and the axis by (machine, axis) names, beside the ids they had
  (``machine_id``, ``axis_id``, ``test_id``), and the names of the machines or axes a merge's
  ids are (``refs``: ``old``, ``new``; null for one merged away);
* ``certificates.jsonl``: one certificate of the register a line (number, laboratory, series,
  counter, status, the number it replaces and why, customer, issue date, media type, inputs,
  SHA-256, the test's SHA-256) and its document, byte for byte, as ``certificates/<sha256>``;
* each test record's ``withdrawn``: why the test was withdrawn ("" while it counts).

Import restores them in the transaction that stores the tests (all or nothing):

* ids are those of the database imported into: a test's by its SHA-256, a machine's and an
  axis's by name. A machine or axis that no longer exists (merged into another) gets a negative
  id of its own, never one a row can take, the same in every entry that names it (its columns
  and a merge's ``old``/``new`` ids), so the trail of a machine still gathers the machines
  merged into it (:func:`axiscal.store.corrections.audit`). ``what`` is kept as written (it may
  name the ids of the database it was written in);
* an entry already in the trail (same time, person, action, words and reason) is not added
  twice, so an import can be run again;
* certificates keep their numbers, counters, status and amendments; one whose number the
  laboratory has already given to another document refuses the archive; one already in the
  register (same number, same document) is counted, not stored again;
* a test stored by this import and withdrawn in the archive is withdrawn here with its reason;
  a test stored before whose corrections arrive with this import (new audit entries naming it)
  takes its record's corrected metadata (withdrawal, note, operator, instrument, date), so the
  trail and the test agree.

An archive of format ``axiscal.history/1`` (before these records) has none of them and imports
as before.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import re

from axiscal.errors import AxiscalError, DataFormatError

__all__ = ["AUDIT", "CERTIFICATES", "export_records", "check_audit", "check_certificates",
           "validate_certificates", "restore", "MAX_COUNTER", "STATUSES"]

AUDIT, CERTIFICATES = "audit.jsonl", "certificates.jsonl"
_SHA256 = re.compile(r"[0-9a-f]{64}")
_OPT_INT = (int, type(None))
#: Fields of an audit entry: types (None: may be null).
_AUDIT_FIELDS = {"at": (str,), "by": (str,), "action": (str,), "what": (str,),
                 "reason": (str,), "old": (dict,), "new": (dict,), "test": (str, type(None)),
                 "machine": (str, type(None)), "axis": (list, type(None)),
                 "machine_id": _OPT_INT, "axis_id": _OPT_INT, "test_id": _OPT_INT,
                 "refs": (dict,)}
_CERT_FIELDS = {"test": (str,), "laboratory": (str,), "series": (str,), "counter": (int,),
                "number": (str,), "customer": (str,), "issued": (str,), "status": (str,),
                "replaces": (str,), "reason": (str,), "media_type": (str,), "sha256": (str,),
                "document": (str,), "inputs": (dict,), "created": (str,)}


# -- export ------------------------------------------------------------------------------------
def export_records(store, shas: dict[int, str], machine: str | None = None
                   ) -> tuple[list[dict], list[tuple[dict, bytes]]]:
    """The audit entries and certificates (with their documents) of the exported tests.

    ``shas`` maps the id of each exported test to its SHA-256. With ``machine``, the entries of
    that machine (and of the machines merged into it) and of its tests; else the whole trail.
    """
    from sqlalchemy import select

    from axiscal.store.models import Audit, Axis, Certificate, Machine

    with store._guard("read"), store._session() as s:
        machines = dict(s.execute(select(Machine.id, Machine.name)).all())
        axes = {i: (machines.get(m), a) for i, m, a in
                s.execute(select(Axis.id, Axis.machine_id, Axis.name))}
        q = select(Audit).order_by(Audit.id)
        if machine is not None:
            from axiscal.store.corrections import _merged_ids

            mid = next((i for i, n in machines.items() if n == machine), None)
            ids = _merged_ids(s, mid) if mid is not None else []
            q = q.where(Audit.machine_id.in_(ids) | Audit.test_id.in_(list(shas))
                        | (Audit.action == "laboratory"))    # the laboratory goes with it
        audit = [_audit_entry(a, shas, machines, axes) for a in s.scalars(q)]
        certs = [_certificate_entry(c, shas) for c in s.scalars(
            select(Certificate).order_by(Certificate.id)) if c.test_id in shas]
    return audit, certs


def _audit_entry(a, shas, machines, axes) -> dict:
    old, new = json.loads(a.old_json), json.loads(a.new_json)
    return {"at": a.at.isoformat(), "by": a.by, "action": a.action, "what": a.what,
            "reason": a.reason, "old": old, "new": new, "test": shas.get(a.test_id),
            "machine": machines.get(a.machine_id), "axis": _axis_ref(axes, a.axis_id),
            "machine_id": a.machine_id, "axis_id": a.axis_id, "test_id": a.test_id,
            "refs": {k: _merge_ref(a.action, v, machines, axes) for k, v in
                     (("old", old), ("new", new))}}


def _axis_ref(axes, axis_id):
    axis = axes.get(axis_id)
    return list(axis) if axis and axis[0] is not None else None


def _merge_ref(action: str, values: dict, machines, axes):
    """The name of the machine (or [machine, axis]) a merge's old or new id is, if it exists."""
    if action == "merge-machines":
        return machines.get(values.get("id"))
    if action == "merge-axes":
        return _axis_ref(axes, values.get("axis_id"))
    return None


def _certificate_entry(c, shas) -> tuple[dict, bytes]:
    from sqlalchemy.orm import object_session

    from axiscal.store.models import Certificate

    replaces = ""
    if c.replaces_id is not None:
        replaces = object_session(c).get(Certificate, c.replaces_id).number
    return ({"test": shas[c.test_id], "laboratory": c.laboratory, "series": c.series,
             "counter": c.counter, "number": c.number, "customer": c.customer,
             "issued": c.issued, "status": c.status, "replaces": replaces, "reason": c.reason,
             "media_type": c.media_type, "sha256": c.sha256,
             "document": f"certificates/{c.sha256}", "inputs": json.loads(c.inputs_json),
             "created": c.created.isoformat(), "laboratory_name": c.laboratory_name,
             "prepared_by": c.prepared_by, "approved_by": c.approved_by,
             "approved_role": c.approved_role, "changes": json.loads(c.changes_json or "[]"),
             "as_found": shas.get(c.as_found_test_id)}, c.document)


# -- checking (before the first row) -----------------------------------------------------------
def check_audit(entries: list[tuple[int, dict]], tests: set[str], p) -> list[dict]:
    """Every entry with its fields of their types, its time a date, its test in the archive."""
    out = []
    for n, e in entries:
        _fields(e, _AUDIT_FIELDS, AUDIT, n, p)
        _when(e["at"], AUDIT, n, p)
        if e["test"] is not None and e["test"] not in tests:
            raise DataFormatError(f"{AUDIT} line {n}: its test {e['test'][:64]!r} is not in the "
                                  "archive; nothing was imported", str(p))
        if e["axis"] is not None and not (len(e["axis"]) == 2
                                          and all(isinstance(x, str) for x in e["axis"])):
            raise DataFormatError(f"{AUDIT} line {n}: 'axis' is [machine, axis], two strings",
                                  str(p))
        out.append(e)
    return out


def _register_key(e: dict) -> None:
    """An entry of an archive written before the register was keyed by the laboratory's code
    (no ``laboratory_name``): its ``laboratory`` is the name, the code the start of its series
    (``CODE|YEAR``); the optional fields of later archives default to empty."""
    if not isinstance(e.get("laboratory_name"), str):
        e["laboratory_name"] = e["laboratory"]
        e["laboratory"] = e["series"].split("|", 1)[0] or e["laboratory"]
    for key in ("prepared_by", "approved_by", "approved_role"):
        e[key] = e.get(key) if isinstance(e.get(key), str) else ""
    e["changes"] = e.get("changes") if isinstance(e.get("changes"), list) else []
    e["as_found"] = e.get("as_found") if isinstance(e.get("as_found"), str) else None


def check_certificates(entries: list[tuple[int, dict]], tests: set[str], read, p
                       ) -> list[tuple[dict, bytes]]:
    """Every certificate checked, its document read (``read(name)``) and matching its SHA-256."""
    validate_certificates(entries, p)
    out, seen = [], set()
    for n, e in entries:
        _fields(e, _CERT_FIELDS, CERTIFICATES, n, p)
        _when(e["created"], CERTIFICATES, n, p)
        _register_key(e)
        where = f"{CERTIFICATES} line {n} (certificate {e['number'][:80]})"
        if e["test"] not in tests:
            raise DataFormatError(f"{where}: its test is not in the archive; nothing was "
                                  "imported", str(p))
        if (e["laboratory"], e["number"]) in seen:
            raise DataFormatError(f"{where}: the number appears twice", str(p))
        seen.add((e["laboratory"], e["number"]))
        if not _SHA256.fullmatch(e["sha256"]) or e["document"] != f"certificates/{e['sha256']}":
            raise DataFormatError(f"{where}: 'document' must be certificates/<its sha256>",
                                  str(p))
        try:
            doc = read(e["document"])
        except KeyError:
            raise DataFormatError(f"{where}: its document {e['document']} is missing from the "
                                  "archive; nothing was imported", str(p)) from None
        if hashlib.sha256(doc).hexdigest() != e["sha256"]:
            raise DataFormatError(f"{where}: the document does not match its SHA-256; nothing "
                                  "was imported", str(p))
        out.append((e, doc))
    return out


#: Largest certificate counter the register takes: a laboratory issuing a certificate a second
#: for thirty years stays below it, and the next counter (+1) fits a 64-bit integer column on
#: SQLite and PostgreSQL with room to spare (an imported 2^63 - 1 made every later issue fail,
#: 2^70 ended in a traceback: issue 39).
MAX_COUNTER = 10**9
#: The statuses a certificate of the register has (:mod:`axiscal.store.register`).
STATUSES = ("issued", "superseded")


def validate_certificates(entries: list[tuple[int, dict]], p, register=()) -> None:
    """The register's invariants over an archive's certificates, before anything is stored.

    Each entry's fields of their types (:data:`_CERT_FIELDS`) and within the register's
    columns, and:

    * its ``counter`` a whole number 1 … :data:`MAX_COUNTER`;
    * its ``number`` holding its counter as a run of digits (the laboratory's pattern makes the
      number from the counter, ``{lab}-{year}-{counter:05d}``: a number that does not hold its
      counter would make the register refuse every later number of its series), unique within
      its laboratory, and text of one line;
    * its ``status`` one of :data:`STATUSES`; ``superseded`` only for a certificate another one
      of the archive (or ``register``) replaces;
    * its ``replaces`` "" or the number of a certificate of the same laboratory in the archive
      or in ``register`` ((laboratory, number) pairs), with a ``reason``.

    Raises
    ------
    DataFormatError
        Naming the line, the certificate and the field; nothing is imported.
    """
    from axiscal.store.limits import checked_text
    from axiscal.store.models import Certificate

    known = {(lab, num) for lab, num in register}
    replaced = set()
    for n, e in entries:
        _fields(e, _CERT_FIELDS, CERTIFICATES, n, p)
        known.add((e["laboratory"], e["number"]))
        if e["replaces"]:
            replaced.add((e["laboratory"], e["replaces"]))
    for n, e in entries:
        where = f"{CERTIFICATES} line {n} (certificate {str(e['number'])[:80]!r})"
        try:
            for key in ("laboratory", "series", "number", "customer", "issued", "status",
                        "media_type"):
                checked_text(e[key], key, Certificate, key)
            checked_text(e["reason"], "reason", single_line=False)
        except AxiscalError as exc:
            raise DataFormatError(f"{where}: {exc}", str(p)) from None
        counter = e["counter"]
        if not 1 <= counter <= MAX_COUNTER:
            raise DataFormatError(f"{where}: counter {counter} is outside 1 … {MAX_COUNTER:,}; "
                                  "nothing was imported", str(p))
        if counter not in {int(d) for d in re.findall(r"[0-9]+", e["number"])}:
            raise DataFormatError(f"{where}: the number does not hold its counter {counter}; "
                                  "the register makes every number from its counter; nothing "
                                  "was imported", str(p))
        if e["status"] not in STATUSES:
            raise DataFormatError(f"{where}: status {e['status'][:40]!r} is not one of "
                                  f"{', '.join(STATUSES)}; nothing was imported", str(p))
        if e["status"] == "superseded" and (e["laboratory"], e["number"]) not in replaced:
            raise DataFormatError(f"{where}: superseded, but no certificate of the archive "
                                  "replaces it; nothing was imported", str(p))
        if e["replaces"]:
            if (e["laboratory"], e["replaces"]) not in known or e["replaces"] == e["number"]:
                raise DataFormatError(f"{where}: it replaces {e['replaces'][:80]!r}, which is "
                                      "no other certificate of its laboratory in the archive; "
                                      "nothing was imported", str(p))
            if not e["reason"].strip():
                raise DataFormatError(f"{where}: it replaces {e['replaces'][:80]!r} without a "
                                      "reason (ISO/IEC 17025:2017 §7.8.8.2)", str(p))


def _fields(e: dict, fields: dict, name: str, n: int, p) -> None:
    for key, types in fields.items():
        if key not in e:
            raise DataFormatError(f"{name} line {n}: the entry has no {key!r}", str(p))
        v = e[key]
        if isinstance(v, bool) or not isinstance(v, types):
            raise DataFormatError(f"{name} line {n}: {key!r} is a JSON {type(v).__name__}, "
                                  f"not a {types[0].__name__}", str(p))


def _when(text: str, name: str, n: int, p) -> dt.datetime:
    try:
        return dt.datetime.fromisoformat(text)
    except ValueError:
        raise DataFormatError(f"{name} line {n}: {text[:40]!r} is not a date and time",
                              str(p)) from None


# -- restoring (in the import's transaction) ---------------------------------------------------
def restore(s, records: dict[str, dict], new: set[str], audit: list[dict],
            certificates: list[tuple[dict, bytes]], p) -> tuple[int, int, int]:
    """Withdraw the new tests withdrawn in the archive, add the audit entries and the
    certificates not already kept; returns (audit entries added, certificates added, their
    issued documents: distinct by SHA-256).

    ``records`` are the archive's test records by SHA-256. A test stored before whose
    corrections (edits, withdrawal) come with this import's new audit entries takes the
    corrected metadata of its record, so the trail and the test agree.
    """
    from sqlalchemy import select

    from axiscal.store.models import Test

    for sha in sorted(new):
        if records[sha]["withdrawn"]:
            s.scalars(select(Test).where(Test.sha256 == sha)).one().withdrawn = \
                records[sha]["withdrawn"]
    s.flush()
    added, touched = _restore_audit(s, audit)
    for sha in sorted(touched - new):
        _corrected(s.scalars(select(Test).where(Test.sha256 == sha)).one(), records[sha])
    s.flush()
    return (added, *_restore_certificates(s, certificates, p))


def _corrected(t, rec: dict) -> None:
    """A stored test given the metadata its archive record holds after the corrections."""
    t.withdrawn, t.note = rec["withdrawn"], rec["note"]
    t.operator, t.instrument = rec["operator"], rec["instrument"]
    if rec["date_known"]:
        t.tested_at, t.date_known = dt.datetime.fromisoformat(rec["tested_at"]), True


def _restore_audit(s, entries: list[dict]) -> tuple[int, set[str]]:
    """Add the entries not in the trail; returns their count and the tests they name."""
    from sqlalchemy import func, select

    from axiscal.store.models import Audit, Axis, Machine, Test

    machines = dict(s.execute(select(Machine.name, Machine.id)).all())
    axes = {(m, a): i for i, m, a in s.execute(select(Axis.id, Machine.name, Axis.name)
                                               .join(Machine, Axis.machine_id == Machine.id))}
    low = min([0, *(v for v in s.execute(select(func.min(Audit.machine_id),
                                                func.min(Audit.axis_id))).one() if v is not None)])
    gone = _Gone(low)
    have = set(s.execute(select(Audit.at, Audit.by, Audit.action, Audit.what, Audit.reason)))
    added, touched = 0, set()
    for e in entries:
        at = dt.datetime.fromisoformat(e["at"])
        if (at, e["by"], e["action"], e["what"], e["reason"]) in have:
            continue
        mid = machines.get(e["machine"]) if e["machine"] is not None else None
        mid = mid if mid is not None else gone.id("machine", e["machine_id"])
        aid = axes.get(tuple(e["axis"])) if e["axis"] is not None else None
        aid = aid if aid is not None else gone.id("axis", e["axis_id"])
        tid = s.scalar(select(Test.id).where(Test.sha256 == e["test"])) if e["test"] else None
        old, new = (_ids(e[k], e["action"], e["refs"].get(k), machines, axes, gone)
                    for k in ("old", "new"))
        s.add(Audit(at=at, by=e["by"], action=e["action"], what=e["what"], reason=e["reason"],
                    machine_id=mid, axis_id=aid, test_id=tid,
                    old_json=json.dumps(old, ensure_ascii=False),
                    new_json=json.dumps(new, ensure_ascii=False)))
        added += 1
        touched |= {e["test"]} if e["test"] else set()
    s.flush()
    return added, touched


class _Gone:
    """Negative ids, one per machine or axis of the archive no longer in the history."""

    def __init__(self, low: int):
        self.next, self.ids = low - 1, {}

    def id(self, what: str, old: int | None) -> int | None:
        if old is None:
            return None
        if (what, old) not in self.ids:
            self.ids[what, old] = self.next
            self.next -= 1
        return self.ids[what, old]


def _ids(values: dict, action: str, ref, machines: dict, axes: dict, gone: _Gone) -> dict:
    """A merge's ``old``/``new`` with the ids of this history: of the machine (or axis) by the
    name exported with it (``refs``), else the negative id of the one gone."""
    out, key, what = dict(values), {"merge-machines": "id", "merge-axes": "axis_id"}.get(
        action), "machine" if action == "merge-machines" else "axis"
    if key is None or not isinstance(out.get(key), int):
        return out
    found = machines.get(ref) if isinstance(ref, str) else (
        axes.get(tuple(ref)) if isinstance(ref, list) else None)
    out[key] = found if found is not None else gone.id(what, out[key])
    return out


def _restore_certificates(s, entries: list[tuple[dict, bytes]], p) -> tuple[int, int]:
    from sqlalchemy import select

    from axiscal.store.models import Certificate, Test

    added = {}
    for e, doc in entries:
        where = f"certificate {e['number'][:80]} of {e['laboratory'][:80]}"
        kept = s.scalars(select(Certificate).where(
            Certificate.laboratory == e["laboratory"], Certificate.number == e["number"])).first()
        if kept is not None:
            if kept.sha256 != e["sha256"]:
                raise DataFormatError(f"{where}: the register holds another document under "
                                      "this number; nothing was imported", str(p))
            continue
        if s.scalar(select(Certificate.id).where(
                Certificate.laboratory == e["laboratory"], Certificate.series == e["series"],
                Certificate.counter == e["counter"])) is not None:
            raise DataFormatError(f"{where}: its counter {e['counter']} of series "
                                  f"{e['series'][:80]!r} is taken in the register by another "
                                  "certificate; nothing was imported", str(p))
        row = Certificate(
            test_id=s.scalar(select(Test.id).where(Test.sha256 == e["test"])),
            laboratory=e["laboratory"], series=e["series"], counter=e["counter"],
            number=e["number"], customer=e["customer"], issued=e["issued"],
            status=e["status"], reason=e["reason"], media_type=e["media_type"], document=doc,
            sha256=e["sha256"], inputs_json=json.dumps(e["inputs"]),
            created=dt.datetime.fromisoformat(e["created"]),
            laboratory_name=e["laboratory_name"], prepared_by=e["prepared_by"],
            approved_by=e["approved_by"], approved_role=e["approved_role"],
            changes_json=json.dumps(e["changes"]), as_found_test_id=(
                s.scalar(select(Test.id).where(Test.sha256 == e["as_found"]))
                if e["as_found"] else None))
        s.add(row)
        added[e["laboratory"], e["number"]] = (row, e["replaces"])
    s.flush()
    for (lab, _), (row, replaces) in added.items():
        if replaces:
            row.replaces_id = s.scalar(select(Certificate.id).where(
                Certificate.laboratory == lab, Certificate.number == replaces))
    s.flush()
    return len(added), len({row.sha256 for row, _ in added.values()})
