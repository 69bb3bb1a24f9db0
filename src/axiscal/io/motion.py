"""Files of the five-DOF motion-error measurement: the TOML configuration and the data file.

Data file (``axiscal motion analyze FILE``; written by ``axiscal motion simulate --csv``)
----------------------------------------------------------------------------------------
UTF-8 CSV. Lines starting with ``#`` are comments; ``# title: TEXT`` names the measurement. The
first other line is the header; the columns, in any order, are::

    run, angle_deg, ez_arcsec, ey_arcsec, ex_arcsec, dy_um, dz_um   [, dx_um]

one row per run and angle: ``run`` a whole number (1, 2, ...), ``angle_deg`` the commanded angle
in degrees, then the angular positioning error εz, the tilt error motions εy and εx in arcseconds
and the radial (Y) and axial error motions δy, δz (optionally δx) in micrometres. Every run has the
same angles, equally spaced over one turn (a closing 360° row is allowed). Example::

    # axiscal motion errors v1
    # title: HSD-200RT, 2026-11-22
    run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um
    1,0,0,0,0,0,0
    1,30,12.1,-3.4,2.2,0.81,-0.35
    ...

Configuration (``axiscal motion simulate CONFIG.toml``): see ``examples/motion_indexing_table.toml``,
which documents every key. Unknown keys are refused by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from axiscal._parse import MAX_MAGNITUDE, check_run_number, finite_number
from axiscal.errors import ConfigError, DataFormatError
from axiscal.instruments.five_dof import Detector, FiveDofSystem, Mounting
from axiscal.io._files import read_text
from axiscal.machines.error_functions import ZERO, Harmonic, HarmonicSeries
from axiscal.machines.rotary import TWO_PI, ErrorMotion, RotaryAxis
from axiscal.procedures.motion_errors import BeamDrift, ReferenceAxis
from axiscal.standards.iso230_7 import MotionErrorData
from axiscal.units import ARCSEC, MM, UM

__all__ = ["MotionConfig", "parse_motion_config", "read_motion_config", "parse_motion_errors",
           "read_motion_errors", "format_motion_errors", "COLUMNS"]

#: Data-file columns and their SI factors (``dx_um`` optional).
COLUMNS = {"ez_arcsec": ARCSEC, "ey_arcsec": ARCSEC, "ex_arcsec": ARCSEC, "dy_um": UM, "dz_um": UM,
           "dx_um": UM}


@dataclass(frozen=True)
class MotionConfig:
    """Everything a simulated motion-error measurement needs (SI inside).

    Attributes
    ----------
    machine, axis_name : str
    axis : RotaryAxis
    system : FiveDofSystem
    reference : ReferenceAxis
    drift : BeamDrift
    step_deg, dwell, samples, runs, seed, duration, interval, drift_window
        Test settings (degrees, seconds, counts).
    """

    machine: str
    axis_name: str
    axis: RotaryAxis
    system: FiveDofSystem
    reference: ReferenceAxis
    drift: BeamDrift
    step_deg: float = 30.0
    dwell: float = 30.0
    samples: int = 10
    runs: int = 3
    seed: int = 2018
    duration: float = 3600.0
    interval: float = 10.0
    drift_window: int = 7


def read_motion_config(path) -> MotionConfig:
    """Read a TOML configuration (see :func:`parse_motion_config`)."""
    text = read_text(path)
    if not text.strip() or all(not ln.strip() or ln.lstrip().startswith("#")
                               for ln in text.splitlines()):
        raise ConfigError(f"{path}: the file is empty; give at least an [axis] or [test] table "
                          "(see examples/motion_indexing_table.toml)")
    return parse_motion_config(text, str(path))


def parse_motion_config(text: str, source: str = "<config>") -> MotionConfig:
    """Parse a motion-error TOML configuration; every key is checked and named on error.

    Examples
    --------
    >>> cfg = parse_motion_config('[test]\\nstep_deg = 45\\n[axis.positioning]\\nharmonics = [[1, 10.0, 0.0]]')
    >>> cfg.step_deg, round(float(cfg.axis.positioning(math.pi / 2)) / ARCSEC, 6)
    (45.0, 10.0)
    """
    from axiscal._schema import loads_toml, remember_document

    doc = loads_toml(text, source)

    t = _Table(remember_document(doc, source, text), source, text=text)
    machine = t.sub("machine")
    test = t.sub("test")
    cfg = dict(
        machine=machine.text("name", ""), axis_name=machine.text("axis", "C"),
        # bounds: the command line's (--runs at most 100), and sizes a simulation can hold
        step_deg=test.num("step_deg", 30.0, lo=0.1, hi=360.0),
        dwell=test.num("dwell_s", 30.0, lo=0.0, hi=3600.0),
        samples=test.int("samples", 10, hi=1000), runs=test.int("runs", 3, lo=2, hi=100),
        seed=test.int("seed", 2018, lo=0, hi=2**63 - 1),
        duration=60 * test.num("stability_duration_min", 60.0, lo=1e-3, hi=10_080.0),
        interval=test.num("stability_interval_s", 10.0, lo=1e-3, hi=3600.0),
        drift_window=test.int("drift_window", 7, hi=10_001),
    )
    if cfg["drift_window"] % 2 == 0:
        raise ConfigError(f"{source}: [test] drift_window = {cfg['drift_window']} must be odd")
    if cfg["samples"] - 1 > cfg["dwell"]:
        raise ConfigError(f"{source}: [test] samples = {cfg['samples']} readings 1 s apart do not "
                          f"fit in dwell_s = {cfg['dwell']:g} s at each stop")
    check_simulated_readings(cfg["step_deg"], cfg["samples"], cfg["runs"], f"{source}: [test] ")
    machine.done()
    test.done()
    cfg.update(axis=_axis(t.sub("axis"), cfg["axis_name"]), system=_system(t),
               reference=_reference(t.sub("reference")), drift=_drift(t.sub("drift")))
    t.done()
    return MotionConfig(**cfg)


#: Most readings one simulated indexing or repeatability test may take (each holds five channels);
#: the stability run has the same bound on the command line.
MAX_SIMULATED_READINGS = 1_000_000


def check_simulated_readings(step_deg: float, samples: int, runs: int, where: str = "") -> None:
    """Refuse an indexing or repeatability test of more than :data:`MAX_SIMULATED_READINGS`."""
    readings = round(360.0 / step_deg) * samples * runs
    if readings > MAX_SIMULATED_READINGS:
        raise ConfigError(f"{where}step_deg = {step_deg:g}, samples = {samples} and runs = {runs} "
                          f"make {readings:.3g} readings; at most {MAX_SIMULATED_READINGS:g} are "
                          "simulated (a larger step, fewer samples or fewer runs)")


def _axis(t: "_Table", name: str) -> RotaryAxis:
    pos = t.sub("positioning")
    positioning = _harmonics(pos, ARCSEC)
    rep = pos.num("repeatability", 0.0, lo=0.0) * ARCSEC
    pos.done()
    motions = {}
    for key, unit in (("tilt_x", ARCSEC), ("tilt_y", ARCSEC), ("radial_x", UM), ("radial_y", UM),
                      ("axial", UM)):
        m = t.sub(key)
        motions[key] = ErrorMotion(_harmonics(m, unit), m.num("asynchronous", 0.0, lo=0.0) * unit,
                                   m.num("offset", 0.0) * unit)
        m.done()
    t.done()
    return RotaryAxis(name=name, positioning=positioning, repeatability_sigma=rep, **motions)


def _system(t: "_Table") -> FiveDofSystem:
    ins = t.sub("instrument")
    psd_res = ins.num("psd_resolution_um", 0.5, lo=1e-6) * UM
    qd_res = ins.num("qd_resolution_um", 0.08, lo=1e-6) * UM
    psd = Detector(psd_res, ins.num("psd_noise_um", psd_res / UM / 6, lo=0.0) * UM, 7e-3 / 2**16)
    qd = Detector(qd_res, ins.num("qd_noise_um", qd_res / UM / 6, lo=0.0) * UM, 160 * UM / 2**16)
    system = FiveDofSystem(
        f1=ins.num("f1_mm", 200.0, lo=1e-3) * MM, f2=ins.num("f2_mm", 200.0, lo=1e-3) * MM,
        h=ins.num("h_mm", 30.0, lo=1e-3) * MM, l=ins.num("l_mm", 250.0, lo=1e-3) * MM,
        height=ins.num("height_mm", 50.0) * MM, psd1=psd, psd2=psd, qd1=qd, qd2=qd,
        beam_jitter=ins.num("beam_jitter_urad", 0.07, lo=0.0) * 1e-6)
    ins.done()
    mt = t.sub("mounting")
    if mt.bool("realistic", False):
        system = system.with_realistic_mounting()
    m = system.mounting
    mounting = Mounting(
        beam_yaw=mt.num("beam_yaw_arcsec", m.beam_yaw / ARCSEC) * ARCSEC,
        beam_pitch=mt.num("beam_pitch_arcsec", m.beam_pitch / ARCSEC) * ARCSEC,
        ref_eccentricity=mt.pair("ref_eccentricity_um", m.ref_eccentricity, UM),
        ref_tilt=mt.pair("ref_tilt_arcsec", m.ref_tilt, ARCSEC),
        unit_offset=mt.pair("unit_offset_mm", m.unit_offset, MM),
        focal_error=mt.num("focal_error", m.focal_error),
        separation_error=mt.num("separation_error_mm", m.separation_error / MM) * MM)
    rot = mt.list("detector_rotation_deg", None, 4)
    mt.done()
    system = replace(system, mounting=mounting)
    if rot is not None:
        system = replace(system, **{k: replace(getattr(system, k), rotation=math.radians(v))
                                    for k, v in zip(("psd1", "psd2", "qd1", "qd2"), rot)})
    return system


def _reference(t: "_Table") -> ReferenceAxis:
    ref = ReferenceAxis(step=t.num("step_arcsec", 0.33, lo=0.0) * ARCSEC,
                        encoder_error=_harmonics(t, ARCSEC, "encoder_error"),
                        encoder_noise=t.num("encoder_noise_arcsec", 0.05, lo=0.0) * ARCSEC)
    t.done()
    return ref


def _drift(t: "_Table") -> BeamDrift:
    rate = t.pair("rate_urad_per_h", (1.0, -0.7), 1.0)
    d = BeamDrift(rate=(rate[0] * 1e-6 / 3600, rate[1] * 1e-6 / 3600),
                  wander=t.num("wander_urad", 0.5, lo=0.0) * 1e-6,
                  period=60 * t.num("period_min", 20.0, lo=1e-3))
    t.done()
    return d


def _harmonics(t: "_Table", unit: float, key: str = "harmonics") -> HarmonicSeries:
    rows = t.get(key, [])
    if not isinstance(rows, list):
        raise ConfigError(f"{t.where(key)} must be a list of [order, amplitude, phase_deg]")
    out = []
    for row in rows:
        if (not isinstance(row, list) or len(row) != 3
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                           and math.isfinite(v) for v in row)
                or int(row[0]) != row[0] or not 1 <= row[0] <= MAX_ORDER
                or abs(row[1]) > MAX_AMPLITUDE or abs(row[2]) > 36_000):
            raise ConfigError(f"{t.where(key)}: entry {row!r} must be [order (whole, 1 to "
                              f"{MAX_ORDER}), amplitude (within ±{MAX_AMPLITUDE:g}), phase_deg]")
        out.append(Harmonic(float(row[1]) * unit, TWO_PI / int(row[0]), math.radians(row[2])))
    return HarmonicSeries(tuple(out)) if out else ZERO


#: Highest harmonic order per turn and largest amplitude (arcsec or µm) taken in a configuration.
MAX_ORDER, MAX_AMPLITUDE = 3600, 1e6


class _Table:
    """A TOML table whose keys are taken one by one; ``done()`` refuses the rest by name."""

    def __init__(self, d, source, path="", text=None):
        if not isinstance(d, dict):
            raise ConfigError(f"{source}: [{path}] must be a table")
        self.d, self.source, self.path, self.used, self.doc_text = d, source, path, set(), text

    def where(self, key):
        """``file:line: [table] key`` (the line found in the text, as every reader says it)."""
        from axiscal._schema import _Lines

        loc = (_Lines(self.doc_text, self.source).where(self.path, key) if self.doc_text
               else self.source)
        return f"{loc}: {'[' + self.path + '] ' if self.path else ''}{key}"

    def get(self, key, default):
        self.used.add(key)
        return self.d.get(key, default)

    def sub(self, key):
        return _Table(self.get(key, {}), self.source, f"{self.path}.{key}".strip("."), self.doc_text)

    def num(self, key, default, lo=None, hi=None):
        from axiscal._schema import Num, SchemaError

        try:
            return Num("", lo, hi).check(self.get(key, default), self.where(key))
        except SchemaError as exc:
            raise ConfigError(str(exc)) from None

    def int(self, key, default, lo=1, hi=None):
        v = self.get(key, default)
        if isinstance(v, bool) or not isinstance(v, int) or v < lo:
            raise ConfigError(f"{self.where(key)} = {v!r} must be a whole number >= {lo}")
        if hi is not None and v > hi:
            raise ConfigError(f"{self.where(key)} = {v!r} must be at most {hi}")
        return v

    def text(self, key, default):
        v = self.get(key, default)
        if not isinstance(v, str):
            raise ConfigError(f"{self.where(key)} = {v!r} must be text")
        return v

    def bool(self, key, default):
        v = self.get(key, default)
        if not isinstance(v, bool):
            raise ConfigError(f"{self.where(key)} = {v!r} must be true or false")
        return v

    def list(self, key, default, n):
        v = self.get(key, default)
        if v is None:
            return None
        if (not isinstance(v, list) or len(v) != n
                or not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                           and math.isfinite(x) for x in v)):
            raise ConfigError(f"{self.where(key)} = {v!r} must be a list of {n} finite numbers")
        return [float(x) for x in v]

    def pair(self, key, default_si, unit):
        v = self.list(key, [x / unit for x in default_si], 2)
        return (v[0] * unit, v[1] * unit)

    def done(self):
        extra = sorted(set(self.d) - self.used)
        if extra:
            from axiscal._schema import refuse_unknown

            refuse_unknown(self.d, self.used, f"[{self.path}]" if self.path else "")


def read_motion_errors(path) -> MotionErrorData:
    """Read a five-error data file (format in the module docstring)."""
    return parse_motion_errors(read_text(path), str(path))


def parse_motion_errors(text: str, source: str = "<text>") -> MotionErrorData:
    """Parse the five-error CSV (module docstring) into SI :class:`MotionErrorData`.

    Raises
    ------
    DataFormatError
        Naming the line and the problem.

    Examples
    --------
    >>> rows = "\\n".join(f"1,{a},{a / 90},0,0,0,0" for a in range(0, 360, 90))
    >>> d = parse_motion_errors("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\\n" + rows)
    >>> d.n_runs, round(float(d.ez[0, 2]) / ARCSEC, 6)
    (1, 2.0)
    """
    title, header, rows = "", None, []
    for i, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            if line[1:].strip().lower().startswith("title:"):
                title = line[1:].strip()[6:].strip()
            continue
        cells = [c.strip() for c in line.split(",")]
        if header is None:
            header = _header(cells, source, i)
            continue
        if len(cells) != len(header):
            raise DataFormatError(f"{len(cells)} values where the header has {len(header)}", source, i)
        vals = [finite_number(c, name, source, i, limit=math.inf if name == "run" else MAX_MAGNITUDE)
                for c, name in zip(cells, header)]
        rows.append((i, dict(zip(header, vals))))
    if header is None or not rows:
        raise DataFormatError("no header and data rows", source)
    return _assemble(rows, header, title, source)


def _header(cells, source, line):
    need = ["run", "angle_deg", "ez_arcsec", "ey_arcsec", "ex_arcsec", "dy_um", "dz_um"]
    unknown = [c for c in cells if c not in need and c != "dx_um"]
    missing = [c for c in need if c not in cells]
    if unknown or missing or len(set(cells)) != len(cells):
        raise DataFormatError(f"header must hold {', '.join(need)} (and optionally dx_um) once each; "
                              f"missing {missing}, unknown {unknown}", source, line)
    return cells


def _assemble(rows, header, title, source) -> MotionErrorData:
    runs: dict[int, list] = {}
    for line, r in rows:
        run = check_run_number(r["run"], len(rows), source, line)
        runs.setdefault(run, []).append((line, r))
    first = None
    out = {k: [] for k in COLUMNS if k in header}
    for n, lst in sorted(runs.items()):
        angles = [r["angle_deg"] for _, r in lst]
        if first is None:
            first = angles
        elif angles != first:
            raise DataFormatError(f"run {n} has angles {angles} but run {min(runs)} has {first}",
                                  source, lst[0][0])
        for k in out:
            out[k].append([r[k] * COLUMNS[k] for _, r in lst])
    ch = {k.split("_")[0]: np.array(v) for k, v in out.items()}
    try:
        return MotionErrorData(np.radians(first), title=title, **ch)
    except ValueError as exc:
        raise DataFormatError(str(exc), source) from None


def format_motion_errors(data: MotionErrorData) -> str:
    """The data file text of ``data`` (see the module docstring); parses back to the same data."""
    cols = ["ez_arcsec", "ey_arcsec", "ex_arcsec", "dy_um", "dz_um"] + (["dx_um"] if data.dx is not None else [])
    lines = ["# axiscal motion errors v1"]
    if data.title:
        lines.append(f"# title: {data.title}")
    lines.append(",".join(["run", "angle_deg", *cols]))
    deg = np.degrees(data.theta)
    for j in range(data.n_runs):
        for i, a in enumerate(deg):
            vals = [getattr(data, c.split("_")[0])[j, i] / COLUMNS[c] for c in cols]
            lines.append(",".join([str(j + 1), f"{a:.6g}", *(f"{v:.6f}" for v in vals)]))
    return "\n".join(lines) + "\n"
