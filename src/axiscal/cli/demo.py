"""``axiscal demo``: the main job on the embedded defaults (what ``make demo`` runs).

Simulates an ISO 230-2 positioning test of an 800 mm linear axis and of a turntable over a full
turn, then a complete rotary-axis calibration of the turntable with the angular interferometer and
the counter-rotating reference calibrator (set-up checks, optics self-calibration, capture,
evaluation, error budget). Configurations are in ``axiscal/data/``. It prints every result beside
the truth the simulation knew and writes plots, HTML reports, the simulated data and an index page
into ``--out``, and a PDF calibration certificate of the linear and of the rotary test (what a
customer receives: the measurement, its uncertainty and the ISO 14253-1 verdicts, no truth).
"""

from __future__ import annotations

from pathlib import Path

import typer

from axiscal.cli._common import note, out_path

DEMOS = (("linear", "demo_linear.toml", "X axis, 800 mm"), ("rotary", "demo_rotary.toml", "C axis, full turn (ideal reference)"))
#: What the demonstration certificates carry besides the user configuration (axiscal config).
DEMO_JOB = {
    "customer": {"name": "Demonstration customer (simulated readings)"},
    "conditions": {"measuring_line": "along the axis through the table centre (simulated)",
                   "feed": "not applicable (simulation)", "dwell": "not applicable (simulation)"},
}
DEMO_TOLERANCES = {"linear": {"A": 20.0, "E": 15.0, "R": 8.0, "B": 5.0},
                   "rotary": {"A": 14.0, "E": 12.0, "R": 6.0, "B": 4.0}}


def demo(
    out: Path = typer.Option(Path("axiscal-demo"), "--out", help="Folder for plots, reports and data (created)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulation's random numbers (a whole number >= 0)."),
) -> None:
    """Run the demonstration: linear and rotary positioning tests and a full rotary calibration, simulated, evaluated and reported."""
    import tomllib
    from importlib import resources

    from axiscal.cli.simulate import render_simulation, write_outputs
    from axiscal.errors import InputError
    from axiscal.procedures.positioning import simulate_from_config

    if out.exists() and not out.is_dir():
        raise InputError(f"--out {out} exists and is not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the folder --out {out}: {exc.strerror or exc}") from None
    out_path(out / "index.html", "the demonstration")   # writable, before the simulations run
    pages = []
    for name, cfg, label in DEMOS:
        config = tomllib.loads(resources.files("axiscal.data").joinpath(cfg).read_text("utf-8"))
        sim = simulate_from_config(config, seed=seed)
        typer.echo("")
        render_simulation(sim)
        write_outputs(sim, out / f"{name}_iso230-2.png", out / f"{name}_report.html",
                      out / f"{name}_data.csv")
        _certificate(out / f"{name}_certificate.pdf", sim, name)
        pages.append((label, f"{name}_report.html", sim.result))
    pages.append(_rotary_calibration(out))
    _write_index(out, pages)
    note(f"\nopen {out / 'index.html'} for the reports")


def _certificate(path: Path, sim, name: str) -> None:
    """The customer certificate (PDF) of a demonstration test; skipped, said, without WeasyPrint."""
    import importlib.util

    from axiscal.cli._certificate import load_config, write_certificate
    from axiscal.io.user_config import merge

    if importlib.util.find_spec("weasyprint") is None:
        note(f"no {path.name}: a PDF needs WeasyPrint (pip install 'axiscal[report]')")
        return
    cfg = merge(load_config(None), DEMO_JOB)
    out_path(path, "certificate")
    data = (path.parent / f"{name}_data.csv").read_bytes()
    write_certificate(path, sim.dataset, sim.result, cfg, data, DEMO_TOLERANCES[name])
    note(f"wrote certificate {path}")


def _rotary_calibration(out: Path):
    """The full rotary calibration chain on the embedded turntable configuration."""
    import tomllib
    from importlib import resources

    from axiscal.cli.rotary import render_rotary
    from axiscal.procedures.rotary_config import run_rotary_config
    from axiscal.report.rotary import write_rotary_report

    cfg = resources.files("axiscal.data").joinpath("rotary_turntable.toml").read_text("utf-8")
    result = run_rotary_config(tomllib.loads(cfg))
    typer.echo("")
    render_rotary(result, "rotary calibration of the turntable (angular interferometer + reference calibrator)")
    write_rotary_report(out / "rotary_calibration_report.html", result)
    note(f"wrote report {out / 'rotary_calibration_report.html'}")
    return ("C axis, rotary calibration chain", "rotary_calibration_report.html", result.result)


def _write_index(out: Path, pages) -> None:
    from axiscal.report.html import Report, unit_label

    rep = Report("axiscal demonstration", subtitle="Simulated ISO 230-2 positioning tests, evaluated and compared with the truth")
    rows = [[label, r.A, r.E, r.R, r.B, unit_label(r.deviation_unit)] for label, _, r in pages]
    rep.add_table(["Axis", "A", "E", "R", "B", "unit"], rows, digits=2)
    rep.add_html("<ul>" + "".join(f'<li><a href="{href}">{label}: full report</a></li>'
                                  for label, href, _ in pages)
                 + "".join(f'<li><a href="{n}_certificate.pdf">{n} test: calibration certificate '
                           "(PDF)</a></li>" for n, _, _ in DEMOS if (out / f"{n}_certificate.pdf").exists())
                 + "</ul>")
    rep.write(out / "index.html")
    note(f"wrote {out / 'index.html'}")


def register(app: typer.Typer) -> None:
    """Add the ``demo`` command."""
    app.command("demo")(demo)
