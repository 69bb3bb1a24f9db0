"""The reads a page makes on every view (axiscal.store.queries) give what the ORM gave, and the
history's generation changes with every write a history page shows (issue 31)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.io.csv import format_positioning_csv
from axiscal.store import corrections, open_store, queries
from axiscal.store.database import NotFoundError


def _file(seed: int, machine: str = "VMC", axis: str = "X", day: int = 1) -> bytes:
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 800, 11)
    up = rng.normal(0, 1, (11, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2, "mm", "um",
        Metadata(machine=machine, axis=axis, date=f"2024-05-{day:02d}"))).encode()


@pytest.fixture
def store(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    s = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    for k in range(3):
        s.add(_file(k, day=k + 1), f"x{k}.csv")
    s.add(_file(9, axis="Y", day=9), "y.csv")
    yield s
    s.close()


def test_a_stored_test_reads_its_bytes_only_when_asked(store):
    """Everything but the bytes comes in three statements; the bytes, with their length known
    beforehand, come on first use and are the file as it was stored."""
    from sqlalchemy import event

    statements = []
    event.listen(store.engine, "before_cursor_execute",
                 lambda c, cur, sql, *a: statements.append(sql))
    t = store.get(2)
    selects = [s for s in statements if s.lstrip().upper().startswith("SELECT")]
    assert len(selects) == 3
    assert not any("test.raw," in s or s.rstrip().endswith("test.raw") for s in selects)
    assert t.size == len(_file(1, day=2)) and t.summary.machine == "VMC"
    assert t.summary.parameters["E"][1] == "um" and list(t.summary.parameters)[0] == "A"
    assert t.raw == _file(1, day=2)
    assert len([s for s in statements if s.lstrip().upper().startswith("SELECT")]) == 4
    with pytest.raises(NotFoundError):
        store.get(99)


def test_a_listing_narrowed_to_key_parameters_keeps_their_values(store):
    """``parameters=names`` holds those names (and the first parameter), with the values a full
    listing gives; an empty tuple holds none."""
    full = {t.id: t for t in store.tests()}
    narrow = store.tests(parameters=("E", "R"))
    assert [t.id for t in narrow] == list(full)              # same tests, same order
    for t in narrow:
        assert set(t.parameters) == {"A", "E", "R"}            # A: each test's first parameter
        assert all(t.parameters[k] == full[t.id].parameters[k] for k in t.parameters)
        assert len(full[t.id].parameters) > 10
    assert all(t.parameters == {} for t in store.tests(parameters=()))
    assert [t.id for t in store.tests(axis="y", parameters=())] == [4]


def test_one_machine_equals_its_summary_among_all(store):
    whole = {m.id: m for m in store.machines()}
    m = store.machine(1)
    assert m == whole[1] and m.axes == ("X", "Y") and m.tests == 4
    assert queries.machine_names(store) == [(1, "VMC")]
    for bad in (2, 0, 2**63):
        with pytest.raises(NotFoundError):
            store.machine(bad)


def test_the_generation_changes_with_every_write_a_history_page_shows(store):
    """A new test, a correction of a test, a withdrawal, a renamed machine: each changes the
    generation; reading does not."""
    seen = [queries.generation(store)]
    store.tests(), store.get(1)
    assert queries.generation(store) == seen[-1]
    writes = [lambda: store.add(_file(20, day=20), "n.csv"),
              lambda: corrections.edit_test(store, 1, by="ana", reason="typo", note="new note"),
              lambda: corrections.withdraw(store, 2, by="ana", reason="bad mount"),
              lambda: corrections.rename_machine(store, 1, "VMC 2", by="ana", reason="sold"),
              lambda: store.add(_file(21, machine="Other", day=21), "o.csv")]
    for write in writes:
        write()
        now = queries.generation(store)
        assert now not in seen
        seen.append(now)
    assert store.add(_file(20, day=20), "again.csv").duplicate     # nothing written
    assert queries.generation(store) == seen[-1]
