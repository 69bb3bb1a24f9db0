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
#: The demonstration's own laboratory and job: its certificates never use the user's configuration
#: (axiscal config). Dates are the day the demo runs (the simulation's test), the instrument's
#: calibration is due a year later; the simulated machine is at 20 °C.
DEMO_CONFIG = {
    "company": {"name": "axiscal Demonstration Laboratory",
                "address": ["Simulated readings: not an accredited laboratory"], "code": "DEMO"},
    "operator": {"name": "axiscal demo"},
    "customer": {"name": "Demonstration customer (simulated readings)",
                 "address": ["Simulation, no real address"]},
    "machine": {"maker": "axiscal", "model": "simulated machine", "serial": "SIM-0001",
                "location": "a simulation (no workshop)"},
    "conditions": {"measuring_line": "along the axis through the table centre (simulated)",
                   "feed": "not applicable (simulation)", "dwell": "not applicable (simulation)",
                   "air_temperature": 20.0, "material_temperature": 20.0},
    "certificate": {"signatory": "A. Demonstrator",
                    "signatory_role": "Signatory of the demonstration (simulated)",
                    "specification": "the tolerances of axiscal's demonstration"},
    "uncertainty": {"e_ve": 0.2, "e_ve_source": "declared"},
}
DEMO_TOLERANCES = {"linear": {"A": 20.0, "E": 15.0, "R": 8.0, "B": 5.0},
                   "rotary": {"A": 14.0, "E": 12.0, "R": 6.0, "B": 4.0}}


def demo(
    out: Path = typer.Option(Path("axiscal-demo"), "--out", help="Folder for plots, reports and data (created)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulation's random numbers (a whole number >= 0)."),
    db: str = typer.Option(None, "--db", help="History database for the demo's tests (default: history.sqlite in --out)."),
) -> None:
    """Run the demonstration: linear and rotary positioning tests and a full rotary calibration, simulated, evaluated and reported.

    Example: axiscal demo --out demo-output
    """
    import tomllib
    from importlib import resources

    from axiscal import api
    from axiscal.cli.simulate import render_simulation, write_outputs
    from axiscal.errors import InputError

    if out.exists() and not out.is_dir():
        raise InputError(f"--out {out} exists and is not a folder")
    created = not out.exists()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the folder --out {out}: {exc.strerror or exc}") from None
    out_path(out / "index.html", "the demonstration")   # writable, before the simulations run
    if db:   # opened (driver, server, schema) before anything is written
        from axiscal.store import open_store

        try:
            open_store(db)
        except Exception:
            if created:
                out.rmdir()
            raise
    pages = []
    url = db or f"sqlite:///{(out / 'history.sqlite').resolve()}"
    for name, cfg, label in DEMOS:
        config = tomllib.loads(resources.files("axiscal.data").joinpath(cfg).read_text("utf-8"))
        sim = api.simulate(config, seed, kind="positioning")
        typer.echo("")
        render_simulation(sim.test)
        write_outputs(sim, out / f"{name}_iso230-2.png", None, out / f"{name}_data.csv")
        sim.report(out / f"{name}_report.html", uncertainty=_inputs(name))   # the certificate's U
        note(f"wrote report {out / f'{name}_report.html'}")
        _certificate(out / f"{name}_certificate.pdf", sim.test, name, url)
        pages.append((label, f"{name}_report.html", sim.result, _budget(sim, name)))
    pages.append(_rotary_calibration(out))
    _write_index(out, pages)
    _measured_inputs(out, seed)
    _history(out, url, seed)
    note(f"\nopen {out / 'index.html'} for the reports")


def _history(out: Path, db: str, seed: int) -> None:
    """Store the demo's tests and a compensation loop (before/after) in the history; list and
    compare them."""
    import tomllib
    from dataclasses import replace
    from importlib import resources

    from axiscal.compensation.loop import run_compensation_loop
    from axiscal.io._files import write_text_atomic
    from axiscal.io.csv import format_positioning_csv
    from axiscal.store import open_store
    from axiscal.store.analysis import compare_tests

    store = open_store(db)
    for name in ("linear", "rotary"):
        p = out / f"{name}_data.csv"
        store.add(p.read_bytes(), p.name)
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_compensation.toml")
                        .read_text("utf-8"))
    loop = run_compensation_loop(cfg, seed=seed)
    ids = []
    for label, ds in (("before", loop.before_data), ("after", loop.after_data)):
        ds = replace(ds, metadata=replace(ds.metadata, machine=cfg["meta"]["machine"],
                                          axis=cfg["axis"]["name"],
                                          notes=f"compensation loop: {label}"))
        p = out / f"compensation_{label}_data.csv"
        write_text_atomic(p, format_positioning_csv(ds))
        tables = ((loop.controller_file.controller, loop.controller_file.filename,
                   loop.controller_file.text),) if label == "before" else ()
        ids.append(store.add(p.read_bytes(), p.name, note=f"compensation loop: {label}",
                             tables=tables).id)
    from axiscal.report.labels import unit_text

    typer.echo(f"\ncalibration history ({db}):")
    for t in store.tests():
        key = "E" if "E" in t.parameters else next(iter(t.parameters))
        v, u = t.parameters[key][0], unit_text(t.parameters[key][1])
        typer.echo(f"  test {t.id:>3}  {t.machine} {t.axis}  {t.kind}  {key} = {v:.3f} {u}  "
                   f"{t.filename}")
    c = compare_tests(store.get(ids[0]), store.get(ids[1]))
    typer.echo(f"\nthe linear axis before and after compensation (axiscal history compare "
               f"{ids[0]} {ids[1]} --db {db}):")
    typer.echo(str(c))
    typer.echo(f"\ncertificate register (axiscal certificate list --db {db}):")
    for r in store.certificates():
        typer.echo(f"  {r}")


#: The job file the README's certificate example uses (one test's customer, machine, conditions and
#: tolerances); ``make demo`` writes it as ``job.toml``.
JOB_TOML = """\
[customer]
name = "Example Machining AG"
address = ["Industriestrasse 4", "73728 Esslingen"]
[machine]
maker = "Example"
model = "VMC-800"
serial = "VMC8-0042"
location = "Hall 2, cell 5"
[conditions]
date = "2026-11-20"
air_temperature = 20.3
material_temperature = 20.5
measuring_line = "X axis, 100 mm above the table centre"
feed = "2000 mm/min"
dwell = "4 s"
[certificate]
specification = "Purchase order 4711 (positioning tolerances of the VMC-800 acceptance)"
[tolerance]
E = 15
R = 8
"""

#: The simulated axis behind the demo's raw readings and continuous record.
_RAW_AXIS = {"name": "X", "kind": "linear", "travel_mm": [-10, 810], "scale_error_ppm": 5.0,
             "backlash_um": 2.0, "repeatability_um": 0.2}


def _measured_inputs(out: Path, seed: int) -> None:
    """Inputs as a real job brings them, for the README's tour: a job file, raw laser readings
    with the environment log of the test (``compensate-environment``), and a test plan with the
    laser's continuous record of it (``capture``), simulated on an 800 mm axis."""
    import numpy as np

    from axiscal.io._files import write_bytes_atomic, write_text_atomic
    from axiscal.io.measured import format_environment_log, format_raw_readings
    from axiscal.io.rtx import format_rtx
    from axiscal.machines.config import axis_from_config
    from axiscal.procedures.environment import simulate_raw_test
    from axiscal.procedures.positioning import plan_linear
    from axiscal.procedures.record_simulation import RecordSettings, simulate_record

    axis = axis_from_config(_RAW_AXIS)
    write_text_atomic(out / "job.toml", JOB_TOML)
    raw, log, _ = simulate_raw_test(
        plan_linear(800, runs=3, dwell=2.0), axis, np.random.default_rng(seed + 4),
        lambda t: (20.0 + t / 300, 101325.0, 45.0, 20.3 + t / 600), dead_path=0.15)
    write_text_atomic(out / "raw.csv", format_raw_readings(raw, "machine=VMC-800 axis=X"))
    write_text_atomic(out / "env.csv", format_environment_log(log))
    plan = plan_linear(800, runs=5, dwell=2.0)
    write_text_atomic(out / "plan.csv", plan.to_csv())
    from axiscal.io.measured import parse_plan_csv

    _, x, _ = simulate_record(parse_plan_csv(plan.to_csv()), axis, np.random.default_rng(seed + 5),
                              RecordSettings(sample_rate=2000.0))
    write_bytes_atomic(out / "run.rtx", format_rtx(x * 1e6, 2000.0, Axis="X"))
    note(f"wrote {out / 'job.toml'}, raw.csv, env.csv, plan.csv and run.rtx (inputs for the "
         "README's tour)")


def _certificate(path: Path, sim, name: str, db: str) -> None:
    """The customer certificate (PDF) of a demonstration test, issued through the register of the
    demo's history with the demo's own laboratory; skipped, said, without WeasyPrint."""
    import datetime as dt
    import importlib.util

    from axiscal.report.issue import write_certificate
    from axiscal.store import open_store

    if importlib.util.find_spec("weasyprint") is None:
        note(f"no {path.name}: a PDF needs WeasyPrint (pip install 'axiscal[report]')")
        return
    today = dt.date.today()
    rotary = name == "rotary"
    instrument = {"name": f"simulated {'rotary calibrator' if rotary else 'laser interferometer'}",
                  "serial": "SIM-1", "certificate": f"SIM-CAL-{name.upper()}",
                  "due": (today + dt.timedelta(days=365)).isoformat()}
    cfg = {**DEMO_CONFIG, "conditions": {**DEMO_CONFIG["conditions"], "date": today.isoformat()},
           "machine": {**DEMO_CONFIG["machine"],
                       "model": sim.dataset.metadata.machine or "simulated machine"},
           "instrument": [instrument],   # E_VE declared: 0.2 µm, 0.1 arcsec (a still simulation)
           "uncertainty": _inputs(name)}
    out_path(path, "certificate")
    data = path.parent / f"{name}_data.csv"
    o = write_certificate(path, sim.dataset, sim.result, cfg, data.read_bytes(),
                          DEMO_TOLERANCES[name], store=open_store(db), filename=data.name,
                          customer_supplied=tuple(DEMO_TOLERANCES[name]))
    note(f"wrote certificate {path}: {o.number or 'DRAFT'}")


def _inputs(name: str) -> dict:
    """The demo's uncertainty inputs: E_VE declared, 0.2 µm (linear) or 0.1 arcsec (rotary),
    for a still simulation; the same in its report, its index and its certificate."""
    return {**DEMO_CONFIG["uncertainty"], "e_ve": 0.1 if name == "rotary" else 0.2}


def _budget(sim, name: str):
    """The ISO 230-2:2014 Annex A budget of a demo test's record, with :func:`_inputs`."""
    from axiscal.store.kinds import positioning_record, with_uncertainty

    return with_uncertainty(positioning_record(sim.dataset, sim.result, others=False),
                            _inputs(name)).budget


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
    return ("C axis, rotary calibration chain", "rotary_calibration_report.html", result.result,
            result.budget if hasattr(result.budget, "U") else None)


def _write_index(out: Path, pages) -> None:
    from axiscal.report.html import Report, unit_label

    rep = Report("axiscal demonstration", subtitle="Simulated ISO 230-2 positioning tests, evaluated and compared with the truth")
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    def cell(r, b, p):
        v = getattr(r, p)
        u = b.U(p) if b is not None else None
        return "—" if v is None else f"{v:.2f}" + (f" ± {format_uncertainty(u)}" if u else "")

    rows = [[label, *(cell(r, b, p) for p in "AERB"), unit_label(r.deviation_unit)]
            for label, _, r, b in pages]
    rep.add_table(["Axis", "A", "E", "R", "B", "unit"], rows, digits=2)
    rep.add_text("Each value ± its expanded uncertainty U (k = 2) by ISO 230-2:2014 Annex A, "
                 "from the inputs each report lists; a value without ± has no Annex A budget (the "
                 "rotary calibration chain states its error budget in its report).")
    rep.add_html("<ul>" + "".join(f'<li><a href="{href}">{label}: full report</a></li>'
                                  for label, href, _, _ in pages)
                 + "".join(f'<li><a href="{n}_certificate.pdf">{n} test: calibration certificate '
                           "(PDF)</a></li>" for n, _, _ in DEMOS if (out / f"{n}_certificate.pdf").exists())
                 + "</ul>")
    rep.write(out / "index.html")
    note(f"wrote {out / 'index.html'}")


def register(app: typer.Typer) -> None:
    """Add the ``demo`` command."""
    app.command("demo")(demo)
