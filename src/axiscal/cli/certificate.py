"""``axiscal certificate list|show|issue|reissue``: the certificate register of the calibration
history.

Certificates are issued by ``axiscal iso230-2 FILE --report CERT.pdf`` (and ``make demo``), and
for a stored test of any kind with an uncertainty budget by ``axiscal certificate issue ID``, when
every mandatory item of ISO/IEC 17025:2017 §7.8 is given; each has a number unique per
laboratory, and the issued document and its SHA-256 are kept with the test
(:mod:`axiscal.store.register`, :mod:`axiscal.report.issue`). An amendment (§7.8.8) is a reissue:
a new number that replaces the old one, with the reason; the old one is kept, marked superseded.

JSON output (``--json``), stable keys: ``list`` prints a list of objects with ``number``,
``laboratory`` (the laboratory's code, the register's key), ``laboratory_name`` (as printed),
``test_id``, ``customer``, ``issued``, ``status`` (``issued`` or ``superseded``), ``replaces``,
``replaced_by``, ``reason``, ``media_type``, ``sha256``, ``prepared_by``, ``approved_by``,
``approved_role``, ``changes`` (an amendment's ``what``/``old``/``new``), ``test_withdrawn``
(why the test was withdrawn after issue; "" while it counts) and ``as_found_test_id``;
``show`` and ``reissue`` print one such object (``reissue``: the new certificate) and ``path``
when a document was written.

Exit codes: 0 done, 2 a user error (no such certificate, a reissue that would lack a mandatory
item, no reason given).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._certificate import APPROVED_BY, DRAFT, JOB, PAPER, PREPARED_BY, RULE
from axiscal.cli._common import note, print_json
from axiscal.cli._history_store import DB as _DB      # the history's --db and --json,
from axiscal.cli._history_store import JSON as _JSON  # the same options
from axiscal.cli._history_store import open_db

__all__ = ["register", "record_json"]

app = typer.Typer(help="The certificate register: numbers, issued documents and amendments "
                  "(ISO/IEC 17025:2017 §7.8.8) kept in the calibration history.",
                  no_args_is_help=True)

_LAB = typer.Option(None, "--laboratory", help="The laboratory's code (\\[company] code; its "
                    "name is accepted too), where two laboratories share a database.")


def record_json(r) -> dict:
    """The stable JSON object of a register entry (see the module docstring)."""
    return {"number": r.number, "laboratory": r.laboratory, "test_id": r.test_id,
            "customer": r.customer, "issued": r.issued, "status": r.status,
            "replaces": r.replaces, "replaced_by": r.replaced_by, "reason": r.reason,
            "media_type": r.media_type, "sha256": r.sha256,
            "laboratory_name": r.laboratory_name, "prepared_by": r.prepared_by,
            "approved_by": r.approved_by, "approved_role": r.approved_role,
            "changes": list(r.changes), "test_withdrawn": r.test_withdrawn,
            "as_found_test_id": r.as_found_test_id}


@app.command("list")
def list_(db: Optional[str] = _DB, laboratory: Optional[str] = _LAB,
          json_out: bool = _JSON) -> None:
    """List the register, newest first: number, status, date of issue, test, customer.

    Example: axiscal certificate list --db sqlite:///history.sqlite
    """

    rows = open_db(db).certificates(laboratory)
    if json_out:
        print_json([record_json(r) for r in rows])
        return
    if not rows:
        typer.echo("no certificates in the register")
    for r in rows:
        typer.echo(str(r))


@app.command("show")
def show(number: str = typer.Argument(..., help="The certificate number."),
         out: Optional[Path] = typer.Option(None, "--out", help="Write the issued document, "
                                            "byte for byte, to this file."),
         db: Optional[str] = _DB, laboratory: Optional[str] = _LAB,
         json_out: bool = _JSON) -> None:
    """Show one certificate of the register (its SHA-256 checked) and write its document.

    Example: axiscal certificate show PM-2026-00001 --out PM-2026-00001.pdf
    """
    from axiscal.io._files import write_bytes_atomic

    r = open_db(db).certificate(number, laboratory)
    if out is not None:
        write_bytes_atomic(out, r.document)
    if json_out:
        print_json({**record_json(r), **({"path": str(out)} if out else {})})
    else:
        typer.echo(str(r))
        typer.echo(f"laboratory {r.laboratory} ({r.laboratory_name}); {r.media_type}, "
                   f"{len(r.document)} bytes, SHA-256 {r.sha256}")
        for c in r.changes:
            typer.echo(f"  changed: {c.get('what')}: {c.get('old')} → {c.get('new')}")
        if r.test_withdrawn:
            typer.echo(f"WARNING: the test of this certificate was withdrawn after issue "
                       f"({r.test_withdrawn}); the certificate stands as issued, its results "
                       "no longer count in the history")
    if out is not None:
        note(f"wrote {out}")


@app.command("reissue")
def reissue(number: str = typer.Argument(..., help="The number of the certificate to amend."),
            reason: str = typer.Option(..., "--reason", help="Why it is amended (printed on "
                                       "the new certificate)."),
            out: Path = typer.Option(..., "--out", help="The new certificate (.pdf)."),
            job: Optional[Path] = typer.Option(None, "--job", help="Corrections (TOML, the "
                                               "tables of a job file) over the inputs kept with "
                                               "the old certificate."),
            prepared_by: str = PREPARED_BY, approved_by: str = APPROVED_BY,
            db: Optional[str] = _DB, laboratory: Optional[str] = _LAB,
            json_out: bool = _JSON) -> None:
    """Amend a certificate: a new number replaces it; the old one stays, marked superseded.

    The reason is printed on the new certificate, which names the one it replaces (ISO/IEC
    17025:2017 §7.8.8).

    Example: axiscal certificate reissue PM-2026-00001 --reason "serial number corrected" --job fix.toml --out PM-2026-00002.pdf
    """
    from axiscal.cli._common import report_path
    from axiscal.io.user_config import load_job
    from axiscal.report.kind_certificate import reissue as reissue_certificate

    report_path(out)
    corrections = load_job(job) if job is not None else None
    o = reissue_certificate(open_db(db), number, reason, out, corrections,
                            laboratory=laboratory, prepared_by=prepared_by,
                            approved_by=approved_by)
    if json_out:
        print_json({**record_json(o.record), "path": str(out)})
    else:
        typer.echo(str(o.record))
    note(f"issued certificate {o.record.number}, replacing {number}: {out}")


@app.command("issue")
def issue(test_id: int = typer.Argument(..., help="The stored test (history list)."),
          out: Path = typer.Option(..., "--out", help="The certificate (.pdf or .html)."),
          job: Optional[Path] = JOB,
          tolerance: list[str] = typer.Option([], "--tolerance", help="Acceptance tolerance "
                                              "as NAME=VALUE, NAME a result of the test "
                                              "(history show --json: quantities)."),
          rule: Optional[str] = RULE, paper: Optional[str] = PAPER, draft: bool = DRAFT,
          prepared_by: str = PREPARED_BY, approved_by: str = APPROVED_BY,
          db: Optional[str] = _DB, json_out: bool = _JSON) -> None:
    """Certify a stored test of any kind with an uncertainty budget, numbered by the register.

    Positioning (ISO 230-2), diagonal squareness, ballbar (G and H), five-axis location
    errors, ISO 230-3 thermal and volumetric tests: each result with its U and k, decided by
    ISO 14253-1 against the tolerances given. A kind without a budget (straightness, five
    motion errors) is refused: a statement of conformity needs U.

    Example: axiscal certificate issue 4 --job job.toml --tolerance squareness=20 --out sq.pdf
    """
    from axiscal.cli._certificate import tell_outcome
    from axiscal.cli._common import report_path
    from axiscal.cli.iso230_2 import parse_tolerances
    from axiscal.report.issue import load_config
    from axiscal.report.kind_certificate import certify_stored

    report_path(out)
    outcome = certify_stored(open_db(db), test_id, out, load_config(job),
                             parse_tolerances(tolerance), rule, paper=paper,
                             prepared_by=prepared_by, approved_by=approved_by)
    if json_out and not outcome.draft:
        print_json({**record_json(outcome.record), "path": str(out)})
    elif json_out:
        print_json({"draft": True, "missing": list(outcome.missing), "path": str(out)})
    tell_outcome(outcome, draft)


@app.command("as-found-as-left")
def as_found_as_left(
        found: int = typer.Argument(..., help="The stored test before the adjustment "
                                    "(compensation, repair): 'as found'."),
        left: int = typer.Argument(..., help="The stored test after it: 'as left'."),
        out: Path = typer.Option(..., "--out", help="The certificate (.pdf or .html)."),
        job: Optional[Path] = JOB,
        tolerance: list[str] = typer.Option([], "--tolerance", help="Acceptance tolerance as "
                                            "NAME=VALUE, decided for both tests."),
        rule: Optional[str] = RULE, paper: Optional[str] = PAPER, draft: bool = DRAFT,
        prepared_by: str = PREPARED_BY, approved_by: str = APPROVED_BY,
        db: Optional[str] = _DB, json_out: bool = _JSON) -> None:
    """Certify a compensated axis from two stored tests: as found and as left, each with U.

    Both tests' results, U and verdicts are reported (ISO/IEC 17025:2017 §7.8.4.1 d); the
    number is the as-left test's, the as-found test named beside it in the register.

    Example: axiscal certificate as-found-as-left 3 7 --job job.toml --out X-as-left.pdf
    """
    from axiscal.cli._certificate import tell_outcome
    from axiscal.cli._common import report_path
    from axiscal.cli.iso230_2 import parse_tolerances
    from axiscal.io.user_config import config_problem
    from axiscal.report.issue import load_config, write_as_found_as_left
    from axiscal.store import open_store

    report_path(out)
    outcome = write_as_found_as_left(out, open_store(db), found, left, load_config(job),
                                     parse_tolerances(tolerance), rule, paper, job,
                                     config_note=config_problem(), prepared_by=prepared_by,
                                     approved_by=approved_by)
    if json_out and not outcome.draft:
        print_json({**record_json(outcome.record), "path": str(out)})
    elif json_out:
        print_json({"draft": True, "missing": list(outcome.missing), "path": str(out)})
    tell_outcome(outcome, draft)


def register(root: typer.Typer) -> None:
    """Add the ``certificate`` command group to the application."""
    root.add_typer(app, name="certificate")
