"""``axiscal history rename-machine|rename-axis|merge|edit|withdraw|reinstate|drift-check|audit``.

Corrections that lose nothing (:mod:`axiscal.store.corrections`; ISO/IEC 17025:2017 §7.5.2
and §8.4.2): every command that changes a record needs ``--by NAME`` and ``--reason TEXT``
and writes one entry of the audit trail; ``audit`` lists the trail.

JSON output (``--json``): a change prints its audit entry (``id``, ``at``, ``by``, ``action``,
``what``, ``reason``, ``machine_id``, ``axis_id``, ``test_id``, ``old``, ``new``); ``audit``
prints a list of them, newest first; ``drift-check`` prints the drift check kept (``id``,
``test_id``, ``filename``, ``sha256``, ``e_ve``, ``unit``, ``readings``, ``by``, ``replaced``:
the declared E_VE it replaced or null, ``notice``: that in words or "").
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import print_json
from axiscal.cli._history_store import DB as db_opt
from axiscal.cli._history_store import open_db as _store

__all__ = ["add_commands"]

_BY = typer.Option(..., "--by", help="Who makes the change (kept in the audit trail).")
_REASON = typer.Option(..., "--reason", help="Why (kept in the audit trail; ISO/IEC "
                       "17025:2017 §7.5.2).")
_JSON = typer.Option(False, "--json", help="Print the audit entry as JSON (stable keys).")


def _done(entry, json_out: bool) -> None:
    if json_out:
        print_json(entry.as_dict())
    else:
        from axiscal.errors import one_line

        # the trail keeps every word; the terminal gets the change, not a 50 kB note back
        typer.echo(one_line(f"{entry.what} (audit entry {entry.id}, by {entry.by}: "
                            f"{entry.reason})", 400))


def add_commands(app: typer.Typer) -> None:
    """Add the correction commands to the ``history`` group ``app``."""
    _renames(app)
    _merge_and_edit(app)
    _withdrawals(app)


def _renames(app: typer.Typer) -> None:
    from axiscal.store import corrections as c

    @app.command("rename-machine")
    def rename_machine(old: str = typer.Argument(..., help="The machine's name now."),
                       new: str = typer.Argument(..., help="Its new name."),
                       by: str = _BY, reason: str = _REASON, db: Optional[str] = db_opt,
                       json_out: bool = _JSON) -> None:
        """Rename a machine (its tests stay; the old name is kept in the audit trail).

        Example: axiscal history rename-machine "DMU 50" "DMU 50 S/N 1234" --by Ng --reason serial
        """
        _done(c.rename_machine(_store(db), old, new, by=by, reason=reason), json_out)

    @app.command("rename-axis")
    def rename_axis(machine: str = typer.Argument(..., help="The machine."),
                    axis: str = typer.Argument(..., help="The axis's name now."),
                    new: str = typer.Argument(..., help="Its new name."),
                    by: str = _BY, reason: str = _REASON, db: Optional[str] = db_opt,
                    json_out: bool = _JSON) -> None:
        """Rename an axis of a machine.

        Example: axiscal history rename-axis VMC-800 X1 X --by "A. Ng" --reason "typo"
        """
        _done(c.rename_axis(_store(db), machine, axis, new, by=by, reason=reason), json_out)



def _merge_and_edit(app: typer.Typer) -> None:
    from axiscal.store import corrections as c

    @app.command("merge")
    def merge(source: str = typer.Argument(..., help="The machine (or, with --machine, the "
                                           "axis) whose tests move."),
              into: str = typer.Argument(..., help="The machine (or axis) they move to."),
              machine: Optional[str] = typer.Option(None, "--machine", help="Merge two axes "
                                                    "of this machine instead of two machines."),
              by: str = _BY, reason: str = _REASON, db: Optional[str] = db_opt,
              json_out: bool = _JSON) -> None:
        """Merge two machines (or two axes of one machine): every test moves, none is lost.

        Example: axiscal history merge "VMC 800" VMC-800 --by "A. Ng" --reason "one machine"
        """
        s = _store(db)
        entry = (c.merge_axes(s, machine, source, into, by=by, reason=reason) if machine
                 else c.merge_machines(s, source, into, by=by, reason=reason))
        _done(entry, json_out)

    @app.command("edit")
    def edit(test_id: int = typer.Argument(..., help="Test id (from 'history list')."),
             date: Optional[str] = typer.Option(None, "--date", help="Test date YYYY-MM-DD."),
             operator: Optional[str] = typer.Option(None, "--operator", help="Operator."),
             instrument: Optional[str] = typer.Option(None, "--instrument",
                                                      help="Instrument and its serial."),
             note_: Optional[str] = typer.Option(None, "--note", help="The note."),
             by: str = _BY, reason: str = _REASON, db: Optional[str] = db_opt,
             json_out: bool = _JSON) -> None:
        """Edit a test's metadata (its readings never change); old values kept in the trail.

        Example: axiscal history edit 12 --date 2025-03-01 --by "A. Ng" --reason "log book"
        """
        _done(c.edit_test(_store(db), test_id, by=by, reason=reason, date=date,
                          operator=operator, instrument=instrument, note=note_), json_out)



def _withdrawals(app: typer.Typer) -> None:
    from axiscal.store import corrections as c

    @app.command("withdraw")
    def withdraw(test_id: int = typer.Argument(..., help="Test id."), by: str = _BY,
                 reason: str = _REASON, db: Optional[str] = db_opt,
                 json_out: bool = _JSON) -> None:
        """Withdraw a test: it stays, marked, but leaves trends and compares.

        Example: axiscal history withdraw 12 --by "A. Ng" --reason "beam clipped on run 3"
        """
        _done(c.withdraw(_store(db), test_id, by=by, reason=reason), json_out)

    @app.command("reinstate")
    def reinstate(test_id: int = typer.Argument(..., help="Test id."), by: str = _BY,
                  reason: str = _REASON, db: Optional[str] = db_opt,
                  json_out: bool = _JSON) -> None:
        """Count a withdrawn test again.

        Example: axiscal history reinstate 12 --by "A. Ng" --reason "withdrawn by mistake"
        """
        _done(c.reinstate(_store(db), test_id, by=by, reason=reason), json_out)

    @app.command("drift-check")
    def drift_check(test_id: int = typer.Argument(..., help="Test id (a positioning test)."),
                    file: Path = typer.Argument(..., help="Drift-check file (CSV: a 'reading' "
                                                "column, or one column of numbers, in the "
                                                "test's deviation unit)."),
                    by: str = _BY,
                    reason: str = typer.Option("drift check of the test uploaded", "--reason",
                                               help="Why (kept in the audit trail)."),
                    db: Optional[str] = db_opt,
                    json_out: bool = typer.Option(False, "--json", help="Print the drift "
                                                  "check kept as JSON (stable keys).")) -> None:
        """Keep a drift check with a stored positioning test: its E_VE, measured, is the budget's.

        ISO 230-2:2014 Annex A.5; an E_VE declared for the test is replaced, and said.

        Example: axiscal history drift-check 12 dc.csv --by "A. Ng"
        """
        from axiscal.cli._common import note
        from axiscal.io._files import read_bytes
        from axiscal.store.laboratory import add_drift_check

        if not by.strip():
            from axiscal.errors import InputError

            raise InputError("--by: give who keeps the drift check (the audit trail records it)")
        kept = add_drift_check(_store(db), test_id, read_bytes(file), file.name, by=by,
                               reason=reason)
        if json_out:
            print_json({"id": kept.id, "test_id": kept.test_id, "filename": kept.filename,
                        "sha256": kept.sha256, "e_ve": kept.e_ve, "unit": kept.unit,
                        "readings": kept.readings, "by": kept.by, "replaced": kept.replaced,
                        "notice": kept.notice})
        else:
            from axiscal.units import display

            typer.echo(f"test {kept.test_id}: drift check {kept.filename} kept ({kept.readings} "
                       f"readings), E_VE {kept.e_ve:g} {display(kept.unit)}".rstrip())
        if kept.notice:
            note(kept.notice)

    @app.command("audit")
    def audit(machine: Optional[str] = typer.Option(None, "--machine", help="Only this "
                                                    "machine (and machines merged into it)."),
              test_id: Optional[int] = typer.Option(None, "--test", help="Only this test."),
              db: Optional[str] = db_opt,
              json_out: bool = typer.Option(False, "--json", help="Print as JSON.")) -> None:
        """The audit trail: every change, newest first (who, when, what, why, old, new).

        Example: axiscal history audit --machine VMC-800
        """
        rows = c.audit(_store(db), machine=machine, test_id=test_id)
        if json_out:
            print_json([r.as_dict() for r in rows])
            return
        if not rows:
            typer.echo("no change recorded")
        for r in rows:
            typer.echo(f"{r.id:>5}  {r.at:%Y-%m-%d %H:%M:%S} UTC  {r.by}: {r.what}; "
                       f"why: {r.reason}; was {_short(r.old)}, now {_short(r.new)}")


def _short(values: dict) -> str:
    import json

    return json.dumps(values, ensure_ascii=False)
