"""The sign-off form's fields: their labels (the words the page and every message use), the
job and the laboratory they carry, and each missing item of a certificate named by the label of
the field that gives it, with a link to that field.

:func:`axiscal.report.certificate_content.missing_items` names what a certificate lacks in the
words of the configuration file and the command line (``[customer] name``); a person on the
page has only the form, so :func:`missing_fields` says each item by its field's label
(``Customer``) and links to it (``#f-customer_name``), and never shows a file's or an option's
name.
"""

from __future__ import annotations

import re

from axiscal.errors import InputError
from axiscal.web.inputs import form_number

__all__ = ["LABELS", "JOB_FIELDS", "LAB_FIELDS", "INSTRUMENTS", "INSTRUMENT_KEYS",
           "missing_fields", "lab_from_form", "lab_defaults", "plain", "checked_fields"]

#: Instrument rows of the form (``[[instrument]]`` of a job file).
INSTRUMENTS = 3
INSTRUMENT_KEYS = ("name", "serial", "certificate", "due")
#: Form field -> (table, key) of a job file.
JOB_FIELDS = {"customer_name": ("customer", "name"), "customer_address": ("customer", "address"),
              "machine_maker": ("machine", "maker"), "machine_model": ("machine", "model"),
              "machine_serial": ("machine", "serial"),
              "machine_location": ("machine", "location"),
              "date": ("conditions", "date"),
              "air_temperature": ("conditions", "air_temperature"),
              "material_temperature": ("conditions", "material_temperature"),
              "operator": ("operator", "name"),
              "signatory": ("certificate", "signatory"),
              "signatory_role": ("certificate", "signatory_role"),
              "specification": ("certificate", "specification")}
#: The laboratory's fields (kept in the history, :mod:`axiscal.store.laboratory`).
LAB_FIELDS = ("lab_name", "lab_address", "lab_code", "lab_signatories", "lab_e_ve", "lab_cmc")
#: The label of every field, as the page shows it.
LABELS = {
    "lab_name": "Laboratory name", "lab_address": "Laboratory address (one line each)",
    "lab_code": "Laboratory code (starts each certificate number)",
    "lab_signatories": "Authorised signatories (one a line: name, role)",
    "lab_e_ve": "E_VE declared [µm] (environmental variation, when no drift check is measured)",
    "lab_cmc": "CMC [µm] (the laboratory's least U per parameter, e.g. E=1.0, A=1.0, R=0.6)",
    "drift_check": "Drift check file (E_VE measured beside this test)",
    "customer_name": "Customer", "customer_address": "Customer address (one line each)",
    "machine_maker": "Maker", "machine_model": "Model", "machine_serial": "Serial number",
    "machine_location": "Location of the calibration",
    "date": "Date of test", "air_temperature": "Air temperature [°C]",
    "material_temperature": "Material temperature [°C]",
    "operator": "Operator (carried out the test)",
    "signatory": "Approved by (authorised signatory)",
    "signatory_role": "Approver's role",
    "specification": "Specification (contract or standard)",
    "amend_reason": "Reason for the amendment",
    "save_for_approval": "Save for approval",
    **{f"instrument{i}_{k}": f"Instrument {i}: " + w for i in range(1, INSTRUMENTS + 1)
       for k, w in (("name", "name"), ("serial", "serial"),
                    ("certificate", "calibration certificate"), ("due", "due (YYYY-MM-DD)"))},
}

#: (pattern in an item of ``missing_items``, field) in the order they are tried.
_FIELD_OF = (
    (r"^laboratory identity", "lab_name"),
    (r"\[customer\] name", "customer_name"), (r"\[customer\] address", "customer_address"),
    (r"\[machine\] maker", "machine_maker"), (r"\[machine\] model", "machine_model"),
    (r"\[machine\] serial", "machine_serial"), (r"^location of the calibration",
                                                 "machine_location"),
    (r"\[conditions\] date", "date"), (r"air_temperature", "air_temperature"),
    (r"material_temperature", "material_temperature"),
    (r"^instruments used", "instrument1_name"),
    (r"(?i)e_ve", "drift_check"),
    (r"\[certificate\] specification", "specification"),
    (r"^approval by an authorised signatory: you ", "save_for_approval"),
    (r"^preparation by another account", "save_for_approval"),
    (r"^approval by an authorised signatory", "lab_signatories"),
    (r"^approval by a second person", "operator"),
    (r"\[operator\] name", "operator"),
    (r"signatory_role", "signatory_role"), (r"\[certificate\] signatory", "signatory"),
)
#: A configuration file's hint in brackets, and its remaining table and option words.
_HINTS = re.compile(r"\s*\((?:[^()]*?)(?:\[|--|axiscal )[^()]*\)")
_CONFIG_WORDS = re.compile(r"\s*\[\[?\w+\]\]?( \w+)?|\s*--[\w-]+(?:[ =][A-Z_]+(?:=VALUE)?)?")
#: ``[table] key`` of a job file -> the label of the field that gives it.
_AS_LABEL = {**{f"[{t}] {k}": f for f, (t, k) in JOB_FIELDS.items()},
             "[company] name": "lab_name", "[company] address": "lab_address",
             "[company] code": "lab_code"}


#: Fields of several lines (one address line, one signatory each): line breaks allowed.
MULTI_LINE = frozenset({"customer_address", "lab_address", "lab_signatories", "amend_reason",
                        "reason"})


def checked_fields(values: dict) -> dict:
    """``values`` if no field holds a control character (C0, C1, DEL) or a bidirectional
    control, a field of :data:`MULTI_LINE` none but line breaks: the rule of every text
    axiscal writes (:func:`axiscal.store.limits.checked_text`), each field named by its label.

    Raises
    ------
    InputError
        ``Customer 'Kunde\\x1b[31mAG' holds a control character U+001B (ESC); ...``
    """
    from axiscal.store.limits import checked_text

    for field, text in values.items():
        if isinstance(text, str):
            checked_text(text, LABELS.get(field, field), single_line=field not in MULTI_LINE)
    return values


def plain(text: str) -> str:
    """A message in the form's words: a configuration file's hints in brackets left out, a
    ``[table] key`` named by its field's label, no table or option name left."""
    out = _HINTS.sub("", text)
    for ref, field in _AS_LABEL.items():
        out = out.replace(ref, LABELS[field])
    out = _CONFIG_WORDS.sub("", out)
    out = re.sub(r"\s*;\s*(?=[.;]|$)", "", out)
    return re.sub(r"\s{2,}", " ", out).strip(" ;:")


def missing_fields(missing, values: dict, signed_in: bool = False) -> list[tuple]:
    """(label, anchor, what is wrong) of each missing item: the label of the form field that
    gives it and ``#f-FIELD`` (both "" for an item no field gives, such as a U the readings
    make zero), in the page's words only.

    ``values`` are the form's (to find the instrument row an item names); ``signed_in``: the
    approver is the signed-in account, so an approval item points at the signatories' list."""
    out = []
    for item in missing:
        field = next((f for pat, f in _FIELD_OF if re.search(pat, item)), "")
        row = re.search(r"instrument '([^']*)'", item)
        if row:
            i = next((i for i in range(1, INSTRUMENTS + 1)
                      if values.get(f"instrument{i}_name", "").strip() == row.group(1)), 1)
            key = "certificate" if "certificate number" in item else "due"
            field = f"instrument{i}_{key}"
        if field in ("signatory", "signatory_role") and signed_in:
            field = "lab_signatories"
        words = plain(item)
        if field == "drift_check":
            words = ("E_VE, the environmental variation: upload the drift check measured "
                     "beside this test, or declare E_VE in the laboratory's fields")
        if field == "lab_name":
            words = "the laboratory's name and address"
        out.append((LABELS.get(field, ""), f"f-{field}" if field else "", words))
    return out


def lab_defaults(lab: dict) -> dict:
    """The laboratory's fields of the form, filled from a configuration's tables."""
    c = lab.get("company", {})
    signs = lab.get("signatory") or []
    signs = signs if isinstance(signs, list) else [signs]
    unc = lab.get("uncertainty", {}) or {}
    cmc = (unc.get("linear") or {}).get("cmc") or {}
    e_ve = unc.get("e_ve") if str(unc.get("e_ve_source", "declared")) == "declared" else None
    return {"lab_name": str(c.get("name", "")),
            "lab_address": "\n".join(map(str, c.get("address", []))) if isinstance(
                c.get("address"), list) else str(c.get("address", "")),
            "lab_code": str(c.get("code", "")),
            "lab_signatories": "\n".join(
                ", ".join(x for x in (str(s.get("name", "")), str(s.get("role", ""))) if x)
                for s in signs if isinstance(s, dict)),
            "lab_e_ve": "" if e_ve is None else f"{float(e_ve):g}",
            "lab_cmc": ", ".join(f"{k}={float(v):g}" for k, v in cmc.items())}


def lab_from_form(values: dict, kept: dict, instruments: list) -> dict:
    """The laboratory's tables from the form's fields, over ``kept`` (the history's): the
    company, the signatories, the instruments of the form's rows, E_VE declared and the CMC
    of linear axes.

    Raises
    ------
    InputError
        A signatory line without a name, a CMC that is not NAME=NUMBER, E_VE not a number;
        each named by its field's label.
    """
    checked_fields(values)
    lab = {k: (dict(v) if isinstance(v, dict) else v) for k, v in kept.items()}
    company = dict(lab.get("company", {}))
    for field, key in (("lab_name", "name"), ("lab_code", "code")):
        if values.get(field, "").strip():
            company[key] = values[field].strip()
    lines = [x.strip() for x in values.get("lab_address", "").splitlines() if x.strip()]
    if lines:
        company["address"] = lines
    if company:
        lab["company"] = company
    signs = []
    for line in values.get("lab_signatories", "").splitlines():
        if not line.strip():
            continue
        name, _, role = line.partition(",")
        if not name.strip():
            raise InputError(f"{LABELS['lab_signatories']}: the line {line.strip()!r} has no "
                             "name; write NAME, ROLE")
        signs.append({"name": name.strip(), "role": role.strip()})
    if signs:
        lab["signatory"] = signs
    if instruments:
        lab["instrument"] = instruments
    unc = dict(lab.get("uncertainty", {}) or {})
    if values.get("lab_e_ve", "").strip():
        unc.update(e_ve=form_number(values["lab_e_ve"], LABELS["lab_e_ve"], 0.0, 1e4),
                   e_ve_source="declared")
    cmc = {}
    for part in re.split(r"[,;\s]+", values.get("lab_cmc", "").strip()):
        if not part:
            continue
        name, eq, num = part.partition("=")
        if not eq or not name.strip():
            raise InputError(f"{LABELS['lab_cmc']}: {part!r}; write PARAMETER=VALUE, e.g. E=1.0")
        cmc[name.strip()] = form_number(num, f"CMC of {name.strip()} [µm]", 0.0, 1e4)
    if cmc:
        unc["linear"] = {**dict(unc.get("linear", {}) or {}), "cmc": cmc}
    if unc:
        lab["uncertainty"] = unc
    return lab
