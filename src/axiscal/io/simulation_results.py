"""The simulations of an instrument or a machine run from their configuration, with the stable
``--json`` object of their command, for the commands and the public API (:mod:`axiscal.api`)
alike.

* :func:`scale_homing` — ``axiscal scale home``: referencing of one laser-scale axis through the
  environmental compensator (Renishaw, "Laser scale axis referencing": events A, B, Z, C).
* :func:`gantry_homing` — ``axiscal scale gantry``: twin-axis homing, skew and deskew (Renishaw,
  "Laser scale axis referencing", twin-axis sequence).
* :func:`motion_simulation` — ``axiscal motion simulate``: five motion errors of a rotary axis
  measured at once (Optics Express 2018, "Five-DOF motion errors of a rotary axis", eqs. 1-6 and
  the beam-drift compensation), evaluated by ISO 230-7:2015 (:func:`iso230_7_json`).
* :func:`volumetric_map` — ``axiscal volumetric map``: the volumetric error field of the 21
  geometric errors (ISO 230-1:2012 §3, rigid-body model of ISO/TR 16907:2015) and the body
  diagonals (ISO 230-6:2002).
* :func:`environment_compensation` — ``axiscal compensate-environment``: what the compensation of raw
  laser readings for the air (Ciddor 1996) and the material (ISO 1:2016, 20 °C) did.

Each returns a :class:`SimulationRun`: the library's record, the parts a figure or a report
needs, and the ``--json`` object (the keys are documented in each command's module).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

__all__ = ["SimulationRun", "scale_homing", "gantry_homing", "motion_simulation", "iso230_7_json",
           "volumetric_map", "simulated_volumetric_machine", "volumetric_tables_for",
           "volumetric_compensation", "volumetric_linuxcnc", "ballbar_simulation",
           "write_controller_files",
           "environment_compensation",
           "environment_options", "environment_json",
           "MOTION_CHANNELS", "TRUE_SQUARENESS_UM_PER_M", "SIMULATION_KINDS", "DOCUMENTS",
           "simulation_kind", "run_configured", "simulation_dict", "write_simulated_data"]

#: The five channels of the five-DOF system and their JSON keys (units in the names).
MOTION_CHANNELS = {"ez": "ez_arcsec", "ey": "ey_arcsec", "ex": "ex_arcsec", "dy": "dy_um",
                   "dz": "dz_um"}
#: Squareness of ``axiscal volumetric simulate``'s machine (xy, yz, zx), µm/m: a configuration
#: written without ``[simulation] squareness_um_per_m`` was simulated with these.
TRUE_SQUARENESS_UM_PER_M = (25.0, -15.0, 30.0)


#: What :func:`axiscal.simulate` runs, by the name of its kind.
SIMULATION_KINDS = ("positioning", "rotary-calibration", "scale-homing", "gantry-homing",
                    "five-dof", "ballbar")
#: The document each kind of run follows, shown with its results in a notebook.
DOCUMENTS = {"rotary-calibration": 'Renishaw, "Interferometric calibration of rotary axes"',
             "scale-homing": 'Renishaw, "Laser scale axis referencing"',
             "gantry-homing": 'Renishaw, "Laser scale axis referencing"',
             "five-dof": "ISO 230-7:2015",
             "ballbar": "ISO 230-4:2005",
             "volumetric-map": "ISO/TR 16907:2015 and ISO 230-6:2002",
             "volumetric-compensation": "ISO 230-1:2012 and ISO 230-6:2002",
             "environment": "Ciddor 1996 and ISO 1:2016"}
_SCALE_TABLES = ("laser", "compensator", "switch", "homing")
_MOTION_TABLES = ("instrument", "mounting", "reference", "drift")
_MOTION_AXIS = ("positioning", "tilt_x", "tilt_y", "radial_x", "radial_y", "axial")
_BALLBAR_TABLES = ("ballbar", "servo")


def simulation_kind(cfg: dict) -> str:
    """The kind of simulation a configuration's tables ask for (the order of
    :func:`axiscal.simulate`'s documentation)."""
    axis = cfg.get("axis")
    if "calibrator" in cfg:
        return "rotary-calibration"
    if "gantry" in cfg:
        return "gantry-homing"
    if any(t in cfg for t in _SCALE_TABLES):
        return "scale-homing"
    if any(t in cfg for t in _BALLBAR_TABLES):
        return "ballbar"
    if any(t in cfg for t in _MOTION_TABLES) or (
            isinstance(axis, dict) and any(isinstance(axis.get(k), dict) for k in _MOTION_AXIS)):
        return "five-dof"
    return "positioning"


def run_configured(kind: str, path: Any, seed: int | None = None,
                   text: str | None = None, compensated: bool = True) -> "SimulationRun":
    """Run a ``scale-homing``, ``gantry-homing``, ``five-dof`` or ``ballbar`` configuration
    file, as ``axiscal scale home``, ``scale gantry``, ``motion simulate`` and ``ballbar
    simulate`` do; ``text``: the configuration's TOML instead of the file's (``path`` then
    only names it in messages), read by the same schema; ``compensated`` False: a five-DOF
    run without the beam-drift compensation (``motion simulate --no-compensation``)."""
    if kind == "ballbar":
        from axiscal.io.ballbar_config import parse_ballbar_config, read_ballbar_config

        cfg = read_ballbar_config(path) if text is None else parse_ballbar_config(text, str(path))
        return ballbar_simulation(cfg, 0 if seed is None else seed, str(path))
    if kind == "five-dof":
        from axiscal.io.motion import parse_motion_config, read_motion_config

        cfg = read_motion_config(path) if text is None else parse_motion_config(text, str(path))
        return motion_simulation(cfg, seed, compensated, str(path))
    from axiscal.io.scale_config import (GANTRY_SCHEMA, SCHEMA, parse_scale_config,
                                         read_scale_config)

    gantry = kind == "gantry-homing"
    scale = (read_scale_config(path, gantry=gantry) if text is None else
             parse_scale_config(text, str(path), GANTRY_SCHEMA if gantry else SCHEMA))
    return gantry_homing(scale, seed) if gantry else scale_homing(scale, seed)


@dataclass(frozen=True, eq=False)
class SimulationRun:
    """One simulation's record and its command's ``--json`` object.

    Attributes
    ----------
    kind : str
        ``scale-homing``, ``gantry-homing``, ``five-dof``, ``volumetric-map`` or
        ``environment``.
    record : object
        The library's record (``ReferencingRun``, ``TwinHomingResult``, ``MotionRun``,
        ``VolumetricMap``, ``ReadingCorrections``).
    json : dict
        The ``--json`` object of the command.
    parts : dict
        What the figure and the report need beside the record (the axis, the ISO 230-7
        result, the truth ...).
    """

    kind: str
    record: Any
    json: dict
    parts: dict = field(default_factory=dict)


def scale_homing(cfg: dict, seed: int | None = None) -> SimulationRun:
    """``axiscal scale home``: referencing of one axis (a configuration read by
    :func:`axiscal.io.scale_config.read_scale_config`); ``seed`` (``--seed``) replaces
    ``[homing] seed``."""
    from axiscal.io.scale_config import axis_from_config, homing_from_config
    from axiscal.procedures.referencing import simulate_referencing

    cfg = _with_seed(cfg, "homing", seed)
    axis = axis_from_config(cfg)
    kwargs = homing_from_config(cfg, axis)
    run = simulate_referencing(axis, **kwargs)
    air = axis.air
    ppm = float(axis.compensator.correction_ppm(air.temperature, air.pressure, air.humidity,
                                                air.material_temperature))
    d = run.to_dict()
    d.update(compensation_ppm=ppm, laser_count_rate_hz=axis.laser.count_rate(kwargs["homing_speed"]),
             controller_max_speed_m_per_s=axis.controller.max_speed())
    if kwargs["moves"] and run.homed:
        d["tracking"] = run.tracking()
    return SimulationRun("scale-homing", run, d, {"axis": axis, "compensation_ppm": ppm})


def gantry_homing(cfg: dict, seed: int | None = None) -> SimulationRun:
    """``axiscal scale gantry``: twin-axis homing (a configuration read by
    ``read_scale_config(path, gantry=True)``; ``seed`` replaces ``[gantry] seed``); the skew
    limit needed adds 3 sigma of the difference of the two switches (3·σ·√2, counts)."""
    from axiscal.io.scale_config import twin_axis_from_config
    from axiscal.procedures.twin_axis import (required_skew_limit, simulate_twin_homing,
                                              worst_case_runs)

    g, run_kwargs, sigma = twin_axis_from_config(_with_seed(cfg, "gantry", seed))
    run = simulate_twin_homing(g, **run_kwargs)
    worst = worst_case_runs(g)
    spread = int(round(3.0 * sigma * 2 ** 0.5))
    d = run.to_dict()
    d["required_skew_limit"] = required_skew_limit(g, spread)
    d["switch_sigma_counts"] = sigma
    d["worst_case"] = [{"virtual_1": w.virtual_1, "virtual_2": w.virtual_2,
                        "skew_before_sync": w.skew_check.skew, "alarm": w.alarm} for w in worst]
    return SimulationRun("gantry-homing", run, d, {"gantry": g, "worst": worst, "spread": spread})


def _with_seed(cfg: dict, table: str, seed: int | None) -> dict:
    """The configuration with ``[table] seed`` set from ``seed`` (if given)."""
    if seed is not None:
        cfg = {**cfg, table: {**cfg.get(table, {}), "seed": seed}}
    return cfg


def motion_simulation(cfg: Any, seed: int | None = None, compensated: bool = True,
                      config_name: str = "") -> SimulationRun:
    """``axiscal motion simulate``: one indexing test (a ``MotionConfig``), measured beside the
    truth and evaluated by ISO 230-7:2015; ``seed`` None is the configuration's."""
    from axiscal.units import ARCSEC, UM

    import numpy as np

    from axiscal.procedures.motion_errors import INPUTS, crosstalk, indexing_test, to_motion_data
    from axiscal.standards.iso230_7 import evaluate

    rng = np.random.default_rng(cfg.seed if seed is None else seed)
    run = indexing_test(cfg.axis, cfg.system, rng, cfg.step_deg, cfg.reference, cfg.drift,
                        cfg.dwell, samples=cfg.samples)
    which = "measured" if compensated else "uncompensated"
    measured = getattr(run, which)
    data = to_motion_data([run], which, title=cfg.machine)
    result = evaluate(data)
    ct = crosstalk(cfg.system)
    res = cfg.system.resolutions()
    diff = measured - run.truth
    d = {
        "config": config_name, "compensated": compensated,
        "positions": [{"angle_deg": round(float(np.degrees(t)), 9),
                       "measured": five_channels(measured, i), "truth": five_channels(run.truth, i)}
                      for i, t in enumerate(measured.theta)],
        "max_abs_error": {k: float(np.max(np.abs(v))) for k, v in five_channels(diff).items()},
        "resolutions": {"angular_arcsec": res.angular / ARCSEC, "tilt_x_arcsec": res.tilt_x / ARCSEC,
                        "displacement_um": res.displacement * 1e6},
        "crosstalk": {"inputs": list(INPUTS), "outputs": list(MOTION_CHANNELS),
                      "matrix": ct.table(), "spurious": channel_dict(ct.spurious),
                      "residual": channel_dict(ct.residual)},
        "iso230_7": iso230_7_json(result),
    }
    return SimulationRun("five-dof", run, d, {"measured": measured, "data": data, "result": result,
                                              "crosstalk": ct, "resolutions": res,
                                              "machine": cfg.machine, "axis": cfg.axis_name})


def five_channels(errors: Any, i: int | None = None) -> dict:
    """The five errors (all positions, or position ``i``) in arcsec and µm by their JSON keys."""
    from axiscal.units import ARCSEC, UM


    out = {}
    for ch, key in MOTION_CHANNELS.items():
        v = getattr(errors, ch) if i is None else getattr(errors, ch)[i]
        out[key] = v / (ARCSEC if ch[0] == "e" else UM)
    return out


def channel_dict(values: dict) -> dict:
    """A value per channel (radians, metres) in arcsec and µm by the channels' JSON keys."""
    from axiscal.units import ARCSEC, UM

    return {MOTION_CHANNELS[c]: v / (ARCSEC if c[0] == "e" else UM) for c, v in values.items()}


def iso230_7_json(result: Any) -> dict:
    """The stable JSON object of an ISO 230-7:2015 result (``iso230_7`` of ``axiscal motion
    simulate``, ``repeatability`` and ``analyze``; keys in :mod:`axiscal.cli.motion`)."""
    from axiscal.units import ARCSEC, UM

    import numpy as np

    def k(kind):
        return (UM, "um") if kind == "length" else (ARCSEC, "arcsec")

    def opt(v, unit):
        return None if math.isnan(v) else v / unit

    motions = [{"name": m.name, "unit": k(m.kind)[1], "total": m.total / k(m.kind)[0],
                "synchronous": m.synchronous / k(m.kind)[0],
                "asynchronous": opt(m.asynchronous, k(m.kind)[0]),
                "fundamental": m.fundamental / k(m.kind)[0],
                "fundamental_removed": m.fundamental_removed}
               for m in result.motions]
    loc, pos = result.location, result.positioning
    return {
        "n_runs": result.n_runs, "angles_deg": np.round(np.degrees(result.theta), 9),
        "motions": motions,
        "location": {"x0_um": opt(loc.x0, UM), "y0_um": loc.y0 / UM,
                     "a0_arcsec": loc.a0 / ARCSEC, "b0_arcsec": loc.b0 / ARCSEC},
        "positioning": {"range_arcsec": pos.range / ARCSEC,
                        "repeatability_arcsec": opt(pos.repeatability, ARCSEC),
                        "mean_arcsec": pos.mean / ARCSEC},
        "closure": {c: v / (ARCSEC if c[0] == "e" else UM) for c, v in result.closure.items()},
        "warnings": list(result.warnings),
    }


def volumetric_map(cfg: Any, grid: int = 11) -> SimulationRun:
    """``axiscal volumetric map``: the error field on a ``grid``³ grid and the four body
    diagonals of a ``VolumetricConfig``; a simulated configuration adds the truth and the
    largest |mapped − true| over the grid."""
    import numpy as np

    from axiscal.standards.volumetric import body_diagonals, map_volume

    e = cfg.errors
    vmap = map_volume(e, grid, tool_offset=cfg.tool_offset)
    diags = body_diagonals(e, tool_offset=cfg.tool_offset)
    truth = _truth_map(cfg, grid) if cfg.simulation else None
    out = {"machine": cfg.name, "chain": str(e.chain),
           "tool_offset_mm": [v * 1e3 for v in cfg.tool_offset], **vmap.summary(),
           "diagonals": [{"name": d.name, "start_mm": d.start * 1e3, "end_mm": d.end * 1e3,
                          "range_um": d.range * 1e6} for d in diags],
           "missing": list(e.missing)}
    if truth is not None:
        out["truth"] = {"largest_um": truth.largest * 1e6,
                        "range_um": {a: v * 1e6 for a, v in truth.ranges.items()}}
        out["mapped_minus_true_um"] = float(np.abs(vmap.error - truth.error).max()) * 1e6
    return SimulationRun("volumetric-map", vmap, out,
                         {"diagonals": diags, "truth": truth, "config": cfg, "grid": grid})


def volumetric_tables_for(cfg: Any, receiving: dict | None = None, spacing: float = 20.0,
                          verify: bool = False) -> Any:
    """The positioning and cross-axis tables of a ``VolumetricConfig`` in the order of Chapman,
    "Calibration of machine squareness", Appendix II (``[compensation]`` ``receiving``,
    ``spacing_mm`` and ``resolution_um`` over the arguments' defaults); ``verify`` needs a
    simulated configuration (checked first)."""
    from axiscal.compensation.volumetric import volumetric_tables
    from axiscal.errors import InputError

    if verify and not cfg.simulation:
        raise InputError(f"{cfg.path}: --verify needs a simulated machine (a configuration "
                         "written by 'axiscal volumetric simulate --out')")
    c = cfg.compensation
    return volumetric_tables(cfg.errors, tool_offset=cfg.tool_offset,
                             receiving={**c.get("receiving", {}), **(receiving or {})},
                             spacing=float(c.get("spacing_mm", spacing)),
                             resolution=float(c.get("resolution_um", 0.1)))


def volumetric_compensation(cfg: Any, tables: Any, controller: str, *, verify: bool = False,
                            out: Any = None) -> SimulationRun:
    """``axiscal volumetric compensate CONFIG --controller C [--verify] [--out DIR]`` (a
    controller of tables: ``siemens-840d``, ``heidenhain``, ``csv``): the tables written for
    the controller (into the folder ``out`` if given), and with ``verify`` the simulated
    machine re-measured with them applied (:func:`axiscal.compensation.volumetric.verify`,
    its random stream the configuration's seed + 1)."""
    import numpy as np

    from axiscal.compensation.volumetric import verify as run_verify
    from axiscal.compensation.volumetric import write_tables

    travel_mm = cfg.errors.travel_mm
    files = write_tables(tables, controller, travel_mm)
    result = None
    if verify:
        machine, _ = simulated_volumetric_machine(cfg)
        result = run_verify(machine, cfg.errors, tables, controller,
                            np.random.default_rng(int(cfg.simulation.get("seed", 1)) + 1))
    written = write_controller_files(files, out, cfg.inputs) if out is not None else []
    d = {"controller": controller, "receiving": tables.receiving, "files": written,
         "left_by_tables_um": tables.uncompensable * 1e6}
    if result is not None:
        d["verify"] = result.to_dict()
    return SimulationRun("volumetric-compensation", tables, d,
                         {"files": files, "verify": result, "config": cfg})


def volumetric_linuxcnc(cfg: Any, tables: Any, *, verify: bool = False,
                        out: Any = None) -> SimulationRun:
    """``axiscal volumetric compensate CONFIG --controller linuxcnc [--verify --on-controller]
    [--out DIR]``: a COMP_FILE per joint, the cross-axis tables and the 3-D grid for LinuxCNC
    (:func:`axiscal.compensation.on_controller_volumetric.linuxcnc_compensation`), written into
    ``out`` if given; ``verify`` measures the simulated machine through a real, headless
    LinuxCNC bare, with the tables alone and with the 3-D correction (its random stream the
    configuration's seed + 1)."""
    from pathlib import Path

    import numpy as np

    from axiscal.compensation.on_controller_volumetric import (linuxcnc_compensation,
                                                               linuxcnc_outputs,
                                                               verify_on_linuxcnc)
    from axiscal.io._files import write_files_atomic

    comp = linuxcnc_compensation(cfg.errors, tables)
    files = linuxcnc_outputs(comp)
    result = None
    if verify:
        machine, _ = simulated_volumetric_machine(cfg)
        result = verify_on_linuxcnc(machine, cfg.errors, tables, np.random.default_rng(
            int(cfg.simulation.get("seed", 1)) + 1))
    if out is not None:
        write_files_atomic(Path(out), dict(files), cfg.inputs)
    d = {"controller": "linuxcnc", "receiving": tables.receiving,
         "files": list(files) if out is not None else [],
         "left_by_tables_um": tables.uncompensable * 1e6, "grid_spacing_mm": comp.spacing}
    if result is not None:
        d["verify"] = result.to_dict()
    return SimulationRun("volumetric-compensation", tables, d,
                         {"files": files, "verify": result, "config": cfg, "linuxcnc": comp})


def ballbar_simulation(cfg: dict, seed: int, source: str) -> SimulationRun:
    """``axiscal ballbar simulate``: a CW + CCW circular test (ISO 230-4:2005) of the
    configured machine, servo and ballbar, in the format ``ballbar analyze`` reads; ``--json``
    ``config``, ``out`` (None here: the command names the file it wrote), ``seed``, ``truth``
    (the configuration as read, defaults filled in) and ``samples_per_run``."""
    from axiscal.io.ballbar_config import simulate_configured

    data = simulate_configured(cfg, seed, source)
    d = {"config": source, "out": None, "seed": seed, "truth": cfg,
         "samples_per_run": len(data.runs[0].angles)}
    return SimulationRun("ballbar", data, d, {"data": data})


def write_controller_files(files: list, out: Any, inputs=()) -> list[str]:
    """Write controller files (and their companions, renamed after their table when two
    tables have one) into the folder ``out``, all or none, none replacing one of ``inputs``
    (:func:`axiscal.io._files.write_files_atomic`); the names written, in order."""
    from pathlib import Path

    from axiscal.io._files import write_files_atomic

    texts: dict = {}
    for f in files:
        texts[f.filename] = f.text
        for name, text in f.extra_files.items():
            extra = name if name not in texts else f"{Path(f.filename).stem}_{name}"
            texts[extra] = text
    return write_files_atomic(Path(out), texts, inputs)


def _truth_map(cfg: Any, grid: int) -> Any:
    from axiscal.procedures.volumetric import true_field
    from axiscal.standards.volumetric import map_volume

    machine, _ = simulated_volumetric_machine(cfg)
    return map_volume(cfg.errors, grid, tool_offset=cfg.tool_offset,
                      field=true_field(machine, cfg.errors.reference, cfg.tool_offset,
                                       cfg.errors.measured_tool_offset))


def simulated_volumetric_machine(cfg: Any) -> tuple:
    """The simulated machine a volumetric configuration was measured on (regenerated from its
    ``[simulation]`` seed and squareness) and the random generator after it."""
    import numpy as np

    from axiscal.errors import ConfigError
    from axiscal.machines.three_axis import simulated_machine

    seed = cfg.simulation.get("seed", 1)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ConfigError(f"{cfg.path}: [simulation] seed = {seed!r}: a whole number >= 0")
    sq = cfg.simulation.get("squareness_um_per_m", list(TRUE_SQUARENESS_UM_PER_M))
    travel = tuple((lo * 1e3, hi * 1e3) for lo, hi in (cfg.errors.travel[a] for a in "XYZ"))
    rng = np.random.default_rng(seed)
    return simulated_machine(rng, chain=str(cfg.errors.chain), travel_mm=travel,
                             squareness_um_per_m=tuple(sq)), rng


def environment_compensation(raw: Any, log: Any = None, *, out: Any = None,
                             **options: Any) -> SimulationRun:
    """``axiscal compensate-environment``: raw laser readings (``RawReadings``) compensated for
    the air at each reading's time and referred to 20 °C
    (:func:`axiscal.procedures.environment.compensate_raw_readings`, whose keyword options these
    are); the compensated test is written to ``out`` (positioning CSV) if given."""
    from axiscal.io._files import write_text_atomic
    from axiscal.io.csv import format_positioning_csv
    from axiscal.procedures.environment import compensate_raw_readings

    ds, detail = compensate_raw_readings(raw, log, detail=True, **options)
    if out is not None:
        write_text_atomic(out, format_positioning_csv(ds))
    return SimulationRun("environment", detail, environment_json(ds, raw.readings.size, out),
                         {"dataset": ds})


def environment_options(conditions: dict) -> dict:
    """The conditions given instead of the log's (``air_temperature`` °C, ``pressure`` Pa,
    ``humidity`` %, ``material_temperature`` °C, ``expansion_ppm`` ppm/K) as the keywords of
    :func:`environment_compensation` (ppm/K to 1/K)."""
    from axiscal.errors import InputError

    known = ("air_temperature", "pressure", "humidity", "material_temperature", "expansion_ppm")
    unknown = sorted(set(conditions) - set(known))
    if unknown:
        raise InputError(f"compensate_environment: unknown condition {unknown[0]!r} "
                         f"(one of {', '.join(known)})")
    opts = dict(conditions)
    ppm = opts.pop("expansion_ppm", None)
    return {**opts, "expansion_coefficient": None if ppm is None else ppm * 1e-6}


def environment_json(ds: Any, readings: int, out: Any) -> dict:
    """The ``--json`` of ``axiscal compensate-environment``: where the compensated test went,
    how many readings, what was applied (the metadata's words) and the air and material
    temperatures over the test (``[min, max]``, °C; the material null without its
    compensation)."""
    env = ds.metadata.environment
    return {"out": None if out is None else str(out), "readings": int(readings),
            "applied": ds.metadata.notes, "air_temperature_c": env.air_temperature,
            "material_temperature_c": env.mean_material_temperature}


def simulation_dict(kind: str, test: Any, seed: int | None) -> dict:
    """The ``--json`` object of any :class:`axiscal.api.Simulation`, as plain JSON types:
    ``axiscal simulate`` (the ISO 230-2 keys, ``truth``, ``seed``), ``rotary simulate``'s
    summary, or a :class:`SimulationRun`'s ``json``."""
    import json

    from axiscal._json import jsonable
    from axiscal.io.results import result_json

    if kind == "rotary-calibration":
        d = test.summary()
    elif kind == "positioning":
        d = {**result_json(test.result), "truth": test.truth, "seed": seed}
    else:
        d = test.json
    return json.loads(json.dumps(jsonable(d)))


def write_simulated_data(kind: str, dataset: Any, path: Any, encoding: str | None = None) -> Any:
    """Write simulated readings as an instrument's file: a positioning test as tidy CSV
    (``.csv``), axiscal JSON (``.json``) or Renishaw ``.rtl``/``.rta``, as ``axiscal simulate
    --data``; a five-DOF run as
    the ``.csv`` of ``motion simulate --csv``. Returns the path.

    ``encoding`` (``simulate --encoding``): the code page of a Renishaw export
    (:func:`axiscal.io.renishaw.encode`); refused for any other file, which is UTF-8."""
    from pathlib import Path

    from axiscal.errors import InputError
    from axiscal.io._files import write_text_atomic

    suffix = Path(path).suffix.lower()
    if encoding is not None and suffix not in (".rtl", ".rta"):
        raise InputError(f"--encoding {encoding} is the code page of a Renishaw .rtl/.rta "
                         f"export; {Path(path).name} is written as UTF-8: drop --encoding")
    fmt: Any
    if kind == "five-dof" and suffix == ".csv":
        from axiscal.io.motion import format_motion_errors as fmt
    elif kind == "ballbar":     # the analyze format, whatever the name (--out of the command)
        from axiscal.io.ballbar import format_ballbar as fmt
    elif kind not in ("positioning", "rotary-calibration"):
        raise InputError(f"write_data {path}: a {kind} run writes no readings here"
                         + (" (give a .csv file)" if kind == "five-dof" else ""))
    elif suffix == ".json":
        from axiscal.io.json import format_positioning_json as fmt
    elif suffix == ".csv":
        from axiscal.io.csv import format_positioning_csv as fmt
    elif suffix in (".rtl", ".rta"):
        from axiscal.io import renishaw

        fmt = renishaw.format_rtl if suffix == ".rtl" else renishaw.format_rta
    else:
        raise InputError(f"write_data {path}: give a .csv, .json, .rtl or .rta file")
    if encoding is not None:
        from axiscal.io._files import write_bytes_atomic
        from axiscal.io.renishaw import encode

        write_bytes_atomic(path, encode(fmt(dataset), encoding))
        return Path(path)
    write_text_atomic(path, fmt(dataset))
    return Path(path)
