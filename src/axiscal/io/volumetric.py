"""The volumetric machine configuration (TOML) and the measured files it names.

Format
------
::

    [machine]
    name = "VMC-800"
    chain = "X Y | Z"              # work-piece side | tool side (``|`` = the machine base)
    travel_mm = { X = [0, 800], Y = [0, 500], Z = [-500, 0] }
    reference_mm = [400, 250, -250] # where every measuring line crossed (default: the middle)
    measured_tool_offset_mm = [0, 0, -100]
    tool_offset_mm = [0, 0, -100]   # where the map and the tables apply (default: as measured)

    [errors]                        # ISO 230-1 names; each a file or an inline function
    EXX = "X_EXX.csv"               # positioning test (any positioning file axiscal reads):
                                    # the mean bidirectional deviation of ISO 230-2 is used
    EYX = "X_EYX.csv"               # straightness file (position,deviation)
    ECX = "X_ECX.csv"               # angular file (position,deviation, deviation_unit=arcsec)
    EAY = { positions_mm = [0, 250, 500], values = [0, 1.5, 0.5], unit = "arcsec" }
    EZZ = { polynomial = [0, 0.01], unit = "um" }   # c0 + c1·p + …, p in mm
    EBX = { positions_mm = [0, 400, 800], values = [0, 2, 1], unit = "urad", U = 1.5 }
                                    # U: its expanded uncertainty (k = 2) in its unit, over
                                    # [volumetric_uncertainty] (iso230_9_volumetric)

    [squareness]                    # µm/m, positive when the angle exceeds 90°
    xy = 25.0
    yz = -15.0
    zx = 30.0

    [compensation]                  # optional
    receiving = { xy = "Y", yz = "Z", zx = "Z" }
    spacing_mm = 20
    resolution_um = 0.1

    [simulation]                    # written by ``axiscal volumetric simulate`` only
    seed = 1

Angular files are straightness-like CSVs (``# position_unit=mm deviation_unit=arcsec axis=X
about=Z``, header ``position,deviation``) with an angle unit (arcsec, urad, mrad, deg) or ``um/m``
(µrad). Paths are relative to the configuration file (to ``base`` for
:func:`parse_volumetric_config`'s text). A missing error motion is taken as zero
and said; an unknown key or table is refused by name.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal import units
from axiscal.errors import AxiscalError, ConfigError, DataFormatError
from axiscal.io._tidy import number, parse_tidy
from axiscal.standards.volumetric import (AXES, ERROR_NAMES, PAIRS, ErrorFunction,
                                          GeometricErrors, KinematicChain)

__all__ = ["VolumetricConfig", "read_volumetric_config", "parse_volumetric_config",
           "parse_angular", "format_angular", "write_simulation", "format_volumetric_inline"]

_SECTIONS = {"machine", "errors", "squareness", "compensation", "simulation"}
_MACHINE_KEYS = {"name", "chain", "travel_mm", "reference_mm", "measured_tool_offset_mm",
                 "tool_offset_mm"}
_COMP_KEYS = {"receiving", "spacing_mm", "resolution_um"}
_SIM_KEYS = {"seed", "squareness_um_per_m", "points"}


class VolumetricConfig:
    """What a configuration holds: the measured errors, the tool offset, settings and its path."""

    def __init__(self, errors: GeometricErrors, tool_offset, name: str, compensation: dict,
                 simulation: dict, path: Path):
        self.errors, self.tool_offset, self.name = errors, np.asarray(tool_offset, float), name
        self.compensation, self.simulation, self.path = compensation, simulation, path
        #: U (k = 2, m or rad) an inline error states (``U`` in its table), by error name.
        self.uncertainty: dict = {}
        #: Every file the configuration was read from: itself and the measured files it names
        #: (an output written into their folder must not replace one).
        self.inputs: tuple = (path,)


def read_volumetric_config(path) -> VolumetricConfig:
    """Read a volumetric configuration and every file it names, relative to its folder (see
    :func:`parse_volumetric_config`)."""
    from axiscal.io._files import read_text

    p = Path(path)
    return parse_volumetric_config(read_text(p), str(p), p.parent)


def parse_volumetric_config(text: str, source: str = "<text>", base=".") -> VolumetricConfig:
    """Check a volumetric configuration's TOML ``text`` (format in the module docstring) and read
    every file it names, a relative name taken from the folder ``base``; messages name
    ``source``. ``base=None``: the configuration must hold every error inline (the one file the
    calibration history keeps of a volumetric test); a file name is refused, all named.

    Raises
    ------
    ConfigError
        An unknown section or key, a missing travel or chain, a wrong type or value.
    DataFormatError, MissingFileError
        A named file that cannot be read (the message names the file).
    """
    from axiscal._schema import loads_toml, remember_document

    p = Path(source)
    cfg = remember_document(loads_toml(text, source), source, text)
    _known(cfg, _SECTIONS, p, "")
    m = _table(cfg, "machine", p, required=True)
    _known(m, _MACHINE_KEYS, p, "[machine]")
    if "chain" not in m or "travel_mm" not in m:
        raise ConfigError(f"{p}: [machine] needs chain and travel_mm")
    chain = KinematicChain.parse(m["chain"])
    travel = _travel(m["travel_mm"], p)
    mid = [sum(travel[a]) / 2 * 1e3 for a in AXES]
    ref = np.asarray(_triple(m.get("reference_mm", mid), p, "reference_mm")) * 1e-3
    tm = np.asarray(_triple(m.get("measured_tool_offset_mm", [0, 0, 0]), p,
                            "measured_tool_offset_mm")) * 1e-3
    tool = np.asarray(_triple(m.get("tool_offset_mm", list(tm * 1e3)), p, "tool_offset_mm")) * 1e-3
    errs = _table(cfg, "errors", p)
    _known(errs, set(ERROR_NAMES), p, "[errors]")
    named = [f"{k} = {v[:60]!r}" for k, v in errs.items() if isinstance(v, str)]
    if base is None and named:
        raise ConfigError(f"{p}: [errors] names files ({', '.join(named[:3])}"
                          f"{f' and {len(named) - 3} more' if len(named) > 3 else ''}); a "
                          "volumetric test kept as one file holds every error inline: write it "
                          "with 'axiscal volumetric map CONFIG --inline FILE'")
    functions = {name: _function(name, spec, p, Path(base or ".")) for name, spec in errs.items()}
    sq = _table(cfg, "squareness", p)
    _known(sq, set(PAIRS), p, "[squareness]")
    squareness = {k: _number(v, p, f"[squareness] {k}", 1e4) * 1e-6 for k, v in sq.items()}
    comp = _table(cfg, "compensation", p)
    _known(comp, _COMP_KEYS, p, "[compensation]")
    sim = _table(cfg, "simulation", p)
    _known(sim, _SIM_KEYS, p, "[simulation]")
    try:
        errors = GeometricErrors(chain, functions, squareness, ref, tm, travel)
    except AxiscalError as exc:
        raise ConfigError(f"{p}: {exc}") from None
    out = VolumetricConfig(errors, tool, str(m.get("name", p.stem)), comp, sim, p)
    out.uncertainty = _given_uncertainty(errs, p)
    out.inputs = (p, *(Path(base or ".") / spec for spec in errs.values()
                       if isinstance(spec, str)))
    return out


def parse_angular(text: str, source: str = "<text>") -> tuple[np.ndarray, np.ndarray, str]:
    """Read an angular CSV: positions (m), angles (rad) and the moving axis.

    Examples
    --------
    >>> u, a, axis = parse_angular("# deviation_unit=arcsec axis=X about=Z\\n"
    ...                            "position,deviation\\n0,0\\n100,2\\n")
    >>> u.tolist(), round(float(a[1]) * 1e6, 3), axis
    ([0.0, 0.1], 9.696, 'X')
    """
    meta, rows = parse_tidy(text, ("position", "deviation"),
                            {"position_unit", "deviation_unit", "axis", "about", "machine",
                             "date", "notes"}, source)
    try:
        fp = units.factor(meta.get("position_unit", "mm"), "length")
        du = meta.get("deviation_unit", "arcsec")
        fd = 1e-6 if du.replace("µ", "u").lower() == "um/m" else units.factor(du, "angle")
    except AxiscalError as exc:
        raise DataFormatError(str(exc), source) from None
    u = np.array([number(r["position"], "position", source, n) for n, r in rows]) * fp
    a = np.array([number(r["deviation"], "deviation", source, n) for n, r in rows]) * fd
    return u, a, meta.get("axis", "").upper()


def format_angular(u_m, angle_rad, axis: str, about: str) -> str:
    """The angular CSV of ``angle_rad`` at ``u_m`` (mm and arcsec)."""
    lines = [f"# position_unit=mm deviation_unit=arcsec axis={axis} about={about}",
             "position,deviation"]
    lines += [f"{p * 1e3:.9g},{a / units.ARCSEC:.9g}" for p, a in zip(u_m, angle_rad)]
    return "\n".join(lines) + "\n"


def write_simulation(out_dir, machine, errors: GeometricErrors, datasets: dict, seed: int,
                     squareness_um_per_m, points: int) -> Path:
    """Write the measured files and the configuration of a simulated machine; returns its path.

    ``datasets`` holds the positioning tests (axis -> PositioningDataset); the other error
    motions are written from ``errors`` as straightness and angular files.
    """
    from axiscal.io._files import write_files_atomic
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.straightness import StraightnessData, format_straightness

    out = Path(out_dir)
    names = {}
    texts = {}

    def write_text_atomic(path, text):   # gathered, then written all or nothing
        texts[Path(path).name] = text
    for a in AXES:
        f = f"{a}_E{a}{a}.csv"
        write_text_atomic(out / f, format_positioning_csv(datasets[a]))
        names[f"E{a}{a}"] = f
        for b in AXES:
            if b == a:
                continue
            fn = errors.functions[f"E{b}{a}"]
            f = f"{a}_E{b}{a}.csv"
            write_text_atomic(out / f, format_straightness(
                StraightnessData(fn.positions, fn.values, a, b)))
            names[f"E{b}{a}"] = f
        for r, about in zip("ABC", AXES):
            fn = errors.functions[f"E{r}{a}"]
            f = f"{a}_E{r}{a}.csv"
            write_text_atomic(out / f, format_angular(fn.positions, fn.values, a, about))
            names[f"E{r}{a}"] = f
    travel = ", ".join(f"{a} = [{lo * 1e3:g}, {hi * 1e3:g}]"
                       for a, (lo, hi) in errors.travel.items())
    lines = ["# axiscal volumetric configuration, written by `axiscal volumetric simulate`",
             "[machine]", f'name = "{machine.name}"', f'chain = "{machine.chain}"',
             f"travel_mm = {{ {travel} }}",
             f"reference_mm = [{', '.join(f'{v * 1e3:g}' for v in errors.reference)}]",
             "measured_tool_offset_mm = "
             f"[{', '.join(f'{v * 1e3:g}' for v in errors.measured_tool_offset)}]", "",
             "[errors]"]
    lines += [f'{k} = "{v}"' for k, v in names.items()]
    lines += ["", "[squareness]  # µm/m, as measured"]
    lines += [f"{k} = {v * 1e6:.6f}" for k, v in errors.squareness.items()]
    lines += ["", "[simulation]  # the truth: regenerated from the seed by `volumetric map`",
              f"seed = {int(seed)}", f"points = {int(points)}",
              f"squareness_um_per_m = [{', '.join(f'{v:g}' for v in squareness_um_per_m)}]"]
    cfg = out / "volumetric.toml"
    texts[cfg.name] = "\n".join(lines) + "\n"
    write_files_atomic(out, texts)
    return cfg


def format_volumetric_inline(text: str, cfg: VolumetricConfig) -> str:
    """The configuration ``text`` (read as ``cfg``) with every error it names by file written
    inline, as the reader took it from the file (``positions_mm`` and ``values`` in µm, or µrad
    for an angle: a positioning test's mean bidirectional deviation, a straightness or angular
    file's points), every other table as it was: one self-contained file, the one a
    calibration history keeps of a volumetric test. Numbers are written as Python's shortest
    repr (a double round-trips; scaled to mm and µm the map agrees with the files' to about
    1e-15 relative).

    Examples
    --------
    The file ``x.csv`` read as three points (here given inline to the reader):

    >>> head = '''[machine]
    ... chain = "X Y | Z"
    ... travel_mm = { X = [0, 100], Y = [0, 100], Z = [-100, 0] }
    ... [errors]
    ... '''
    >>> cfg = parse_volumetric_config(head + "EXX = { positions_mm = [0, 50, 100], "
    ...                               "values = [0, 1, 2] }", "vol.toml")
    >>> print(format_volumetric_inline(head + 'EXX = "x.csv"', cfg).splitlines()[-1])
    EXX = { positions_mm = [0.0, 50.0, 100.0], values = [0.0, 1.0, 2.0], unit = "um" }
    """
    from axiscal._schema import loads_toml

    doc = loads_toml(text, str(cfg.path))
    errors = dict(doc.get("errors", {}))
    for name, spec in errors.items():
        if isinstance(spec, str):
            f = cfg.errors.functions[name]
            angular = name[1] in "ABC"
            errors[name] = {"positions_mm": [float(v) * 1e3 for v in f.positions],
                            "values": [float(v) * 1e6 for v in f.values],
                            "unit": "urad" if angular else "um"}
    doc["errors"] = errors
    doc["machine"] = {"name": cfg.name, **doc["machine"]}   # as read (default: the file's stem)
    lines = [f"# axiscal volumetric configuration of {cfg.name}, every error inline "
             "(axiscal volumetric map --inline)"]
    for section, table in doc.items():
        lines += ["", f"[{section}]"]
        lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def _toml_key(k: str) -> str:
    import json
    import re

    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _toml_value(v) -> str:
    """A value of a volumetric configuration as TOML (strings, numbers, booleans, arrays and
    inline tables: what its reader takes)."""
    import json

    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)                # the shortest text a double round-trips through
    if isinstance(v, str):
        return json.dumps(v)          # JSON's escapes are TOML basic-string escapes
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise ConfigError(f"a value of type {type(v).__name__} cannot be written to TOML")


# -- helpers ---------------------------------------------------------------------------------
def _function(name: str, spec, p: Path, base: Path) -> ErrorFunction:
    angular = name[1] in "ABC"
    if isinstance(spec, str):
        return _from_file(name, base / spec, angular)
    if not isinstance(spec, dict):
        raise ConfigError(f"{p}: [errors] {name} = {spec!r}: give a file name or an inline table")
    _known(spec, {"positions_mm", "values", "polynomial", "unit", "U"}, p, f"[errors] {name}")
    f = _unit_factor(name, spec, p)
    if "polynomial" in spec:
        coef = [_number(c, p, f"[errors] {name} polynomial", 1e6) for c in
                _list(spec["polynomial"], p, name)]
        u = np.linspace(-1000.0, 1000.0, 4001)      # mm: any travel up to ±1 m
        return ErrorFunction(u * 1e-3, np.polyval(coef[::-1], u) * f, f"{name} polynomial")
    if "positions_mm" not in spec or "values" not in spec:
        raise ConfigError(f"{p}: [errors] {name}: give positions_mm and values, or polynomial")
    u = [_number(v, p, f"[errors] {name} positions_mm", 1e6) for v in
         _list(spec["positions_mm"], p, name)]
    v = [_number(v, p, f"[errors] {name} values", 1e6) for v in _list(spec["values"], p, name)]
    try:
        return ErrorFunction(np.array(u) * 1e-3, np.array(v) * f, f"{name} inline")
    except AxiscalError as exc:
        raise ConfigError(f"{p}: [errors] {name}: {exc}") from None


def _unit_factor(name: str, spec: dict, p: Path) -> float:
    """SI per unit of an inline error's ``unit`` (default µm, or arcsec for an angle)."""
    angular = name[1] in "ABC"
    unit = str(spec.get("unit", "arcsec" if angular else "um"))
    try:
        return (1e-6 if unit.replace("µ", "u").lower() == "um/m" and angular
                else units.factor(unit, "angle" if angular else "length"))
    except AxiscalError as exc:
        raise ConfigError(f"{p}: [errors] {name}: {exc}") from None


def _given_uncertainty(errs: dict, p: Path) -> dict:
    """``U`` (k = 2) of each inline error that states one, SI (m or rad): in the error's own
    ``unit``, a finite number ≥ 0 (:mod:`axiscal.standards.iso230_9_volumetric` uses it over
    its class's input)."""
    out = {}
    for name, spec in errs.items():
        if isinstance(spec, dict) and "U" in spec:
            v = _number(spec["U"], p, f"[errors] {name} U", 1e6)
            if v < 0:
                raise ConfigError(f"{p}: [errors] {name} U = {v!r}: an expanded uncertainty "
                                  "(k = 2) ≥ 0 in the error's unit")
            out[name] = v * _unit_factor(name, spec, p)
    return out


def _from_file(name: str, path: Path, angular: bool) -> ErrorFunction:
    from axiscal.io._files import read_text

    text = read_text(path)
    src = str(path)
    axis = name[-1]
    if angular:
        u, v, declared = parse_angular(text, src)
    elif name[1] == axis:
        from axiscal.io import parse_positioning
        from axiscal.standards.iso230_2 import evaluate

        ds = parse_positioning(text, src)
        if ds.axis_kind.value != "linear":
            raise DataFormatError(f"{name} needs a linear positioning test", src)
        r = evaluate(ds)
        u = ds.targets * units.factor(ds.target_unit, "length")
        v = r.mean_bi * units.factor(ds.deviation_unit, "length")
        declared = ds.metadata.axis.upper()
    else:
        from axiscal.io.straightness import parse_straightness

        d = parse_straightness(text, source=src)
        u, v, declared = d.positions, d.deviations, d.axis
        if d.direction and d.direction != name[1]:
            raise DataFormatError(f"{name} is a deviation along {name[1]}, the file says "
                                  f"direction={d.direction}", src)
    if declared and declared != axis:
        raise DataFormatError(f"{name} is an error of axis {axis}, the file says axis={declared}",
                              src)
    order = np.argsort(u, kind="stable")
    try:
        return ErrorFunction(np.asarray(u)[order], np.asarray(v)[order], src)
    except AxiscalError as exc:
        raise DataFormatError(str(exc), src) from None


def _travel(t, p: Path) -> dict:
    if not isinstance(t, dict) or set(t) != set(AXES):
        raise ConfigError(f"{p}: [machine] travel_mm = {t!r}: give X, Y and Z as [low, high] mm")
    out = {}
    for a in AXES:
        lo, hi = (_number(v, p, f"travel_mm {a}", 1e5) for v in _list(t[a], p, f"travel_mm {a}"))
        if not hi > lo:
            raise ConfigError(f"{p}: travel_mm {a} = {t[a]!r}: high must exceed low")
        out[a] = (lo * 1e-3, hi * 1e-3)
    return out


def _triple(v, p: Path, key: str) -> list[float]:
    vals = _list(v, p, key)
    if len(vals) != 3:
        raise ConfigError(f"{p}: {key} = {v!r}: give [x, y, z] in mm")
    return [_number(x, p, key, 1e5) for x in vals]


def _list(v, p: Path, key: str) -> list:
    if not isinstance(v, (list, tuple)) or len(v) < 1:
        raise ConfigError(f"{p}: {key} = {v!r}: expected a list of numbers")
    if key.startswith("travel") and len(v) != 2:
        raise ConfigError(f"{p}: {key} = {v!r}: give [low, high]")
    return list(v)


def _number(v, p: Path, key: str, bound: float) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) \
            or abs(v) > bound:
        raise ConfigError(f"{p}: {key} = {v!r}: expected a finite number within ±{bound:g}")
    return float(v)


def _table(cfg: dict, key: str, p: Path, required: bool = False) -> dict:
    t = cfg.get(key)
    if t is None:
        if required:
            raise ConfigError(f"{p}: the [{key}] table is missing")
        return {}
    if not isinstance(t, dict):
        raise ConfigError(f"{p}: {key} must be a table [{key}]")
    return t


def _known(d: dict, keys: set, p: Path, where: str) -> None:
    """Refuse an unknown key or table by name, with the file and line (one message style)."""
    from axiscal._schema import refuse_unknown

    refuse_unknown(d, keys, where)
