"""The laboratory kept in the history, drift checks kept beside their tests, and the one
configuration a sign-off from the history is made with.

A certificate needs the laboratory's identity (ISO/IEC 17025:2017 §7.8.2.1 c: name, address;
the code its numbers are keyed by), its authorised signatories (§7.8.2.1 o, §6.2.6 c), its
instruments with their calibration (§7.8.4.1 c, §6.5), E_VE of the uncertainty budget (ISO
230-2:2014 Annex A.5: declared, or measured by a drift check) and its CMC (ILAC-P14:09/2020
§5.4). The command line reads these from the user configuration; the workbench keeps them in
the history, where an engineer edits them (:func:`set_laboratory`, an audit entry each time,
§7.5.2) and where they do not depend on a file on the server. A drift check uploaded for a test
is kept with it, byte for byte, and its E_VE becomes an uncertainty input of the test's record
(:func:`add_drift_check`): the test's page, its JSON, the API and the archive give the U it
makes, as the sign-off does.

:func:`signoff_config` is how a sign-off from the history resolves its configuration: the user
configuration, the laboratory kept in the history over it, the job's tables (a form) over
both; and as the uncertainty inputs, the stored test's own (those it was stored with,
:meth:`~axiscal.store.history.StoredTest.record`) over the laboratory's, with the E_VE of the
test's newest drift check over them. :func:`axiscal.report.issue.budget_for` then makes the budget
from that configuration, the one call every path makes.
"""

from __future__ import annotations

import datetime as dt
import json
from dataclasses import dataclass

from axiscal.errors import InputError

__all__ = ["laboratory", "set_laboratory", "add_drift_check", "drift_checks", "DriftCheckRecord",
           "result_with_drift_check",
           "signoff_config", "last_certificate_inputs", "LABORATORY_TABLES"]

#: The configuration tables the history's laboratory holds.
LABORATORY_TABLES = ("company", "signatory", "instrument", "uncertainty")


@dataclass(frozen=True)
class DriftCheckRecord:
    """A drift check kept with a test: its file (name, SHA-256), the number of readings and
    E_VE, their range, in the test's deviation unit (ISO 230-2:2014 Annex A.5)."""

    id: int
    test_id: int
    filename: str
    sha256: str
    e_ve: float
    readings: int
    created: dt.datetime
    by: str

    @property
    def inputs(self) -> dict:
        """The uncertainty inputs it gives, as ``axiscal iso230-2 --drift-check`` gives them."""
        return {"e_ve": self.e_ve, "e_ve_source": "drift check"}


def laboratory(store) -> dict:
    """The laboratory's tables as the history keeps them ({} when none was entered)."""
    from axiscal.store.models import Laboratory

    with store._guard("read"), store._session() as s:
        row = s.get(Laboratory, 1)
        return json.loads(row.tables_json) if row is not None else {}


def set_laboratory(store, tables: dict, *, by: str, reason: str):
    """Keep ``tables`` (of :data:`LABORATORY_TABLES`) as the laboratory; an audit entry with
    the old and the new tables. Returns the :class:`~axiscal.store.corrections.AuditRecord`.

    Raises
    ------
    InputError
        A table not of :data:`LABORATORY_TABLES`; an instrument without a name; no change.
    """
    from axiscal.io.user_config import check_instruments
    from axiscal.store.corrections import _change, _log
    from axiscal.store.models import Laboratory

    unknown = sorted(set(tables) - set(LABORATORY_TABLES))
    if unknown:
        raise InputError(f"laboratory: {', '.join(unknown)} is not kept; "
                         f"{', '.join(LABORATORY_TABLES)} are")
    check_instruments(tables, "laboratory")
    from axiscal.store.limits import checked_tables

    checked_tables(tables, "laboratory:")
    new = json.loads(json.dumps(tables))
    now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0)
    with _change(store) as s:
        row = s.get(Laboratory, 1)
        old = json.loads(row.tables_json) if row is not None else {}
        if old == new:
            raise InputError("the laboratory already has these values; nothing changed")
        if row is None:
            s.add(Laboratory(id=1, tables_json=json.dumps(new), updated=now,
                             updated_by=(by or "").strip()[:200]))
        else:
            row.tables_json, row.updated, row.updated_by = json.dumps(new), now, by[:200]
        changed = sorted(k for k in set(old) | set(new) if old.get(k) != new.get(k))
        return _log(s, by, reason, "laboratory", "laboratory: " + ", ".join(changed)
                    + " edited", old, new)


def add_drift_check(store, test_id: int, raw: bytes, filename: str, *, by: str,
                    reason: str = "drift check of the test uploaded") -> DriftCheckRecord:
    """Keep a drift-check file with stored test ``test_id`` and its E_VE (the range of its
    readings in the test's deviation unit, :func:`~axiscal.standards.iso230_9_inputs.
    environmental_variation`, the call ``axiscal iso230-2 --drift-check`` makes) as an input of
    the test's uncertainty budget (its stored record made again by the one call, in the same
    transaction); an audit entry with the E_VE before and after.

    Raises
    ------
    InputError, DataFormatError
        Not a drift check (:func:`~axiscal.io.drift.parse_drift_check`), fewer than 2 readings,
        a test that is not a positioning test.
    """
    from axiscal.store.corrections import _change, _log, _test
    from axiscal.store.kinds import drift_check_record
    from axiscal.store.models import DriftCheck

    from axiscal.store.limits import checked_text

    name = checked_text((filename or "drift-check.csv").replace("\\", "/").rsplit("/", 1)[-1]
                        [:300], "drift check's file name")
    record = drift_check_record(raw, name)     # the one place a drift check becomes E_VE
    e_ve = record["e_ve"]
    stored = store.get(test_id)
    if stored.summary.kind != "iso230-2":
        raise InputError(f"test {stored.summary.id} is a {stored.summary.kind} test: E_VE (a "
                         "drift check) is an input of a positioning test's budget (ISO "
                         "230-2:2014 Annex A)")
    before = dict(stored.result.get("uncertainty_inputs") or {})
    result = result_with_drift_check(stored.evaluate_again(), before, record)
    now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0)
    with _change(store) as s:
        t = _test(s, test_id)
        row = DriftCheck(test_id=t.id, filename=name, raw=raw,
                         sha256=record["sha256"], e_ve=e_ve,
                         readings=int(record["samples"]), created=now, by=(by or "").strip()[:200])
        s.add(row)
        t.result_json = result            # the test's record: its budget with this E_VE
        s.flush()
        _log(s, by, reason, "drift-check", f"test {t.id}: drift check {name} kept, E_VE "
             f"{e_ve:g}", {k: before.get(k) for k in ("e_ve", "e_ve_source")},
             {"file": name, "sha256": row.sha256, "e_ve": e_ve, "e_ve_source": "drift check",
              "readings": row.readings},
             machine_id=t.axis.machine_id, axis_id=t.axis_id, test_id=t.id)
        return _record(row)


def result_with_drift_check(ev, before: dict, record: dict) -> str:
    """A positioning test's stored result (JSON) with drift check ``record``
    (:func:`~axiscal.store.kinds.drift_check_record`) kept and its E_VE over the uncertainty
    inputs ``before``: ``ev`` (the test's evaluation) with the budget made again by the one call
    (:func:`~axiscal.store.kinds.with_uncertainty`). :func:`add_drift_check` and an archive's
    import (:mod:`axiscal.store.archive_laboratory`) make the test's record with it."""
    from axiscal._json import jsonable
    from axiscal.store.kinds import with_drift_check, with_uncertainty

    ev, inputs = with_drift_check(ev, before, record)
    return json.dumps(jsonable(with_uncertainty(ev, inputs).stored_result()))


def drift_checks(store, test_id: int) -> list[DriftCheckRecord]:
    """The drift checks kept with a test, newest first."""
    from sqlalchemy import select

    from axiscal.store.models import DriftCheck

    with store._guard("read"), store._session() as s:
        return [_record(r) for r in s.scalars(select(DriftCheck).where(
            DriftCheck.test_id == int(test_id)).order_by(DriftCheck.id.desc()))]


def signoff_config(store, stored, user_config: dict, job: dict | None = None,
                   lab: dict | None = None) -> dict:
    """The configuration a sign-off of stored test ``stored`` is made with (see the module's
    docstring): ``user_config``, the history's laboratory (or ``lab``, the laboratory as a form
    is about to keep it), ``job``; the uncertainty inputs the test's own (stored with it) over
    the laboratory's, its newest drift check's E_VE over them.

    Raises
    ------
    InputError
        E_VE given in the job too, beside a drift check: given twice (as the command line's
        ``--drift-check`` with ``--uncertainty e_ve``).
    """
    from axiscal.io.user_config import merge

    lab = laboratory(store) if lab is None else lab
    cfg = merge(merge(user_config, lab), job or {})
    inputs = merge(dict(cfg.get("uncertainty") or {}),
                   dict(stored.record().inputs or {}))
    checks = drift_checks(store, stored.summary.id)
    if checks:
        if "e_ve" in ((job or {}).get("uncertainty") or {}):
            raise InputError("E_VE is given twice: by the drift check kept with the test and by "
                             "the form; give one")
        inputs.update(checks[0].inputs)
    return {**cfg, "uncertainty": inputs}


def last_certificate_inputs(store, machine_id: int) -> tuple[int | None, dict]:
    """(test id, inputs) of the newest certificate of any test of a machine ((None, {}) if
    none): what a new sign-off of the machine starts from (customer, item, instruments,
    tolerances; and the conditions, when it is of the same test)."""
    from sqlalchemy import select

    from axiscal.store.models import Axis, Certificate, Test

    q = (select(Certificate.test_id, Certificate.inputs_json)
         .join(Test, Test.id == Certificate.test_id)
         .join(Axis, Axis.id == Test.axis_id).where(Axis.machine_id == int(machine_id))
         .order_by(Certificate.id.desc()).limit(1))
    with store._guard("read"), store._session() as s:
        found = s.execute(q).first()
    return (found[0], json.loads(found[1])) if found else (None, {})


def _record(r) -> DriftCheckRecord:
    return DriftCheckRecord(r.id, r.test_id, r.filename, r.sha256, r.e_ve, r.readings,
                            r.created, r.by)
