"""Streams and environments (issue 39): the real console script in a child process.

Standard output closed, full or broken; consoles in ASCII, cp437, Latin-1 and the C locale;
``COLUMNS`` of 80, 20, 0 and 10,000,000; HOME not writable. Each is what a user's shell gives the
process, so these run ``python -m axiscal`` (the entry point that sets the process up), not
CliRunner.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
POS = ("# machine=VMC-800 axis=X target_unit=mm deviation_unit=um\n"
       "target,direction,run,deviation\n"
       + "".join(f"{t},{d},{r},{0.001 * t + 0.5 * r + (d == '-') + 120:.3f}\n"
                 for r in (1, 2) for t in (0, 100, 200, 300) for d in "+-"))


@pytest.fixture(scope="module")
def pos(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("streams") / "pos.csv"
    p.write_text(POS)
    return p


def _env(**kw) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "PYTHONIOENCODING")}
    env["PYTHONPATH"] = str(ROOT / "src")
    env.update(kw)
    return {k: v for k, v in env.items() if v is not None}


def _axiscal(*args, stdout=subprocess.PIPE, env=None, close_reader=False, preexec=None):
    p = subprocess.Popen([sys.executable, "-m", "axiscal", *map(str, args)], stdout=stdout,
                         stderr=subprocess.PIPE, env=env or _env(), preexec_fn=preexec)
    if close_reader:
        p.stdout.close()
        out = b""
    else:
        out = p.stdout.read() if stdout == subprocess.PIPE else b""
    err = p.stderr.read().decode()
    return p.wait(), out, err


@pytest.mark.parametrize("args", [["iso230-2", "{pos}", "--json"], ["--help"]])
def test_a_broken_pipe_is_quiet_and_not_exit_1(pos, args):
    """Issue 39: ``| head -1`` exited 1, the code for "tolerance not met". Now 141 (128 +
    SIGPIPE, what a shell shows for a Unix tool ended by it) and nothing on stderr."""
    code, _, err = _axiscal(*[a.replace("{pos}", str(pos)) for a in args], close_reader=True)
    assert (code, err) == (141, "")


@pytest.mark.parametrize("args", [["iso230-2", "{pos}"], ["--help"]])
def test_a_full_stdout_is_one_line_and_exit_74(pos, args):
    """Issue 39: stdout to /dev/full ended in a traceback."""
    if not Path("/dev/full").exists():
        pytest.skip("no /dev/full on this system")
    with open("/dev/full", "w") as full:
        code, _, err = _axiscal(*[a.replace("{pos}", str(pos)) for a in args], stdout=full)
    assert code == 74
    assert err.strip().splitlines() == ["axiscal: error: cannot write to standard output: the "
                                        "disk is full (No space left on device)"]


def test_a_closed_stdout_is_one_line_and_exit_74(pos):
    """Issue 39: ``>&-`` (stdout closed) ended in a traceback."""
    code, _, err = _axiscal("iso230-2", pos, stdout=None, preexec=lambda: os.close(1))
    assert code == 74
    assert err.strip().splitlines() == ["axiscal: error: standard output is closed; redirect "
                                        "it to a file or to /dev/null"]


@pytest.mark.parametrize("env", [{"PYTHONIOENCODING": "cp437"},
                                 {"LC_ALL": "C", "LANG": "C", "PYTHONUTF8": "0",
                                  "PYTHONCOERCECLOCALE": "0"}])
def test_any_console_encoding_prints(pos, env):
    """Issue 39: a console in cp437, latin-1, ascii or LC_ALL=C with PYTHONUTF8=0 ended in a
    UnicodeEncodeError. µ, ° and ″ fall back to ASCII spellings where the encoding lacks them."""
    code, out, err = _axiscal("iso230-2", pos, env=_env(**env))
    assert code in (0, 1) and "Traceback" not in err, err
    text = out.decode(env.get("PYTHONIOENCODING", "ascii"))
    assert "positioning test" in text
    if env.get("PYTHONIOENCODING", "ascii") == "ascii":
        assert text.isascii() and "[um]" in text


@pytest.mark.parametrize("columns", ["80", "20", "0"])
def test_tables_never_cut_a_number(pos, columns):
    """Issue 39: at 80 columns a cell showed ``121.6…`` (a wrong number); at 20 cells were
    empty; ``COLUMNS=0`` printed nothing with exit 0. Every mean of the file is printed whole."""
    code, out, err = _axiscal("iso230-2", pos, env=_env(COLUMNS=columns))
    text = out.decode()
    assert code in (0, 1), err
    assert "…" not in text
    for t in ("100", "200", "300"):
        assert f"│ {t} " in text or f"│   {t} " in text or f" {t} │" in text


def test_an_absurd_width_is_clamped(pos):
    """Issue 39: ``COLUMNS=10000000 axiscal --help`` took 68 s; clamped to 1000 columns."""
    import time

    t0 = time.perf_counter()
    code, out, _ = _axiscal("--help", env=_env(COLUMNS="10000000"))
    assert code == 0 and time.perf_counter() - t0 < 30
    assert max(len(line) for line in out.decode().splitlines()) <= 1000


def test_matplotlib_cache_goes_to_a_temporary_folder_without_home(pos, tmp_path):
    """Issue 39: with HOME not writable every ``--plot`` printed matplotlib's cache warning."""
    env = _env(HOME="/nonexistent", MPLCONFIGDIR=None, XDG_CACHE_HOME=None,
               XDG_CONFIG_HOME=None, MPLBACKEND="Agg")
    code, _, err = _axiscal("iso230-2", pos, "--plot", tmp_path / "p.png", env=env)
    assert code in (0, 1) and (tmp_path / "p.png").is_file()
    assert "Matplotlib" not in err and "writable" not in err, err


def test_clamp_columns():
    from axiscal.cli import clamp_columns

    for given, want in [("0", None), ("-1", None), ("x", None), ("5", "20"), ("80", "80"),
                        ("10000000", "1000")]:
        env = {"COLUMNS": given}
        clamp_columns(env)
        assert env.get("COLUMNS") == want, given


#: A child that runs the console script with one library call replaced by one that signals the
#: process itself: the signal arrives in the middle of the work, every time.
_SIGNALLED = """
import os, signal, sys
import {module} as m
real = m.{name}
def stop(*a, **kw):
    {before}
    os.kill(os.getpid(), signal.{signal})
    return real(*a, **kw)
m.{name} = stop
from axiscal.cli import main
sys.argv = ["axiscal", *sys.argv[1:]]
main()
"""


def _signalled(args, module, name, sig, cwd, before="pass"):
    code = _SIGNALLED.format(module=module, name=name, signal=sig, before=before)
    p = subprocess.run([sys.executable, "-c", code, *map(str, args)], capture_output=True,
                       text=True, env=_env(), cwd=cwd, timeout=120)
    return p.returncode, p.stderr


def test_sigterm_during_export_leaves_no_partial_archive(pos, tmp_path):
    """Issue 39: SIGTERM during ``history export`` left a 5.4 MB hidden partial archive (6 of 6
    tries). Now the temporary file goes, exit 143, one line saying nothing was written."""
    from axiscal.store import open_store

    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    open_store(db).add(pos.read_bytes(), pos.name).id
    before = sorted(p.name for p in tmp_path.iterdir())
    code, err = _signalled(["history", "export", tmp_path / "h.zip", "--db", db],
                           "zipfile", "ZipFile.writestr", "SIGTERM", tmp_path)
    assert code == 143, err
    assert err.strip().splitlines() == ["axiscal: terminated (SIGTERM); no file was written; "
                                        "temporary files removed"]
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_sigterm_while_creating_the_database_leaves_nothing(pos, tmp_path):
    """Issue 39: SIGTERM during database creation left a ``.creating`` trio."""
    code, err = _signalled(["history", "add", pos, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}"],
                           "alembic.command", "upgrade", "SIGTERM", tmp_path)
    assert code == 143, err
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_says_what_was_written(tmp_path):
    """Issue 39: Ctrl-C in ``demo`` said "nothing was written" after 7 files and a certificate.
    The message names the files written before the interrupt."""
    code, err = _signalled(["volumetric", "simulate", "--out", tmp_path / "vol"],
                           "axiscal.io.volumetric", "write_simulation", "SIGINT", tmp_path,
                           before="tmp = __import__('pathlib').Path(sys.argv[-1]);"
                                  " __import__('axiscal.io._files', fromlist=['x'])"
                                  ".write_text_atomic(tmp / 'a.txt', 'a')")
    assert code == 130, err
    assert "interrupted; wrote before it:" in err and "a.txt" in err


def test_a_file_size_limit_is_named_as_such(pos, tmp_path):
    """Issue 39: "disk I/O error" where the cause was ``ulimit -f``. The history and a set of
    files say the file-size limit, in one line, exit 2 (SIGXFSZ no longer ends the process)."""
    import resource

    from axiscal.store import open_store

    db = tmp_path / "h.sqlite"
    open_store(f"sqlite:///{db}").add(pos.read_bytes(), pos.name)
    limit = 16384   # smaller than what one test adds to the write-ahead log

    def small():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    other = tmp_path / "other.csv"
    other.write_text(POS.replace(",120.", ",121."))
    code, _, err = _axiscal("history", "add", other, "--db", f"sqlite:///{db}", preexec=small)
    assert code == 2 and "file-size limit" in err and len(err.strip().splitlines()) == 1, err
    code, _, err = _axiscal("volumetric", "simulate", "--out", tmp_path / "vol",
                            preexec=lambda: resource.setrlimit(resource.RLIMIT_FSIZE,
                                                               (4096, 4096)))
    assert code == 2 and "file-size limit" in err and "none of the 19 files" in err, err
    assert list((tmp_path / "vol").iterdir()) == []
