"""What the commands that write a certificate share: their options and how an outcome is told.

Building and issuing the certificate is library work (:mod:`axiscal.report.issue`); this module
only parses and renders.
"""

from __future__ import annotations

import typer

__all__ = ["JOB", "RULE", "PAPER", "DRAFT", "DRAFT_EXIT", "PREPARED_BY", "APPROVED_BY",
           "tell_outcome"]

JOB = typer.Option(None, "--job", help="Job file (TOML): customer, machine, test conditions (date, air and material temperature), tolerances (marked as supplied by the customer), specification; overrides the user configuration (axiscal config).")
RULE = typer.Option(None, "--rule", help="Decision rule for tolerances: iso14253-1 (conformance proven with U; default) or simple (simple acceptance, stated on the certificate).")
PAPER = typer.Option(None, "--paper", help="Paper of a PDF report: A4 (default) or Letter.")
DRAFT = typer.Option(False, "--draft", help="A certificate lacking a mandatory item (ISO/IEC 17025:2017 §7.8.2, §7.8.4) is written as a DRAFT either way; with --draft that is not an error (exit 0 instead of 3).")
PREPARED_BY = typer.Option("", "--prepared-by", help="Who prepared the certificate (default: the configuration's \\[operator] name); printed and kept in the register.")
APPROVED_BY = typer.Option("", "--approved-by", help="The authorised signatory who approves the issue (one of the configuration's \\[\\[signatory]] names; default \\[certificate] signatory); never the person who prepared it. Printed and kept in the register.")
#: Exit code of a command whose certificate came out as a DRAFT (without --draft).
DRAFT_EXIT = 3


def tell_outcome(outcome, draft_ok: bool) -> None:
    """Say what was written: the number and register of an issued certificate, or each missing
    item of a DRAFT (stderr; exit 3 unless ``draft_ok``)."""
    from axiscal.cli._common import note

    if not outcome.draft:
        r = outcome.record
        extra = f", replaces {r.replaces}" if r.replaces else ""
        extra += f"; prepared by {r.prepared_by}, approved by {r.approved_by}"
        note(f"issued certificate {r.number}{extra} (SHA-256 {r.sha256[:16]}…, kept in the "
             f"register with test {r.test_id}): {outcome.path}")
        return
    typer.echo(f"axiscal: {outcome.path} is a DRAFT, not a certificate; missing:", err=True)
    for m in outcome.missing:
        typer.echo(f"  - {m}", err=True)
    if not draft_ok:
        raise typer.Exit(DRAFT_EXIT)
