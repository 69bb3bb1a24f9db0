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

import dataclasses
import datetime as dt
import json
from dataclasses import dataclass

from axiscal.errors import InputError

__all__ = ["laboratory", "set_laboratory", "signatory_list", "check_signatory_change",
           "add_drift_check", "drift_checks", "DriftCheckRecord", "result_with_drift_check",
           "signoff_config", "signoff_record", "reads_e_ve", "last_certificate_inputs",
           "LABORATORY_TABLES"]

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
    #: The E_VE declared for the test (stored with it at upload) that this drift check's
    #: replaced, in the test's deviation unit ``unit``; None when none was declared. What
    #: keeping it did, not what is kept: left out of comparisons with :func:`drift_checks`' rows.
    replaced: float | None = dataclasses.field(default=None, compare=False)
    unit: str = dataclasses.field(default="", compare=False)

    @property
    def notice(self) -> str:
        """What keeping it changed that the user did not ask for in words ("" when nothing):
        a declared E_VE replaced by the measured one."""
        if self.replaced is None:
            return ""
        from axiscal.units import display

        u = f" {display(self.unit)}" if self.unit else ""
        return (f"E_VE given twice: the drift check's {self.e_ve:g}{u} replaces the declared "
                f"{self.replaced:g}{u} (ISO 230-2:2014 Annex A.5: E_VE measured by a drift "
                "check; the audit trail keeps both)")

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


def set_laboratory(store, tables: dict, *, by: str, reason: str, account: str | None = None,
                   inherited: dict | None = None):
    """Keep ``tables`` (of :data:`LABORATORY_TABLES`) as the laboratory; an audit entry with
    the old and the new tables. Returns the :class:`~axiscal.store.corrections.AuditRecord`.

    ``account`` is the signed-in account making the change (the workbench with accounts; None
    on one's own computer and on the command line, where the local user is trusted): a change
    of the authorised signatories (their names or roles) is then made only by one of the
    signatories before the change (ISO/IEC 17025:2017 §6.2.5, §6.2.6 c: personnel authorised
    by the laboratory; §7.8.2.1 o), checked in the same transaction as the write; while none is
    listed, any engineer may list the first ones (there is no administrator role). The
    signatories before the change are those kept, else ``inherited``'s (the server's user
    configuration, which the page shows when the history keeps none).

    Raises
    ------
    InputError
        A table not of :data:`LABORATORY_TABLES`; an instrument without a name; no change.
    NotAuthorisedError
        ``account`` changes the signatories and is not one of them.
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
        if account is not None:
            check_signatory_change(old, new, account, inherited)
        if row is None:
            s.add(Laboratory(id=1, tables_json=json.dumps(new), updated=now,
                             updated_by=(by or "").strip()[:200]))
        else:
            row.tables_json, row.updated, row.updated_by = json.dumps(new), now, by[:200]
        changed = sorted(k for k in set(old) | set(new) if old.get(k) != new.get(k))
        return _log(s, by, reason, "laboratory", "laboratory: " + ", ".join(changed)
                    + " edited", old, new)


def signatory_list(tables: dict) -> list[tuple[str, str]]:
    """The ``[[signatory]]`` entries of laboratory ``tables`` as (name, role), in order; without
    any, the one ``[certificate] signatory`` (as :func:`axiscal.report.issue.signatories`)."""
    listed = tables.get("signatory") or []
    listed = listed if isinstance(listed, list) else [listed]
    out = [(str(t.get("name", "")).strip(), str(t.get("role", "")).strip())
           for t in listed if isinstance(t, dict) and str(t.get("name", "")).strip()]
    cert = tables.get("certificate") or {}
    if not out and str(cert.get("signatory") or "").strip():
        out = [(str(cert["signatory"]).strip(), str(cert.get("signatory_role", "")).strip())]
    return out


def check_signatory_change(old: dict, new: dict, account: str,
                           inherited: dict | None = None) -> None:
    """Refuse a change of the authorised signatories by ``account`` when it is not one of them
    (see :func:`set_laboratory`); nothing is refused while no signatory is listed.

    Raises
    ------
    NotAuthorisedError
        The list (a name or a role) changes and ``account`` is not on the list before it.
    """
    from axiscal.errors import NotAuthorisedError

    base = signatory_list(inherited or {})
    before = signatory_list(old) or base
    after = signatory_list(new) or base
    if before == after or not before:
        return
    if (account or "").strip().casefold() not in {n.casefold() for n, _ in before}:
        raise NotAuthorisedError(
            f"Authorised signatories: only one of them ({', '.join(n for n, _ in before)}) may "
            f"change the list; the account {account!r} is not (ISO/IEC 17025:2017 §6.2.6)")


def add_drift_check(store, test_id: int, raw: bytes, filename: str, *, by: str,
                    reason: str = "drift check of the test uploaded") -> DriftCheckRecord:
    """Keep a drift-check file with stored test ``test_id`` and its E_VE (the range of its
    readings in the test's deviation unit, :func:`~axiscal.standards.iso230_9_inputs.
    environmental_variation`, the call ``axiscal iso230-2 --drift-check`` makes) as an input of
    the test's uncertainty budget (its stored record made again by the one call, in the same
    transaction); an audit entry with the E_VE before and after.

    An E_VE declared for the test when it was stored (its uncertainty input ``e_ve``, not a
    drift check's) is replaced by the measured one, and said: the record returned carries it
    (``replaced``) and its :attr:`~DriftCheckRecord.notice`, which every front end shows where
    the user acted. Replaced rather than refused: the drift check is the measurement ISO
    230-2:2014 Annex A.5 asks for, a declared E_VE its stand-in, and a stored test's declared
    input cannot be taken back otherwise (when both come at once, at upload, the user chooses:
    :func:`~axiscal.store.kinds.with_drift_check` refuses).

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
    positioning = stored.summary.kind == "iso230-2"
    if not positioning and not reads_e_ve(stored.record()):
        raise InputError(f"test {stored.summary.id} is a {stored.summary.kind} test: E_VE (a "
                         "drift check) is an input of a positioning test's budget (ISO "
                         "230-2:2014 Annex A) and of a budget that reads it (a diagonal "
                         "test's); this one does not")
    before = dict(stored.result.get("uncertainty_inputs") or {})
    ev = stored.evaluate_again()
    declared = before.get("e_ve") if before.get("e_ve_source") != "drift check" else None
    if positioning:
        result = result_with_drift_check(ev, before, record)
    else:                        # the budget's own input e_ve (its table has no e_ve_source)
        from axiscal._json import jsonable
        from axiscal.store.kinds import with_uncertainty

        result = json.dumps(jsonable(with_uncertainty(ev, {
            **before, "e_ve": e_ve}).stored_result()))
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
        return dataclasses.replace(
            _record(row), replaced=None if declared is None else float(declared),
            unit=getattr(ev.evaluation, "deviation_unit", ""))


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
                   lab: dict | None = None, checks: list | None = None) -> dict:
    """The configuration a sign-off of stored test ``stored`` is made with (see the module's
    docstring): ``user_config``, the history's laboratory (or ``lab``, the laboratory as a form
    is about to keep it), ``job``; the uncertainty inputs the test's own (stored with it) over
    the laboratory's, its newest drift check's E_VE over them (``checks``: the test's drift
    checks, newest first, when read already).

    Raises
    ------
    InputError
        E_VE given in the job too, beside a drift check: given twice (as the command line's
        ``--drift-check`` with ``--uncertainty e_ve``).
    """
    from axiscal.io.user_config import merge

    lab = laboratory(store) if lab is None else lab
    cfg = merge(merge(user_config, lab), job or {})
    inputs = merge(dict(cfg.get("uncertainty") or {}),     # the inputs of stored.record()
                   dict(stored.result.get("uncertainty_inputs") or {}))
    checks = drift_checks(store, stored.summary.id) if checks is None else checks
    if checks:
        if "e_ve" in ((job or {}).get("uncertainty") or {}):
            raise InputError("E_VE is given twice: by the drift check kept with the test and by "
                             "the form; give one")
        inputs.update(checks[0].inputs)
    return {**cfg, "uncertainty": inputs}


def reads_e_ve(ev) -> bool:
    """True when the budget of record ``ev`` (of a kind other than a positioning test) has the
    input E_VE (a diagonal test's, ISO/TR 230-9)."""
    return any(getattr(i, "name", None) == "e_ve"
               for i in getattr(ev.budget, "inputs", None) or ())


def signoff_record(store, stored, cfg: dict):
    """The record a sign-off of stored test ``stored`` of a kind other than a positioning test
    certifies: its stored record, and where its budget reads E_VE, E_VE resolved exactly as a
    positioning test's is (:func:`signoff_config` ``cfg``: the test's own input, else the
    laboratory's E_VE declared, a drift check kept with the test over both), the budget made
    again by the one call (:func:`axiscal.store.kinds.with_uncertainty`). An E_VE given by none
    stays assumed in the budget, and the certificate lists it as missing."""
    from axiscal.store.kinds import with_uncertainty

    ev = stored.record()
    e_ve = (cfg.get("uncertainty") or {}).get("e_ve")
    if e_ve is None or not reads_e_ve(ev) or (ev.inputs or {}).get("e_ve") == e_ve:
        return ev
    return with_uncertainty(ev, {**(ev.inputs or {}), "e_ve": e_ve})


def last_certificate_inputs(store, machine_id: int,
                            like_test: int | None = None) -> tuple[int | None, dict]:
    """(test id, inputs) of the newest certificate of any test of a machine ((None, {}) if
    none): what a new sign-off of the machine starts from (customer, item, instruments; and the
    conditions, when it is of the same test). With ``like_test``, only certificates of tests of
    the same axis and kind as that test: where a sign-off takes its tolerances from (a tolerance
    of E of the X axis, in µm, is no tolerance of the C axis's E, in arcsec, nor of a diagonal
    test's)."""
    from sqlalchemy import select

    from axiscal.store.models import Axis, Certificate, Test

    q = (select(Certificate.test_id, Certificate.inputs_json)
         .join(Test, Test.id == Certificate.test_id)
         .join(Axis, Axis.id == Test.axis_id).where(Axis.machine_id == int(machine_id))
         .order_by(Certificate.id.desc()).limit(1))
    if like_test is not None:
        like = select(Test.axis_id, Test.kind).where(Test.id == int(like_test)).subquery()
        q = q.where(Test.axis_id == select(like.c.axis_id).scalar_subquery(),
                    Test.kind == select(like.c.kind).scalar_subquery())
    with store._guard("read"), store._session() as s:
        found = s.execute(q).first()
    return (found[0], json.loads(found[1])) if found else (None, {})


def _record(r) -> DriftCheckRecord:
    return DriftCheckRecord(r.id, r.test_id, r.filename, r.sha256, r.e_ve, r.readings,
                            r.created, r.by)
