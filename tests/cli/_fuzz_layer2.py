"""The second layer of the CLI fuzz harness (issue 39), derived from the interface like the first.

The first layer (:mod:`_fuzz_cases`) varies one input value at a time. This layer tries what a
hostile user tried beyond that:

* **outputs at inputs and at the history**: every output option (``--out``, ``--report``,
  ``--plot``, ``--csv``, ``--data``, ``--json-out``) of every command pointed at each input file
  of its base invocation and, for a command that opens the history (a ``--db`` option), at the
  history database's own file (:func:`output_cases`);
* **writer fields**: every field every controller writer declares (its ``FIELDS``) and the axis
  name given control characters, line breaks carrying a line of G-code (``M30``), the format's
  delimiters, 1,000 characters, and huge and negative numbers (:func:`writer_cases`);
* **archive records**: every field of an archive's header, of its first test record and of a
  certificate record set to hostile values (2^70, 2^63 - 1, -5, a number as a string, "",
  a line break, a lone surrogate, 5,000 characters, null, a list) (:func:`archive_variants`);
* **environments**: base invocations run by the real console script with ``COLUMNS`` 0, 20 and
  10,000,000, an ASCII console, HOME not writable, and standard output closed, full or a pipe
  whose reader has gone (:func:`env_cases`, :func:`check_env`).

The rule is the first layer's (:func:`_fuzz_cases.check`), and in addition: the history database
is still a SQLite file after any case that named it as an output; a file written by a case holds
no line ``M30`` that an argument injected; and for the environments, the exit code and stderr
that each stream condition calls for (74 and one line for closed or full, 141 and nothing for a
broken pipe), no number cut with an ellipsis, an ASCII console given ASCII.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

import _fuzz_cases as fc

OUTPUT_OPTIONS = ("--out", "--report", "--plot", "--csv", "--data", "--json-out")
#: Arguments that name an output: (command, parameter).
OUTPUT_ARGUMENTS = {("history export", "archive")}
#: Hostile names for a writer's name fields and the axis (the M30 line is looked for after).
NAMES = ["X\nM30", "X1]=0\nM30\n;[", "X)\n(M30", "X\r\nM30", "\x07X", "A" * 1000, "X;",
         "\u202eX", "X Y", ""]
NUMBERS = ["-1", "-5", str(2**31), str(2**63 - 1), str(10**20), "99999999999999999999", "0"]
#: Hostile values of an archive's JSON fields.
ARCHIVE_VALUES = {"2^70": 2**70, "2^63-1": 2**63 - 1, "-5": -5, "'2'": "2", "''": "",
                  "line break": "a\nM30", "surrogate": "VMC\udcff", "5000 chars": "x" * 5000,
                  "null": None, "[]": []}
MARK = "M30"


# -- outputs at inputs and at the history -----------------------------------------------------
def output_cases(cmds: dict) -> list:
    """Every output option of every command at each input of its base and at the history."""
    out = []
    for name, cmd in sorted(cmds.items()):
        base = fc.BASES.get(name, [])
        has_db = any(p.name == "db" for p in cmd.params)
        for param in cmd.params:
            output = (param.param_type_name == "option" and param.opts[0] in OUTPUT_OPTIONS) \
                or (name, param.name) in OUTPUT_ARGUMENTS
            if not output or fc._kind(param) != "path":
                continue
            param._command = cmd
            own = fc._base_value(base, param)
            targets = [v for v in fc._inputs(base) if v != own]
            if has_db:
                targets.append("{dbfile}")
            for target in targets:
                args = fc._replace(base, param, target)
                if has_db and "--db" not in args:
                    args += ["--db", "{db}"]
                where = "the history database" if target == "{dbfile}" else target
                out.append(fc.Case(name, args, f"{fc._label(param)} at {where} (layer 2)"))
    return out


# -- writer fields ----------------------------------------------------------------------------
def writer_cases() -> list:
    """Every declared field of every controller writer, and the axis name, made hostile."""
    from axiscal.compensation.controllers import CONTROLLERS, controller

    out = []
    for ctrl in CONTROLLERS:
        suffix = ".csv" if ctrl == "csv" else ".txt"
        base = ["{d}/pos.csv", "-c", ctrl, "--spacing", "100", "--out", "{c}/table" + suffix]
        fields = getattr(controller(ctrl), "FIELDS", {})
        for option, field in fields.items():
            for value in (NAMES if field.pattern else NUMBERS):
                shown = value if len(value) < 30 else f"{len(value)} characters"
                out.append(fc.Case("compensate", base + ["-o", f"{option}={value}"],
                                   f"{ctrl} -o {option}={shown!r} (layer 2)"))
        for value in NAMES:
            shown = value if len(value) < 30 else f"{len(value)} characters"
            out.append(fc.Case("compensate", base + ["--axis", value],
                               f"{ctrl} --axis {shown!r} (layer 2)"))
    return out


# -- archive records --------------------------------------------------------------------------
_HEAD_FIELDS = ("format", "tests", "audit", "certificates")
_RECORD_FIELDS = ("machine", "axis", "kind", "filename", "sha256", "instrument", "operator",
                  "note", "date", "withdrawn", "tables")
_CERT_FIELDS = ("counter", "number", "status", "replaces", "laboratory", "series", "test",
                "issued", "created", "media_type", "customer", "inputs")


def archive_variant_names() -> list[str]:
    names = ["with a certificate (valid)"]
    for where, keys in (("header", _HEAD_FIELDS), ("record", _RECORD_FIELDS),
                        ("certificate", _CERT_FIELDS)):
        names += [f"{where} {k} = {v}" for k in keys for v in ARCHIVE_VALUES]
    return names


def archive_variants(data: bytes) -> dict[str, bytes]:
    """{what: archive bytes} of every field mutation (empty bytes for an empty ``data``: the
    names alone, for :func:`_fuzz_cases.file_mutations`)."""
    names = archive_variant_names()
    if not data:
        return {n: b"" for n in names}
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        files = {i.filename: z.read(i) for i in z.infolist()}
    lines = files["history.jsonl"].decode().splitlines()
    head, first = json.loads(lines[0]), json.loads(lines[1])
    doc = b"%PDF-1.4 certificate LAB-2026-00001\n"
    sha = hashlib.sha256(doc).hexdigest()
    cert = {"test": first["sha256"], "laboratory": "Lab", "series": "LAB|2026", "counter": 1,
            "number": "LAB-2026-00001", "customer": "C", "issued": "2026-11-24",
            "status": "issued", "replaces": "", "reason": "",
            "media_type": "application/pdf", "sha256": sha, "document": f"certificates/{sha}",
            "inputs": {}, "created": "2026-11-24T10:00:00"}
    out = {}
    for what in names:
        h, r, c = dict(head, certificates=1), dict(first), dict(cert)
        if what != "with a certificate (valid)":
            where, rest = what.split(" ", 1)
            key, label = rest.split(" = ", 1)
            {"header": h, "record": r, "certificate": c}[where][key] = ARCHIVE_VALUES[label]
        new = dict(files)
        new["history.jsonl"] = "\n".join([json.dumps(h), json.dumps(r), *lines[2:]]).encode()
        new["certificates.jsonl"] = (json.dumps(c) + "\n").encode()
        new[f"certificates/{sha}"] = doc
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
            for name, content in new.items():
                z.writestr(name, content)
        out[what] = buf.getvalue()
    return out


# -- the added rule -----------------------------------------------------------------------------
def check_more(args: list, r: dict, made: list) -> list[str]:
    """What a case breaks of the second layer's rule beyond :func:`_fuzz_cases.check`."""
    faults = []
    for a in args:
        if a.endswith(os.path.join("db", "h.sqlite")) and Path(a).is_file():
            if Path(a).read_bytes()[:16] != b"SQLite format 3\x00":
                faults.append("the history database is no longer SQLite")
    if r.get("exit") == 0 and any(MARK in a for a in args):
        for p in made:
            try:
                text = Path(p).read_text(errors="replace")
            except OSError:
                continue
            if any(line.strip().lstrip("(;#").strip() == MARK for line in text.splitlines()):
                faults.append(f"{Path(p).name} holds an injected line {MARK}")
    return faults


# -- environments ---------------------------------------------------------------------------------
@dataclass
class EnvCase:
    """One base invocation under one environment or stream condition."""

    command: str
    args: list
    what: str
    env: dict
    stream: str = ""            # "", "closed", "full", "broken"

    @property
    def name(self) -> str:
        return f"{self.command}: {self.what} (environment)"


ENVIRONMENTS = {
    "COLUMNS=0": ({"COLUMNS": "0"}, ""), "COLUMNS=20": ({"COLUMNS": "20"}, ""),
    "COLUMNS=10000000": ({"COLUMNS": "10000000"}, ""),
    "ASCII console": ({"PYTHONIOENCODING": "ascii"}, ""),
    "HOME not writable": ({"HOME": "/nonexistent", "MPLCONFIGDIR": None,
                           "XDG_CACHE_HOME": None}, ""),
    "stdout closed": ({}, "closed"), "stdout full": ({}, "full"),
    "stdout a broken pipe": ({}, "broken"),
}
#: Commands whose base invocation is quick and prints (the environment rule needs output).
ENV_COMMANDS = ("iso230-2", "evaluate", "air", "plan linear", "history list", "history show",
                "squareness diagonal", "rotary budget", "formats", "certificate list",
                "straightness", "squareness circular")


def env_cases() -> list[EnvCase]:
    out = []
    for name in ENV_COMMANDS:
        for what, (env, stream) in ENVIRONMENTS.items():
            out.append(EnvCase(name, list(fc.BASES.get(name, [])), what, env, stream))
    return out


def run_env_case(case: EnvCase, places: dict, home: Path, timeout: float = 60.0) -> dict:
    """Run ``python -m axiscal`` under the case's environment; exit code, stdout, stderr."""
    fill = dict(places, **{"{c}": str(home)})
    args = []
    for a in case.args:
        for k, v in fill.items():
            a = a.replace(k, v)
        args.append(a)
    env = dict(os.environ, PYTHONPATH=str(fc.ROOT / "src"), HOME=str(home), MPLBACKEND="Agg",
               AXISCAL_DB=places["{db}"], PYTHONWARNINGS="default,ignore::DeprecationWarning,"
               "ignore::ResourceWarning")
    env.pop("COLUMNS", None)
    env.update(case.env)
    env = {k: v for k, v in env.items() if v is not None}
    argv = [sys.executable, "-m", "axiscal", *case.command.split(), *args]
    stdout = subprocess.PIPE
    pre = None
    full = None
    if case.stream == "closed":
        stdout, pre = None, (lambda: os.close(1))
    elif case.stream == "full":
        full = open("/dev/full", "w")
        stdout = full
    try:
        p = subprocess.Popen(argv, stdout=stdout, stderr=subprocess.PIPE, env=env, cwd=home,
                             preexec_fn=pre)
        if case.stream == "broken":
            p.stdout.close()
            out = b""
        else:
            out = p.stdout.read() if stdout == subprocess.PIPE else b""
        err = p.stderr.read()
        code = p.wait(timeout=timeout)
    finally:
        if full is not None:
            full.close()
    return {"exit": code, "stdout": out, "stderr": err.decode("utf-8", "replace")}


def check_env(case: EnvCase, r: dict) -> list[str]:
    """What the result of an environment case breaks (module docstring)."""
    faults = []
    err, code = r["stderr"], r["exit"]
    lines = err.strip().splitlines()
    if "Traceback" in err:
        faults.append("traceback: " + lines[-1][:200])
    if "Matplotlib" in err or "is not a writable directory" in err:
        faults.append("matplotlib's cache warning")
    if case.stream in ("closed", "full"):
        if code != 74 and not (code == 0 and not err):
            faults.append(f"exit {code} for stdout {case.stream}: {err[:200]!r}")
        elif code == 74 and len(lines) != 1:
            faults.append(f"not one line for stdout {case.stream}: {err[:200]!r}")
    elif case.stream == "broken":
        if code not in (141, 0) or (code == 141 and err.strip()):
            faults.append(f"exit {code} for a broken pipe, stderr {err[:200]!r}")
    else:
        if code not in (0, 1, 2, 3):
            faults.append(f"exit {code}: {err[:200]!r}")
        if code == 2 and len(lines) != 1:
            faults.append(f"not ONE error line: {err[:200]!r}")
        out = r["stdout"]
        import re

        if re.search(r"[0-9.]…\s*[│|]".encode(), out):   # a number cut at a cell's border
            faults.append("a cell cut with an ellipsis")
        if case.env.get("PYTHONIOENCODING") == "ascii" and not out.isascii():
            faults.append("non-ASCII bytes on an ASCII console")
    return faults
