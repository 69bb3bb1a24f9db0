"""Fuzz harness over the whole command line: every command survives every hostile input.

The commands are discovered from the typer app (so commands added later are covered without
editing this file). For each command, hypothesis draws hostile inputs: for a file argument an
empty file, binary bytes, a folder, a missing file, a TOML with an unknown table or key, a value of
the wrong type or of absurd magnitude; for a numeric option 0, negative, 1e308, nan, inf and huge
counts. Each invocation runs in a child process with a memory limit (RLIMIT_AS) and a time limit,
and must end with:

* exit code 0, 1 (a failed tolerance) or 2 (bad input), never a traceback;
* on exit 1 or 2: exactly one line on stderr, ``axiscal: error: ...``, and no output file left;
* no warning text (numpy RuntimeWarning ...) on stderr.

A hostile FILE (empty, binary, folder, missing, unknown table) must be refused (exit 2).
The budget is fixed and derandomized (``_EXAMPLES`` per command) to keep ``make test`` short.
"""

from __future__ import annotations

import json
import os
import resource
import select
import subprocess
import sys
from pathlib import Path

import pytest
import typer
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer._click import core

from axiscal.cli import app

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
WORKER = Path(__file__).with_name("_fuzz_worker.py")
MEMORY_LIMIT = 3 * 2**30     # bytes of address space of the child
TIME_LIMIT = 60.0            # seconds for one invocation
#: hypothesis examples per command (AXISCAL_FUZZ_EXAMPLES=200 for a longer hunt)
_EXAMPLES = int(os.environ.get("AXISCAL_FUZZ_EXAMPLES", "8"))

#: Options that name files axiscal writes; they must not be left behind by a failed run.
OUTPUTS = {"--report": ".html", "--plot": ".png", "--csv": ".csv", "--out": ".csv",
           "--data": ".csv"}
#: Options that name files axiscal reads.
INPUT_OPTIONS = {"--file", "--verify", "--read"}

#: A valid invocation of the commands that need input files (the harness mutates it); a command
#: not listed gets its file arguments from the hostile files only.
BASES = {
    "iso230-2": ["{tmp}/pos.csv"],
    "simulate": [str(EXAMPLES / "compensation_linear.toml")],
    "motion simulate": [str(EXAMPLES / "motion_indexing_table.toml")],
    "motion stability": [str(EXAMPLES / "motion_indexing_table.toml")],
    "motion repeatability": [str(EXAMPLES / "motion_indexing_table.toml")],
    "motion analyze": ["{tmp}/motion.csv"],
    "rotary simulate": [str(EXAMPLES / "rotary_turntable.toml")],
    "rotary budget": ["--alpha", "10", "--beta", "10"],
    "scale home": [str(EXAMPLES / "scale_single.toml")],
    "scale gantry": [str(EXAMPLES / "scale_gantry.toml")],
    "squareness biaxial": [str(EXAMPLES / "squareness_L180_x.csv"),
                           str(EXAMPLES / "squareness_L180_y.csv")],
    "squareness diagonal": ["--x-length", "600", "--y-length", "800", "--d1", "5", "--d2", "-3"],
    "squareness circular": [str(EXAMPLES / "squareness_ballbar_150mm.csv")],
    "straightness": [str(EXAMPLES / "squareness_L180_x.csv")],
    "plan linear": ["--length", "800"],
    "compensate": ["--verify", str(EXAMPLES / "compensation_linear.toml")],
}

HOSTILE_NUMBERS = ["0", "-1", "-1e308", "1e308", "nan", "inf", "-inf", "1e-300",
                   "4294967297", "99999999999999999999", "abc", ""]
HOSTILE_FILES = ["empty", "binary", "folder", "missing", "unknown_table", "comment_only"]
HOSTILE_TOML_VALUES = ["0", "-1", "1e308", "nan", "inf", "4294967297", '"text"', "[]", "{}",
                       "true"]


def _commands():
    """(path, click command) of every leaf command of the app, found by walking its groups."""
    root = typer.main.get_command(app)

    def walk(cmd, path, ctx):
        if hasattr(cmd, "list_commands"):
            sub = core.Context(cmd, info_name=path[-1] if path else "axiscal", parent=ctx)
            for name in cmd.list_commands(sub):
                yield from walk(cmd.get_command(sub, name), path + [name], sub)
        else:
            yield " ".join(path), cmd

    return list(walk(root, [], None))


COMMANDS = dict(_commands())


def _numeric(cmd) -> list[str]:
    return [p.opts[0] for p in cmd.params if p.param_type_name == "option"
            and type(p.type).__name__ in ("FiniteFloat", "FiniteFloatRange", "IntRange",
                                          "IntParamType")]


def _file_inputs(cmd) -> list:
    """Names of the file parameters axiscal reads: positional paths and INPUT_OPTIONS."""
    out = []
    for p in cmd.params:
        if type(p.type).__name__ != "TyperPath":
            continue
        if p.param_type_name == "argument":
            out.append(("argument", p.name))
        elif p.opts[0] in INPUT_OPTIONS:
            out.append(("option", p.opts[0]))
    return out


class Worker:
    """A child Python with a memory limit that runs invocations one at a time."""

    def __init__(self, cwd: Path):
        self.cwd = cwd
        self._start()

    def _start(self) -> None:
        def limit():
            resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))

        env = dict(os.environ, PYTHONWARNINGS="default", COLUMNS="120")
        self.proc = subprocess.Popen([sys.executable, str(WORKER)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True, cwd=self.cwd,
                                     preexec_fn=limit, env=env)
        assert json.loads(self._line(TIME_LIMIT)) == "ready"

    def _line(self, timeout: float) -> str:
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        if not ready:
            self.proc.kill()
            self.proc.wait()
            raise AssertionError(f"no answer within {timeout:g} s (a hang)")
        line = self.proc.stdout.readline()
        if not line:
            raise AssertionError(f"the child died (exit {self.proc.wait()}), e.g. beyond the "
                                 f"{MEMORY_LIMIT / 2**30:g} GiB memory limit")
        return line

    def run(self, args: list[str]) -> dict:
        if self.proc.poll() is not None:   # killed by an earlier case (a hang or the memory
            self._start()                  # limit, reported there): a fresh child for this one
        self.proc.stdin.write(json.dumps(args) + "\n")
        self.proc.stdin.flush()
        return json.loads(self._line(TIME_LIMIT))

    def close(self):
        if self.proc.poll() is None:
            self.proc.stdin.close()
            self.proc.wait(timeout=10)


def _data_files(tmp: Path) -> None:
    """Valid data files the bases use (a positioning CSV, a five-error file)."""
    rows = ["target,direction,run,deviation"]
    for run in (1, 2):
        for t in (0, 100, 200, 300):
            for d in ("+", "-"):
                rows.append(f"{t},{d},{run},{0.001 * t + 0.5 * run + (d == '-'):.3f}")
    (tmp / "pos.csv").write_text("# target_unit=mm deviation_unit=um axis=X\n" + "\n".join(rows)
                                 + "\n")
    rows = [f"{r},{a},{a / 90 + r},0.1,0,0.2,0" for r in (1, 2) for a in range(0, 360, 30)]
    (tmp / "motion.csv").write_text("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n"
                                    + "\n".join(rows) + "\n")


def _hostile_file(tmp: Path, kind: str, like: str | None, n: int) -> str:
    p = tmp / f"in{n}{Path(like).suffix if like else '.toml'}"
    if kind == "empty":
        p.write_text("")
    elif kind == "binary":
        p.write_bytes(bytes(range(256)) * 8)
    elif kind == "folder":
        p.mkdir()
    elif kind == "unknown_table":
        text = Path(like).read_text() if like and Path(like).suffix == ".toml" else ""
        p.write_text(text + "\n[no_such_table]\nx = 1\n")
    elif kind == "comment_only":
        p.write_text("# nothing but a comment\n")
    return str(p)


def _toml_with(like: str, tmp: Path, line_no: int, value: str, n: int) -> str | None:
    """``like`` with the value of its line_no-th ``key = number`` line replaced by ``value``."""
    lines = Path(like).read_text().splitlines()
    keyed = [i for i, ln in enumerate(lines) if "=" in ln and not ln.lstrip().startswith(("#", "["))
             and ln.split("=", 1)[1].split("#")[0].strip()[:1] in "-+.0123456789"]
    if not keyed:
        return None
    i = keyed[line_no % len(keyed)]
    lines[i] = lines[i].split("=", 1)[0] + "= " + value
    p = tmp / f"mut{n}.toml"
    p.write_text("\n".join(lines) + "\n")
    return str(p)


def _check(name: str, args: list[str], r: dict, tmp: Path, outputs: list[Path],
           must_fail: bool) -> None:
    said = f"axiscal {name} {' '.join(args)}\n--- stderr:\n{r['stderr']}"
    assert r["traceback"] is None, f"traceback from {said}\n{r['traceback']}"
    assert r["exit"] in (0, 1, 2), f"exit {r['exit']} from {said}"
    assert "Warning:" not in r["stderr"] and "warnings.warn" not in r["stderr"], said
    if must_fail:
        assert r["exit"] == 2, f"a hostile file was accepted: {said}\n{r['stdout'][:500]}"
    if r["exit"] != 0:
        lines = r["stderr"].strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), \
            f"not one error line: {said}"
        assert len(lines[0]) > len("axiscal: error: ") + 10, said
        left = [str(p) for p in outputs if p.exists()]
        assert not left, f"output left behind after an error: {left} from {said}"


def _kinds(name: str) -> list[str]:
    """What can be made hostile for a command: its numbers, its files, its TOML configuration."""
    cmd = COMMANDS[name]
    toml_in_base = [a for a in BASES.get(name, []) if a.endswith(".toml")]
    return ((["number"] if _numeric(cmd) else []) + (["file"] if _file_inputs(cmd) else [])
            + (["toml"] if toml_in_base else []))


#: Commands with nothing a user can make hostile (no number option, no file) are not fuzzed;
#: test_unfuzzed_commands_take_no_input checks that this list stays true.
FUZZED = sorted(n for n in COMMANDS if _kinds(n))
UNFUZZED = sorted(set(COMMANDS) - set(FUZZED))


def test_unfuzzed_commands_take_no_input():
    for name in UNFUZZED:
        cmd = COMMANDS[name]
        assert not _numeric(cmd) and not _file_inputs(cmd), name
    assert len(FUZZED) > 30


@pytest.mark.parametrize("name", FUZZED)
def test_command_survives_hostile_input(name, tmp_path):
    cmd = COMMANDS[name]
    _data_files(tmp_path)
    base = [a.replace("{tmp}", str(tmp_path)) for a in BASES.get(name, [])]
    numeric = _numeric(cmd)
    inputs = _file_inputs(cmd)
    kinds = _kinds(name)
    toml_in_base = [a for a in base if a.endswith(".toml")]
    worker = Worker(tmp_path)
    counter = iter(range(10**6))

    @settings(max_examples=_EXAMPLES, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(st.data())
    def case(data):
        n = next(counter)
        kind = data.draw(st.sampled_from(kinds))
        args, must_fail = list(base), False
        if kind == "number":
            opt = data.draw(st.sampled_from(numeric))
            args += [opt, data.draw(st.sampled_from(HOSTILE_NUMBERS))]
        elif kind == "file":
            where, pname = data.draw(st.sampled_from(inputs))
            hostile = data.draw(st.sampled_from(HOSTILE_FILES))
            if where == "argument":
                positional = [a for a in base if not a.startswith("-") and Path(a).suffix]
                like = positional[0] if positional else None
                path = _hostile_file(tmp_path, hostile, like, n)
                args = [path if a == like else a for a in base] if like else base + [path]
            else:
                like = base[base.index(pname) + 1] if pname in base else None
                path = _hostile_file(tmp_path, hostile, like, n)
                args = [a for a in base if a not in (pname, like)] + [pname, path]
                if pname != "--verify" and "--verify" in args:
                    i = args.index("--verify")
                    del args[i:i + 2]
            must_fail = hostile in ("binary", "folder", "missing", "unknown_table") or \
                (hostile in ("empty", "comment_only") and Path(path).suffix != ".csv"
                 and name not in ("compensate",))
        else:
            like = data.draw(st.sampled_from(toml_in_base))
            path = _toml_with(like, tmp_path, data.draw(st.integers(0, 200)),
                              data.draw(st.sampled_from(HOSTILE_TOML_VALUES)), n)
            if path is None:
                return
            args = [path if a == like else a for a in base]
        outputs = []
        for opt, suffix in OUTPUTS.items():
            if any(opt in p.opts for p in cmd.params):
                out = tmp_path / f"out{n}{suffix}"
                args += [opt, str(out)]
                outputs.append(out)
        r = worker.run([*name.split(), *args])
        _check(name, args, r, tmp_path, outputs, must_fail)

    try:
        case()
    finally:
        worker.close()


def test_every_command_is_reached():
    """The walk finds the commands of the README tour (new ones are added automatically)."""
    for name in ("iso230-2", "scale gantry", "motion stability", "squareness circular"):
        assert name in COMMANDS
