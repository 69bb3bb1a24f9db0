"""Issue 40, defect 4: one rule for every text axiscal writes into a certificate, the
laboratory or the history (:func:`axiscal.store.limits.checked_text`). A field holding a
control character (ESC starting a terminal colour, BEL, NUL) or a bidirectional control
(U+202E RIGHT-TO-LEFT OVERRIDE, U+2066 LEFT-TO-RIGHT ISOLATE; Unicode Standard Annex #9,
table 4) is refused in one line naming the field and the character, on the sign-off form and
in a job file of the command line, and nothing is kept: no certificate, no laboratory, no
file. An address keeps its line breaks and nothing else of them."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.web.app import create_app
from axiscal.web.signoff_form import LABELS

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
CHARS = {"ESC": "\x1b[31m", "BEL": "\x07", "NUL": "\x00", "U+202E": "\u202e", "U+2066": "\u2066"}
CODES = {"ESC": "U+001B", "BEL": "U+0007", "NUL": "U+0000", "U+202E": "U+202E",
         "U+2066": "U+2066"}
#: Every text field of the sign-off form -> where a job file gives it ((table, key), list table).
FIELDS = {"customer_name": ("customer", "name"), "customer_address": ("customer", "address"),
          "machine_maker": ("machine", "maker"), "machine_model": ("machine", "model"),
          "machine_serial": ("machine", "serial"), "machine_location": ("machine", "location"),
          "date": ("conditions", "date"), "operator": ("operator", "name"),
          "signatory": ("certificate", "signatory"),
          "signatory_role": ("certificate", "signatory_role"),
          "specification": ("certificate", "specification"),
          "instrument1_name": ("instrument", "name"),
          "instrument1_serial": ("instrument", "serial"),
          "instrument1_certificate": ("instrument", "certificate"),
          "instrument1_due": ("instrument", "due"),
          "lab_name": ("company", "name"), "lab_address": ("company", "address"),
          "lab_code": ("company", "code"), "lab_signatories": ("signatory", "name")}
GOOD = {"customer_name": "Kunde AG", "customer_address": "Werkstr. 5\n12345 Berlin",
        "machine_maker": "DMG", "machine_model": "DMU 50", "machine_serial": "S-1",
        "machine_location": "Hall 2", "date": "2026-03-02", "operator": "A. Operator",
        "signatory": "B. Signatory", "signatory_role": "Head of laboratory",
        "specification": "ISO 230-2", "instrument1_name": "Laser XL-80",
        "instrument1_serial": "L-1", "instrument1_certificate": "C-1",
        "instrument1_due": "2027-06-30", "lab_name": "Precision Metrology GmbH",
        "lab_address": "Werkstr. 1\n70173 Stuttgart", "lab_code": "PM",
        "lab_signatories": "B. Signatory, Head of laboratory", "tol_E": "30"}


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("ctl")
    (tmp / "config.toml").write_text('[certificate]\npaper = "A4"\n', encoding="utf-8")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("AXISCAL_CONFIG", str(tmp / "config.toml"))
        c = TestClient(create_app(f"sqlite:///{tmp / 'web.sqlite'}"),
                       base_url="http://127.0.0.1")
        c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
        r = c.post("/upload", data={"csrf": c.token, "machine": "VMC-800"},
                   files={"file": (ECMC.name, ECMC.read_bytes(), "text/plain")})
        assert r.status_code == 200 and "/tests/1" in str(r.url)
        c.store = c.app.state.store
        yield c


@pytest.mark.parametrize("char", CHARS)
@pytest.mark.parametrize("field", FIELDS)
def test_sign_off_form_refuses_a_control_character(bench, field, char):
    """Issue pressed with one field holding the character: a 400 page saying the field's
    label and the character's code point; no certificate, no laboratory kept."""
    value = GOOD[field].replace(" ", CHARS[char], 1) if " " in GOOD[field] else \
        GOOD[field] + CHARS[char]
    r = bench.post("/tests/1/signoff", data={"csrf": bench.token, "action": "issue",
                                             **{**GOOD, field: value}},
                   follow_redirects=False)
    assert r.status_code == 400, r.text[-2000:]
    said = re.sub(r"<[^>]+>", "", r.text).replace("&#39;", "'").replace("&#34;", '"')
    assert f"holds a control character {CODES[char]}" in said
    label = LABELS[field].replace("&", "&amp;")
    assert label.split(" (")[0] in said
    from axiscal.store.laboratory import laboratory

    assert bench.store.certificates() == [] and laboratory(bench.store) == {}


def test_sign_off_form_keeps_an_address_of_several_lines(bench):
    """A line break (the browser's CR LF) is an address's, not a control character."""
    from axiscal.web.signoff_form import checked_fields

    assert checked_fields({"customer_address": "Werkstr. 5\r\n12345 Berlin"})
    with pytest.raises(Exception, match=r"Customer 'Kunde\\nAG' holds a control character "
                                        r"U\+000A \(a line break\)"):
        checked_fields({"customer_name": "Kunde\nAG"})


def test_laboratory_page_and_rename_refuse_a_bidi_override(bench):
    """/laboratory and a machine's rename: U+202E refused (was printed reversed in a
    certificate's laboratory name), nothing changed."""
    r = bench.post("/laboratory", data={"csrf": bench.token, "lab_name": "Precision\u202eHbmG",
                                        "reason": "new name"})
    assert r.status_code == 400 and "U+202E (RIGHT-TO-LEFT OVERRIDE)" in r.text
    from axiscal.store.corrections import rename_machine
    from axiscal.store.laboratory import laboratory

    assert laboratory(bench.store) == {}
    with pytest.raises(Exception, match=r"U\+202E"):
        rename_machine(bench.store, "VMC-800", "VMC\u202e008", by="a", reason="typo")
    assert [m.name for m in bench.store.machines()] == ["VMC-800"]


def _job(field: str, value: str) -> str:
    """A job file giving ``value`` where the form's ``field`` is given."""
    import json

    table, key = FIELDS[field]
    text = json.dumps(value)             # \u001b ...: a TOML basic string's escapes too
    if table in ("instrument", "signatory"):
        return f"[[{table}]]\n" + ('name = "X"\n' if key != "name" else "") + f"{key} = {text}\n"
    if key == "address":
        return f'[{table}]\n{key} = ["Werkstr. 5", {text}]\n'
    return f"[{table}]\n{key} = {text}\n"


@pytest.mark.parametrize("char", CHARS)
@pytest.mark.parametrize("field", FIELDS)
def test_job_file_refuses_a_control_character(tmp_path, field, char):
    """The command line's job file (:func:`axiscal.io.user_config.load_job`, what
    ``--job`` reads): refused naming the file, ``[table] key`` and the character."""
    from axiscal.errors import InputError
    from axiscal.io.user_config import load_job

    p = tmp_path / "job.toml"
    p.write_text(_job(field, "A" + CHARS[char] + "B"), encoding="utf-8")
    table, key = FIELDS[field]
    with pytest.raises(InputError, match=rf"job.toml: \[{table}\] {key} .* holds a control "
                                         rf"character {re.escape(CODES[char])}"):
        load_job(p)


@pytest.mark.parametrize("char", ["ESC", "BEL", "U+202E"])
def test_certificate_issue_with_such_a_job_writes_nothing(tmp_path, monkeypatch, char):
    """``axiscal certificate issue 1 --job JOB --out C.html``: one line, exit 2, no file, no
    certificate in the register (the reviewer's ESC in the customer was printed in the PDF)."""
    from axiscal.cli import app
    from axiscal.store import open_store

    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    st = open_store(db)
    st.add(ECMC.read_bytes(), ECMC.name, machine="VMC-800")
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    (tmp_path / "job.toml").write_text(_job("customer_name", "Kunde" + CHARS[char] + "AG"),
                                       encoding="utf-8")
    r = CliRunner().invoke(app, ["certificate", "issue", "1", "--job", str(tmp_path / "job.toml"),
                                 "--out", str(tmp_path / "c.html"), "--db", db])
    assert r.exit_code == 2, r.output
    assert f"[customer] name 'Kunde" in r.stderr and CODES[char] in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "c.html").exists() and open_store(db).certificates() == []
