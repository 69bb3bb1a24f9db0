"""What the commands that write a certificate share: configuration, budget, decisions, number.

The user configuration (``axiscal config``) and a job file are merged here, the uncertainty
budget and the decisions are formed by the standards modules, and the certificate itself is a
pure function in :mod:`axiscal.report.certificate`.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
from pathlib import Path
from typing import Any

import typer

__all__ = ["JOB", "RULE", "PAPER", "load_config", "decisions_for", "info_for"]

JOB = typer.Option(None, "--job", help="Job file (TOML): customer, machine, test conditions, tolerances, uncertainty inputs, report number; overrides the user configuration (axiscal config).")
RULE = typer.Option(None, "--rule", help="Decision rule for tolerances: iso14253-1 (conformance proven with U; default) or simple (simple acceptance, stated on the certificate).")
PAPER = typer.Option(None, "--paper", help="Paper of a PDF report: A4 (default) or Letter.")


def load_config(job: Path | None) -> dict[str, Any]:
    """The user configuration with the job file on top."""
    from axiscal.io.user_config import load_job, load_user_config, merge

    cfg = load_user_config()
    return merge(cfg, load_job(job)) if job is not None else cfg


def decisions_for(values, budget, tolerances: dict, cfg: dict, rule: str | None):
    """Tolerances of the command line over those of the configuration, decided by the rule."""
    from axiscal.standards.iso14253_1 import RULE_TEXT, _rule, decide_all

    tol = {**cfg.get("tolerance", {}), **tolerances}
    r = _rule(rule or cfg.get("certificate", {}).get("rule", "iso14253-1"))
    return (decide_all(values, budget, tol, r) if tol else ()), r, RULE_TEXT[r]


def info_for(cfg: dict, job: Path | None, dataset_bytes: bytes, paper: str | None):
    """Certificate information: the configuration, today's date, a report number."""
    from axiscal.io.user_config import config_path, logo_data_uri
    from axiscal.report.certificate import certificate_info

    today = _dt.date.today()
    prefix = str(cfg.get("certificate", {}).get("number_prefix", "AXC-"))
    number = f"{prefix}{today:%Y%m%d}-{hashlib.sha256(dataset_bytes).hexdigest()[:6].upper()}"
    if paper is not None:
        cfg = {**cfg, "certificate": {**cfg.get("certificate", {}), "paper": paper}}
    where = job if job is not None and cfg.get("company", {}).get("logo") else config_path()
    return certificate_info(cfg, number=number, issued=today.isoformat(),
                            logo=logo_data_uri(cfg, where))


def write_certificate(path, dataset, result, cfg: dict, data_bytes: bytes, tolerances=None,
                      rule: str | None = None, paper: str | None = None, job: Path | None = None):
    """Budget, decisions and certificate of one positioning test, written to ``path``
    (.html or .pdf); returns the decisions."""
    from axiscal.report.certificate import positioning_certificate
    from axiscal.standards.iso230_9 import positioning_budget

    budget = positioning_budget(dataset, result, cfg.get("uncertainty"))
    decisions, _, rule_text = decisions_for(result.parameters(), budget, tolerances or {}, cfg, rule)
    info = info_for(cfg, job, data_bytes, paper)
    positioning_certificate(dataset, result, budget, info, decisions, rule_text).write(path)
    return decisions
