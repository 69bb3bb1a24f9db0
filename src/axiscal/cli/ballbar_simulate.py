"""``axiscal ballbar simulate CONFIG.toml``: a simulated ballbar test in the analyze format.

The configuration's tables ([machine], [servo], [ballbar], [test]; all keys optional, units in
the key names) are read by :mod:`axiscal.io.ballbar_config`; the test runs through
:func:`axiscal.simulate` (``kind="ballbar"``), whose ``to_dict()`` is ``--json``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, out_path, print_json


def simulate(
    config: Path = typer.Argument(..., help="TOML file (sections machine, servo, ballbar, test)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the trace CSV here."),
    seed: int = typer.Option(0, "--seed", min=0, help="Seed of the noise, a whole number >= 0."),
    json_out: bool = typer.Option(False, "--json", help="Print the truth and file as JSON."),
) -> None:
    """Simulate a CW + CCW ballbar test (servo dynamics, ballbar instrument) as analyze reads it.

    Example: axiscal ballbar simulate examples/ballbar_sim.toml --out trace.csv --seed 1
    """
    from axiscal import api

    if out is not None:
        out_path(out, "trace")
    sim = api.simulate(config, seed, kind="ballbar")
    d = sim.to_dict()
    if out is not None:
        sim.write_data(out)
    if json_out:
        print_json({**d, "out": None if out is None else str(out)})
        return
    if out is None:
        from axiscal.io.ballbar import format_ballbar

        typer.echo(format_ballbar(sim.dataset), nl=False)
    else:
        axes, truth = sim.dataset.axes, d["truth"]
        note(f"wrote {out} ({d['samples_per_run']} samples per direction; simulation truth: "
             f"{_truth_text({**truth['machine'], **truth['servo']}, axes)})")


def _truth_text(truth: dict, axes) -> str:
    """The simulated machine's errors and servo as the reports name them (``Backlash X 5.00
    µm``), not as the configuration's keys (``--json`` gives those)."""
    from axiscal.report.labels import fmt, quantity

    parts = (quantity(k, axes=axes) for k in truth)
    return ", ".join(f"{name} {fmt(v, unit)} {unit}".rstrip()
                     for (name, unit), v in zip(parts, truth.values()))
