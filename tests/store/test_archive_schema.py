"""Archive records validated by the register's invariants before anything is stored (issue 39).

Each mutation is one a hostile or careless archive held when the issue was filed: an imported
certificate ``counter`` of 2^70 (a traceback), 2^63 − 1 (every later issue failed), −5 (numbers
``LAB-2026--0004``), a ``number`` not matching its counter (every later issue refused, no way
out), ``status: "revoked"``, a ``replaces`` naming no certificate, ``"tests": "2"`` (skipped the
truncation check), a lone surrogate or a line break in a machine name. Every one refuses the
archive naming the field, and the database is left as it was.
"""

from __future__ import annotations

import json
import zipfile

import pytest

from axiscal.errors import AxiscalError
from axiscal.store import open_store
from axiscal.store import corrections as cx
from axiscal.store.archive import export_history, import_history
from tests.store.test_archive_records import _history
from tests.store.test_archive_trust import rewrite


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    d = tmp_path_factory.mktemp("schema")
    src, _ = _history(d)
    export_history(src, d / "h.zip")
    return d / "h.zip"


def _certs(field, value, which=-1):
    def change(z, name):
        lines = z.read(name).decode().splitlines()
        e = json.loads(lines[which])
        e[field] = value
        lines[which] = json.dumps(e)
        return "\n".join(lines) + "\n"
    return "certificates.jsonl", change


def _record(field, value):
    def change(z, name):
        lines = z.read(name).decode().splitlines()
        e = json.loads(lines[1])
        e[field] = value
        lines[1] = json.dumps(e)      # ensure_ascii: a surrogate as \udcff, as JSON allows
        return "\n".join(lines) + "\n"
    return "history.jsonl", change


def _head(field, value):
    def change(z, name):
        lines = z.read(name).decode().splitlines()
        e = json.loads(lines[0])
        e[field] = value
        return "\n".join([json.dumps(e)] + lines[1:]) + "\n"
    return "history.jsonl", change


CASES = {
    "counter 2^70": (_certs("counter", 2**70), "counter 1180591620717411303424 is outside"),
    "counter 2^63-1": (_certs("counter", 2**63 - 1), "is outside 1 … 1,000,000,000"),
    "counter -5": (_certs("counter", -5), "counter -5 is outside"),
    "counter a string": (_certs("counter", "2"), "'counter' is a JSON str"),
    "number not its counter": (_certs("number", "PM-2026-00009"), "does not hold its counter"),
    "status revoked": (_certs("status", "revoked"), "status 'revoked' is not one of"),
    # the certificate it replaced is then superseded by none: refused at whichever comes first
    "replaces nothing": (_certs("replaces", "PM-2026-99999"), "no other certificate|by none|"
                         "no certificate of the archive replaces"),
    "replaces itself": (_certs("replaces", "PM-2026-00002"), "no other certificate|"
                        "no certificate of the archive replaces"),
    "superseded by none": (_certs("replaces", ""), "superseded, but no certificate"),
    "number with a line break": (_certs("number", "PM-2026-00002\nX"), "control character"),
    "tests a string": (_head("tests", "2"), "'tests' is a JSON str"),
    "machine with a surrogate": (_record("machine", "VMC\udcff"), "not UTF-8 text"),
    "machine with a line break": (_record("machine", "VMC\nX"), "control character"),
    "instrument of 5000 characters": (_record("instrument", "x" * 5000), "at most 200"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_mutated_archive_is_refused_before_any_row(archive, tmp_path, case):
    (name, change), words = CASES[case]
    with zipfile.ZipFile(archive) as z:
        data = change(z, name)
    if name == "history.jsonl":
        bad = rewrite(archive, tmp_path / "bad.zip", jsonl=data.encode())
    else:
        bad = rewrite(archive, tmp_path / "bad.zip", drop=(name,), extra=((name, data),))
    dst = open_store(f"sqlite:///{tmp_path / 'dst.sqlite'}")
    with pytest.raises(AxiscalError, match=words) as err:
        import_history(dst, bad)
    assert "\n" not in str(err.value).strip()
    assert dst.tests() == [] and cx.audit(dst) == [] and dst.certificates() == []


def test_the_unmutated_archive_imports(archive, tmp_path):
    """The checks refuse none of what axiscal itself writes."""
    dst = open_store(f"sqlite:///{tmp_path / 'dst.sqlite'}")
    assert import_history(dst, archive) == (5, 0)
    assert len(dst.certificates()) == 2
