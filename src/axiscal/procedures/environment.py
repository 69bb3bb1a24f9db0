"""Raw laser readings compensated for the air and the material: the deviations ISO 230-2 asks for.

A laser interferometer counts fringes of its vacuum wavelength λ0 in air of index n: the optical
path it sees is ``n·(D + L)`` for a reflector at ``L`` beyond the datum and a dead path ``D``
(interferometer to reflector at the datum). A raw reading computed with an index ``n_r`` (1 for
the vacuum wavelength) is ``r = [n(t)·(D + L) − n(t0)·D] / n_r``, so the displacement is

    L = (n_r·r + n(t0)·D) / n(t) − D                               (1)

with ``n(t)`` the index of the air at the reading's time from the environment log (Ciddor 1996 by
default, Edlén 1966 or Birch & Downs selectable: :func:`axiscal.physics.air.refractive_index`)
and ``t0`` the time the laser was zeroed (its first reading at the datum). Equation (1) is
:func:`axiscal.physics.interferometry.dead_path_correction` and the wavelength compensation
together (Renishaw, "Interferometric calibration of rotary axes", on the air's effect; NIST,
Engineering Metrology Toolbox, "Refractive index of air").

The material is then referred to 20 °C (ISO 1:2022): a machine whose scale is at ``T_m`` reaches a
point whose length at 20 °C is ``(P − d)/(1 + α(T_m − 20))`` from the datum ``d``
(:func:`axiscal.physics.thermal.normalise_length`), with ``T_m`` the mean of the material sensors
at the reading's time and α the expansion coefficient. The deviation is that position minus the
target (ISO 230-2:2014 §3.1 notation ``x_ij = P_ij − P_i``).

What was applied (equation, index range, air and material temperature ranges, α, dead path) is
recorded in the dataset's metadata notes, so every report states it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from axiscal import units
from axiscal.datasets import Environment, Metadata, PositioningDataset
from axiscal.errors import InputError

__all__ = ["RawReadings", "EnvironmentLog", "simulate_raw_test", "Conditions", "Compensated", "conditions_at", "compensate_displacements",
           "compensate_raw_readings", "MAX_GAP_S"]

@dataclass(frozen=True, eq=False)
class RawReadings:
    """Raw laser readings of a positioning test (SI: s, m)."""

    times: np.ndarray
    targets: np.ndarray          # in target_unit
    directions: np.ndarray       # "+" / "-"
    runs: np.ndarray
    readings: np.ndarray         # m
    target_unit: str
    dead_path: float             # m
    index: float                 # refractive index the readings were computed with
    datum: float                 # target (target_unit) at which the laser was zeroed
    meta: dict = field(default_factory=dict)
    source: str = "<text>"


@dataclass(frozen=True, eq=False)
class EnvironmentLog:
    """Samples of the air and the material over a test."""

    times: np.ndarray            # s
    air_temperature: np.ndarray  # °C
    pressure: np.ndarray         # Pa
    humidity: np.ndarray         # %RH
    material_temperature: np.ndarray   # °C, shape (n, sensors); sensors may be 0
    expansion_coefficient: float | None   # 1/K
    source: str = "<text>"


#: Longest interval between two log samples a reading may fall into, seconds.
MAX_GAP_S = 300.0


@dataclass(frozen=True, eq=False)
class Conditions:
    """The air and the material at each reading's time."""

    air_temperature: np.ndarray
    pressure: np.ndarray
    humidity: np.ndarray
    material_temperature: np.ndarray | None   # mean of the sensors, or None
    expansion_coefficient: float | None


@dataclass(frozen=True, eq=False)
class Compensated:
    """Displacements compensated for the air (and the material), with what was applied."""

    displacement: np.ndarray        # m, from the datum, at 20 °C if the material was compensated
    index: np.ndarray               # n at each reading
    applied: str                    # what was done, in words (kept in the metadata)
    conditions: Conditions


def conditions_at(times, log=None, *, air_temperature=None, pressure=None, humidity=None,
                  material_temperature=None, expansion_coefficient=None,
                  max_gap: float = MAX_GAP_S) -> Conditions:
    """The environment at ``times`` (s): interpolated in ``log``, or the constants given.

    A constant given beside a log replaces the log's column. A time outside the log or inside a
    gap longer than ``max_gap`` is refused by name (the air cannot be guessed there).
    """
    t = np.asarray(times, dtype=float)
    if log is not None:
        lt = log.times
        outside = (t < lt[0]) | (t > lt[-1])
        if outside.any():
            k = int(np.argmax(outside))
            raise InputError(f"a reading at {t[k]:g} s is outside the environment log "
                             f"({lt[0]:g} … {lt[-1]:g} s)")
        gaps = np.flatnonzero(np.diff(lt) > max_gap)
        for g in gaps:
            inside = (t > lt[g]) & (t < lt[g + 1])
            if inside.any():
                raise InputError(f"the environment log has a gap from {lt[g]:g} to "
                                 f"{lt[g + 1]:g} s (more than {max_gap:g} s) with readings in "
                                 f"it (first at {t[inside][0]:g} s)")

    def column(const, values):
        if const is not None:
            return np.full(t.shape, float(const))
        if log is None:
            return None
        return np.interp(t, log.times, values)

    air = column(air_temperature, None if log is None else log.air_temperature)
    p = column(pressure, None if log is None else log.pressure)
    h = column(humidity, None if log is None else log.humidity)
    if air is None or p is None or h is None:
        raise InputError("the air's temperature, pressure and humidity are needed: give an "
                         "environment log or all three values")
    mat = None
    if material_temperature is not None:
        mat = np.full(t.shape, float(material_temperature))
    elif log is not None and log.material_temperature.shape[1]:
        mat = np.interp(t, log.times, log.material_temperature.mean(axis=1))
    alpha = expansion_coefficient
    if alpha is None and log is not None:
        alpha = log.expansion_coefficient
    return Conditions(air, p, h, mat, alpha)


def compensate_displacements(times, readings, *, conditions: Conditions, dead_path: float = 0.0,
                             reading_index: float = 1.0, equation: str = "ciddor",
                             normalise_material: bool = True) -> Compensated:
    """Equation (1) of the module docstring, then the material to 20 °C.

    Parameters
    ----------
    times : array_like, s
    readings : array_like, m
        Raw displacements from the datum; the first one is taken at the datum (``t0``).
    conditions : Conditions
        At the same times (:func:`conditions_at`).
    dead_path : float, m
    reading_index : float
        Index the readings were computed with (1: vacuum wavelength).
    equation : {"ciddor", "edlen", "birch-downs"}
    normalise_material : bool
        Refer to 20 °C (needs a material temperature and α).
    """
    from axiscal.physics.air import refractive_index
    from axiscal.physics.thermal import REFERENCE_TEMPERATURE

    r = np.asarray(readings, dtype=float)
    c = conditions
    try:
        n = refractive_index(c.air_temperature, c.pressure, c.humidity, equation=equation)
    except InputError as exc:
        k = _first_invalid(c, equation)
        raise InputError(f"the environment at {np.asarray(times)[k]:g} s "
                         f"({c.air_temperature[k]:g} °C, {c.pressure[k]:g} Pa, "
                         f"{c.humidity[k]:g} %RH) is outside the {equation} equation's "
                         f"validity: {exc}") from None
    n = np.atleast_1d(np.asarray(n, dtype=float))
    if not (0 <= dead_path <= 100):
        raise InputError(f"dead path {dead_path!r} m: between 0 and 100 m")
    length = (reading_index * r + n[0] * dead_path) / n - dead_path
    words = [f"air: {_equation_name(equation)}, n from {n.min():.9f} to {n.max():.9f} "
             f"(air {c.air_temperature.min():.2f} … {c.air_temperature.max():.2f} °C, "
             f"{c.pressure.min():.0f} … {c.pressure.max():.0f} Pa, "
             f"{c.humidity.min():.0f} … {c.humidity.max():.0f} %RH); dead path "
             f"{dead_path * 1e3:g} mm; raw readings at index {reading_index:g}"]
    if normalise_material:
        if c.material_temperature is None or c.expansion_coefficient is None:
            raise InputError("referring the axis to 20 °C needs the material temperature and "
                             "its expansion coefficient (or ask for air compensation only)")
        k = 1.0 + c.expansion_coefficient * (c.material_temperature - REFERENCE_TEMPERATURE)
        length = length / k
        words.append(f"material to 20 °C (ISO 1): α = {c.expansion_coefficient * 1e6:g} ppm/K, "
                     f"{c.material_temperature.min():.2f} … {c.material_temperature.max():.2f} "
                     f"°C")
    else:
        words.append("material not referred to 20 °C")
    return Compensated(length, n, "; ".join(words), c)


@dataclass(frozen=True, eq=False)
class ReadingCorrections:
    """What the compensation did to each raw reading, in the readings' order (for plots)."""

    times: np.ndarray               # s
    raw_deviation_um: np.ndarray    # the raw reading minus the target
    deviation_um: np.ndarray        # the compensated reading minus the target
    conditions: Conditions


def compensate_raw_readings(raw, log=None, *, equation: str = "ciddor",
                            normalise_material: bool = True, max_gap: float = MAX_GAP_S,
                            detail: bool = False, **constants):
    """A positioning test from raw readings and an environment log (or constants).

    ``constants``: ``air_temperature`` (°C), ``pressure`` (Pa), ``humidity`` (%RH),
    ``material_temperature`` (°C), ``expansion_coefficient`` (1/K), each replacing the log's.
    With ``detail`` the result is ``(dataset, ReadingCorrections)``.
    """
    cond = conditions_at(raw.times, log, max_gap=max_gap, **constants)
    out = compensate_displacements(raw.times, raw.readings, conditions=cond,
                                   dead_path=raw.dead_path, reading_index=raw.index,
                                   equation=equation, normalise_material=normalise_material)
    f = units.factor(raw.target_unit, "length")
    positions = raw.datum + out.displacement / f
    deviation_um = (positions - raw.targets) * f / units.UM
    ds = _dataset(raw.targets, raw.directions, raw.runs, deviation_um, raw.target_unit,
                  raw.source)
    m = raw.meta
    env = Environment(
        air_temperature=float(np.mean(cond.air_temperature)),
        material_temperature=() if cond.material_temperature is None
        else (float(np.mean(cond.material_temperature)),),
        pressure=float(np.mean(cond.pressure)), humidity=float(np.mean(cond.humidity)),
        expansion_coefficient=cond.expansion_coefficient)
    notes = f"compensated by axiscal from raw laser readings: {out.applied}"
    ds = replace(ds, metadata=Metadata(machine=m.get("machine", ""), axis=m.get("axis", ""),
                                       operator=m.get("operator", ""),
                                       date=m.get("date", ""),
                                       instrument=m.get("instrument", ""), notes=notes,
                                       environment=env))
    if not detail:
        return ds
    raw_um = (raw.datum + raw.readings / f - raw.targets) * f / units.UM
    return ds, ReadingCorrections(np.asarray(raw.times), raw_um, deviation_um, cond)


def _dataset(targets, directions, runs, deviation, target_unit, source) -> PositioningDataset:
    """Readings labelled by target, direction and run into the dataset's arrays."""
    t = np.unique(targets)
    n_runs = int(runs.max())
    if runs.min() < 1 or n_runs > 1000:
        raise InputError(f"{source}: run numbers must be 1 … 1000")
    up = np.full((t.size, n_runs), np.nan)
    down = np.full((t.size, n_runs), np.nan)
    idx = np.searchsorted(t, targets)
    for i, d, j, v in zip(idx, directions, runs, deviation):
        arr = up if d == "+" else down
        if not np.isnan(arr[i, j - 1]):
            raise InputError(f"{source}: target {t[i]:g} run {j} direction {d} is given twice")
        arr[i, j - 1] = v
    if np.isnan(down).all():
        down = np.zeros((t.size, 0))
    return PositioningDataset("linear", t, up, down, target_unit, "um")


def _first_invalid(c: Conditions, equation: str) -> int:
    from axiscal.physics.air import refractive_index

    for k in range(c.air_temperature.size):
        try:
            refractive_index(c.air_temperature[k], c.pressure[k], c.humidity[k],
                             equation=equation)
        except InputError:
            return k
    return 0


def _equation_name(equation: str) -> str:
    return {"ciddor": "Ciddor (1996)", "edlen": "Edlén (1966)",
            "birch-downs": "Birch & Downs (1993/94)"}.get(equation, equation)


def simulate_raw_test(plan, axis, rng: np.random.Generator, environment, *,
                      dead_path: float = 0.1, expansion_coefficient: float = 11.5e-6,
                      laser_noise: float = 0.02e-6, feed: float = 20.0, log_interval: float = 7.0,
                      equation: str = "ciddor", material_sensors: int = 2):
    """A linear test measured by a simulated laser in drifting air, on a machine that expands.

    ``environment(t)`` gives (air °C, Pa, %RH, material °C) at time ``t`` (s). The machine's
    deviations at 20 °C are the axis's (``axis.move``); its true positions expand with the
    material, ``L = (P − d)(1 + α(T_m − 20))``; the laser reads the raw value of equation (1)
    computed with the vacuum wavelength, plus its noise. Returns ``(raw, log, truth)``: the raw
    readings, an environment log sampled every ``log_interval`` s (sensors read the truth), and
    the dataset of true deviations at 20 °C.
    """
    from axiscal.physics.air import refractive_index

    from axiscal.procedures.positioning import execute_plan

    f = units.factor(plan.target_unit, "length")
    datum = float(plan.targets[0])
    times, targets, dirs, runs, readings = [], [], [], [], []
    up = np.full((plan.targets.size, plan.runs), np.nan)
    down = np.full((plan.targets.size, plan.runs if plan.bidirectional else 0), np.nan)
    n0 = None
    t = 0.0
    for t, s, d, actual in execute_plan(plan, axis, rng, feed, f):      # actual: m, at 20 °C
        dev = actual - s.position * f
        (up if d > 0 else down)[s.target_index, s.run - 1] = dev / units.UM
        air, p, h, tm = environment(t)
        n = float(refractive_index(air, p, h, equation=equation))
        if n0 is None:
            n0 = n
        length = (actual - datum * f) * (1 + expansion_coefficient * (tm - 20.0))
        raw = n * (dead_path + length) - n0 * dead_path + rng.normal(0.0, laser_noise)
        times.append(t)
        targets.append(s.position)
        dirs.append(s.direction)
        runs.append(s.run)
        readings.append(raw)
    lt = np.arange(0.0, t + log_interval, log_interval)
    env = np.array([environment(x) for x in lt])
    log = EnvironmentLog(lt, env[:, 0], env[:, 1], env[:, 2],
                         np.repeat(env[:, 3:4], material_sensors, axis=1),
                         expansion_coefficient, "simulation")
    raw = RawReadings(np.array(times), np.array(targets), np.array(dirs), np.array(runs),
                      np.array(readings), plan.target_unit, dead_path, 1.0, datum,
                      {"machine": "simulated", "axis": plan.axis}, "simulation")
    truth = PositioningDataset("linear", plan.targets, up, down, plan.target_unit, "um")
    return raw, log, truth
