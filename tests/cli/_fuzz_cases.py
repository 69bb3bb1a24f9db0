"""The hostile cases of the CLI fuzz harness, derived from the command line's own interface.

The typer app is walked (every command and sub-command, :func:`commands`); for every parameter
its click type, bounds, ``is_flag`` and ``multiple`` decide the hostile values
(:func:`hostile_values`):

* integers: −1, 0, 2^31, 2^63, 10^20 (and not a number); a history id is an integer argument;
* floats: nan, ±inf, 1e308, −0, 5e-324 (the smallest subnormal) and not a number;
* strings: empty, 1 MB, a NUL, a right-to-left mark, a lone surrogate; ``--db``: every
  SQLAlchemy scheme whose driver is not installed and a server that does not answer;
* paths: a folder, a FIFO, a missing parent folder, a read-only folder, a loop of symbolic
  links, each input file of the command itself (so an output naming an input is tried);
* flags: given; options that take several values: given three times.

Each command runs from a valid invocation (:data:`BASES`) with one parameter made hostile. Every
input file of a base is also mutated (:func:`file_mutations`): truncated, its header numbers set
to nan, 1e308 and −1, its units swapped, its targets written in inches (a ``target`` column
divided by 25.4), its first two columns swapped, one byte of every class
inserted (NUL, control, DEL, invalid UTF-8, BOM, right-to-left mark, encoded surrogate, CR),
and, for a TOML configuration, every ``key = value`` line set to hostile values, deleted, an
unknown key added, and three bombs (arrays nested 3,000 deep, a dotted key of 200,000 parts, a
2 MB file); a JSON input gets 100,000 nested brackets.

The rule a case must satisfy (:func:`check`): either success (exit 0, or 1 for a failed
tolerance, 3 for a DRAFT certificate) with an output (stdout or a new file), or exactly ONE line
``axiscal: error: ...`` on stderr and exit 2; never a traceback or a numpy warning; within the
time and memory limits; no output file left after a failure; every input file byte-identical
afterwards. Whether a value is hostile or legitimately valid (``--seed 0``) is not decided in
advance: the rule holds for both.
"""

from __future__ import annotations

import hashlib
import os
import random
import re
import shutil
import stat
from dataclasses import dataclass
from pathlib import Path

import typer
from typer._click import core

from axiscal.errors import MAX_MESSAGE   # the longest line an error is cut to (one_line)

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

#: Seconds and bytes of address space one case may take (issue 30). ``demo`` runs the whole
#: tour (about 10 s alone, 25 s on a loaded machine), so its valid cases get more time.
TIME_LIMIT = 20.0
SLOW = {"demo": 180.0}
MEMORY_LIMIT = 2 * 2**30

INTS = ["-1", "0", str(2**31), str(2**63), str(10**20), "1.5"]
FLOATS = ["nan", "inf", "-inf", "1e308", "-0", "5e-324", "abc"]
STRINGS = ["", "x" * 2**20, "a\x00b", "\u202eX-axis", "\udcff"]
#: SQLAlchemy dialects whose driver is not installed, and a PostgreSQL server that does not answer.
DB_URLS = ["mysql://u@127.0.0.1:1/x", "mariadb://u@127.0.0.1:1/x", "oracle://u@127.0.0.1:1/x",
           "mssql://u@127.0.0.1:1/x", "postgresql+psycopg2://u@127.0.0.1:1/x",
           "mysql+pymysql://u@127.0.0.1:1/x", "sqlite+pysqlcipher:///x.db",
           "firebird://u@127.0.0.1:1/x", "postgresql://127.0.0.1:1/x",
           "postgresql+psycopg://127.0.0.1:1/x", "sqlite:////nonexistent-folder/h.sqlite",
           "not a url"]
PATHS = ["folder", "fifo", "missing_parent", "readonly_folder", "symlink_loop", "input"]
BYTE_CLASSES = {"nul": b"\x00", "control": b"\x07\x1b", "del": b"\x7f", "latin1": b"\xb5",
                "invalid_utf8": b"\xc3\x28", "bom": b"\xef\xbb\xbf", "rtl": "\u202e".encode(),
                "surrogate": b"\xed\xa0\x80", "cr": b"\r", "tab": b"\t"}
TOML_VALUES = ["nan", "inf", "-1", "0", "1e308", str(2**63), '"text"', "[]", "{}", "true",
               '"' + "x" * 2**20 + '"']
MACHINE = "VMC-800"

#: A valid invocation of each command ({d}: the data folder, {c}: the case's folder, {db}: the
#: history). A command not listed runs with no argument but the hostile one.
BASES = {
    "air": [],
    "ballbar analyze": ["{d}/trace.csv"],
    "ballbar simulate": ["{d}/ballbar_sim.toml", "--out", "{c}/trace.csv"],
    "ballbar volumetric": ["{d}/trace.csv"],
    "capture": ["{d}/run.rtx", "--plan", "{d}/plan.csv", "--out", "{c}/data.csv"],
    "certificate list": ["--db", "{db}"],
    "certificate reissue": ["C-1", "--reason", "typo", "--out", "{c}/cert.pdf", "--db", "{db}"],
    "certificate show": ["C-1", "--db", "{db}"],
    "compensate": ["{d}/pos.csv", "--out", "{c}/table.csv"],
    "compensate-environment": ["{d}/raw.csv", "--environment", "{d}/env.csv", "--out",
                               "{c}/data.csv"],
    "demo": ["--out", "{c}/demo", "--db", "sqlite:///{c}/demo.sqlite"],
    "evaluate": ["{d}/pos.csv", "--standard", "iso230-2:2014"],
    "history add": ["{d}/pos2.csv", "--db", "{db}"],
    "history compare": ["1", "1", "--db", "{db}"],
    "history export": ["{c}/out.zip", "--db", "{db}"],
    "history import": ["{d}/history.zip", "--db", "{db}"],
    "history list": ["--db", "{db}"],
    "history machines": ["--db", "{db}"],
    "history rename-machine": ["VMC-900", "VMC-901", "--db", "{db}"],
    "history show": ["1", "--db", "{db}"],
    "history trend": ["--machine", MACHINE, "--axis", "X", "--db", "{db}"],
    "iso230-2": ["{d}/pos.csv"],
    "motion analyze": ["{d}/motion.csv"],
    "motion repeatability": ["{d}/motion_indexing_table.toml"],
    "motion simulate": ["{d}/motion_indexing_table.toml"],
    "motion stability": ["{d}/motion_indexing_table.toml"],
    "plan linear": ["--length", "800"],
    "rotary budget": ["--alpha", "10", "--beta", "10"],
    "rotary simulate": ["{d}/rotary_turntable.toml"],
    "scale gantry": ["{d}/scale_gantry.toml"],
    "scale home": ["{d}/scale_single.toml"],
    "serve": ["--add-user", "bob", "--users", "{c}/users.toml"],
    "simulate": ["{d}/compensation_linear.toml"],
    "squareness biaxial": ["{d}/squareness_L180_x.csv", "{d}/squareness_L180_y.csv"],
    "squareness circular": ["{d}/squareness_ballbar_150mm.csv"],
    "squareness diagonal": ["--x-length", "600", "--y-length", "800", "--d1", "5", "--d2", "-3"],
    "straightness": ["{d}/squareness_L180_x.csv"],
    "volumetric compensate": ["{d}/vol/volumetric.toml", "--controller", "siemens-840d"],
    "volumetric map": ["{d}/vol/volumetric.toml"],
    "volumetric simulate": ["--out", "{c}/vol"],
    "thermal plan": ["--test", "spindle"],
    "thermal simulate": ["--test", "linear", "--out", "{c}/log.csv"],
    "thermal evaluate": ["{d}/thermal1.csv"],
    "thermal model": ["{d}/thermal1.csv", "--validate", "{d}/thermal2.csv"],
    "thermal compensate": ["{d}/thermal1.csv", "--validate", "{d}/thermal2.csv"],
}

#: Suffix of a file an option names when the base gives none (reports, plots, tables).
SUFFIX = {"--plot": ".png", "--report": ".html", "--csv": ".csv", "--out": ".csv",
          "--data": ".csv", "--json-out": ".json", "--job": ".toml", "--users": ".toml"}


def commands() -> dict:
    """{"group sub": click command} of every leaf command of the app, found by walking it."""
    from axiscal.cli import app

    root = typer.main.get_command(app)

    def walk(cmd, path, ctx):
        if hasattr(cmd, "list_commands"):
            sub = core.Context(cmd, info_name=path[-1] if path else "axiscal", parent=ctx)
            for name in cmd.list_commands(sub):
                yield from walk(cmd.get_command(sub, name), path + [name], sub)
        else:
            yield " ".join(path), cmd

    return dict(walk(root, [], None))


@dataclass
class Case:
    """One invocation: the command, its arguments (with placeholders) and what was made hostile."""

    command: str
    args: list
    what: str
    prepare: tuple = ()          # (kind, placeholder) of hostile paths made in the case folder
    mutation: tuple = ()         # (input file, what, name in the case folder)

    @property
    def name(self) -> str:
        return f"{self.command}: {self.what}"


def _kind(param) -> str:
    t = type(param.type).__name__
    if getattr(param, "is_flag", False) or t == "BoolParamType":
        return "flag"
    if t in ("IntRange", "IntParamType"):
        return "int"
    if t in ("FiniteFloat", "FiniteFloatRange", "FloatParamType", "FloatRange"):
        return "float"
    if t in ("TyperPath", "Path"):
        return "path"
    return "string"


def hostile_values(param) -> list:
    """The hostile values of one parameter, from its click type (module docstring)."""
    kind = _kind(param)
    if kind == "int":
        return INTS
    if kind == "float":
        return FLOATS
    if kind == "path":
        return [f"@{p}" for p in PATHS]
    if kind == "string" and param.opts[0] == "--db":
        return DB_URLS + STRINGS[:1]
    return STRINGS


def _label(param) -> str:
    return param.opts[0] if param.param_type_name == "option" else param.name.upper()


def _replace(base: list, param, value) -> list:
    """``base`` with ``param`` set to ``value`` (an argument replaced in place, an option's value
    replaced or appended)."""
    if param.param_type_name == "option":
        args, i = list(base), 0
        out = []
        while i < len(args):
            if args[i] in param.opts:
                i += 2
                continue
            out.append(args[i])
            i += 1
        return out + [param.opts[0], value]
    positional = _positionals(base)
    args = list(base)
    index = [p.name for p in _arguments(param)].index(param.name)
    if index < len(positional):
        args[positional[index]] = value
        return args
    return args + ["x"] * (index - len(positional)) + [value]   # earlier arguments: any word


def _arguments(param):
    return [p for p in param._command.params if p.param_type_name == "argument"]


def _positionals(base: list) -> list[int]:
    """Indices of the positional arguments of ``base`` (values not following an option)."""
    out, i = [], 0
    while i < len(base):
        if base[i].startswith("--"):
            i += 2
            continue
        out.append(i)
        i += 1
    return out


def _base_value(base: list, param):
    for i, a in enumerate(base):
        if param.param_type_name == "option" and a in param.opts and i + 1 < len(base):
            return base[i + 1]
    if param.param_type_name == "argument":
        pos = _positionals(base)
        index = [p.name for p in _arguments(param)].index(param.name)
        return base[pos[index]] if index < len(pos) else None
    return None


def _suffix(param, base) -> str:
    given = _base_value(base, param)
    if given and Path(given).suffix:
        return Path(given).suffix
    return SUFFIX.get(param.opts[0], ".csv")


def _inputs(base: list) -> list[str]:
    return [a for a in base if a.startswith("{d}/")]


def parameter_cases(name: str, cmd) -> list[Case]:
    """One case per hostile value of every parameter of ``cmd``."""
    base = BASES.get(name, [])
    cases = []
    for param in cmd.params:
        if param.name in ("help",):
            continue
        param._command = cmd
        label = _label(param)
        kind = _kind(param)
        if kind == "flag":
            if param.opts[0] not in ("--help",) and not param.secondary_opts:
                cases.append(Case(name, base + [param.opts[0]], f"{label} given"))
            continue
        for value in hostile_values(param):
            values = [value]
            prepare = ()
            if value.startswith("@"):
                what = value[1:]
                if what == "input":
                    values = [v for v in _inputs(base) if v != _base_value(base, param)]
                else:
                    where = {"missing_parent": "no/such/x", "readonly_folder": "ro/x"}
                    values = [f"{{c}}/{where.get(what, what)}{_suffix(param, base)}"]
                    prepare = ((what, values[0]),)
            for v in values:
                args = _replace(base, param, v)
                if getattr(param, "multiple", False) and param.param_type_name == "option":
                    args = args + [param.opts[0], v, param.opts[0], v]
                shown = v if len(v) < 40 else f"{len(v)}-character string"
                cases.append(Case(name, args, f"{label} = {shown!r}", prepare))
    return cases


def _mutate_text(text: str) -> dict[str, str]:
    """Mutations of a text data file: header numbers, units, columns, truncation."""
    lines = text.splitlines()
    out = {"truncated": text[: len(text) // 2]}
    head = [i for i, ln in enumerate(lines) if ln.startswith("#") or ":" in ln[:40]]
    number = re.compile(r"(?<=[=: ])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?")
    for bad in ("nan", "1e308", "-1"):
        new = list(lines)
        for i in head:
            new[i] = number.sub(bad, new[i])
        out[f"header numbers {bad}"] = "\n".join(new) + "\n"
    swaps = {"mm": "um", "um": "mm", "deg": "mm", "arcsec": "um"}
    out["units swapped"] = re.sub(r"\b(mm|um|deg|arcsec)\b", lambda m: swaps[m.group(1)], text)
    out["units inch"] = re.sub(r"\bmm\b", "inch", text)
    # what a unit slip leaves: the targets in inches, the rest in mm (a file without a target
    # column unchanged, so that the name does not depend on the content)
    out["targets in inches"] = _targets_in_inches(lines) or text

    def swap(ln):
        cells = ln.split(",")
        return ",".join([cells[1], cells[0]] + cells[2:]) if len(cells) > 1 else ln

    out["columns swapped"] = "\n".join(ln if ln.startswith("#") else swap(ln)
                                       for ln in lines) + "\n"
    out["1 MB header line"] = "# " + "x" * 2**20 + "\n" + text
    return out


def _targets_in_inches(lines: list[str]) -> str | None:
    """The file with its ``target`` column divided by 25.4, or None without such a column."""
    head = next((i for i, ln in enumerate(lines) if ln and not ln.startswith("#")), None)
    cells = [c.strip() for c in lines[head].split(",")] if head is not None else []
    if "target" not in cells:
        return None
    col, out = cells.index("target"), list(lines)
    for i in range(head + 1, len(out)):
        row = out[i].split(",")
        if len(row) > col and re.fullmatch(r"-?\d+(\.\d*)?", row[col].strip()):
            row[col] = f"{float(row[col]) / 25.4:.9f}"
            out[i] = ",".join(row)
    return "\n".join(out) + "\n"


def _mutate_toml(text: str) -> dict[str, str]:
    """Mutations of a TOML configuration per its keys (every ``key = value`` line)."""
    lines = text.splitlines()
    keyed = [i for i, ln in enumerate(lines)
             if "=" in ln and not ln.lstrip().startswith(("#", "["))]
    out = {}
    for i in keyed:
        key = lines[i].split("=", 1)[0].strip()
        for value in TOML_VALUES:
            new = list(lines)
            new[i] = f"{key} = {value}"
            shown = value if len(value) < 20 else "a 1 MB string"
            out[f"{key} = {shown}"] = "\n".join(new) + "\n"
        out[f"{key} deleted"] = "\n".join(lines[:i] + lines[i + 1:]) + "\n"
    out["unknown key"] = text + "\nno_such_key = 1\n"
    out["arrays nested 3000 deep"] = text + "\nbomb = " + "[" * 3000 + "]" * 3000 + "\n"
    out["dotted key of 200000 parts"] = "a" + ".a" * 200_000 + " = 1\n" + text
    out["2 MB file"] = text + ("# padding\n" * 220_000)
    return out


def _variants(src: str, data: bytes) -> dict[str, bytes]:
    """{what: bytes} of every mutation of the input file ``src`` holding ``data``."""
    suffix = Path(src).suffix
    variants: dict[str, bytes] = {}
    if suffix == ".toml":
        text = data.decode()
        variants.update({k: v.encode() for k, v in _mutate_toml(text).items()})
        for value in TOML_VALUES[:6]:
            variants[f"every number = {value}"] = re.sub(
                r"(?m)^(\s*[A-Za-z_][\w.]*\s*=\s*)-?\d[\d.eE+-]*", lambda m: m.group(1) + value,
                text).encode()
    elif suffix in (".csv", ".json"):
        variants.update({k: v.encode() for k, v in _mutate_text(data.decode()).items()})
    else:   # binary (an .rtx): truncated, and its text header's numbers made hostile
        variants["truncated"] = data[: len(data) // 2]
        for bad in (b"nan", b"1e308", b"-1", b"0"):
            variants[f"header numbers {bad.decode()}"] = re.sub(
                rb"(Sample rate|Actual sample rate|Sample no): [^\r\n]*",
                lambda m: m.group(1) + b": " + bad, data)
    if suffix == ".zip":   # every field of its records (the second layer, issue 39)
        from _fuzz_layer2 import archive_variants

        variants.update(archive_variants(data))
    for cls, b in BYTE_CLASSES.items():
        variants[f"byte {cls}"] = data[: len(data) // 3] + b + data[len(data) // 3:]
    variants["empty"] = b""
    variants["100000 nested brackets"] = b"[" * 100_000 + b"]" * 100_000
    return variants


def file_mutations(name: str) -> list[Case]:
    """Every input file of the command's base, mutated (module docstring). The mutated bytes are
    made when the case runs (:func:`prepare_case`), from the fixtures; the names of the mutations
    of a generated file do not depend on its content (a generated TOML gets the ``every number``
    ones only)."""
    base = BASES.get(name, [])
    cases = []
    for index, given in enumerate(base):
        if not given.startswith("{d}/"):
            continue
        src = given[4:]
        example = EXAMPLES / src
        data = example.read_bytes() if example.is_file() else None
        names = _variants(src, data if data is not None else b"")
        if data is None and src.endswith(".toml"):
            names = {k: v for k, v in names.items() if not re.match(r"\S+ (=|deleted)", k)
                     or k.startswith("every number")}
        for what in names:
            fname = "bomb.json" if what == "100000 nested brackets" else f"mut{Path(src).suffix}"
            args = list(base)
            args[index] = "{c}/" + fname
            cases.append(Case(name, args, f"{src} {what}", mutation=(src, what, fname)))
    return cases


def all_cases(names=None) -> list[Case]:
    """Every case of every command (or of ``names``)."""
    cmds = commands()
    out = []
    for name in sorted(names or cmds):
        out += parameter_cases(name, cmds[name]) + file_mutations(name)
    return out + [c for c in layer2_cases(cmds) if names is None or c.command in names]


def layer2_cases(cmds=None) -> list[Case]:
    """The second layer's cases that run like the first's (:mod:`_fuzz_layer2`): outputs at
    inputs and at the history, writer fields (archive fields are among the file mutations)."""
    import _fuzz_layer2 as l2

    return l2.output_cases(cmds or commands()) + l2.writer_cases()


def sample(cases: list[Case], n: int, seed: int = 30) -> list[Case]:
    """A seeded sample of ``n`` cases, at least one of each command but the :data:`SLOW` ones
    (``demo``: a valid case runs the whole tour, a minute on a loaded machine; ``make fuzz``
    runs them)."""
    rng = random.Random(seed)
    cases = [c for c in cases if c.command not in SLOW]
    by_cmd: dict[str, list] = {}
    for c in cases:
        by_cmd.setdefault(c.command, []).append(c)
    picked = [rng.choice(v) for v in by_cmd.values()]
    rest = [c for c in cases if c not in picked]
    return picked + rng.sample(rest, max(0, min(n - len(picked), len(rest))))


# -- fixtures -------------------------------------------------------------------------------
_FIXTURES: dict[str, bytes] = {}


def make_fixtures(root: Path) -> dict:
    """Write the valid input files of the bases into ``root/data`` and a history with one test
    into ``root/db``; returns the placeholders {d}, {db}."""
    import numpy as np
    from typer.testing import CliRunner

    from axiscal.cli import app
    from axiscal.io.json import format_positioning_json
    from axiscal.io.measured import format_environment_log, format_raw_readings, parse_plan_csv
    from axiscal.io.rtx import format_rtx
    from axiscal.io import parse_positioning
    from axiscal.machines.config import axis_from_config
    from axiscal.procedures.environment import simulate_raw_test
    from axiscal.procedures.positioning import plan_linear
    from axiscal.procedures.record_simulation import RecordSettings, simulate_record

    d = root / "data"
    d.mkdir(parents=True)
    (root / "db").mkdir()
    for f in EXAMPLES.iterdir():
        if f.suffix in (".toml", ".csv"):
            shutil.copyfile(f, d / f.name)
    rows = ["target,direction,run,deviation"]
    for run in (1, 2, 3):
        for t in (0, 100, 200, 300):
            for s in ("+", "-"):
                rows.append(f"{t},{s},{run},{0.001 * t + 0.5 * run + (s == '-'):.3f}")
    text = "\n".join(rows) + "\n"
    (d / "pos.csv").write_text(f"# machine={MACHINE} axis=X target_unit=mm deviation_unit=um\n"
                               + text)
    (d / "pos2.csv").write_text("# machine=VMC-900 axis=Y target_unit=mm deviation_unit=um\n"
                                + text.replace(",0.5", ",0.6"))
    (d / "pos.json").write_text(format_positioning_json(
        parse_positioning((d / "pos.csv").read_text())))
    rows = [f"{r},{a},{a / 90 + r},0.1,0,0.2,0" for r in (1, 2) for a in range(0, 360, 30)]
    (d / "motion.csv").write_text("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n"
                                  + "\n".join(rows) + "\n")
    axis = axis_from_config({"name": "X", "kind": "linear", "travel_mm": [-10, 410],
                             "scale_error_ppm": 5.0, "backlash_um": 2.0,
                             "repeatability_um": 0.2})
    plan = plan_linear(400, runs=2, dwell=2.0)
    raw, log, _ = simulate_raw_test(plan, axis, np.random.default_rng(5),
                                    lambda t: (20.0 + t / 300, 101325.0, 45.0, 20.3 + t / 600),
                                    dead_path=0.15)
    (d / "raw.csv").write_text(format_raw_readings(raw, f"machine={MACHINE} axis=X"))
    (d / "env.csv").write_text(format_environment_log(log))
    runner = CliRunner()
    r = runner.invoke(app, ["plan", "linear", "--length", "400", "--runs", "2", "--dwell", "2",
                            "--csv", str(d / "plan.csv")])
    assert r.exit_code == 0, r.output
    t, x, _ = simulate_record(parse_plan_csv((d / "plan.csv").read_text()), axis,
                              np.random.default_rng(6), RecordSettings(sample_rate=200.0))
    (d / "run.rtx").write_bytes(format_rtx(x * 1e6, 200.0, Axis="X"))
    db = f"sqlite:///{root / 'db' / 'h.sqlite'}"
    for args in (["ballbar", "simulate", str(d / "ballbar_sim.toml"), "--out",
                  str(d / "trace.csv")],
                 ["volumetric", "simulate", "--out", str(d / "vol")],
                 ["thermal", "simulate", "--test", "linear", "--out", str(d / "thermal1.csv")],
                 ["thermal", "simulate", "--test", "linear", "--seed", "2", "--duty", "0.5",
                  "--start-h", "13", "--out", str(d / "thermal2.csv")],
                 ["history", "add", str(d / "pos.csv"), "--db", db],
                 ["history", "export", str(d / "history.zip"), "--db", db]):
        r = runner.invoke(app, args)
        assert r.exit_code == 0, (args, r.output)
    for f in d.rglob("*"):
        if f.is_file():
            _FIXTURES[str(f.relative_to(d))] = f.read_bytes()
    return {"{d}": str(d), "{db}": db, "{dbfile}": str(root / "db" / "h.sqlite")}


def prepare_case(case: Case, folder: Path, places: dict) -> list[str]:
    """Make the case's folder (hostile paths, mutated files); the arguments, filled in."""
    folder.mkdir()
    fill = dict(places, **{"{c}": str(folder)})
    for kind, ph in case.prepare:
        p = Path(ph.replace("{c}", str(folder)))
        if kind == "folder":
            p.mkdir()
        elif kind == "fifo":
            os.mkfifo(p)
        elif kind == "readonly_folder":
            p.parent.mkdir()
            p.parent.chmod(stat.S_IRUSR | stat.S_IXUSR)
        elif kind == "symlink_loop":
            os.symlink(p.name, p)       # a link to itself
    if case.mutation:
        src, what, fname = case.mutation
        (folder / fname).write_bytes(_variants(src, _FIXTURES[src])[what])
    out = []
    for a in case.args:
        for k, v in fill.items():
            a = a.replace(k, v)
        out.append(a)
    return out


def snapshot(folder: Path) -> dict:
    """{relative path: SHA-256} of every file (and the names of every other entry) below."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for n in filenames + dirnames:
            p = Path(dirpath) / n
            rel = str(p.relative_to(folder))
            if p.is_symlink() or not p.is_file():
                out[rel] = "entry"
            else:
                out[rel] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def check(case: Case, args: list, r: dict, before_data: dict, after_data: dict,
          before_case: dict, after_case: dict) -> list[str]:
    """What the result ``r`` of ``case`` breaks of the rule (module docstring); [] if nothing."""
    faults = []
    err = r["stderr"]
    lines = err.strip().splitlines()
    if r.get("traceback"):
        faults.append("traceback: " + r["traceback"].strip().splitlines()[-1][:300])
    if r.get("timeout"):
        faults.append(r["timeout"])
    if "Warning" in err or "warnings.warn" in err:
        faults.append("warning text on stderr: " + err[:200])
    if r["exit"] in (0, 1, 3) and not r.get("traceback"):   # 1: a tolerance failed, 3: a DRAFT
        made = set(after_case) - set(before_case)
        if not r["stdout"].strip() and not made:
            faults.append(f"exit {r['exit']} with no output")
    elif r["exit"] == 2:
        if len(lines) != 1 or not lines[0].startswith("axiscal: error: "):
            faults.append(f"not ONE error line: {err[:300]!r}")
        elif len(lines[0]) > MAX_MESSAGE or r.get("stderr_chars", 0) > MAX_MESSAGE + 2:
            faults.append(f"an error of {r.get('stderr_chars', len(err))} characters")
        left = sorted(set(after_case) - set(before_case))
        if left:
            faults.append(f"left behind after an error: {left}")
    elif not r.get("timeout"):
        faults.append(f"exit {r['exit']}: {err[:200]!r}")
    changed = sorted(k for k in before_data if after_data.get(k) != before_data[k])
    changed += sorted(k for k in before_case if after_case.get(k) != before_case[k])
    if changed:
        faults.append(f"an input changed: {changed}")
    return faults
