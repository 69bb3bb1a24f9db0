"""Issue 39, as a hostile user found it: every case of the issue as a regression test.

Outputs that would destroy an input or the history, text injected into controller files, numbers
that are not numbers, archives that jam the register, streams and environments, half-done work.
A refusal is ONE line ``axiscal: error: ...`` with exit 2, nothing written, every input
byte-identical (:func:`_assertions.one_error_line`).
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

from _assertions import one_error_line

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
POS = ("# machine=VMC-800 axis=X target_unit=mm deviation_unit=um\n"
       "target,direction,run,deviation\n"
       + "".join(f"{t},{d},{r},{0.001 * t + 0.5 * r + (d == '-'):.3f}\n"
                 for r in (1, 2) for t in (0, 100, 200, 300) for d in "+-"))


def _run(*args, **kw):
    return runner.invoke(app, [str(a) for a in args], **kw)


def _sha(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def lin(tmp_path_factory) -> Path:
    """A simulated positioning test of the demo's linear axis (21 targets over 800 mm)."""
    d = tmp_path_factory.mktemp("lin")
    r = _run("simulate", ROOT / "src/axiscal/data/demo_linear.toml", "--data", d / "lin.csv")
    assert r.exit_code == 0, r.output
    return d / "lin.csv"


# -- 2. text injected into controller files -------------------------------------------------
def test_a_ren_axis_with_a_line_break_adds_no_line(lin, tmp_path):
    """Issue 39: ``--axis $'X\\nCompensation spacing : 1 mm'`` added a line to a ``.ren``."""
    out = tmp_path / "t.ren"
    r = _run("compensate", lin, "--spacing", 40, "-c", "renishaw-ren", "--axis",
             "X\nCompensation spacing : 1 mm", "--out", out)
    assert r.exit_code == 0, r.output
    lines = out.read_text().splitlines()
    assert lines[1] == "Axis : X_Compensation_spacing_1_mm"
    assert sum(ln.startswith("Compensation spacing") for ln in lines) == 1
    assert "axis name in the source data" in r.output   # cleaned, and said


def test_a_json_metadata_axis_with_a_line_break_adds_no_line(lin, tmp_path):
    """Issue 39: the same through ``metadata.axis`` of a JSON data file."""
    from axiscal.io import parse_positioning
    from axiscal.io.json import format_positioning_json

    d = json.loads(format_positioning_json(parse_positioning(lin.read_text())))
    d["metadata"]["axis"] = "X\nCompensation spacing : 1 mm"
    src = tmp_path / "lin.json"
    src.write_text(json.dumps(d))
    out = tmp_path / "t.ren"
    assert _run("compensate", src, "--spacing", 40, "-c", "renishaw-ren", "--out",
                out).exit_code == 0
    assert sum(ln.startswith("Compensation spacing") for ln in out.read_text().splitlines()) == 1


@pytest.mark.parametrize("controller, option, words", [
    ("siemens-840d", "machine_axis=X1]=0\nM30\n;[", ["machine_axis", "machine axis name"]),
    ("fanuc", "axis_number=99999999999999999999", ["axis_number", "1 … 32"]),
    ("fanuc", "axis_number=-3", ["axis_number"]),
    ("fanuc", "reference_number=-5", ["reference_number"]),
    ("linuxcnc", "joint=99", ["joint", "0 … 15"]),
    ("heidenhain", "driving_axis=X\nBEGIN", ["driving_axis", "axis letter"]),
])
def test_a_writer_option_outside_its_grammar_is_refused(lin, tmp_path, controller, option,
                                                        words):
    """Issue 39: ``-o machine_axis=$'X1]=0\\nM30\\n;['`` wrote ``M30`` into an 840D table;
    ``-o axis_number=99999999999999999999`` wrote ``N3620A99999999999999999999P0``."""
    out = tmp_path / "t.txt"
    one_error_line(_run("compensate", lin, "--spacing", 40, "-c", controller, "-o", option,
                        "--out", out), *words)
    assert not out.exists()


# -- 1. outputs never touch inputs ----------------------------------------------------------
@pytest.fixture
def history(tmp_path) -> Path:
    """A history holding one test, at ``r.html`` (the name the issue's hostile user chose)."""
    db = tmp_path / "r.html"
    src = tmp_path / "pos.csv"
    src.write_text(POS)
    assert _run("history", "add", src, "--db", f"sqlite:///{db}").exit_code == 0
    return db


@pytest.mark.parametrize("args", [
    ["history", "show", "1", "--report", "{db}"],
    ["history", "show", "1", "--plot", "{db}.png"],   # the -wal/-shm are inputs, not this
    ["history", "export", "{db}"],
    ["history", "show", "1", "--report", "{link}"],
])
def test_an_output_at_the_history_database_is_refused(history, tmp_path, args):
    """Issue 39: ``history show 1 --report r.html --db sqlite:///r.html`` overwrote the history
    with the report ("not even SQLite" afterwards); ``history export h.zip --db
    sqlite:///h.zip`` likewise. A symbolic link to the database is the database too."""
    link = tmp_path / "link.html"
    link.symlink_to(history)
    before = _sha(history)
    fill = {"{db}": str(history), "{link}": str(link)}
    argv = [fill.get(a, a) for a in args]
    if argv[-1].endswith(".png"):
        argv[-1] = str(history) + ".png"
        assert _run(*argv, "--db", f"sqlite:///{history}").exit_code == 0   # not the database
        return
    if args[1] == "export":   # an archive must be .zip: the database named so
        zipped = tmp_path / "h.zip"
        history.rename(zipped)
        history, before, argv = zipped, _sha(zipped), ["history", "export", str(zipped)]
    one_error_line(_run(*argv, "--db", f"sqlite:///{history}"), "history database",
                   "would destroy the history")
    assert _sha(history) == before
    assert history.read_bytes()[:16] == b"SQLite format 3\x00"


def test_an_output_at_the_default_history_is_refused(history, monkeypatch):
    """The history named by AXISCAL_DB (no --db) is an input all the same."""
    monkeypatch.setenv("AXISCAL_DB", f"sqlite:///{history}")
    before = _sha(history)
    one_error_line(_run("history", "show", "1", "--report", history), "history database")
    assert _sha(history) == before


@pytest.fixture(scope="module")
def vol(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("vol") / "vol"
    assert _run("volumetric", "simulate", "--out", d).exit_code == 0
    return d


def test_volumetric_tables_never_replace_a_measured_file(vol, tmp_path):
    """Issue 39: ``volumetric compensate CONFIG --out DIR`` overwrote a measurement file the
    configuration names when a table had the same name (exit 0). Now refused, nothing written."""
    import shutil

    d = tmp_path / "v"
    shutil.copytree(vol, d)
    (d / "X_EXX.csv").rename(d / "X_compensation_X.csv")
    cfg = d / "volumetric.toml"
    cfg.write_text(cfg.read_text().replace('"X_EXX.csv"', '"X_compensation_X.csv"'))
    before = {p.name: _sha(p) for p in d.iterdir()}
    one_error_line(_run("volumetric", "compensate", cfg, "--controller", "csv", "--out", d),
                   "X_compensation_X.csv", "would replace the input")
    assert {p.name: _sha(p) for p in d.iterdir()} == before   # nothing written, nothing left


def test_volumetric_simulate_on_a_full_disk_leaves_no_file(tmp_path, monkeypatch):
    """Issue 39: ``volumetric simulate --out`` on a full disk left 7 of 19 files. The 19 are
    written all or nothing, and the message names the full disk."""
    import errno

    real = Path.write_bytes
    calls = []

    def full(self, data):
        calls.append(self)
        if len(calls) == 8:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(self, data)

    monkeypatch.setattr(Path, "write_bytes", full)
    out = tmp_path / "vol"
    one_error_line(_run("volumetric", "simulate", "--out", out), "the disk is full",
                   "none of the 19 files")
    assert list(out.iterdir()) == []


def test_two_outputs_of_one_run_with_one_name_are_refused(tmp_path):
    from axiscal.errors import InputError
    from axiscal.io._files import write_files_atomic

    with pytest.raises(InputError, match="two outputs of one run"):
        write_files_atomic(tmp_path, {"X.COM": "a", "x.com": "b"})
    with pytest.raises(InputError, match="not a plain file name"):
        write_files_atomic(tmp_path, {"../X.COM": "a"})
    assert list(tmp_path.iterdir()) == []


# -- 3. numbers parsed by one strict grammar ------------------------------------------------
@pytest.mark.parametrize("fmt", ["csv", "rtl"])
@pytest.mark.parametrize("bad", ["١٢", "１２", "1_0", "٣٤.٥"])
def test_digits_of_other_scripts_and_underscores_are_not_numbers(tmp_path, fmt, bad):
    """Issue 39: ``١٢`` and ``１２`` read as 12 and ``1_0`` as 10 (Python's ``float()`` accepts
    them) in a tidy CSV or ``.rtl``, changing A from 14.09 to 17.10 with exit 0."""
    from axiscal.io import parse_positioning
    from axiscal.io.renishaw import format_rtl

    if fmt == "csv":
        lines = POS.splitlines()
        lines[4] = lines[4].replace("100,", f"{bad},", 1) if bad[0] != "1" else \
            lines[4].replace(",1,", f",{bad},", 1)
        text = "\n".join(lines) + "\n"
    else:
        text = format_rtl(parse_positioning(POS))
        lines = text.splitlines()
        i = lines.index("1   2      0.6")   # run 1, target 2: the deviation
        lines[i] = f"1   2      {bad}" if bad[0] != "1" else f"1   {bad}      0.6"
        text = "\n".join(lines) + "\n"
    src = tmp_path / f"t.{fmt}"
    src.write_text(text, encoding="utf-8")
    one_error_line(_run("iso230-2", src), "not a")


def test_strict_grammar_keeps_ordinary_numbers():
    from axiscal._parse import strict_float

    assert [strict_float(t) for t in ("1", "-2.5", "+.5", "3.", "1e-3", "1E+3", " 7 ")] == \
        [1.0, -2.5, 0.5, 3.0, 1e-3, 1e3, 7.0]


def test_a_json_target_of_400_digits_is_one_line(lin, tmp_path):
    """Issue 39: a JSON target ``10**400`` (an integer literal) ended in a traceback."""
    from axiscal.io import parse_positioning
    from axiscal.io.json import format_positioning_json

    d = json.loads(format_positioning_json(parse_positioning(lin.read_text())))
    d["targets"][1] = 10**400
    src = tmp_path / "big.json"
    src.write_text(json.dumps(d))
    one_error_line(_run("iso230-2", src), "401 digits", "out of range")


@pytest.mark.parametrize("value", ["1e150", "1e200", "-1e300"])
def test_uncertainty_inputs_beyond_1e100_are_refused(lin, value):
    """Issue 39: ``--uncertainty e_ve=1e200`` (every input at >= 1e150) ended in a traceback
    (OverflowError squaring it in the GUM sum)."""
    one_error_line(_run("iso230-2", lin, "--uncertainty", f"e_ve={value}"), "e_ve", "range"
                   if value[0] != "-" else "e_ve")


def test_uncertainty_input_from_a_configuration_beyond_1e100_is_refused(lin, tmp_path):
    """The same bound from the configuration file's [uncertainty] table."""
    cfg = tmp_path / "job.toml"
    cfg.write_text("[uncertainty]\ne_ve = 1e200\n")
    r = _run("iso230-2", lin, "--job", cfg)
    one_error_line(r, "e_ve", "implausible: give 0 to 1000")   # the input's own range


# -- 5/6. the history's fields at the edge ---------------------------------------------------
def test_a_5000_character_instrument_is_refused_naming_the_field(tmp_path):
    """Issue 39: a 5,000-character instrument was stored on SQLite and refused on PostgreSQL
    ("value too long for type character varying(200)", naming no field). Both now refuse it
    before a row is made, naming the field and the limit read from the model."""
    src = tmp_path / "pos.csv"
    src.write_text(POS)
    one_error_line(_run("history", "add", src, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}",
                        "--instrument", "x" * 5000), "instrument of 5000 characters",
                   "at most 200")


def test_a_machine_name_with_a_line_break_is_refused(tmp_path):
    """Issue 39: a newline was accepted in a machine name."""
    src = tmp_path / "pos.csv"
    src.write_text(POS)
    one_error_line(_run("history", "add", src, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}",
                        "--machine", "VMC\nM30"), "machine name", "control character")


def test_renaming_a_machine_to_its_own_name_is_no_audited_change(history):
    """Issue 39: ``rename-machine MA MA`` was audited as a change."""
    url = f"sqlite:///{history}"
    one_error_line(_run("history", "rename-machine", "VMC-800", "VMC-800", "--reason", "x",
                        "--by", "me", "--db", url), "already has that name")
    r = _run("history", "audit", "--db", url, "--json")
    if r.exit_code == 0:
        assert "rename-machine" not in r.stdout


def test_a_read_only_command_creates_no_folder_and_no_database(tmp_path):
    """Issue 39: ``history list --db sqlite:///typo/h.sqlite`` made the folder and an empty
    database."""
    for args in (["history", "list"], ["history", "machines"], ["certificate", "list"],
                 ["history", "audit"]):
        one_error_line(_run(*args, "--db", f"sqlite:///{tmp_path / 'typo' / 'h.sqlite'}"),
                       "no history database")
    assert list(tmp_path.iterdir()) == []


# -- smaller items ----------------------------------------------------------------------------
def test_a_resolution_rounding_every_correction_to_zero_is_refused(lin, tmp_path):
    """Issue 39: ``compensate --resolution 1e300`` wrote an all-zero table (exit 0)."""
    out = tmp_path / "t.csv"
    one_error_line(_run("compensate", lin, "--spacing", 40, "--resolution", "1e300", "--out",
                        out), "rounds every correction to zero")
    assert not out.exists()


@pytest.mark.parametrize("args, words", [
    (["--overrun", "1e6"], "--overrun"), (["--dwell", "1e9"], "--dwell"),
    (["--overrun", "-1"], "--overrun"),
])
def test_plan_overrun_and_dwell_are_bounded(args, words):
    """Issue 39: ``plan --overrun 1e6 --dwell 1e9`` was accepted."""
    one_error_line(_run("plan", "linear", "--length", "800", *args), words)


def test_an_instrument_without_name_is_refused_by_config(tmp_path, monkeypatch):
    """Issue 39: a configuration's ``[[instrument]]`` without ``name`` ended a certificate in a
    traceback, and ``axiscal config`` accepted the file."""
    cfg = tmp_path / "config.toml"
    cfg.write_text('[[instrument]]\nserial = "1"\n')
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    one_error_line(_run("config"), "[[instrument]] 1 has no name")


def test_a_long_note_is_not_echoed_back(history, tmp_path):
    """Issue 39: a 50 kB note was echoed back. ``history add --note`` takes at most 10,000
    characters, as the workbench's upload does; the line an edit prints says the change in at
    most 400 characters (the trail keeps every word)."""
    url = f"sqlite:///{history}"
    src = tmp_path / "other.csv"
    src.write_text(POS.replace(",0.5", ",0.7"))
    one_error_line(_run("history", "add", src, "--note", "n" * 50_000, "--db", url),
                   "note of 50000 characters")
    r = _run("history", "edit", "1", "--note", "n" * 2000, "--by", "me", "--reason", "x",
             "--db", url)
    assert r.exit_code == 0, r.output
    assert len(r.stdout.strip()) <= 400 and r.stdout.count("\n") == 1
    r = _run("history", "audit", "--db", url, "--json")
    assert r.exit_code == 0 and "n" * 2000 in r.stdout
