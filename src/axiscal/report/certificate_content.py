"""What a certificate must carry before it is issued, and the text it cannot print.

:func:`missing_items` lists, in plain words, each mandatory item of ISO/IEC 17025:2017 §7.8.2.1
and §7.8.4.1 that a certificate lacks: the laboratory's name and address (c), a unique number
(b), the customer's name and contact (e), the item (f: maker, model, serial number), the date of
calibration (h) and of issue (i), the method (d), the conditions under which it was made
(§7.8.4.1 a: air and material temperature, measured), the measurement's metrological
traceability through the instruments' certificates (§7.8.4.1 c, §6.5; an instrument due before
the date of calibration breaks it), the results with their expanded uncertainty and coverage
factor (§7.8.4.1 a, JCGM 100:2008 §7.2.6: never zero), the decision rule and the specification
when a statement of conformity is given (§7.8.6.2) and the name and role of the person who
authorises it (§7.8.2.1 o). A certificate with any item missing is a DRAFT, never numbered.

:func:`check_dates` refuses a test dated after the date of issue; :func:`refuse_unrenderable`
refuses a name that no font of the certificate can draw (it would print as empty boxes).
"""

from __future__ import annotations

import datetime as _dt
import functools
import math
import re
import subprocess
import unicodedata
from typing import Any

from axiscal.errors import ConfigError, InputError

__all__ = ["missing_items", "check_dates", "parse_date", "refuse_unrenderable", "FONTS",
           "calibration_date", "measured_temperatures"]

#: The certificate's fonts, in the order of its CSS font-family: DejaVu Sans for Latin, Greek
#: and Cyrillic, Noto Sans CJK (Debian's fonts-noto-cjk) for Chinese, Japanese and Korean.
FONTS = ("DejaVu Sans", "Noto Sans CJK SC")
_PLACEHOLDERS = {"", "...", "…", "YYYY-MM-DD"}


def parse_date(text: Any, what: str) -> _dt.date:
    """``YYYY-MM-DD`` (or an ISO 8601 date and time) as a date; anything else names ``what``."""
    t = str(text).strip()
    try:
        return _dt.date.fromisoformat(t[:10])
    except ValueError:
        if re.fullmatch(r"\d{4}-\d{2}-\d{2}", t[:10]):        # the form is right, the day is not
            raise InputError(f"{what}: {t[:10]} is not a date (no such day in the "
                             "calendar)") from None
        raise InputError(f"{what} {t!r}: write it as YYYY-MM-DD") from None


def calibration_date(dataset, info) -> str:
    """The date of the test: the data file's, else the job's ``[conditions] date`` ('' if none)."""
    return str(dataset.metadata.date or info.conditions.get("date") or "")


def measured_temperatures(dataset, info) -> tuple[Any, Any]:
    """(air, material) temperature in °C as measured: the data file's environment, else the
    job's ``[conditions] air_temperature`` and ``material_temperature`` (None if neither)."""
    env, cond = dataset.metadata.environment, info.conditions
    air = env.air_temperature if env.air_temperature is not None else cond.get("air_temperature")
    mat = (sum(env.material_temperature) / len(env.material_temperature)
           if env.material_temperature else cond.get("material_temperature"))
    return air, mat


def check_dates(tested: str, issued: str) -> None:
    """Refuse a date of calibration after the date of issue (one line)."""
    if tested and issued and parse_date(tested, "date of test") > parse_date(issued,
                                                                              "date of issue"):
        raise InputError(f"date of test {tested} is after the date of issue {issued}: a "
                         "certificate reports a calibration already made")


def missing_items(dataset, result, budget, info, decisions, config_note: str = "") -> list[str]:
    """Each mandatory item the certificate lacks, in plain words ([] when it may be issued).

    ``config_note`` says why the user configuration identifies no laboratory (see
    :func:`axiscal.io.user_config.config_problem`): named when the laboratory's name or address
    is missing, or is the template's (a job file may carry them instead).
    """
    out = _identity(info, config_note)
    tested = calibration_date(dataset, info)
    if not tested:
        out.append("date of calibration (not in the data file; give [conditions] date)")
    air, mat = measured_temperatures(dataset, info)
    for name, v in (("air", air), ("material", mat)):
        if v is None:
            out.append(f"{name} temperature during the test, measured (not in the data file or "
                       f"the environment log; give [conditions] {name}_temperature)")
    out += _instruments(info, tested)
    out += _results(result, budget)
    if decisions and not info.specification:
        out.append("source of the specification the verdict is given against ([certificate] "
                   "specification: the contract, or the standard such as ISO 10791-2)")
    if not info.signatory:
        out.append("name of the person authorising the certificate ([certificate] signatory)")
    if not info.signatory_role:
        out.append("role of the person authorising the certificate ([certificate] "
                   "signatory_role)")
    return out


def _identity(info, config_note: str) -> list[str]:
    from axiscal.io.user_config import TEMPLATE_COMPANY

    c, m, out = info.company, info.machine, []
    if c.get("name") == TEMPLATE_COMPANY:
        out.append("laboratory identity: " + (config_note or f"[company] name is still the "
                                              f"template's {TEMPLATE_COMPANY!r}"))
    elif not c.get("name") or not c.get("address"):
        out.append("laboratory identity: " + (config_note or "[company] name and address"))
    cust = info.customer
    if not cust.get("name"):
        out.append("customer name ([customer] name)")
    if not cust.get("address"):
        out.append("customer address ([customer] address)")
    for key, what in (("maker", "maker"), ("model", "model"), ("serial", "serial number")):
        if not str(m.get(key, "")).strip():
            out.append(f"{what} of the machine calibrated ([machine] {key})")
    if not str(m.get("location") or info.conditions.get("location") or "").strip():
        out.append("location of the calibration: the laboratory or the customer's site "
                   "(ISO/IEC 17025:2017 §7.8.2.1 c; [machine] location)")
    return out


def _instruments(info, tested: str) -> list[str]:
    if not info.instruments:
        return ["instruments used, with their calibration certificates ([[instrument]])"]
    out = []
    for i in info.instruments:
        for key, what in (("certificate", "calibration certificate number"),
                          ("due", "calibration due date")):
            if str(getattr(i, key)).strip() in _PLACEHOLDERS:
                out.append(f"{what} of the instrument {i.name!r}")
        if str(i.due).strip() not in _PLACEHOLDERS and tested:
            due = parse_date(i.due, f"[[instrument]] {i.name!r} due")
            if due < parse_date(tested, "date of test"):
                out.append(f"a valid calibration of the instrument {i.name!r}: due {due}, "
                           f"overdue on the date of calibration {tested}")
    return out


def _results(result, budget) -> list[str]:
    out = [f"input of the uncertainty budget: {m}" for m in getattr(budget, "missing", ())]
    for name, v in result.parameters().items():
        U = budget.U(name) if v is not None else 1.0
        if U is None or not math.isfinite(U) or U <= 0:
            out.append(f"expanded uncertainty of {name} (zero or none; a zero uncertainty is "
                       "never a defensible statement, JCGM 100:2008 §7.2.6)")
    if not budget.k or budget.k <= 0:
        out.append("coverage factor k of the expanded uncertainty")
    return out


def refuse_unrenderable(texts: dict[str, Any]) -> None:
    """Refuse a text with a character none of :data:`FONTS` draws (one line naming it).

    ``texts`` maps where a text comes from (``[customer] name``) to the text. Each character is
    looked up in the cmap of the fonts the certificate uses (fontTools), as fontconfig would
    fall back; where a font is not installed its characters count as missing. Where fontconfig
    finds none of them (no ``fc-list``), nothing can be checked and nothing is refused.
    """
    cmaps = _cmaps()
    if not cmaps:
        return
    for where, text in texts.items():
        for ch in str(text):
            if ch.isspace() or unicodedata.category(ch) in ("Cc", "Cf"):
                continue
            if not any(ord(ch) in c for c in cmaps):
                raise ConfigError(f"{where}: the character {ch!r} (U+{ord(ch):04X}, "
                                  f"{unicodedata.name(ch, 'unnamed')}) is in no font of the "
                                  f"certificate ({', '.join(FONTS)}); it would print as an "
                                  "empty box")


@functools.lru_cache(maxsize=1)
def _cmaps() -> tuple[frozenset, ...]:
    from fontTools.ttLib import TTFont

    out = []
    for family in FONTS:
        try:
            found = subprocess.run(["fc-list", "--format", "%{file}|%{index}\n",
                                    f"{family}:style=Regular", ], capture_output=True,
                                   text=True, check=False).stdout.split()
            found = found or subprocess.run(["fc-list", "--format", "%{file}|%{index}\n",
                                             family], capture_output=True, text=True,
                                            check=False).stdout.split()
        except OSError:
            found = []
        if found:
            path, _, index = found[0].rpartition("|")
            out.append(frozenset(TTFont(path, fontNumber=int(index or 0), lazy=True)
                                 .getBestCmap()))
    return tuple(out)
