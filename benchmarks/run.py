"""Run every benchmark in this folder and print one table (``make bench``).

Each ``bench_*.py`` module defines ``run() -> list[dict]``; a row has the keys ``name``,
``value`` (a throughput or a latency), ``unit``, and optionally ``reference`` (what the value is
compared with, measured in the same run), ``ratio`` (value / reference, or reference / value,
as the row says in ``name``) and ``aim`` (the goal, in words). Benchmarks never assert: they
report. Run one module with ``python benchmarks/run.py bench_iso230_2``.
"""

from __future__ import annotations

import importlib
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main(argv: list[str]) -> int:
    sys.path.insert(0, str(HERE))
    names = argv or sorted(p.stem for p in HERE.glob("bench_*.py"))
    rows = []
    for name in names:
        mod = importlib.import_module(name)
        t0 = time.perf_counter()
        for row in mod.run():
            row.setdefault("module", name)
            rows.append(row)
            _print_row(row)
        print(f"  ({name}: {time.perf_counter() - t0:.1f} s)", flush=True)
    return 0


def _print_row(r: dict) -> None:
    ratio = f"  ratio {r['ratio']:.2f}" if r.get("ratio") is not None else ""
    ref = f"  [reference: {r['reference']}]" if r.get("reference") else ""
    aim = f"  aim: {r['aim']}" if r.get("aim") else ""
    print(f"{r['name']:<60} {r['value']:>14.4g} {r['unit']:<14}{ratio}{ref}{aim}", flush=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
