"""Corrections that lose nothing: rename, merge, edit, withdraw, each an entry in the audit trail.

ISO/IEC 17025:2017 §7.5.2 asks that amendments to technical records be traceable to previous
versions or to the original observations, the original and the amended data and files both kept,
with the date of the change, what was changed and who changed it; §8.4.2 that records be kept
and retrievable. So here:

* nothing is deleted from the history: a test is *withdrawn* with a reason (and can be
  reinstated); it stays, marked, retrievable by its id, but leaves trends and compares;
* a machine or axis renamed keeps its id; a machine (or axis) merged into another gives the
  other all its axes (tests) and only its now empty row goes; its old name and id stay in the
  trail, and its old address leads to the machine it was merged into;
* every change is one :class:`~axiscal.store.models.Audit` row written in the same transaction
  as the change: who (``by``), when (UTC), what (words), why (``reason``), the old and the new
  values as JSON. ``by`` and ``reason`` are required: a change nobody owns or explains is refused.

Machines are named by name or by id (an ``int``); axes by machine and axis name.
"""

from __future__ import annotations

import datetime as dt
import json
from contextlib import contextmanager
from dataclasses import dataclass

from axiscal.errors import InputError
from axiscal.store.history import NotFoundError, _date, _name, _test_id

__all__ = ["AuditRecord", "rename_machine", "rename_axis", "merge_machines", "merge_axes",
           "edit_test", "withdraw", "reinstate", "audit", "machine_id", "EDITABLE"]

#: The metadata of a test that :func:`edit_test` changes (its measured data never change).
EDITABLE = ("date", "operator", "instrument", "note")
#: Longest reason or name of the person who made a change.
MAX_REASON, MAX_BY = 2000, 200


@dataclass(frozen=True)
class AuditRecord:
    """One entry of the audit trail."""

    id: int
    at: dt.datetime
    by: str
    action: str
    what: str
    reason: str
    machine_id: int | None
    axis_id: int | None
    test_id: int | None
    old: dict
    new: dict

    def as_dict(self) -> dict:
        return {"id": self.id, "at": self.at.isoformat() + "Z", "by": self.by,
                "action": self.action, "what": self.what, "reason": self.reason,
                "machine_id": self.machine_id, "axis_id": self.axis_id,
                "test_id": self.test_id, "old": self.old, "new": self.new}


def rename_machine(store, machine, new_name: str, *, by: str, reason: str) -> AuditRecord:
    """Give a machine a new name (its id, axes and tests stay)."""
    new_name = _name(new_name, "machine", "new name")
    with _change(store) as s:
        m = _machine(s, machine)
        if m.name == new_name:   # an audit entry for no change would be a false record
            raise InputError(f"machine {new_name!r} already has that name; nothing to change")
        _free_machine_name(s, new_name, m.id)
        old = m.name
        m.name = new_name
        return _log(s, by, reason, "rename-machine", f"machine {old!r} renamed {new_name!r}",
                    {"name": old}, {"name": new_name}, machine_id=m.id)


def rename_axis(store, machine, axis: str, new_name: str, *, by: str,
                reason: str) -> AuditRecord:
    """Give an axis of a machine a new name (its id and tests stay)."""
    new_name = _name(new_name, "axis", "new name").upper()
    if len(new_name) > 50:
        raise InputError(f"axis name of {len(new_name)} characters; at most 50")
    with _change(store) as s:
        m = _machine(s, machine)
        a = _axis(s, m, axis)
        if _find_axis(s, m.id, new_name) not in (None, a):
            raise InputError(f"{m.name} already has an axis {new_name}: merge the two axes "
                             "instead")
        old = a.name
        if old == new_name:
            raise InputError(f"axis {new_name} of {m.name!r} already has that name; nothing "
                             "to change")
        a.name = new_name
        return _log(s, by, reason, "rename-axis", f"axis {old} of {m.name!r} renamed {new_name}",
                    {"axis": old}, {"axis": new_name}, machine_id=m.id, axis_id=a.id)


def merge_machines(store, source, target, *, by: str, reason: str) -> AuditRecord:
    """Move every axis and test of ``source`` to ``target``; axes of one name become one axis.

    The emptied ``source`` row goes; its name and id stay in the trail (``old``).
    """
    with _change(store) as s:
        src, dst = _machine(s, source), _machine(s, target)
        if src.id == dst.id:
            raise InputError(f"machine {src.name!r} cannot be merged into itself")
        moved = {}
        for a in list(src.axes):
            same = _find_axis(s, dst.id, a.name)
            if same is None:
                moved[a.name] = len(a.tests)
                a.machine = dst
            else:
                _same_kind(a, same)
                moved[a.name] = _move_tests(s, a, same)
        s.flush()
        s.expire_all()
        entry = _log(s, by, reason, "merge-machines", f"machine {src.name!r} (id {src.id}) "
                     f"merged into {dst.name!r}", {"name": src.name, "id": src.id},
                     {"name": dst.name, "id": dst.id, "tests_moved": moved}, machine_id=dst.id)
        s.delete(src)
        return entry


def merge_axes(store, machine, source: str, target: str, *, by: str,
               reason: str) -> AuditRecord:
    """Move every test of axis ``source`` of a machine to its axis ``target``."""
    with _change(store) as s:
        m = _machine(s, machine)
        a, b = _axis(s, m, source), _axis(s, m, target)
        if a.id == b.id:
            raise InputError(f"axis {a.name} cannot be merged into itself")
        _same_kind(a, b)
        n = _move_tests(s, a, b)
        return _log(s, by, reason, "merge-axes", f"axis {a.name} of {m.name!r} merged into "
                    f"{b.name} ({n} tests)", {"axis": a.name, "axis_id": a.id},
                    {"axis": b.name, "axis_id": b.id, "tests_moved": n}, machine_id=m.id,
                    axis_id=b.id)


def edit_test(store, test_id, *, by: str, reason: str, **changes) -> AuditRecord:
    """Change a test's metadata (:data:`EDITABLE`: date, operator, instrument, note)."""
    unknown = sorted(set(changes) - set(EDITABLE))
    if unknown:
        raise InputError(f"{', '.join(unknown)}: only {', '.join(EDITABLE)} of a test are edited")
    changes = {k: str(v).strip() for k, v in changes.items() if v is not None}
    if not changes:
        raise InputError(f"nothing to change: give one of {', '.join(EDITABLE)}")
    _bounded(changes)
    with _change(store) as s:
        t = _test(s, test_id)
        old, new = {}, {}
        for k, v in changes.items():
            if k == "date":
                if not v:
                    raise InputError("date: give it as YYYY-MM-DD")
                when, _ = _date(v)
                old[k], new[k] = _iso(t.tested_at, t.date_known), when.isoformat()
                t.tested_at, t.date_known = when, True
            else:
                old[k], new[k] = getattr(t, k) or "", v
                setattr(t, k, v)
        if old == new:
            raise InputError(f"test {t.id} already has these values; nothing changed")
        return _log(s, by, reason, "edit", f"test {t.id}: {', '.join(new)} edited", old, new,
                    machine_id=t.axis.machine_id, axis_id=t.axis_id, test_id=t.id)


def withdraw(store, test_id, *, by: str, reason: str) -> AuditRecord:
    """Withdraw a test: it stays, marked with ``reason``, but leaves trends and compares."""
    with _change(store) as s:
        t = _test(s, test_id)
        if t.withdrawn:
            raise InputError(f"test {t.id} is withdrawn already ({t.withdrawn})")
        t.withdrawn = reason.strip()
        return _log(s, by, reason, "withdraw", f"test {t.id} withdrawn", {"withdrawn": False},
                    {"withdrawn": True}, machine_id=t.axis.machine_id, axis_id=t.axis_id,
                    test_id=t.id)


def reinstate(store, test_id, *, by: str, reason: str) -> AuditRecord:
    """Count a withdrawn test again."""
    with _change(store) as s:
        t = _test(s, test_id)
        if not t.withdrawn:
            raise InputError(f"test {t.id} is not withdrawn")
        was = t.withdrawn
        t.withdrawn = ""
        return _log(s, by, reason, "reinstate", f"test {t.id} reinstated",
                    {"withdrawn": True, "reason": was}, {"withdrawn": False},
                    machine_id=t.axis.machine_id, axis_id=t.axis_id, test_id=t.id)


def audit(store, machine=None, test_id=None, limit: int | None = None) -> list[AuditRecord]:
    """The audit trail, newest first: all of it, a machine's (with the machines merged into it
    and their tests) or one test's."""
    from sqlalchemy import select

    from axiscal.store.models import Audit

    a = Audit.__table__.c                  # plain rows (a page shows them on every view)
    q = select(Audit.__table__).order_by(a.id.desc())
    with store._guard("read"), store._session() as s:
        if test_id is not None:
            q = q.where(a.test_id == _test_id(test_id))
        elif machine is not None:
            q = q.where(a.machine_id.in_(_merged_ids(s, _machine(s, machine).id)))
        if limit:
            q = q.limit(limit)
        return [_record(r) for r in s.connection().execute(q)]


def machine_id(store, name: str) -> int:
    """The id of machine ``name``; an old name (renamed, or merged into another machine)
    answers the id of the machine it became, so an old link still leads somewhere."""
    from sqlalchemy import select

    from axiscal.store.models import Audit, Machine

    with store._guard("read"), store._session() as s:
        found = s.scalar(select(Machine.id).where(Machine.name == name))
        if found is not None:
            return found
        for a in s.scalars(select(Audit).where(Audit.action.in_(("merge-machines",
                                                                 "rename-machine")))
                           .order_by(Audit.id.desc())):
            if json.loads(a.old_json).get("name") == name and s.get(Machine, a.machine_id):
                return a.machine_id
    raise NotFoundError(f"no machine {name!r} in the history")


# -- internals -------------------------------------------------------------------------------
@contextmanager
def _change(store):
    """One write transaction: committed when the block ends, rolled back on an error."""
    with store._guard("store"), store._session(write=True) as s:
        try:
            yield s
            s.commit()
        except BaseException:
            s.rollback()
            raise


def _log(s, by: str, reason: str, action: str, what: str, old: dict, new: dict,
         **ids) -> AuditRecord:
    from axiscal.store.models import Audit

    by, reason = (by or "").strip(), (reason or "").strip()
    if not by:
        raise InputError("say who makes the change (--by NAME): the audit trail records it")
    if not reason:
        raise InputError("say why (--reason TEXT): the audit trail records it")
    _bounded({"by": by, "reason": reason})
    now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0)
    row = Audit(at=now, by=by, action=action, what=what, reason=reason,
                old_json=json.dumps(old, ensure_ascii=False),
                new_json=json.dumps(new, ensure_ascii=False), **ids)
    s.add(row)
    s.flush()
    return _record(row)


def _record(a) -> AuditRecord:
    return AuditRecord(a.id, a.at, a.by, a.action, a.what, a.reason, a.machine_id, a.axis_id,
                       a.test_id, json.loads(a.old_json), json.loads(a.new_json))


def _bounded(fields: dict) -> None:
    """Each text within its length, free of control characters (:func:`axiscal.store.limits.
    checked_text`; a reason and a note may hold line breaks)."""
    from axiscal.store.limits import checked_text

    for k, v in fields.items():
        limit = MAX_BY if k in ("by", "operator", "instrument") else MAX_REASON
        if len(v) > limit:
            raise InputError(f"{k} of {len(v)} characters; at most {limit}")
        checked_text(v, k, single_line=k not in ("reason", "note"))


def _machine(s, ref):
    from sqlalchemy import select

    from axiscal.store.models import Machine

    if isinstance(ref, int):
        m = s.get(Machine, ref) if 0 < ref < 2**63 else None
    else:
        m = s.scalars(select(Machine).where(Machine.name == str(ref).strip())).first()
    if m is None:
        raise NotFoundError(f"no machine {ref!r} in the history")
    return m


def _find_axis(s, machine_id: int, name: str):
    from sqlalchemy import select

    from axiscal.store.models import Axis

    return s.scalars(select(Axis).where(Axis.machine_id == machine_id,
                                        Axis.name == name.strip().upper())).first()


def _axis(s, m, name: str):
    a = _find_axis(s, m.id, name)
    if a is None:
        raise NotFoundError(f"machine {m.name!r} has no axis {name.strip().upper()!r}")
    return a


def _test(s, test_id):
    from axiscal.store.models import Test

    t = s.get(Test, _test_id(test_id))
    if t is None:
        raise NotFoundError(f"no test {test_id} in the history")
    return t


def _free_machine_name(s, name: str, own_id: int) -> None:
    from sqlalchemy import select

    from axiscal.store.models import Machine

    other = s.scalar(select(Machine.id).where(Machine.name == name))
    if other is not None and other != own_id:
        raise InputError(f"a machine {name!r} exists already: merge the two machines instead")


def _same_kind(a, b) -> None:
    if a.kind and b.kind and a.kind != b.kind:
        raise InputError(f"axis {a.name} is {a.kind}, axis {b.name} is {b.kind}: only axes "
                         "of one kind merge")


def _move_tests(s, source, target) -> int:
    """Every test of axis ``source`` to axis ``target``; the emptied source axis row goes."""
    from sqlalchemy import update

    from axiscal.store.models import Test

    n = s.execute(update(Test).where(Test.axis_id == source.id)
                  .values(axis_id=target.id)).rowcount
    s.flush()
    s.expire_all()
    s.delete(source)
    s.flush()
    return n


def _merged_ids(s, machine_id: int) -> list[int]:
    """``machine_id`` and the ids of every machine merged into it (and into those)."""
    from sqlalchemy import select

    from axiscal.store.models import Audit

    merges = {}
    for into, old in s.execute(select(Audit.machine_id, Audit.old_json)
                               .where(Audit.action == "merge-machines")):
        merges.setdefault(into, []).append(json.loads(old).get("id"))
    ids, todo = [], [machine_id]
    while todo:
        i = todo.pop()
        if i not in ids:
            ids.append(i)
            todo += merges.get(i, [])
    return ids


def _iso(when: dt.datetime, known: bool) -> str | None:
    return when.isoformat() if known else None
