"""A squareness from two straightness files kept as one test (issue 40, kind ``squareness``):
``axiscal squareness biaxial X.csv Y.csv --inline FILE.toml`` writes both trajectories and every
option to one file (:mod:`axiscal.io.biaxial`); ``history add`` keeps it, and its record is the
command's ``--json`` field by field, its report the command's ``--report``; a hostile or partial
file is refused in one line and nothing is stored.

The trajectories are the project's examples (``examples/squareness_L180_*.csv``: Chapman,
Calibration of machine squareness, machine 1, L set-up at 180°); the references are the
command's own outputs (one record, every path: nothing is recomputed another way)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app as cli_app
from axiscal.errors import AxiscalError
from axiscal.io.biaxial import parse_biaxial_test
from axiscal.store import open_store

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
X, Y = EXAMPLES / "squareness_L180_x.csv", EXAMPLES / "squareness_L180_y.csv"
#: Every option away from its default, so a lost option shows.
OPTIONS = ["--config", "T", "--orientation", "180", "--prism-error", "1.5", "--reference",
           "minimum_zone", "--datum", "Y", "--square", "square"]
runner = CliRunner()


def _run(*args) -> str:
    r = runner.invoke(cli_app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return r.stdout


@pytest.fixture(scope="module")
def kept(tmp_path_factory):
    """The command's --json and --report, its --inline file, and the file stored."""
    d = tmp_path_factory.mktemp("sq")
    inline, report = d / "sq.toml", d / "cli.html"
    out = _run("squareness", "biaxial", X, Y, *OPTIONS, "--json", "--inline", inline,
               "--report", report)
    url = f"sqlite:///{d / 'h.sqlite'}"
    st = open_store(url)
    added = st.add(inline.read_bytes(), inline.name, machine="VMC-800")
    yield {"json": json.loads(out), "inline": inline, "report": report, "store": st,
           "id": added.id, "url": url, "dir": d}
    st.close()


def test_the_stored_record_is_the_command_json_field_by_field(kept):
    """Two files -> inline file -> history -> record: every key of ``squareness biaxial
    --json`` (squareness object, U, each contribution, slopes, straightness, options) equals
    the record's, exactly (the readings are the same doubles); the squareness is its one
    parameter, with the command's U."""
    cli, t = kept["json"], kept["store"].get(kept["id"])
    rec = t.record()
    assert (rec.kind, t.summary.kind, t.summary.axis) == ("squareness", "squareness", "XY")
    for key, value in cli.items():
        assert rec.result[key] == value, key
        assert t.result[key] == value, key                 # as stored
    assert set(cli) <= set(t.result)
    q = t.result["quantities"]["squareness"]
    assert (q["value"], q["U"], q["k"], q["unit"]) == (cli["squareness"]["um_per_m"],
                                                       cli["U_um_per_m"], 2.0, "um/m")
    assert cli["config"] == "T" and cli["orientation"] == 180 and cli["reference"] == \
        "minimum_zone" and cli["prism_error_arcsec"] == 1.5
    assert cli["squareness"]["iso_datum"] == "Y"
    assert rec.budget.U("squareness") == cli["U_um_per_m"]
    shown = json.loads(_run("history", "show", kept["id"], "--db", kept["url"], "--json"))
    assert shown["quantities"]["squareness"] == q and shown["result"] == t.result


def test_an_archive_carries_the_test_and_its_record(kept, tmp_path):
    """Export and import into another history: the same bytes, kind, result and quantities
    (the archive carries the file; the importing history evaluates it again)."""
    from axiscal.store.archive import export_history, import_history

    export_history(kept["store"], tmp_path / "a.zip")
    other = open_store(f"sqlite:///{tmp_path / 'other.sqlite'}")
    import_history(other, tmp_path / "a.zip")
    t, o = kept["store"].get(kept["id"]), other.get(other.tests()[0].id)
    assert (o.raw, o.summary.kind, o.result) == (t.raw, "squareness", t.result)
    assert o.record().quantities == t.record().quantities
    other.close()


def test_the_file_reads_back_to_the_same_doubles(kept):
    """The readings of the inline file are the straightness files' doubles, bit for bit, and
    each file's SHA-256 is kept (by which the workbench links the tests it came from)."""
    import hashlib

    from axiscal.io.straightness import read_straightness

    t = parse_biaxial_test(kept["inline"].read_text(), "sq.toml")
    for data, path, digest in ((t.one, X, t.sha256[0]), (t.two, Y, t.sha256[1])):
        ref = read_straightness(path)
        assert data.positions.tobytes() == ref.positions.tobytes()
        assert data.deviations.tobytes() == ref.deviations.tobytes()
        assert (data.axis, data.direction, data.source) == (ref.axis, ref.direction, path.name)
        assert digest == hashlib.sha256(path.read_bytes()).hexdigest()
    assert (t.config, t.orientation, t.prism_error, t.reference, t.datum, t.square) == \
        ("T", 180, 1.5, "minimum_zone", "Y", "square")


def test_the_history_report_is_the_command_report(kept):
    """``history show ID --report`` writes ``squareness biaxial --report``'s report: the same
    document but for its heading, which names the stored test, and the minute it was
    written."""
    out = kept["dir"] / "history.html"
    _run("history", "show", kept["id"], "--db", kept["url"], "--report", out)

    def body(text):
        text = re.sub(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", "WHEN", text)   # written at
        return re.sub(r"<title>.*?</title>|<h1>.*?</h1>", "", text, flags=re.S)

    cli, stored = kept["report"].read_text(), out.read_text()
    assert body(cli) == body(stored)
    assert "VMC-800 axis XY (test 1, sq.toml: squareness_L180_x.csv, squareness_L180_y.csv)" \
        in stored


def test_the_certificate_states_the_record_and_is_numbered(kept, tmp_path):
    """The kind certificate's squareness is the record's value and U (k = 2); complete (E_VE
    declared too), it is issued and numbered by the register (as ``axiscal certificate issue
    ID``), stating the record's value and U with that E_VE."""
    import copy

    from axiscal.report.kind_certificate import certificate_record, write_kind_certificate
    from tests.report.test_kind_certificate import COMPLETE

    from axiscal.store.kinds import with_uncertainty

    st = kept["store"]
    t = st.get(kept["id"])
    f = certificate_record(t.record(), {"squareness": 200.0}).figures[0]
    q = t.result["quantities"]["squareness"]
    assert (f.name, f.value, f.U, f.k) == ("squareness", q["value"], q["U"], 2.0)
    # E_VE declared (its budget reads it: none given is a missing item, never 0)
    rec = with_uncertainty(t.record(), {**t.record().inputs, "e_ve": 0.5})
    f = certificate_record(rec, {"squareness": 200.0}).figures[0]
    out = write_kind_certificate(tmp_path / "c.html", rec, copy.deepcopy(COMPLETE),
                                 t.raw, {"squareness": 200.0}, store=st,
                                 filename=t.summary.filename, today="2026-11-25",
                                 prepared_by="J. Keller")
    assert out.missing == () and st.certificate(out.number).test_id == kept["id"]
    page = (tmp_path / "c.html").read_text()
    assert f"<td>{f.value_text}</td><td>{f.U_text}</td><td>2</td>" in page
    assert "squareness from two straightness profiles (ISO 230-1:2012)" in page


def _good(kept) -> str:
    return kept["inline"].read_text()


def _first_value(text: str, table: str, key: str, value: str) -> str:
    """``text`` with the first number of ``key`` in ``table`` replaced by ``value``."""
    start = text.index(f"{key} = [", text.index(table)) + len(key) + 4
    return text[:start] + value + text[text.index(",", start):]


HOSTILE = {
    "non-finite": (lambda s: s.replace("positions_m = [-0.4,", "positions_m = [nan,", 1),
                   "[first] positions_m[0] = nan: a finite number"),
    "infinite deviation": (lambda s: _first_value(s, "[second]", "deviations_m", "-inf"),
                           "[second] deviations_m[0] = -inf: a finite number"),
    "huge position": (lambda s: _first_value(s, "[first]", "positions_m", "1e300"),
                      "[first] positions_m[0] = 1e+300: a finite number"),
    "mismatched lengths": (lambda s: s.replace("positions_m = [-0.4, ", "positions_m = [",
                                               1), "[first] 16 positions_m and 17 deviations_m"),
    "unknown key": (lambda s: s.replace("[biaxial]\n", "[biaxial]\nspeed = 3\n"),
                    "[biaxial] 'speed': not a key of a squareness test file"),
    "unknown table": (lambda s: s + "\n[third]\naxis = \"Z\"\n",
                      "[third] is not a table of a squareness test file"),
    "missing table": (lambda s: s[:s.index("[second]")], "no [second] table"),
    "bad orientation": (lambda s: s.replace("orientation = 180", "orientation = 45"),
                        "[biaxial] orientation 45: one of 0, 90, 180 or 270"),
    "bad config": (lambda s: s.replace('config = "T"', 'config = "Q"'),
                   "[biaxial] config 'Q': one of L, T, +"),
    "control character": (lambda s: s.replace('machine = ""', 'machine = "A\\u0007B"'),
                          "[biaxial] machine: at most 300 characters, no control characters"),
    "one position": (lambda s: re.sub(r"positions_m = \[[^\]]*\]", "positions_m = [0.0, 0.0]",
                                      s, count=1).replace(
        s[s.index("deviations_m"):s.index("\n", s.index("deviations_m"))],
        "deviations_m = [0.0, 0.0]", 1), "[first] 2 reading(s) at 1 position(s)"),
}


@pytest.mark.parametrize("case", sorted(HOSTILE))
def test_a_hostile_file_is_refused_in_one_line_and_nothing_stored(kept, tmp_path, case):
    """Each hostile or partial file: ``history add`` exits 2 with one line naming the table
    and key, and the history holds no test."""
    change, words = HOSTILE[case]
    bad = tmp_path / "bad.toml"
    bad.write_text(change(_good(kept)))
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(cli_app, ["history", "add", str(bad), "--db", url, "--machine", "VMC"])
    assert r.exit_code == 2, r.output
    lines = [line for line in r.output.splitlines() if line.strip()]
    assert len(lines) == 1 and words in lines[0], r.output
    assert "Traceback" not in r.output
    st = open_store(url)
    assert st.tests() == []
    st.close()
    with pytest.raises(AxiscalError):
        parse_biaxial_test(bad.read_text(), "bad.toml")


def test_inline_refuses_a_square_error_over_a_degree_and_writes_nothing(tmp_path):
    out = tmp_path / "sq.toml"
    r = runner.invoke(cli_app, ["squareness", "biaxial", str(X), str(Y), "--prism-error",
                                "5000", "--inline", str(out)])
    assert r.exit_code == 2 and not out.exists()
    assert r.output.strip().splitlines() == [
        "axiscal: error: --inline: [biaxial] prism_error_arcsec 5000.0: a finite number of "
        "arcsec within ±3600"]
