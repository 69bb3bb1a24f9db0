"""History archives distrusted (issue 30): an import is all or nothing, checked whole before the
first row; malformed archives and zip bombs refused in one line from what they declare and
from what they really hold; an export never leaves a partial archive and gets the umask's mode.

The import's all-or-nothing rule under SIGKILL is in test_faults.py."""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from sqlalchemy import create_engine, inspect, text
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.store import open_store
from axiscal.store.archive import MAX_RATIO, export_history

from tests.store.test_history import _dataset, _raw

runner = CliRunner()


def dump(url: str) -> dict:
    """Every row of every table, in order: the database's whole content, to compare."""
    engine = create_engine(url)
    try:
        with engine.connect() as c:
            out = {}
            for table in sorted(inspect(c).get_table_names()):
                cols = [x["name"] for x in inspect(c).get_columns(table)]
                out[table] = [tuple(r) for r in c.execute(text(
                    f'SELECT * FROM "{table}" ORDER BY {", ".join(cols)}'))]
            return out
    finally:
        engine.dispose()


def make_archive(tmp_path: Path, n: int, name: str = "a.zip", machine: str = "VMC-800") -> Path:
    """A real archive of ``n`` tests exported from a scratch history."""
    src = open_store(f"sqlite:///{tmp_path / f'src-{name}.sqlite'}")
    rng = np.random.default_rng(n)
    for k in range(n):
        src.add(_raw(_dataset(rng, machine=machine, date=f"2020-{k % 12 + 1:02d}-01")),
                f"t{k}.csv", tables=(("csv", f"t{k}-table.csv", "position,correction\n"),))
    export_history(src, tmp_path / name)
    src.close()
    return tmp_path / name


def rewrite(archive: Path, out: Path, *, jsonl=None, drop=(), extra=()) -> Path:
    """``archive`` copied with history.jsonl replaced (bytes or a function of its lines),
    entries dropped or added."""
    with zipfile.ZipFile(archive) as z, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as w:
        for i in z.infolist():
            if i.filename in drop:
                continue
            data = z.read(i)
            if i.filename == "history.jsonl" and jsonl is not None:
                data = jsonl if isinstance(jsonl, bytes) else \
                    "\n".join(jsonl(data.decode().splitlines())).encode()
            w.writestr(i.filename, data)
        for name, data in extra:
            w.writestr(name, data)
    return out


@pytest.fixture
def history(tmp_path):
    """A history holding two tests of another machine, and its URL."""
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    s = open_store(url)
    rng = np.random.default_rng(77)
    for k in range(2):
        s.add(_raw(_dataset(rng, machine="Lathe-2", date=f"2019-0{k + 1}-01")), f"old{k}.csv")
    s.close()
    return url


def _refused(url, archive, *words):
    before = dump(url)
    r = runner.invoke(app, ["history", "import", str(archive), "--db", url])
    assert r.exit_code == 2, r.output
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "Traceback" not in r.stderr and len(r.stderr) < 400, r.stderr
    for w in words:
        assert w in r.stderr, r.stderr
    assert dump(url) == before
    return r.stderr


def test_one_raw_file_missing_keeps_nothing(tmp_path, history):
    """The issue's case: an archive of 4 tests with the last raw file missing kept 3 of them;
    now the import is refused before the first row and the database is as before."""
    a = make_archive(tmp_path, 4)
    with zipfile.ZipFile(a) as z:
        last = json.loads(z.read("history.jsonl").decode().splitlines()[-1])["raw"]
    bad = rewrite(a, tmp_path / "missing.zip", drop=(last,))
    _refused(history, bad, "missing from the archive", "line 5")


def test_a_raw_file_that_no_longer_evaluates_keeps_nothing(tmp_path, history):
    """A raw file whose bytes match their SHA-256 but do not evaluate (the archive made by
    hand): refused before any row."""
    import hashlib

    a = make_archive(tmp_path, 3)
    junk = b"not,a,measurement\n1,2\n"
    digest = hashlib.sha256(junk).hexdigest()

    def lines(ls):
        rec = json.loads(ls[2])
        rec.update(sha256=digest, raw=f"raw/{digest}-junk.csv", filename="junk.csv")
        return [*ls[:2], json.dumps(rec), *ls[3:]]

    bad = rewrite(a, tmp_path / "junk.zip", jsonl=lines, extra=((f"raw/{digest}-junk.csv", junk),))
    _refused(history, bad, "junk.csv", "nothing was imported")


HEADER = json.dumps({"format": "axiscal.history/1", "tests": 1})


@pytest.mark.parametrize("case, jsonl, words", [
    ("first line not JSON", b"this is not json\n", ("line 1 is not JSON",)),
    ("a list", b"[1, 2, 3]\n", ("line 1", "list")),
    ("nested JSON", b"[" * 100_000 + b"]" * 100_000 + b"\n", ("nested too deeply",)),
    ("a record that is a list", (HEADER + "\n[1, 2]\n").encode(), ("line 2", "list")),
    ("non-UTF-8", HEADER.encode() + b'\n{"machine": "\xff\xfe"}\n', ("not UTF-8", "0xFF")),
    ("empty", b"", ("empty",)),
    ("wrong format", b'{"format": "other/9"}\n', ("other/9",)),
    ("truncated", json.dumps({"format": "axiscal.history/1", "tests": 7}).encode() + b"\n",
     ("announces 7 tests and holds 0",)),
])
def test_malformed_history_jsonl_one_line_each(tmp_path, history, case, jsonl, words):
    """Each of the issue's malformed archives (each gave a traceback) is refused in one line
    naming the fault, and nothing is stored."""
    bad = tmp_path / "bad.zip"
    with zipfile.ZipFile(bad, "w", zipfile.ZIP_DEFLATED) as w:
        w.writestr("history.jsonl", jsonl)
    _refused(history, bad, *words)


@pytest.mark.parametrize("field, change, words", [
    ("machine", None, ("no 'machine'",)),
    ("tables", [["csv", "x.csv"]], ("tables[0]", "three strings")),
    ("tables", "csv", ("'tables' is a JSON str",)),
    ("date_known", "yes", ("'date_known'", "not a bool")),
    ("sha256", "abc", ("64 hexadecimal",)),
    ("machine", "", ("machine",)),
])
def test_malformed_records_one_line_each(tmp_path, history, field, change, words):
    """A record missing ``machine``, a 2-item ``tables`` entry, fields of the wrong type: one
    line, nothing stored (the other records were good)."""
    a = make_archive(tmp_path, 3)

    def lines(ls):
        rec = json.loads(ls[2])
        if change is None:
            del rec[field]
        else:
            rec[field] = change
        return [*ls[:2], json.dumps(rec), *ls[3:]]

    _refused(history, rewrite(a, tmp_path / "bad.zip", jsonl=lines), *words)


def _patch_sizes(data: bytes, name: bytes, size: int) -> bytes:
    """The ZIP with ``name``'s declared uncompressed size set to ``size`` in its local header
    and its central directory record (a lying header)."""
    import struct

    b = bytearray(data)
    at = 0
    while (at := b.find(b"PK\x03\x04", at)) >= 0:
        if b[at + 30:at + 30 + len(name)] == name:
            struct.pack_into("<I", b, at + 22, size)
        at += 4
    at = 0
    while (at := b.find(b"PK\x01\x02", at)) >= 0:
        if b[at + 46:at + 46 + len(name)] == name:
            struct.pack_into("<I", b, at + 24, size)
        at += 4
    return bytes(b)


def test_zip_bombs_refused_from_the_directory_and_while_reading(tmp_path, history):
    """A small zip that would expand to gigabytes is refused before anything is read: an entry
    declared at 3 GiB; an entry 1000 times its compressed size (zeros deflate about 1000:1,
    beyond MAX_RATIO); an entry whose header understates its size (2 KiB declared, 16 MiB
    inside) is stopped at the declared size while reading and refused as damaged."""
    a = make_archive(tmp_path, 2)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as w:
        w.writestr("raw/zeros.bin", bytes(16 * 2**20))
    zeros = buf.getvalue()
    assert len(zeros) < 64 * 1024                                  # the bomb is small

    ratio = rewrite(a, tmp_path / "ratio.zip", extra=(("raw/zeros.bin", bytes(16 * 2**20)),))
    err = _refused(history, ratio, "more than", "zip bomb")
    assert str(MAX_RATIO) in err

    big = tmp_path / "big.zip"
    big.write_bytes(_patch_sizes(zeros, b"raw/zeros.bin", 3 * 2**30))
    _refused(history, big, "expands to 3221225472 bytes")

    with zipfile.ZipFile(a) as z:
        lines = z.read("history.jsonl")
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as w:
        w.writestr("history.jsonl", lines.split(b"\n")[0] + b"\n" + b" " * (16 * 2**20))
        with zipfile.ZipFile(a) as z:
            for i in z.infolist():
                if i.filename != "history.jsonl":
                    w.writestr(i.filename, z.read(i))
    lying = tmp_path / "lying.zip"
    lying.write_bytes(_patch_sizes(buf.getvalue(), b"history.jsonl", 2048))
    _refused(history, lying, "history.jsonl", "damaged")


def test_not_a_zip_one_line(tmp_path, history):
    bad = tmp_path / "x.zip"
    bad.write_bytes(b"PK\x03\x04 but nothing else")
    _refused(history, bad, "not an axiscal history archive")


def test_a_good_archive_imports_whole_and_twice_adds_nothing(tmp_path, history):
    """The checked path still imports: 5 tests with their tables, then 0 added, 5 duplicates."""
    a = make_archive(tmp_path, 5)
    r = runner.invoke(app, ["history", "import", str(a), "--db", history, "--json"])
    assert r.exit_code == 0, r.output
    none = {"audit": 0, "laboratory": 0, "drift_checks": 0, "certificates": 0, "documents": 0}
    assert json.loads(r.stdout) == {"archive": str(a), "added": 5, "duplicates": 0, **none}
    r = runner.invoke(app, ["history", "import", str(a), "--db", history, "--json"])
    assert json.loads(r.stdout) == {"archive": str(a), "added": 0, "duplicates": 5, **none}
    s = open_store(history)
    assert len(s.tests(machine="VMC-800")) == 5
    assert all(s.get(t.id).tables[0][0] == "csv" for t in s.tests(machine="VMC-800"))


def test_export_mode_follows_the_umask(tmp_path, history):
    """An export gets 0666 less the umask (0644 under umask 022), not mkstemp's 0600."""
    old = os.umask(0o022)
    try:
        r = runner.invoke(app, ["history", "export", str(tmp_path / "e.zip"), "--db", history])
        os.umask(0o027)
        r2 = runner.invoke(app, ["history", "export", str(tmp_path / "f.zip"), "--db", history])
    finally:
        os.umask(old)
    assert r.exit_code == 0 and r2.exit_code == 0, r.output + r2.output
    assert (tmp_path / "e.zip").stat().st_mode & 0o777 == 0o644
    assert (tmp_path / "f.zip").stat().st_mode & 0o777 == 0o640


def test_export_to_a_full_disk_leaves_no_archive(tmp_path):
    """RLIMIT_FSIZE below the archive's size (as a full disk): one line, exit 2, and neither
    the archive nor a temporary file is left in the folder."""
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    s = open_store(url)
    rng = np.random.default_rng(5)
    for k in range(3):
        s.add(_raw(_dataset(rng, n_targets=2000, date=f"2021-0{k + 1}-01")), f"big{k}.csv")
    s.close()
    out = tmp_path / "out"
    out.mkdir()

    def small_disk():
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

    p = subprocess.run([sys.executable, "-m", "axiscal", "history", "export",
                        str(out / "e.zip"), "--db", url], capture_output=True, text=True,
                       preexec_fn=small_disk, timeout=120)
    assert p.returncode == 2, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and "Traceback" not in p.stderr, p.stderr
    assert "e.zip" in p.stderr and "no archive was left" in p.stderr
    assert list(out.iterdir()) == []
