"""An archive carries everything the history holds for a certificate (issue 40): the laboratory
kept in the history (identity, signatories, instruments, declared E_VE, CMC; ISO/IEC 17025:2017
§7.8.2.1, §6.5) with its audit trail, and the drift checks kept beside their tests, their files
byte for byte (E_VE measured, ISO 230-2:2014 Annex A.5). ``history export`` then ``history
import`` into an empty history gives the same laboratory, drift checks, records, register and
the same certificate; hostile archives are refused in one line with nothing stored, and a
laboratory or drift check the history imported into holds otherwise is refused by the rule of
:mod:`axiscal.store.archive_laboratory`."""

from __future__ import annotations

import copy
import hashlib
import json
import tomllib
import zipfile
from importlib import resources

import pytest
from sqlalchemy import select

from axiscal.errors import AxiscalError
from axiscal.io.csv import format_positioning_csv
from axiscal.procedures.positioning import simulate_from_config
from axiscal.report.issue import reissue_certificate, write_certificate
from axiscal.store import open_store
from axiscal.store import corrections as cx
from axiscal.store.archive import export_history, import_history
from axiscal.store.laboratory import (add_drift_check, drift_checks, laboratory,
                                      set_laboratory, signoff_config)
from axiscal.store.models import DriftCheck, Laboratory
from tests.store.test_archive_trust import rewrite

#: The laboratory as the workbench keeps it (the tables of tests/report/certificate_jobs.py's
#: COMPLETE configuration that identify the laboratory), with a CMC and a declared E_VE.
LAB = {"company": {"name": "Precision Metrology GmbH", "address": ["Messweg 12", "Stuttgart"],
                   "code": "PM"},
       "signatory": [{"name": "Dr. M. Braun", "role": "Head of laboratory"}],
       "instrument": [{"name": "Laser interferometer", "serial": "L-1", "certificate": "C-77",
                       "due": "2027-04-30"}],
       "uncertainty": {"e_ve": 0.8, "e_ve_source": "declared", "linear": {"cmc": {"E": 1.0}}}}
#: The job of the sign-off (the form's fields).
JOB = {"operator": {"name": "J. Keller"},
       "customer": {"name": "Example Machining AG", "address": ["Industriestr. 4", "Esslingen"]},
       "machine": {"maker": "Example", "model": "VMC-800", "serial": "VMC8-0042",
                   "location": "Example Machining AG, hall 2"},
       "conditions": {"date": "2026-11-20", "air_temperature": 20.4,
                      "material_temperature": 20.6, "measuring_line": "table centre",
                      "feed": "2000 mm/min", "dwell": "4 s"},
       "certificate": {"signatory": "Dr. M. Braun", "specification": "Contract 4711"}}
TOL = {"E": 25.0, "R": 8.0}
TODAY = "2026-11-24"
#: Drift checks: E_VE = 0.4 − (−0.2) = 0.6 µm and 0.5 − 0.1 = 0.4 µm (the range of the
#: readings, ISO 230-2:2014 Annex A.5).
DC1 = b"time_s,reading\n0,0.1\n60,0.4\n120,-0.2\n"
DC2 = b"reading\n0.1\n0.5\n0.3\n"


def _positioning(seed: int) -> bytes:
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    return format_positioning_csv(simulate_from_config(cfg, seed=seed).dataset).encode()


def _certificate(store, tid, path, register=True):
    """The sign-off of stored test ``tid`` from the history (laboratory and drift check kept
    there): issued through the register, or (``register=False``) the page without a number."""
    t = store.get(tid)
    rec = t.record()
    cfg = signoff_config(store, t, {}, copy.deepcopy(JOB))
    return write_certificate(path, rec.dataset, rec.evaluation, cfg, t.raw, TOL,
                             store=store if register else None, filename=t.summary.filename,
                             today=TODAY)


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    """A history with the laboratory (edited once: two audit entries), a positioning test with
    two drift checks uploaded beside it (the newest gives E_VE) and its certificate, and a
    second test stored with its drift check by ``iso230-2 --drift-check --history`` (readings
    kept, no file); exported to ``h.zip``."""
    d = tmp_path_factory.mktemp("lab")
    src = open_store(f"sqlite:///{d / 'src.sqlite'}")
    t1 = src.add(_positioning(1), "x.csv", uncertainty={"resolution": 0.1}).id
    t2 = src.add(_positioning(2), "y.csv", uncertainty={"resolution": 0.1},
                 drift_check=(DC2, "dc-y.csv")).id
    set_laboratory(src, {**LAB, "company": {**LAB["company"], "name": "PM GmbH"}}, by="eng",
                   reason="laboratory entered")
    set_laboratory(src, LAB, by="eng", reason="name as registered")
    add_drift_check(src, t1, DC2, "dc-old.csv", by="J. Keller")
    add_drift_check(src, t1, DC1, "dc.csv", by="J. Keller")
    out = _certificate(src, t1, d / "c.html")
    assert not out.draft and out.number == "PM-2026-00001", out.missing
    assert export_history(src, d / "h.zip") == 2
    return d, src, {"t1": t1, "t2": t2}


def _copy(path, to):
    """A copy of the SQLite history ``path`` (the backup API: its journal too), opened."""
    import sqlite3

    with sqlite3.connect(path) as a, sqlite3.connect(to) as b:
        a.backup(b)
    return open_store(f"sqlite:///{to}")


def _dst(tmp_path, name="dst.sqlite"):
    return open_store(f"sqlite:///{tmp_path / name}")


def _rows(store, model):
    with store._session() as s:
        return list(s.scalars(select(model).order_by(model.id)))


def _by_sha(store) -> dict:
    return {store.get(t.id).sha256: store.get(t.id) for t in store.tests()}


def _empty(store) -> None:
    assert store.tests() == [] and cx.audit(store) == [] and store.certificates() == []
    assert _rows(store, Laboratory) == [] and _rows(store, DriftCheck) == []


def test_export_import_keeps_laboratory_drift_checks_and_the_certificate(source, tmp_path,
                                                                          db_url):
    """Into an empty history on SQLite and on PostgreSQL."""
    d, src, ids = source
    with zipfile.ZipFile(d / "h.zip") as z:
        head = json.loads(z.read("history.jsonl").decode().splitlines()[0])
        files = sorted(n for n in z.namelist() if n.startswith("drift_checks/"))
    assert head == {"format": "axiscal.history/3", "tests": 2, "audit": 4, "certificates": 1,
                    "laboratory": 1, "drift_checks": 2}
    assert files == sorted(f"drift_checks/{hashlib.sha256(b).hexdigest()}" for b in (DC1, DC2))
    dst = open_store(db_url)
    assert import_history(dst, d / "h.zip") == (2, 0)
    # the laboratory, field by field, with who kept it and when
    assert laboratory(dst) == laboratory(src) == LAB
    (a,), (b,) = _rows(src, Laboratory), _rows(dst, Laboratory)
    assert (a.updated, a.updated_by) == (b.updated, b.updated_by)
    # the drift checks: files byte for byte, E_VE, readings, who and when, newest first
    s_sha, d_sha = _by_sha(src), _by_sha(dst)
    t1 = next(s for s, t in s_sha.items() if t.summary.id == ids["t1"])
    fields = ("filename", "sha256", "e_ve", "readings", "created", "by")
    got = [[getattr(r, f) for f in fields] for r in drift_checks(dst, d_sha[t1].summary.id)]
    assert got == [[getattr(r, f) for f in fields] for r in drift_checks(src, ids["t1"])]
    assert [r[:3] for r in got] == [["dc.csv", hashlib.sha256(DC1).hexdigest(), 0.6],
                                    ["dc-old.csv", hashlib.sha256(DC2).hexdigest(),
                                     pytest.approx(0.4, abs=1e-15)]]
    assert sorted(hashlib.sha256(r.raw).hexdigest() for r in _rows(dst, DriftCheck)) == \
        sorted(hashlib.sha256(b).hexdigest() for b in (DC1, DC2))
    # each test's record: the same E_VE (measured), budget, quantities and drift check kept
    for sha, t in s_sha.items():
        assert d_sha[sha].result == t.result
        assert d_sha[sha].result["uncertainty_inputs"]["e_ve_source"] == "drift check"
        assert d_sha[sha].record().budget.U("E") == t.record().budget.U("E")
    assert d_sha[t1].result["uncertainty_inputs"]["e_ve"] == 0.6
    # the register, and the audit trail of the laboratory and the drift checks
    (c,), (c2,) = src.certificates(), dst.certificates()
    assert (c.number, c.status, c.laboratory, c.sha256) == (c2.number, c2.status,
                                                            c2.laboratory, c2.sha256)
    assert dst.certificate(c.number).document == src.certificate(c.number).document
    trail = [(e.at, e.by, e.action, e.reason, e.new) for e in cx.audit(src)]
    assert [(e.at, e.by, e.action, e.reason, e.new) for e in cx.audit(dst)] == trail
    assert [e[2] for e in trail].count("laboratory") == 2
    # the certificate made again from each history: the same page, byte for byte
    a = _certificate(src, ids["t1"], tmp_path / "a.html", register=False)
    b = _certificate(dst, d_sha[t1].summary.id, tmp_path / "b.html", register=False)
    assert a.missing == b.missing and len(a.missing) == 1       # only the number (no register)
    assert a.path.read_bytes() == b.path.read_bytes()
    assert "0.6" in b.path.read_text() and "Precision Metrology GmbH" in b.path.read_text()
    # and its amendment, issued by each register (the source's copy): the same document
    a = reissue_certificate(_copy(d / "src.sqlite", tmp_path / "copy.sqlite"), c.number,
                            "date corrected", tmp_path / "a2.html", today=TODAY)
    b = reissue_certificate(dst, c.number, "date corrected", tmp_path / "b2.html", today=TODAY)
    assert a.number == b.number == "PM-2026-00002"
    assert a.path.read_bytes() == b.path.read_bytes()
    # once more: nothing added twice
    assert import_history(dst, d / "h.zip") == (0, 2)
    assert len(_rows(dst, DriftCheck)) == 2 and len(_rows(dst, Laboratory)) == 1


def test_a_history_keeping_another_laboratory_refuses_the_archive(source, tmp_path):
    """The rule: another laboratory in the history imported into refuses the archive (which
    laboratory certifies is its decision, never an import's); nothing of it is stored."""
    d, src, ids = source
    dst = _dst(tmp_path, "other-lab.sqlite")
    set_laboratory(dst, {"company": {"name": "Other Lab", "code": "OL"}}, by="x", reason="ours")
    with pytest.raises(AxiscalError, match=r"another laboratory \(OL\) than the archive's "
                       r"\(company, instrument, signatory, uncertainty differ\)"):
        import_history(dst, d / "h.zip")
    assert dst.tests() == [] and dst.certificates() == [] and len(cx.audit(dst)) == 1
    assert laboratory(dst) == {"company": {"name": "Other Lab", "code": "OL"}}


def test_drift_checks_of_a_test_held_before_are_merged(source, tmp_path):
    """The rule: the history imported into holds the test already, without drift checks (a
    backup refreshed from an earlier export); the archive's drift checks are added and the
    test's record is made again with the newest one's E_VE over the inputs it was stored with,
    as the test's page does: the same record, E_VE 0.6 µm, as the source's."""
    d, src, ids = source
    dst = _dst(tmp_path, "had-test.sqlite")
    own = dst.add(src.get(ids["t1"]).raw, "x.csv", uncertainty={"resolution": 0.1})
    assert "drift_check" not in dst.get(own.id).result
    assert import_history(dst, d / "h.zip") == (1, 1)
    assert [r.filename for r in drift_checks(dst, own.id)] == ["dc.csv", "dc-old.csv"]
    assert dst.get(own.id).result == src.get(ids["t1"]).result
    assert dst.get(own.id).result["uncertainty_inputs"]["e_ve"] == 0.6
    assert [a.action for a in cx.audit(dst, test_id=own.id)].count("drift-check") == 2


def test_one_machines_archive_carries_the_laboratory_and_its_trail(source, tmp_path):
    """``history export --machine``: the laboratory goes with the machine's tests, with the
    audit entries of its edits (they name no machine)."""
    d, src, ids = source
    machine = src.get(ids["t1"]).summary.machine
    assert export_history(src, tmp_path / "m.zip", machine=machine) == 2
    with zipfile.ZipFile(tmp_path / "m.zip") as z:
        head = json.loads(z.read("history.jsonl").decode().splitlines()[0])
        actions = [json.loads(x)["action"] for x in z.read("audit.jsonl").decode().splitlines()]
    assert (head["laboratory"], head["drift_checks"]) == (1, 2)
    assert actions.count("laboratory") == 2 and actions.count("drift-check") == 2
    dst = _dst(tmp_path)
    assert import_history(dst, tmp_path / "m.zip") == (2, 0) and laboratory(dst) == LAB


def test_an_archive_of_format_2_imports_and_a_newer_one_is_refused(source, tmp_path):
    d, _, _ = source

    def as_v2(lines):
        head = json.loads(lines[0])
        head["format"] = "axiscal.history/2"
        del head["laboratory"], head["drift_checks"]
        return [json.dumps(head)] + lines[1:]

    with zipfile.ZipFile(d / "h.zip") as z:
        new = [n for n in z.namelist() if n.startswith("drift_checks") or n.startswith("lab")]
    old = rewrite(d / "h.zip", tmp_path / "v2.zip", jsonl=as_v2, drop=new)
    dst = _dst(tmp_path)
    assert import_history(dst, old) == (2, 0)
    assert _rows(dst, Laboratory) == [] and _rows(dst, DriftCheck) == []
    # the tests' records still carry the E_VE their drift checks measured
    assert sorted(t.result["uncertainty_inputs"]["e_ve"] for t in _by_sha(dst).values()) == \
        pytest.approx([0.4, 0.6], abs=1e-15)

    def as_v4(lines):
        return [lines[0].replace("axiscal.history/3", "axiscal.history/4")] + lines[1:]

    newer = rewrite(d / "h.zip", tmp_path / "v4.zip", jsonl=as_v4)
    dst = _dst(tmp_path, "v4.sqlite")
    with pytest.raises(AxiscalError, match="format axiscal.history/4 was written by a newer "
                       "axiscal than this one, which reads axiscal.history/1 … "
                       "axiscal.history/3; update axiscal") as err:
        import_history(dst, newer)
    assert "\n" not in str(err.value)
    _empty(dst)


def _line(name, change, which=0):
    """``name``'s line ``which`` changed by ``change(entry)`` (in place)."""
    def mutate(z):
        lines = z.read(name).decode().splitlines()
        e = json.loads(lines[which])
        change(e)
        lines[which] = json.dumps(e)
        return "\n".join(lines) + "\n"
    return name, mutate


def _set(key, value):
    return lambda e: e.__setitem__(key, value)


def _lab(path, value):
    def change(e):
        t = e["tables"]
        *head, last = path
        for k in head:
            t = t[k]
        t[last] = value
    return _line("laboratory.jsonl", change)


def _no_test(e):
    e["test"] = "0" * 64


def _record_drift(z):
    """Every record's drift check given readings that are not numbers: the test stored with
    its readings only (no file) is refused; the other's record is made from its file."""
    lines = z.read("history.jsonl").decode().splitlines()
    records = [json.loads(x) for x in lines[1:]]
    assert sum(bool(r["drift_check"]) for r in records) == 2
    for r in records:
        r["drift_check"]["readings"] = ["x", 1]
    return "\n".join([lines[0], *map(json.dumps, records)]) + "\n"


def _two_labs(z):
    """Two laboratories, and the header announcing two."""
    lines = z.read("history.jsonl").decode().splitlines()
    lines[0] = lines[0].replace('"laboratory": 1', '"laboratory": 2')
    return {"laboratory.jsonl": z.read("laboratory.jsonl").decode() * 2,
            "history.jsonl": "\n".join(lines) + "\n"}


HOSTILE = {
    "drift check E_VE a string": (_line("drift_checks.jsonl", _set("e_ve", "0.6")),
                                  "'e_ve' is a JSON str, not a float"),
    "drift check readings 2^70": (_line("drift_checks.jsonl", _set("readings", 2**70)),
                                  "'readings' is a number of 22 digits"),
    "drift check E_VE 1e308": (_line("drift_checks.jsonl", _set("e_ve", 1e308)),
                               "states E_VE 1e\\+308 of 3 readings; its file gives 0.4 of 3"),
    "drift check E_VE NaN": (_line("drift_checks.jsonl", _set("e_ve", float("nan"))),
                             "'e_ve' is nan, not a finite number"),
    "drift check of a missing test": (_line("drift_checks.jsonl", _no_test),
                                      "its test '0000.*' is not in the archive"),
    "drift check by a line break": (_line("drift_checks.jsonl", _set("by", "A\nB")),
                                    "control character"),
    "drift check file not its own": (_line("drift_checks.jsonl", _set("file", "raw/x")),
                                     "'file' must be drift_checks/<its sha256>"),
    "drift check created not a date": (_line("drift_checks.jsonl", _set("created", "soon")),
                                       "'soon' is not a date and time"),
    "laboratory updated with an offset": (_line("laboratory.jsonl", _set(
        "updated", "2026-11-24T10:00:00+05:00")), "has an offset; the history keeps UTC"),
    "laboratory tables a list": (_line("laboratory.jsonl", _set("tables", [1])),
                                 "'tables' is a JSON list, not a dict"),
    "laboratory company a string": (_lab(["company"], "PM"), "'company' is a JSON str"),
    "laboratory CMC 10^400": (_lab(["uncertainty", "linear", "cmc", "E"], 10**400),
                              "uncertainty.linear.cmc.E is a whole number of 401 digits"),
    "laboratory CMC infinite": (_lab(["uncertainty", "e_ve"], float("inf")),
                                "uncertainty.e_ve is inf, not a finite number"),
    "laboratory name with a line break": (_lab(["company", "name"], "PM\nX"),
                                          "company.name 'PM\\\\nX' holds a control character"),
    "laboratory table unknown": (_lab(["customer"], {}), "'customer' is not one the laboratory"),
    "laboratory instrument without a name": (_lab(["instrument"], [{"serial": "1"}]),
                                             "has no name"),
    "two laboratories": (("laboratory.jsonl", _two_labs), "holds 2 laboratories"),
    "a record's kept drift check": (("history.jsonl", _record_drift),
                                    "readings are not a list of at least 2 finite numbers"),
}


@pytest.mark.parametrize("case", list(HOSTILE))
def test_a_hostile_archive_is_refused_in_one_line_with_nothing_stored(source, tmp_path, case):
    d, _, _ = source
    (name, change), words = HOSTILE[case]
    with zipfile.ZipFile(d / "h.zip") as z:
        data = change(z)
    data = data if isinstance(data, dict) else {name: data}
    head = data.pop("history.jsonl", None)
    bad = rewrite(d / "h.zip", tmp_path / "bad.zip", jsonl=head and head.encode(),
                  drop=tuple(data), extra=tuple(data.items()))
    dst = _dst(tmp_path)
    with pytest.raises(AxiscalError, match=words) as err:
        import_history(dst, bad)
    assert "\n" not in str(err.value).strip()
    _empty(dst)


def test_a_drift_check_file_missing_or_altered_is_refused(source, tmp_path):
    d, _, _ = source
    with zipfile.ZipFile(d / "h.zip") as z:
        name = sorted(n for n in z.namelist() if n.startswith("drift_checks/"))[0]
    for kw, words in ((dict(drop=(name,)), "is missing from the archive"),
                      (dict(drop=(name,), extra=((name, b"reading\n1\n2\n"),)),
                       "does not match its SHA-256")):
        bad = rewrite(d / "h.zip", tmp_path / "bad.zip", **kw)
        dst = _dst(tmp_path, f"{len(kw)}.sqlite")
        with pytest.raises(AxiscalError, match=words):
            import_history(dst, bad)
        _empty(dst)


def test_history_import_says_what_came_in_beside_the_tests(source, tmp_path):
    """``history import`` counts the laboratory, the drift-check files, the register's
    certificates and their documents and the audit entries it brought, not only the tests; run
    again, it says none came in (everything was kept)."""
    import re

    from typer.testing import CliRunner

    from axiscal.cli import app

    d, _src, _ids = source
    url = f"sqlite:///{tmp_path / 'cli.sqlite'}"
    r = CliRunner().invoke(app, ["history", "import", str(d / "h.zip"), "--db", url])
    assert r.exit_code == 0, r.output
    line = r.output.strip().splitlines()[-1]
    assert re.search(r"imported 2 tests from \S+h\.zip \(0 already stored\); 4 audit entries, "
                     r"1 laboratory record, 2 drift-check files, 1 certificates, 1 issued "
                     r"documents$", line), line
    r = CliRunner().invoke(app, ["history", "import", str(d / "h.zip"), "--db", url, "--json"])
    assert r.exit_code == 0, r.output
    assert {k: v for k, v in json.loads(r.stdout).items() if k != "archive"} == {
        "added": 0, "duplicates": 2, "audit": 0, "laboratory": 0, "drift_checks": 0,
        "certificates": 0, "documents": 0}
