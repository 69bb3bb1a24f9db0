"""The words a certificate, a page and an audit trail use for a field of a configuration, a job
or the laboratory.

A configuration says ``[machine] name`` and ``[[instrument]] 1 due``; a customer's certificate
and the workbench say "Machine" and "Instrument 1: calibration due", the labels the certificate
prints beside the values (:mod:`axiscal.report.certificate`). :func:`field_label` turns one into
the other; :func:`value_text` writes a kept value (a list of address lines, a table) as a
person reads it, never as a Python or JSON literal.

Examples
--------
>>> field_label("[machine] name"), field_label("[company] name")
('Machine', 'Laboratory')
>>> field_label("[[instrument]] 1 due"), field_label("[uncertainty] e_ve_source")
('Instrument 1: calibration due', 'Source of E_VE')
>>> field_label("customer.address"), field_label("[uncertainty] laser_accuracy_ppm")
('Customer address', 'Uncertainty input: laser accuracy ppm')
>>> value_text(["Werkstr. 5", "12345 Berlin"])
'Werkstr. 5, 12345 Berlin'
>>> value_text({"name": "PM GmbH", "address": ["Werkstr. 1", "Stuttgart"]})
'name: PM GmbH; address: Werkstr. 1, Stuttgart'
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["FIELD_LABELS", "field_label", "key_label", "value_text"]

#: (table, key) -> the label the certificate prints for it.
FIELD_LABELS = {
    ("company", "name"): "Laboratory", ("company", "address"): "Laboratory address",
    ("company", "code"): "Laboratory code", ("company", "accreditation"): "Accreditation",
    ("company", "logo"): "Laboratory logo",
    ("customer", "name"): "Customer", ("customer", "address"): "Customer address",
    ("customer", "reference"): "Customer reference",
    ("machine", "name"): "Machine", ("machine", "maker"): "Maker",
    ("machine", "model"): "Model", ("machine", "serial"): "Serial number",
    ("machine", "location"): "Location", ("machine", "axis"): "Axis",
    ("conditions", "date"): "Date of test",
    ("conditions", "air_temperature"): "Air temperature (°C)",
    ("conditions", "material_temperature"): "Material temperature (°C)",
    ("conditions", "measuring_line"): "Location of the measuring line",
    ("conditions", "location"): "Location",
    ("operator", "name"): "Operator",
    ("certificate", "signatory"): "Approved by",
    ("certificate", "signatory_role"): "Approver's role",
    ("certificate", "specification"): "Specification",
    ("certificate", "rule"): "Decision rule", ("certificate", "paper"): "Paper",
    ("certificate", "number_pattern"): "Certificate number pattern",
    ("instrument", "name"): "name", ("instrument", "serial"): "serial number",
    ("instrument", "certificate"): "calibration certificate",
    ("instrument", "due"): "calibration due",
    ("signatory", "name"): "name", ("signatory", "role"): "role",
    ("uncertainty", "e_ve"): "E_VE (environmental variation)",
    ("uncertainty", "e_ve_source"): "Source of E_VE",
    ("uncertainty", "linear"): "Uncertainty inputs of linear axes",
    ("uncertainty", "rotary"): "Uncertainty inputs of rotary axes",
    ("uncertainty", "cmc"): "CMC",
}
#: A table's name where a key of it has no label of its own.
_TABLES = {"company": "Laboratory", "customer": "Customer", "machine": "Machine",
           "conditions": "Test conditions", "operator": "Operator",
           "certificate": "Certificate", "uncertainty": "Uncertainty input",
           "tolerance": "Tolerance", "instrument": "Instrument",
           "signatory": "Authorised signatory"}
_KEY = re.compile(r"^\[\[?(\w+)\]\]?\s*(?:(\d+)\s+)?(.*)$")


def field_label(what: str) -> str:
    """The label of a field named ``[table] key``, ``[[table]] N key`` or ``table.key`` (a key
    that is not one of a table: its words, underscores made spaces)."""
    text = str(what).strip()
    m = _KEY.match(text)
    if m:
        table, n, key = m.group(1), m.group(2), m.group(3).strip()
    elif "." in text:
        table, _, key = text.partition(".")
        n = None
    else:
        return text.replace("_", " ")
    if table == "tolerance":
        return f"Tolerance {key}".strip()
    if n is not None or table in ("instrument", "signatory"):
        words = FIELD_LABELS.get((table, key), key.replace("_", " "))
        return f"{_TABLES[table]}{' ' + n if n else ''}: {words}" if key else \
            f"{_TABLES[table]} {n or ''}".strip()
    if table.endswith("uncertainty"):         # [squareness_uncertainty], [ballbar_uncertainty]
        table = "uncertainty"
    key = key.split(".")[-1] if table != "uncertainty" else key
    if (table, key) in FIELD_LABELS:
        return FIELD_LABELS[(table, key)]
    if not key:
        return _TABLES.get(table, table.replace("_", " ").capitalize())
    head = _TABLES.get(table, table.replace("_", " ").capitalize())
    return f"{head}: {key.replace('_', ' ').replace('.', ' ')}"


#: A bare key of an audit entry's before/after -> its words.
_KEYS = {"e_ve": "E_VE", "e_ve_source": "source of E_VE", "sha256": "SHA-256",
         "company": "laboratory", "signatory": "authorised signatories",
         "instrument": "instrument", "uncertainty": "uncertainty inputs", "file": "file",
         "readings": "readings", "withdrawn": "withdrawn", "cmc": "CMC"}


def key_label(key: str) -> str:
    """A bare key (of an audit entry's values, a table's row) in words.

    >>> key_label("e_ve_source"), key_label("air_temperature")
    ('source of E_VE', 'air temperature')
    """
    k = str(key)
    return _KEYS.get(k, k.replace("_", " "))


def value_text(value: Any) -> str:
    """``value`` as a person reads it: a list joined by commas, a table as ``key: value``
    pairs, ``None`` as "—"."""
    if value is None or value == "":
        return "—"
    if isinstance(value, (list, tuple)):
        return ", ".join(value_text(v) for v in value)
    if isinstance(value, dict):
        return "; ".join(f"{key_label(k)}: {value_text(v)}" for k, v in value.items())
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
