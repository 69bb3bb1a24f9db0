"""Simulations and runs computed from a configuration or raw readings: :func:`simulate`,
:func:`volumetric_map`, :func:`volumetric_compensation` and :func:`compensate_environment`.

``axiscal simulate`` and ``axiscal volumetric compensate`` call these and print
:meth:`axiscal.api.Simulation.to_dict` for ``--json``.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Union

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.api._results import PathLike, Simulation

__all__ = ["simulate", "volumetric_map", "volumetric_compensation", "compensate_environment"]


def simulate(config: Union[PathLike, Mapping[str, Any]], seed: int | None = None, *,
             kind: str | None = None, drift_compensation: bool = True) -> "Simulation":
    """Simulate an instrument or a machine from its configuration.

    Parameters
    ----------
    config : str, Path or mapping
        A TOML configuration, or the same tables as a dict (checked by the file's schema, the
        same keys, units and bounds), its kind told by its tables, in this order:
        ``[calibrator]`` a rotary calibration with the reference calibrator (``axiscal rotary
        simulate``; Renishaw, "Interferometric calibration of rotary axes"); ``[gantry]``
        twin-axis homing (``scale gantry``); ``[laser]``, ``[compensator]``, ``[switch]`` or
        ``[homing]`` referencing of one laser-scale axis (``scale home``; Renishaw, "Laser
        scale axis referencing"); ``[instrument]``, ``[mounting]``, ``[reference]``,
        ``[drift]`` or ``[axis.positioning]`` ... the five motion errors of a rotary axis and
        ISO 230-7:2015 (``motion simulate``; Optics Express 2018, "Five-DOF motion errors of a
        rotary axis"); ``[ballbar]`` or ``[servo]`` a CW + CCW circular test by ISO 230-4:2005
        (``ballbar simulate``; Chapman, "Calibration of machine squareness", Method 4);
        otherwise a positioning test by ISO 230-2:2014 (``axiscal simulate``).
    seed : int, optional
        Seed of the simulation; the same seed gives the same readings. Default as the
        commands: 1 for a positioning test, 0 for a ballbar test, otherwise the
        configuration's.
    kind : str, optional
        ``positioning``, ``rotary-calibration``, ``scale-homing``, ``gantry-homing``,
        ``five-dof`` or ``ballbar``, instead of telling it from the tables.
    drift_compensation : bool
        Five-DOF: the errors with the beam-drift compensation (default), or without it as
        ``motion simulate --no-compensation`` (Optics Express 2018, eqs. 1-6 only).

    Returns
    -------
    Simulation
    """
    from axiscal.api._results import Simulation
    from axiscal.errors import InputError

    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise InputError(f"seed {seed!r}: a whole number >= 0")
    from axiscal.io import simulation_results as sr

    cfg = _load_config(config)
    kind = kind or sr.simulation_kind(cfg)
    if kind in ("scale-homing", "gantry-homing", "five-dof", "ballbar"):
        if isinstance(config, Mapping):
            from axiscal.api._config import SOURCE, toml_text

            run = sr.run_configured(kind, SOURCE, seed, toml_text(config), drift_compensation)
            return Simulation(run, seed, kind, SOURCE)
        return Simulation(sr.run_configured(kind, config, seed, None, drift_compensation), seed,
                          kind, Path(config).name)
    if kind == "rotary-calibration":
        from axiscal.procedures.rotary_config import run_rotary_config

        return Simulation(run_rotary_config(cfg, seed), seed, "rotary-calibration")
    if kind != "positioning":
        raise InputError(f"kind {kind!r}: one of {', '.join(sr.SIMULATION_KINDS)}")
    from axiscal.procedures.positioning import simulate_from_config

    seed = 1 if seed is None else seed
    return Simulation(simulate_from_config(cfg, seed=seed), seed)


def volumetric_map(config: Union[PathLike, Mapping[str, Any]], grid: int = 11, *,
                   base: PathLike | None = None) -> "Simulation":
    """The volumetric error of a three-axis machine from its 21 measured geometric errors.

    The errors of ISO 230-1:2012 combined by the rigid-body model of ISO/TR 16907:2015 over the
    working volume, and the body diagonals of ISO 230-6:2002 (``axiscal volumetric map --json``;
    a simulated configuration adds ``truth`` and ``mapped_minus_true_um``).

    Parameters
    ----------
    config : str, Path or mapping
        The volumetric configuration (TOML; format in the README, "Volumetric configuration"),
        or the same tables as a dict, checked by the file's reader (same keys, units, bounds
        and messages, the source named ``<dict>``).
    grid : int
        Grid points per axis, 2 to 100 (default 11, as the command).
    base : str or Path, optional
        With a dict: the folder its relative file names (``[errors] EXX = "X_EXX.csv"``) are
        taken from (default: the current directory). A file's names are relative to its own
        folder, so ``base`` with a file is refused.

    Returns
    -------
    Simulation
        ``kind`` ``volumetric-map``; ``result`` the ``VolumetricMap``.
    """
    from axiscal.api._results import Simulation
    from axiscal.errors import InputError
    from axiscal.io.simulation_results import volumetric_map as run_map

    if isinstance(grid, bool) or not isinstance(grid, int) or not 2 <= grid <= 100:
        raise InputError(f"grid {grid!r}: a whole number of points per axis, 2 to 100")
    cfg, name = _volumetric_config(config, base)
    return Simulation(run_map(cfg, grid), None, "volumetric-map", name)


def volumetric_compensation(config: Union[PathLike, Mapping[str, Any]], controller: str, *,
                            out: PathLike | None = None,
                            receiving: Mapping[str, str] | None = None, spacing: float = 20.0,
                            verify: bool = False, base: PathLike | None = None) -> "Simulation":
    """Positioning and cross-axis tables that remove what tables can of a volumetric map.

    As ``axiscal volumetric compensate CONFIG --controller C [--verify] [--out DIR] --json``:
    the tables in the order of Chapman, "Calibration of machine squareness", Appendix II;
    ``verify`` re-measures the simulated machine with them applied (volumetric map and body
    diagonals before and after; a configuration of ``volumetric simulate`` only).

    For ``linuxcnc`` the tables are a COMP_FILE per joint, the cross-axis tables and the 3-D
    grid of the Abbe products (``volcomp.json``) with the HAL component that applies them
    through external offsets (docs/linuxcnc.md); ``verify`` then measures through a real,
    headless LinuxCNC bare, with the tables alone and with the 3-D correction, as ``--verify
    --on-controller`` (LinuxCNC installed).

    Parameters
    ----------
    config : str, Path or mapping
        The volumetric configuration (TOML), or its tables as a dict (as :func:`volumetric_map`).
    controller : str
        ``siemens-840d``, ``heidenhain``, ``csv`` or ``linuxcnc``.
    out : str or Path, optional
        Folder for the tables (created if missing).
    receiving : mapping, optional
        Axis receiving each squareness correction, e.g. ``{"zx": "Z"}`` (default: the axis
        aligned to the spindle).
    spacing : float, mm
        Table spacing (default 20 mm, as the command), under the configuration's.
    verify : bool
        Re-measure the simulated machine with the tables applied.
    base : str or Path, optional
        With a dict: the folder of its relative file names (default: the current directory;
        as :func:`volumetric_map`).

    Returns
    -------
    Simulation
        ``kind`` ``volumetric-compensation``; ``result`` the ``VolumetricTables``;
        ``to_dict()`` the command's ``--json`` (``linuxcnc`` adds ``grid_spacing_mm``, and
        when verified ``verify`` holds each figure bare, with the tables and with the 3-D
        correction, the LinuxCNC moves and the largest applied difference).
    """
    from axiscal.api._results import Simulation
    from axiscal.io import simulation_results as sr

    cfg, name = _volumetric_config(config, base)
    if out is not None:
        _folder(Path(out))
    rec = {k.lower(): v for k, v in (receiving or {}).items()}
    tables = sr.volumetric_tables_for(cfg, rec, spacing, verify)
    run = (sr.volumetric_linuxcnc(cfg, tables, verify=verify, out=out) if controller == "linuxcnc"
           else sr.volumetric_compensation(cfg, tables, controller, verify=verify, out=out))
    return Simulation(run, None, "volumetric-compensation", name)


def compensate_environment(raw: PathLike, environment: PathLike | None = None, *,
                           out: PathLike | None = None, equation: str = "ciddor",
                           air_only: bool = False, max_gap: float = 300.0,
                           **conditions: float) -> "Simulation":
    """Raw laser readings compensated for the air at each reading's time and referred to 20 °C.

    As ``axiscal compensate-environment RAW --environment ENV --out OUT --json``: the air's
    refractive index by the named equation and the dead path at each reading, the axis referred
    to 20 °C by ISO 1:2016. Evaluate the test with ``axiscal.evaluate(result.dataset)``.

    Parameters
    ----------
    raw : str or Path
        Raw readings (CSV ``time_s,target,direction,run,reading``; :mod:`axiscal.io.measured`).
    environment : str or Path, optional
        The environment log over the test (CSV or JSON).
    out : str or Path, optional
        Write the compensated positioning CSV there (named in ``to_dict()["out"]``).
    equation : str
        ``ciddor`` (default), ``edlen`` or ``birch-downs``.
    air_only : bool
        Compensate the air only, not the material.
    max_gap : float, s
        Longest gap in the log a reading may fall into (default 300 s, as the command).
    **conditions : float
        Instead of the log's: ``air_temperature`` (°C), ``pressure`` (Pa), ``humidity`` (%),
        ``material_temperature`` (°C), ``expansion_ppm`` (ppm/K).

    Returns
    -------
    Simulation
        ``kind`` ``environment``; ``dataset`` the compensated test.
    """
    from axiscal.api._results import Simulation
    from axiscal.io.measured import read_environment_log, read_raw_readings
    from axiscal.io.simulation_results import environment_compensation, environment_options

    options = environment_options(conditions)
    raw_data = read_raw_readings(raw)
    log = read_environment_log(environment) if environment is not None else None
    run = environment_compensation(raw_data, log, out=out, equation=equation,
                                   normalise_material=not air_only, max_gap=max_gap, **options)
    return Simulation(run, None, "environment", Path(raw).name)


def _load_config(config: Union[PathLike, Mapping[str, Any]]) -> dict:
    if isinstance(config, Mapping):
        return dict(config)
    from axiscal.io._files import load_toml

    return load_toml(Path(config))


def _volumetric_config(config: Union[PathLike, Mapping[str, Any]], base: PathLike | None):
    """(the ``VolumetricConfig``, its name): a file read with its names relative to its folder;
    a dict written as TOML and read by the same reader (:mod:`axiscal.api._config`), its names
    relative to ``base`` (default: the current directory)."""
    from axiscal.errors import InputError
    from axiscal.io.volumetric import parse_volumetric_config, read_volumetric_config

    if not isinstance(config, Mapping):
        if base is not None:
            raise InputError(f"base {str(base)[:80]!r}: only for a configuration given as a "
                             "dict; the files a configuration file names are relative to its "
                             "own folder")
        return read_volumetric_config(config), Path(config).name
    from axiscal.api._config import SOURCE, toml_text

    folder = Path.cwd() if base is None else Path(base)
    if not folder.is_dir():
        raise InputError(f"base {str(base)[:80]!r}: not a folder (the relative file names of "
                         "the configuration are taken from it)")
    return parse_volumetric_config(toml_text(config), SOURCE, folder), SOURCE


def _folder(out: Path) -> None:
    """Create the folder ``out`` (and its parents), or say in one line why it cannot be."""
    from axiscal.errors import InputError

    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create folder {out}: {exc.strerror or exc}") from None
