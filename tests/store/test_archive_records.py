"""An archive carries the record (issue 31; ISO/IEC 17025:2017 §7.5.2 and §8.4.2: records and
their amendments are kept and retrievable): ``history export`` writes the audit trail of the
corrections (renames, merges, edits, withdrawals with their reasons) and the certificate
register with the issued documents; ``history import`` restores them on SQLite and PostgreSQL,
all or nothing, and an archive written before these records still imports."""

from __future__ import annotations

import json
import zipfile

import numpy as np
import pytest

from axiscal.errors import DataFormatError
from axiscal.store import open_store
from axiscal.store import corrections as cx
from axiscal.store.archive import export_history, import_history
from tests.store.test_archive_trust import rewrite
from tests.store.test_register import _issue
from tests.store.test_history import _dataset, _raw

NEW_NAME = "DMU 50 S/N 1234"


def _history(tmp_path):
    """A SQLite history of five tests on two machines, corrected every way the workbench can,
    with a certificate and its amendment; returns the store and the tests' SHA-256 by name."""
    src = open_store(f"sqlite:///{tmp_path / 'src.sqlite'}")
    rng = np.random.default_rng(31)
    sha = {}
    for k, (machine, axis) in enumerate([("M1", "X"), ("M1", "X"), ("M1", "Y"), ("M2", "X"),
                                         ("M2", "Z")]):
        r = src.add(_raw(_dataset(rng, machine=machine, date=f"2024-0{k + 1}-01")),
                    f"t{k}.csv", axis=axis)
        sha[f"t{k}"] = src.get(r.id).sha256
    by = dict(by="A. Auditor")
    cx.rename_machine(src, "M1", NEW_NAME, reason="the owner's name", **by)
    cx.rename_machine(src, "M2", "M2 old cell", reason="moved", **by)
    cx.merge_machines(src, "M2 old cell", NEW_NAME, reason="one machine, two names", **by)
    cx.rename_axis(src, NEW_NAME, "Y", "W", reason="axis renamed on the controller", **by)
    cx.merge_axes(src, NEW_NAME, "Z", "W", reason="Z was W", **by)
    ids = {t.id: src.get(t.id).sha256 for t in src.tests()}
    tid = {v: k for k, v in ids.items()}
    cx.edit_test(src, tid[sha["t0"]], note="after the spindle change", reason="typo", **by)
    cx.withdraw(src, tid[sha["t1"]], reason="laser misaligned", **by)
    old = _issue(src, tid[sha["t2"]])
    _issue(src, tid[sha["t2"]], replaces=old.number, reason="serial number corrected")
    return src, sha


def _trail(store) -> list[tuple]:
    """The audit trail with ids made portable (tests by SHA-256), oldest first."""
    shas = {t.id: store.get(t.id).sha256 for t in store.tests()}
    return [(a.at, a.by, a.action, a.what, a.reason, shas.get(a.test_id), a.new.get("name"))
            for a in reversed(cx.audit(store))]


def _register(store) -> list[tuple]:
    shas = {t.id: store.get(t.id).sha256 for t in store.tests()}
    return sorted((c.number, c.status, c.replaces, c.replaced_by, c.reason, shas[c.test_id],
                   store.certificate(c.number).document) for c in store.certificates())


def test_an_archive_round_trip_keeps_the_audit_trail_and_the_register(tmp_path, db_url):
    src, sha = _history(tmp_path)
    assert export_history(src, tmp_path / "h.zip") == 5
    with zipfile.ZipFile(tmp_path / "h.zip") as z:
        head = json.loads(z.read("history.jsonl").decode().splitlines()[0])
    assert head == {"format": "axiscal.history/3", "tests": 5, "audit": 7, "certificates": 2,
                    "laboratory": 0, "drift_checks": 0}
    dst = open_store(db_url)
    assert import_history(dst, tmp_path / "h.zip") == (5, 0)
    assert _trail(dst) == _trail(src) and len(_trail(dst)) == 7      # who, when, what, why
    assert _register(dst) == _register(src) and len(_register(dst)) == 2
    by_sha = {dst.get(t.id).sha256: t for t in dst.tests()}
    assert by_sha[sha["t1"]].withdrawn == "laser misaligned"         # still withdrawn
    assert [t.withdrawn for s, t in by_sha.items() if s != sha["t1"]] == [""] * 4
    assert by_sha[sha["t0"]].note == "after the spindle change"
    # the trail of the machine gathers the machine merged into it, and old names still lead
    assert len(cx.audit(dst, machine=NEW_NAME)) == len(cx.audit(src, machine=NEW_NAME)) == 7
    target = by_sha[sha["t0"]].machine_id
    assert cx.machine_id(dst, "M1") == cx.machine_id(dst, "M2 old cell") == target
    assert {a.action for a in cx.audit(dst, machine=NEW_NAME)} >= {"rename-machine",
                                                                   "merge-machines",
                                                                   "merge-axes", "edit"}
    assert [a.reason for a in cx.audit(dst, test_id=by_sha[sha["t1"]].id)] == ["laser misaligned"]
    # once more: nothing added twice
    assert import_history(dst, tmp_path / "h.zip") == (0, 5)
    assert len(_trail(dst)) == 7 and len(_register(dst)) == 2


def test_a_register_number_taken_by_another_document_refuses_the_archive(tmp_path, db_url):
    """All or nothing: the laboratory's number PM-2026-00001 already names another document in
    the history imported into, so the archive is refused and nothing of it is stored."""
    src, _ = _history(tmp_path)
    export_history(src, tmp_path / "h.zip")
    dst = open_store(db_url)
    own = dst.add(_raw(_dataset(np.random.default_rng(5), machine="Lathe")), "own.csv")
    _issue(dst, own.id, render=lambda n: b"another document")
    with pytest.raises(DataFormatError, match="another document under this number; nothing"):
        import_history(dst, tmp_path / "h.zip")
    assert len(dst.tests()) == 1 and len(cx.audit(dst)) == 0 and len(dst.certificates()) == 1


@pytest.mark.parametrize("damage, words", [
    ("drop-document", "is missing from the archive"),
    ("drop-audit", "no audit.jsonl inside"),
    ("count", "announces 6 audit entries and audit.jsonl holds 7"),
    ("foreign-test", "its test"),
])
def test_damaged_records_refuse_the_archive_before_any_row(tmp_path, damage, words):
    src, _ = _history(tmp_path)
    export_history(src, tmp_path / "h.zip")
    with zipfile.ZipFile(tmp_path / "h.zip") as z:
        doc = next(n for n in z.namelist() if n.startswith("certificates/"))
        audit = z.read("audit.jsonl").decode().splitlines()
    kw = {"drop-document": dict(drop=(doc,)), "drop-audit": dict(drop=("audit.jsonl",)),
          "count": dict(jsonl=lambda lines: [lines[0].replace('"audit": 7', '"audit": 6')]
                        + lines[1:])}.get(damage)
    if damage == "foreign-test":
        e = json.loads(audit[-1])
        e["test"] = "0" * 64
        kw = dict(drop=("audit.jsonl",), extra=(("audit.jsonl", "\n".join(
            audit[:-1] + [json.dumps(e)]) + "\n"),))
    bad = rewrite(tmp_path / "h.zip", tmp_path / "bad.zip", **kw)
    dst = open_store(f"sqlite:///{tmp_path / 'dst.sqlite'}")
    with pytest.raises(DataFormatError, match=words):
        import_history(dst, bad)
    assert dst.tests() == [] and cx.audit(dst) == [] and dst.certificates() == []


def test_an_archive_of_format_1_still_imports(tmp_path):
    """An archive written before the records (``axiscal.history/1``: no audit.jsonl, no
    certificates, no ``withdrawn`` in a record) imports its tests as before."""
    src, _ = _history(tmp_path)
    export_history(src, tmp_path / "h.zip")

    def old_lines(lines):
        head = {"format": "axiscal.history/1", "tests": 5}
        records = [json.loads(x) for x in lines[1:]]
        for r in records:
            del r["withdrawn"]
        return [json.dumps(head)] + [json.dumps(r) for r in records]

    with zipfile.ZipFile(tmp_path / "h.zip") as z:
        records = [n for n in z.namelist() if not n.startswith("raw/") and n != "history.jsonl"]
    old = rewrite(tmp_path / "h.zip", tmp_path / "old.zip", jsonl=old_lines, drop=records)
    with zipfile.ZipFile(old) as z:
        assert sorted(n for n in z.namelist() if not n.startswith("raw/")) == ["history.jsonl"]
    dst = open_store(f"sqlite:///{tmp_path / 'dst.sqlite'}")
    assert import_history(dst, old) == (5, 0)
    assert cx.audit(dst) == [] and dst.certificates() == []
    assert all(t.withdrawn == "" for t in dst.tests())


def test_corrections_arriving_for_tests_stored_before_are_applied(tmp_path):
    """The tests are in the history already (from an archive of format 1, without records);
    the full archive then brings the trail, and the tests it names take their corrected
    metadata, so the trail and the tests agree: t1 withdrawn, t0's note edited."""
    src, sha = _history(tmp_path)
    export_history(src, tmp_path / "h.zip")
    with zipfile.ZipFile(tmp_path / "h.zip") as z:
        extra = [n for n in z.namelist() if not n.startswith("raw/") and n != "history.jsonl"]

    def old_lines(lines):
        recs = [json.loads(x) for x in lines[1:]]
        for r in recs:
            r.update(withdrawn="", note="")
        return [json.dumps({"format": "axiscal.history/1", "tests": 5})] + [json.dumps(r)
                                                                         for r in recs]

    old = rewrite(tmp_path / "h.zip", tmp_path / "old.zip", jsonl=old_lines, drop=extra)
    dst = open_store(f"sqlite:///{tmp_path / 'dst.sqlite'}")
    assert import_history(dst, old) == (5, 0)
    assert all(t.withdrawn == "" and t.note == "" for t in dst.tests())
    assert import_history(dst, tmp_path / "h.zip") == (0, 5)
    by_sha = {dst.get(t.id).sha256: t for t in dst.tests()}
    assert by_sha[sha["t1"]].withdrawn == "laser misaligned"
    assert by_sha[sha["t0"]].note == "after the spindle change"
    assert _trail(dst) == _trail(src) and _register(dst) == _register(src)


def test_an_old_archives_certificate_is_keyed_by_the_code_of_its_series():
    """Issue 38: an archive written before migration 0005 names the laboratory by its name; on
    import its certificate is keyed by the code (the start of its series, CODE|YEAR), the name
    kept as printed, the later fields empty; a new archive's entry is left as it is."""
    from axiscal.store.archive_records import _register_key

    old = {"laboratory": "Nordkap Labor.", "series": "NKL|2026"}
    _register_key(old)
    assert (old["laboratory"], old["laboratory_name"]) == ("NKL", "Nordkap Labor.")
    assert old["approved_by"] == "" and old["changes"] == [] and old["as_found"] is None
    new = {"laboratory": "NKL", "laboratory_name": "Nordkap Labor", "series": "NKL|2026",
           "approved_by": "Dr. M. Braun", "changes": [{"what": "x", "old": 1, "new": 2}]}
    _register_key(new)
    assert (new["laboratory"], new["approved_by"]) == ("NKL", "Dr. M. Braun")
    assert new["changes"] == [{"what": "x", "old": 1, "new": 2}]
