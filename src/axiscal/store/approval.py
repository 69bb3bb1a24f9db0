"""A sign-off saved for approval: the two-person issue of a certificate from the workbench.

ISO/IEC 17025:2017 §7.8.2.1 o asks a report to identify the person(s) authorising it, and
§6.2.5/§6.2.6 c that the laboratory authorises the personnel who do so. In the workbench with
accounts a certificate is therefore the act of two accounts: the preparer fills the sign-off
form and saves it for approval (:func:`save_for_approval`, an audit entry with the fields), and
an authorised signatory, another account, opens the test, finds the form as saved, and issues
it. The preparer printed and kept in the register is the account that saved the form
(:func:`preparer`), never a name typed on the form.
"""

from __future__ import annotations

import datetime as dt
import json
from dataclasses import dataclass

__all__ = ["SavedSignoff", "save_for_approval", "saved_signoff", "preparer", "clear_saved",
           "signoff_content"]

#: Fields of a saved form that are not its content (the request's own).
_NOT_CONTENT = ("csrf", "action", "by", "reason")


@dataclass(frozen=True)
class SavedSignoff:
    """A sign-off form saved for approval: ``values`` (field -> text), the account that saved
    it (``by``, the preparer) and when (UTC)."""

    test_id: int
    values: dict
    by: str
    saved: dt.datetime


def signoff_content(values: dict) -> dict:
    """The fields of a sign-off form that make the certificate (no token, no button)."""
    return {k: str(v).strip() for k, v in values.items()
            if k not in _NOT_CONTENT and str(v).strip()}


def save_for_approval(store, test_id: int, values: dict, *, by: str) -> SavedSignoff:
    """Keep the sign-off form ``values`` of stored test ``test_id`` as saved by account ``by``
    (replacing an earlier save of the test); an audit entry with the fields before and after.

    Raises
    ------
    InputError
        No account (``by`` empty): a preparer is an account.
    NotFoundError
        No such test.
    """
    from axiscal.errors import InputError
    from axiscal.store.corrections import _change, _log, _test
    from axiscal.store.models import SignoffForApproval

    by = (by or "").strip()
    if not by:
        raise InputError("saving a sign-off for approval needs a signed-in account: the "
                         "preparer is the account that saves it")
    content = signoff_content(values)
    now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0)
    with _change(store) as s:
        t = _test(s, test_id)
        row = s.get(SignoffForApproval, t.id)
        old = {} if row is None else {"by": row.by, "values": json.loads(row.values_json)}
        if row is None:
            row = SignoffForApproval(test_id=t.id)
            s.add(row)
        row.values_json, row.by, row.saved = json.dumps(content, ensure_ascii=False), by[:200], now
        _log(s, by, "saved for approval by an authorised signatory", "signoff-saved",
             f"test {t.id}: sign-off saved for approval by {by}", old,
             {"by": by, "values": content}, machine_id=t.axis.machine_id, axis_id=t.axis_id,
             test_id=t.id)
        return SavedSignoff(t.id, content, row.by, now)


def saved_signoff(store, test_id: int) -> SavedSignoff | None:
    """The sign-off saved for approval of a test, None if none is waiting."""
    from axiscal.store.models import SignoffForApproval

    with store._guard("read"), store._session() as s:
        row = s.get(SignoffForApproval, int(test_id))
        return None if row is None else SavedSignoff(row.test_id, json.loads(row.values_json),
                                                     row.by, row.saved)


def preparer(store, test_id: int, values: dict) -> str:
    """The account that prepared the sign-off ``values`` of a test: the one that saved exactly
    these fields for approval, else "" (not prepared by another account: whoever issues it
    prepared it)."""
    saved = saved_signoff(store, test_id)
    return saved.by if saved is not None and saved.values == signoff_content(values) else ""


def clear_saved(store, test_id: int) -> None:
    """Forget the saved sign-off of a test (its certificate is issued)."""
    from axiscal.store.corrections import _change
    from axiscal.store.models import SignoffForApproval

    with _change(store) as s:
        row = s.get(SignoffForApproval, int(test_id))
        if row is not None:
            s.delete(row)
