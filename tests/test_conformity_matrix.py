"""The conformity matrices of docs/ (ISO/IEC 17025 and ILAC-P14, the controllers' manuals,
ISO 230-3, ISO 10791-6): every row names a test that exists, or says why the clause does not
apply (a dash) or is not met; the clauses the issues list are all there."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


#: Each matrix with the table rows it holds at least and the words a row without a test (a
#: dash) must say: ISO/IEC 17025 and ILAC-P14 (issue 38), ISO 230-3:2020 (issue 44) and
#: ISO 10791-6:2014 (issue 43).
MATRICES = {"conformity.md": (35, ("does not apply", "not met", "none")),
            "iso230_3_conformity.md": (15, ("does not apply", "not met")),
            "conformity_iso10791_6.md": (12, ("not met",))}


def _rows(name: str = "conformity.md"):
    doc = ROOT / "docs" / name
    lines = [x for x in doc.read_text(encoding="utf-8").splitlines() if x.startswith("| ")]
    return [[c.strip() for c in x.strip("|").split("|")] for x in lines[2:]]


@pytest.mark.parametrize("name", sorted(MATRICES))
def test_every_named_test_exists(name):
    """Every row of the matrix names tests (``path::function``) that exist, or says why the
    item has none."""
    least, gap_words = MATRICES[name]
    rows = _rows(name)
    assert len(rows) >= least
    for source, _, how, test in rows:
        if test == "—":
            assert any(w in how for w in gap_words), source
            continue
        for ref in re.findall(r"`([^`]+)`", test):
            path, _, fn = ref.partition("::")
            assert (ROOT / path).is_file(), ref
            assert re.search(rf"^def {re.escape(fn)}\(", (ROOT / path).read_text(
                encoding="utf-8"), re.M), ref


#: Words by which a row of docs/iso230_3_conformity.md states a duration, a sampling, a sensor
#: layout, targets or a duty: axiscal's choices where ISO 230-3:2020's text was not available.
CHOICES = re.compile(r"\b\d+(\.\d+)? (h|min)\b|a sample a minute|sensors? (on|at)|"
                     r"X1, Y1 at|% of the travel|% of the time|% duty|% of the maximum")


def test_iso230_3_choices_are_marked_as_axiscals_reading():
    """docs/iso230_3_conformity.md: every row of ISO 230-3:2020 Clauses 5 to 8 that states a
    duration, a sampling, a sensor layout, targets or a duty says *reading* in its first column
    (the clause text was not available: these are axiscal's defaults with their reasons,
    ``standards/iso230_3_data.py``); each of the four tests has such a row."""
    marked = set()
    for source, _, how, _ in _rows("iso230_3_conformity.md"):
        clause = re.match(r"(ISO 230-3:2020 )?Clauses? ([5-8])\b", source)
        if clause is None:
            continue
        if "*reading" in source:
            marked.add(clause.group(2))
        else:
            assert not CHOICES.search(how), (source, CHOICES.search(how).group(0))
    assert marked == {"5", "6", "7", "8"}


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


def test_the_iso230_3_matrix_covers_its_clauses_and_both_controllers():
    """docs/iso230_3_conformity.md (issue 44): Clauses 5 to 8, the drift check and both
    controllers are there."""
    text = " ".join(r[0] for r in _rows("iso230_3_conformity.md"))
    for item in ("Clause 5", "Clause 6", "Clause 7", "Clause 8", "Annex A.5", "K3", "LinuxCNC"):
        assert item in text, item
