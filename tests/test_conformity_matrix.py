"""docs/conformity.md (issue 38): every row of the conformity matrix names a test that exists,
or says why the clause does not apply (a dash) or is not met; the clauses the issue lists are
all there."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "conformity.md"


def _rows():
    lines = [x for x in DOC.read_text(encoding="utf-8").splitlines() if x.startswith("| ")]
    return [[c.strip() for c in x.strip("|").split("|")] for x in lines[2:]]


def test_every_named_test_exists():
    rows = _rows()
    assert len(rows) >= 35
    for source, _, how, test in rows:
        if test == "—":
            assert ("does not apply" in how or "not met" in how or "none" in how), source
            continue
        for ref in re.findall(r"`([^`]+)`", test):
            path, _, name = ref.partition("::")
            assert (ROOT / path).is_file(), ref
            assert re.search(rf"^def {re.escape(name)}\(", (ROOT / path).read_text(
                encoding="utf-8"), re.M), ref


def test_the_clauses_of_the_issue_are_all_there():
    text = " ".join(r[0] for r in _rows())
    for clause in [f"§7.8.2.1 {c}" for c in "abcdefghijklmnop"] + [
            "§7.8.2.2", "§7.8.3.1", "§7.8.4.1 a", "§7.8.4.1 d", "§7.8.6.1", "§7.8.6.2 c",
            "§7.8.7", "§7.8.8.1", "§7.8.8.2", "§7.8.8.3", "ILAC-P14:09/2020 §5.3",
            "ILAC-P14:09/2020 §6", "ILAC-G8"]:
        assert clause in text, clause


CONTROLLERS = ROOT / "docs" / "controllers_conformity.md"


def test_every_test_the_controllers_matrix_names_exists():
    """docs/controllers_conformity.md (issue 42): each row's tests (``file.py::name``, and
    ``::name`` for the file named before it) are functions of the test suite."""
    rows = [x for x in CONTROLLERS.read_text(encoding="utf-8").splitlines()
            if x.startswith("| ")][2:]
    assert len(rows) >= 30
    found = 0
    for row in rows:
        test = row.strip("|").split("|")[-1]
        current = None
        for ref in re.findall(r"`([^`]*::[^`]+)`", test):
            path, _, name = ref.partition("::")
            if path:
                hits = list((ROOT / "tests").rglob(Path(path).name))
                assert len(hits) == 1, ref
                current = hits[0]
            assert current is not None, (row, ref)
            assert re.search(rf"^def {re.escape(name)}\(", current.read_text("utf-8"), re.M), ref
            found += 1
    assert found >= 30


THERMAL = ROOT / "docs" / "iso230_3_conformity.md"


def test_every_test_the_iso230_3_matrix_names_exists():
    """docs/iso230_3_conformity.md (issue 44): each row names tests that exist, or says why the
    item is not met; Clauses 5 to 8, the drift check and both controllers are there."""
    rows = [[c.strip() for c in x.strip("|").split("|")]
            for x in THERMAL.read_text(encoding="utf-8").splitlines() if x.startswith("| ")][2:]
    assert len(rows) >= 15
    for source, _, how, test in rows:
        if test == "—":
            assert "not met" in how or "does not apply" in how, source
            continue
        for ref in re.findall(r"`([^`]+)`", test):
            path, _, name = ref.partition("::")
            assert (ROOT / path).is_file(), ref
            assert re.search(rf"^def {re.escape(name)}\(", (ROOT / path).read_text(
                encoding="utf-8"), re.M), ref
    text = " ".join(r[0] for r in rows)
    for item in ("Clause 5", "Clause 6", "Clause 7", "Clause 8", "Annex A.5", "K3", "LinuxCNC"):
        assert item in text, item
