"""A stored test's evaluation and products computed once and kept (axiscal.store.cache)."""

from __future__ import annotations

import os
import threading
import time

import numpy as np
import pytest

import axiscal.store.history as history
import axiscal.store.kinds as kinds
from axiscal.datasets import Metadata, PositioningDataset
from axiscal.io.csv import format_positioning_csv
from axiscal.store import cache, open_store

real_evaluate = kinds.evaluate_file


def _file(seed: int) -> bytes:
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 800, 11)
    up = rng.normal(0, 1, (11, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2, "mm", "um",
        Metadata(machine="VMC", axis="X", date="2024-05-06"))).encode()


@pytest.fixture
def counted(monkeypatch, tmp_path):
    """The cache in a fresh folder, and a count of the evaluations made."""
    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    cache.forget_memory()
    calls = []
    real = kinds.evaluate_file
    def counting(*a, **k):
        calls.append(a[1])
        return real(*a, **k)

    monkeypatch.setattr(kinds, "evaluate_file", counting)           # what a view would call
    monkeypatch.setattr(history, "evaluate_file", counting)         # the upload's evaluation
    yield calls
    cache.forget_memory()


def test_a_view_after_upload_is_a_lookup_in_memory_and_on_disk(counted, tmp_path):
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    raw = _file(1)
    r = st.add(raw, "a.csv")
    made_at_upload = len(counted)
    ev = st.get(r.id).evaluate_again()                 # held in memory since the upload
    cache.forget_memory()                              # another worker process: from disk
    ev_disk = st.get(r.id).evaluate_again()
    assert len(counted) == made_at_upload == 1
    fresh = real_evaluate(raw, "a.csv", "iso230-2")
    for name, (value, unit) in fresh.parameters.items():
        assert ev.parameters[name] == ev_disk.parameters[name] == (value, unit)
    np.testing.assert_array_equal(ev_disk.evaluation.mean_bi, fresh.evaluation.mean_bi)


def test_a_test_not_kept_is_evaluated_once_then_kept(counted, tmp_path):
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    r = st.add(_file(2), "b.csv")
    for p in cache.cache_folder().rglob("*"):
        if p.is_file():
            p.unlink()
    cache.forget_memory()
    before = len(counted)
    for _ in range(3):
        st.get(r.id).evaluate_again()
    assert len(counted) == before + 1


def test_another_version_does_not_read_what_an_older_one_kept(counted, tmp_path, monkeypatch):
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    r = st.add(_file(3), "c.csv")
    old_folder = cache.cache_folder()
    monkeypatch.setattr(cache, "_VERSION", ["9.9.9-other"])
    before = len(counted)
    st.get(r.id).evaluate_again()
    assert len(counted) == before + 1
    assert cache.cache_folder() != old_folder and cache.cache_folder().name == "9.9.9-other"


def test_writes_are_whole_and_a_read_only_cache_is_no_error(counted, tmp_path, monkeypatch):
    sha = "ab" * 32
    assert cache.write(sha, "report.html", b"x" * 1000)
    assert cache.read(sha, "report.html") == b"x" * 1000
    assert not [p for p in cache.cache_folder().rglob(".tmp-*")]
    blocked = tmp_path / "file-not-folder"
    blocked.write_text("")
    monkeypatch.setenv("AXISCAL_CACHE", str(blocked))          # a folder that cannot be made
    assert cache.write(sha, "report.html", b"y") is False
    assert cache.kept(sha, "report.html", lambda: "made") == b"made"
    with pytest.raises(ValueError):
        cache.read("../../etc/passwd", "x")


def test_concurrent_requests_for_one_product_make_it_once(counted):
    made = []

    def make():
        made.append(1)
        time.sleep(0.2)
        return "report"

    out = []
    threads = [threading.Thread(target=lambda: out.append(cache.kept("cd" * 32, "r.html", make)))
               for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(made) == 1 and out == [b"report"] * 6


def test_memory_is_bounded_by_stored_bytes(counted, monkeypatch):
    monkeypatch.setattr(cache, "MEMORY_BYTES", 3000)
    for i in range(5):
        cache._hold((f"{i}", "v"), object(), 1000)
    assert len(cache._memory) == 3 and ("4", "v") in cache._memory
    cache._hold(("big", "v"), object(), 4000)                 # over the bound: never held
    assert ("big", "v") not in cache._memory


def test_derived_parts_are_made_once_and_read_back_in_another_process(counted):
    made = []

    def make():
        made.append(1)
        return {"plot": [1.0, 2.0], "rows": ("a", "b")}

    sha = "ef" * 32
    first = cache.derived(sha, "test-page-x", make)
    cache.forget_memory()                                       # another worker: from disk
    again = cache.derived(sha, "test-page-x", make)
    other = cache.derived(sha, "test-page-y", make)             # another configuration
    assert first == again == other and len(made) == 2


def test_two_processes_make_one_product_once(counted, tmp_path):
    import os
    import subprocess
    import sys

    code = ("import pathlib, time\nfrom axiscal.store import cache\n"
            "def make():\n"
            f"    with open({str(tmp_path / 'made')!r}, 'a') as f: f.write('x')\n"
            "    time.sleep(2.0)\n    return 'report'\n"
            "assert cache.kept('12' * 32, 'r.html', make) == b'report'\n")
    procs = [subprocess.Popen([sys.executable, "-c", code], env=os.environ) for _ in range(2)]
    assert [p.wait(60) for p in procs] == [0, 0]
    assert (tmp_path / "made").read_text() == "x"


def test_an_edited_template_is_another_version(monkeypatch):
    """Page parts are drawn by the workbench's templates: a template edited in a checkout (its
    size or modification time) gives another version, so no page part of the old template is
    served."""
    from pathlib import Path

    template = Path(cache.__file__).resolve().parents[1] / "web" / "templates" / "_test_results.html"
    monkeypatch.setattr(cache, "_VERSION", [])
    before = cache._version()
    st = template.stat()
    try:
        os.utime(template, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000_000))
        monkeypatch.setattr(cache, "_VERSION", [])
        assert cache._version() != before
    finally:
        os.utime(template, ns=(st.st_atime_ns, st.st_mtime_ns))
