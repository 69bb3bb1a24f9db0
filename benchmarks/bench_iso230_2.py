"""Latency of ``axiscal iso230-2 FILE --json`` on a 41-target, 5-run bidirectional file.

Reference, measured in the same run: ``python -c "import numpy"`` (the floor any NumPy tool pays).
Aim (issue 30): at most 1.5x that reference. Also the in-process evaluation throughput.

Both are timed with Python's bytecode cache written and used, as after ``pip install`` (which
compiles every module): numpy's is there from its install, axiscal's (an editable checkout) is
written by a first, untimed run. With ``PYTHONDONTWRITEBYTECODE=1`` in the environment an
editable axiscal would compile its 90 modules on every start (about 0.12 s) while numpy does not;
that is no cost a user pays.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def _best_wall(cmd: list[str], repeat: int = 15) -> float:
    """Fastest of ``repeat`` runs (after one untimed run that writes the bytecode cache): the
    intrinsic cost, least disturbed by other load."""
    import os

    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    times = []
    for _ in range(repeat + 1):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       env=env)
        times.append(time.perf_counter() - t0)
    return min(times[1:])


def _write_file(folder: Path) -> Path:
    from axiscal.datasets import PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(0)
    targets = np.round(np.linspace(0, 2000, 41) + rng.uniform(-10, 10, 41) * (np.arange(41) % 40 > 0), 3)
    base = 5 * np.sin(targets / 300)[:, None]
    ds = PositioningDataset.from_arrays("linear", targets, base + rng.normal(0, 0.5, (41, 5)),
                                        base - 2 + rng.normal(0, 0.5, (41, 5)))
    p = folder / "x41.csv"
    p.write_text(format_positioning_csv(ds))
    return p


def run() -> list[dict]:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        f = _write_file(Path(tmp))
        ref = _best_wall([sys.executable, "-c", "import numpy"])
        cli = _best_wall([sys.executable, "-m", "axiscal", "iso230-2", str(f), "--json"])
        rows.append(dict(name="iso230-2 --json latency, 41 targets x 5 runs x 2 dirs",
                         value=cli * 1e3, unit="ms", reference=f"python -c 'import numpy' {ref * 1e3:.0f} ms (best of 15 each)",
                         ratio=cli / ref, aim="ratio <= 1.5"))
        rows.extend(_instruction_rows(f))
    from axiscal.datasets import PositioningDataset
    from axiscal.standards.iso230_2 import evaluate

    rng = np.random.default_rng(1)
    ds = PositioningDataset.from_arrays("linear", np.arange(41.0), rng.normal(0, 1, (41, 5)),
                                        rng.normal(0, 1, (41, 5)))
    n = 2000
    t0 = time.perf_counter()
    for _ in range(n):
        evaluate(ds)
    dt = (time.perf_counter() - t0) / n
    rows.append(dict(name="evaluate() in process, 41 x 5 x 2", value=1.0 / dt, unit="evals/s"))
    rows.extend(_large_csv_rows())
    return rows


def _instructions(cmd: list[str]) -> int | None:
    """Instructions the command executes (valgrind's callgrind, "I refs"), after one run that
    writes the bytecode cache; None without valgrind. Unlike a wall time it does not move with
    the machine's load (a shared 2-core machine's best of 15 can be off by tens of percent)."""
    import os
    import re
    import shutil

    if shutil.which("valgrind") is None:
        return None
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", *cmd],
                         capture_output=True, text=True, env=env).stderr
    found = re.search(r"I\s+refs:\s+([\d,]+)", out)
    return int(found.group(1).replace(",", "")) if found else None


def _instruction_rows(f: Path) -> list[dict]:
    """The same start-up counted in instructions, beside ``import numpy``'s (issue 30)."""
    ref = _instructions([sys.executable, "-c", "import numpy"])
    cli = _instructions([sys.executable, "-m", "axiscal", "iso230-2", str(f), "--json"])
    if ref is None or cli is None:
        return [dict(name="  the same in instructions executed", value=float("nan"), unit="",
                     reference="valgrind not installed: not counted")]
    return [dict(name="  the same in instructions executed (valgrind)", value=float(cli),
                 unit="instructions", reference=f"python -c 'import numpy' {ref:.3g}",
                 ratio=cli / ref, aim="ratio <= 1.5 (the load-independent view)")]


_CHILD = """
import resource, sys, time
from axiscal.io import read_positioning
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
if sys.argv[2] == "axiscal":
    read_positioning(sys.argv[1])
else:                      # the floor: the standard library's csv reader and float()
    import csv
    with open(sys.argv[1], newline="") as fh:
        for row in csv.reader(fh):
            if row and not row[0].startswith("#") and row[0] != "target":
                float(row[0]); float(row[3])
dt = time.perf_counter() - t0
print(dt, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) * 1024)
"""


def _large_csv_rows() -> list[dict]:
    """Streaming a large positioning CSV (issue 11): 1,000,050 readings, about 20 MB."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "big.csv"
        rng = np.random.default_rng(1)
        m, runs = 20001, 25
        t = np.linspace(0, 2000, m)
        with open(f, "w") as fh:
            fh.write("# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n")
            for r in range(1, runs + 1):
                for d in "+-":
                    fh.write("".join(f"{a:.4f},{d},{r},{b:.3f}\n"
                                     for a, b in zip(t, rng.normal(0, 1, m))))
        n = m * runs * 2
        size = f.stat().st_size

        def child(which):
            out = subprocess.run([sys.executable, "-c", _CHILD, str(f), which], check=True,
                                 capture_output=True, text=True).stdout.split()
            return float(out[0]), float(out[1])

        (dt, mem), (ref, _) = child("axiscal"), child("csv")
        rows.append(dict(name=f"read a positioning CSV, {n} readings ({size / 1e6:.0f} MB)",
                         value=n / dt, unit="readings/s",
                         reference=f"csv.reader + float() of the same file {ref:.2f} s",
                         ratio=dt / ref, aim="ratio < 2"))
        rows.append(dict(name="  its peak memory above the interpreter's, per byte of file",
                         value=mem / size, unit="x file", aim="< 3 (memory grows with the readings)"))
    return rows
