"""The environmental compensator of a laser scale (RCU10-like, Renishaw, Laser scale axis referencing).

It sits between the laser head and the machine controller and does three things (Renishaw, Laser scale axis referencing,
"Compensated laser scale system"):

1. **Compensation by exact pulse multiplication and addition.** The laser's uncompensated count
   ``c`` (one count per ``λ_vac/k`` of optical path) becomes the output count

   .. math::
       o = \\left\\lfloor \\frac{c\\,P}{2^{B}} \\right\\rfloor,\\qquad
       \\frac{P}{2^{B}} \\approx R = \\frac{\\lambda_{vac}/k}{n\\,[1 + \\alpha(t_m - 20)]\\;q},

   with n the refractive index of the air (:mod:`axiscal.physics.air`), α and t_m the work-piece
   expansion coefficient and temperature (:mod:`axiscal.physics.thermal`, so that the controller
   tracks the part as it would be at 20 °C) and q the output count size. P is an integer (the
   factor held to ``B = 32`` fractional bits); every output count is computed from the *total*
   laser count with integer arithmetic, so nothing is rounded twice and no error accumulates
   however long the move. When the sensors give a new factor, the output jumps to
   ``floor(c P_new / 2^B)``: the difference is the "pulse addition" of the paper. The streaming
   :class:`PulseMultiplier` does the same incrementally with a remainder accumulator
   (Bresenham) and gives identical counts.

2. **Synthesis of low-bandwidth sine/cosine outputs** with a period of 20, 25, 40, 50 or 100 µm
   and N output counts per period (seed: 256 counts of 78.125 nm for 20 µm). The controller-side
   count is ``m``; the outputs are ``sin(2π m/N)`` and ``cos(2π m/N)`` (a DAC staircase of N
   steps per period).

3. **Rephasing of the reference mark** (:func:`~axiscal.instruments.reference_mark.rephase`,
   re-exported here).

The rephasing and the pulse model of the reference mark are in
:mod:`axiscal.instruments.reference_mark`.
The exact integer arithmetic of item 1 (:func:`multiply`, :class:`PulseMultiplier`) is in
:mod:`axiscal.instruments.pulse_multiplication`, re-exported here.

Examples
--------
>>> out = SineOutput(period=20e-6, counts_per_period=256)
>>> out.count_size * 1e9
78.125
>>> mult = PulseMultiplier(factor_to_integer(8.1))
>>> mult.feed([1, 1, 1, 1]).tolist()   # 8.1 output counts per input count, spread exactly
[8, 8, 8, 8]
>>> mult.output
32
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np

from axiscal.errors import InputError
from axiscal.instruments.laser_scale import LaserHead
from axiscal.instruments.pulse_multiplication import (FACTOR_BITS, PulseMultiplier, expand_counts,
                                                      factor_to_integer, multiply)
from axiscal.instruments.reference_mark import (RephaseResult, reference_virtual,
                                                reference_window, rephase, synthesise)
from axiscal.physics.air import (refractive_index, saturation_vapour_pressure,
                                 water_vapour_pressure)
from axiscal.physics.thermal import REFERENCE_TEMPERATURE

__all__ = [
    "OUTPUT_PERIODS",
    "Compensator",
    "CompensationSummary",
    "compensation_summary",
    "FACTOR_BITS",
    "SineOutput",
    "factor_to_integer",
    "multiply",
    "PulseMultiplier",
    "CompensatorUnit",
    "SimulatedCompensatorUnit",
    "expand_counts",
    "RephaseResult",
    "rephase",
    "synthesise",
    "reference_window",
    "reference_virtual",
    "rephase_periods_for",
]

#: Periods of the synthesised sine/cosine outputs the compensator offers (Renishaw, Laser scale axis referencing), metres.
OUTPUT_PERIODS = (20e-6, 25e-6, 40e-6, 50e-6, 100e-6)

@dataclass(frozen=True)
class SineOutput:
    """The compensator's sine/cosine output format.

    Attributes
    ----------
    period : float, metres
        One of :data:`OUTPUT_PERIODS` (20, 25, 40, 50 or 100 µm).
    counts_per_period : int
        Output counts N per signal period; a multiple of 8 so that B, Z and C fall on whole
        counts (seed: 256).
    """

    period: float = 20e-6
    counts_per_period: int = 256

    def __post_init__(self) -> None:
        if not any(abs(self.period - p) < 1e-12 for p in OUTPUT_PERIODS):
            allowed = ", ".join(f"{p * 1e6:g}" for p in OUTPUT_PERIODS)
            raise InputError(f"sine/cosine output period {self.period * 1e6:g} µm is not one the "
                             f"compensator offers ({allowed} µm)")
        n = self.counts_per_period
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 8 or n % 8:
            raise InputError(f"counts_per_period = {n!r} must be a whole multiple of 8 "
                             "(B, Z and C fall on whole counts only then)")
        object.__setattr__(self, "counts_per_period", int(n))

    @property
    def count_size(self) -> float:
        """Size of one output count, metres (period / N)."""
        return self.period / self.counts_per_period

    @property
    def stage2_counts(self) -> int:
        """Real motion from the switch (A) to the start of the reference pulse (B): N counts."""
        return self.counts_per_period

    @property
    def switch_to_home(self) -> int:
        """Real motion from the switch (A) to the home position (Z): 5N/4 (320 for N = 256)."""
        return self.counts_per_period * 5 // 4

    @property
    def pulse_counts(self) -> int:
        """Width of the reference pulse from B to C: N/2 counts, centred on Z."""
        return self.counts_per_period // 2

    def signal_frequency(self, speed) -> float:
        """Frequency of the sine/cosine outputs at a speed (m/s), Hz."""
        return abs(float(speed)) / self.period


@dataclass(frozen=True)
class Compensator:
    """Settings of the compensator and the multiplication factor it derives from its sensors.

    Attributes
    ----------
    laser : LaserHead
        The head whose counts arrive (count size λ_vac / k; 0.633 µm in Renishaw, Laser scale axis referencing).
    output : SineOutput
        Sine/cosine output format (period and counts per period).
    equation : {"ciddor", "birch-downs", "edlen"}
        Refractive index equation (:func:`axiscal.physics.air.refractive_index`).
    expansion_coefficient : float, 1/K
        α of the work-piece whose expansion the controller should track; 0 for none.
    update_interval : float, seconds
        The sensors are read and the factor renewed every this often (sample and hold).
    co2 : float, µmol/mol
        CO2 content assumed (the compensator has no CO2 sensor).
    bits : int
        Fractional bits of the factor.
    rephase_periods : int
        k: signal periods of real motion over which the rephasing spreads its virtual movement
        (1 in Renishaw, Laser scale axis referencing; more keeps the controller's input frequency within its limit at high
        homing speed, :func:`rephase_periods_for`).
    """

    laser: LaserHead = field(default_factory=LaserHead)
    output: SineOutput = field(default_factory=SineOutput)
    equation: str = "ciddor"
    expansion_coefficient: float = 0.0
    update_interval: float = 1.0
    co2: float = 450.0
    bits: int = FACTOR_BITS
    rephase_periods: int = 1

    def __post_init__(self) -> None:
        k = self.rephase_periods
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k <= 1024:
            raise InputError(f"rephase_periods = {k!r} must be a whole number from 1 to 1024")
        if not np.isfinite(self.expansion_coefficient) or abs(self.expansion_coefficient) > 1e-4:
            raise InputError(f"expansion_coefficient = {self.expansion_coefficient!r} 1/K must "
                             "lie within ±1e-4")
        if not np.isfinite(self.update_interval) or self.update_interval <= 0:
            raise InputError(f"update_interval = {self.update_interval!r} s must be positive")

    @property
    def input_count_size(self) -> float:
        """Uncompensated size of one laser count, metres."""
        return self.laser.count_size

    def ratio(self, temperature, pressure, humidity, material_temperature=REFERENCE_TEMPERATURE):
        """Output counts per laser count for sensor readings (float or array).

        :math:`R = (\\lambda_{vac}/k) / (n\\,[1 + \\alpha (t_m - 20)]\\, q)`.

        Parameters
        ----------
        temperature : array_like, degrees Celsius (air)
        pressure : array_like, Pa
        humidity : array_like, %RH
        material_temperature : array_like, degrees Celsius (work-piece)
        """
        n = refractive_index(temperature, pressure, humidity, co2=self.co2,
                             vacuum_wavelength=self.laser.vacuum_wavelength, equation=self.equation)
        growth = 1.0 + self.expansion_coefficient * (
            np.asarray(material_temperature, dtype=float) - REFERENCE_TEMPERATURE)
        r = self.input_count_size / (np.asarray(n) * growth * self.output.count_size)
        return float(r) if np.ndim(r) == 0 else r

    def factor(self, temperature, pressure, humidity, material_temperature=REFERENCE_TEMPERATURE):
        """The integer factor P (output counts per laser count times 2**bits)."""
        r = np.asarray(self.ratio(temperature, pressure, humidity, material_temperature))
        p = np.rint(r * float(1 << self.bits)).astype(np.int64)
        return int(p) if p.ndim == 0 else p

    def correction_ppm(self, temperature, pressure, humidity,
                       material_temperature=REFERENCE_TEMPERATURE) -> float:
        """The compensation the factor applies to the vacuum-wavelength count, ppm:
        :math:`(1/(n[1 + \\alpha\\Delta t]) - 1) 10^6`."""
        r = self.ratio(temperature, pressure, humidity, material_temperature)
        return (np.asarray(r) * self.output.count_size / self.input_count_size - 1.0) * 1e6

    def factor_schedule(self, times, temperature, pressure, humidity,
                        material_temperature=REFERENCE_TEMPERATURE) -> np.ndarray:
        """Factor in force at each sample: sensors read every ``update_interval`` and held.

        Parameters
        ----------
        times : array_like, seconds (non-decreasing)
        temperature, pressure, humidity, material_temperature : array_like
            What the sensors read at each sample (broadcast to ``times``).

        Returns
        -------
        ndarray of int64, one P per sample.
        """
        t = np.asarray(times, dtype=float)
        if t.ndim != 1 or t.size == 0 or np.any(np.diff(t) < 0):
            raise InputError("sample times must be a non-empty, non-decreasing 1-D array")
        block = np.floor((t - t[0]) / self.update_interval).astype(np.int64)
        first = np.flatnonzero(np.r_[True, np.diff(block) > 0])  # sample of each sensor update
        readings = [np.broadcast_to(np.asarray(a, dtype=float), t.shape)[first]
                    for a in (temperature, pressure, humidity, material_temperature)]
        p = np.atleast_1d(self.factor(*readings))
        return p[np.cumsum(np.r_[True, np.diff(block) > 0]) - 1]


@dataclass(frozen=True)
class CompensationSummary:
    """What the compensator applies for given conditions, and what no compensation would cost.

    Attributes
    ----------
    n : float
        Refractive index of the air.
    n_standard : float
        Refractive index of standard workshop air (20 °C, 101325 Pa, 50 %RH).
    growth : float
        1 + α (t_m - 20) of the work-piece (1 without material compensation).
    ratio : float
        Output counts per laser count the compensator multiplies by (as applied, P / 2**bits).
    factor : int
        P.
    correction_ppm : float
        (1/(n growth) - 1) 10⁶: the compensation applied to the vacuum-wavelength count.
    length : float, metres
        The nominal length the errors are given for.
    raw_error : float, metres
        Error of the raw count read with the vacuum wavelength over ``length``: L (n g - 1).
    weather_error : float, metres
        Error if the scale were corrected once for standard air and never again:
        L (n/n_std - 1) (sign: reading minus true).
    material_error : float, metres
        Work-piece expansion over ``length`` that the material compensation tracks: L (g - 1)
        (a scale compensated for the air only reads the warm part this much too long).
    count_size_in, count_size_out : float, metres
        Laser count (vacuum) and output count.
    """

    n: float
    n_standard: float
    growth: float
    ratio: float
    factor: int
    correction_ppm: float
    length: float
    raw_error: float
    weather_error: float
    material_error: float
    count_size_in: float
    count_size_out: float

    def to_dict(self) -> dict:
        """Plain-data form (the ``axiscal scale compensate --json`` object)."""
        return {
            "n": self.n, "n_standard": self.n_standard, "growth": self.growth,
            "ratio": self.ratio, "factor": self.factor, "correction_ppm": self.correction_ppm,
            "length_mm": self.length * 1e3, "raw_error_um": self.raw_error * 1e6,
            "weather_error_um": self.weather_error * 1e6,
            "material_error_um": self.material_error * 1e6,
            "count_size_in_nm": self.count_size_in * 1e9,
            "count_size_out_nm": self.count_size_out * 1e9,
        }

    def __str__(self) -> str:
        L = self.length * 1e3
        return "\n".join([
            f"compensation factor: {self.correction_ppm:+.3f} ppm "
            f"(n = {self.n:.9f}, work-piece growth {(self.growth - 1) * 1e6:+.3f} ppm)",
            f"pulse multiplication: {self.ratio:.9f} output counts of "
            f"{self.count_size_out * 1e9:.3f} nm per laser count of "
            f"{self.count_size_in * 1e9:.3f} nm (P = {self.factor} / 2^{FACTOR_BITS})",
            f"over {L:g} mm of the part (at 20 °C) a scale without this compensation reads:",
            f"  {self.raw_error * 1e6:+10.2f} µm  raw count read with the vacuum wavelength",
            f"  {self.weather_error * 1e6:+10.2f} µm  corrected once for 20 °C, 101.325 kPa, "
            "50 %RH and never again (the weather)",
            f"  {self.material_error * 1e6:+10.2f} µm  air compensated, work-piece expansion not "
            "tracked",
        ])


def compensation_summary(compensator: "Compensator", temperature: float = 20.0,
                         pressure: float = 101325.0, humidity: float | None = None, *,
                         dew_point: float | None = None,
                         material_temperature: float = REFERENCE_TEMPERATURE,
                         length: float = 1.0) -> CompensationSummary:
    """The factor a compensator applies for given conditions and the errors without it.

    Parameters
    ----------
    compensator : Compensator
    temperature : float, °C
    pressure : float, Pa
    humidity : float, %RH, optional (default 50 unless a dew point is given)
    dew_point : float, °C, optional
    material_temperature : float, °C
        Work-piece temperature (mean of its sensors).
    length : float, metres
        Length over which to state the errors.

    Examples
    --------
    >>> s = compensation_summary(Compensator(), 20.0, 101325.0, 50.0, length=1.0)
    >>> round(s.correction_ppm, 2), round(s.raw_error * 1e6, 1)
    (-271.3, 271.4)
    """
    if humidity is None and dew_point is None:
        humidity = 50.0
    if dew_point is not None:
        if humidity is not None:
            raise InputError("give the humidity as a relative humidity or a dew point, not both")
        humidity = 100.0 * water_vapour_pressure(temperature, dew_point=dew_point) / \
            saturation_vapour_pressure(temperature)
    if not np.isfinite(length) or length <= 0:
        raise InputError(f"length = {length!r} m must be positive")
    comp = compensator
    n = float(refractive_index(temperature, pressure, humidity, co2=comp.co2,
                               vacuum_wavelength=comp.laser.vacuum_wavelength,
                               equation=comp.equation))
    n_std = float(refractive_index(20.0, 101325.0, 50.0, co2=comp.co2,
                                   vacuum_wavelength=comp.laser.vacuum_wavelength,
                                   equation=comp.equation))
    g = 1.0 + comp.expansion_coefficient * (float(material_temperature) - REFERENCE_TEMPERATURE)
    p = int(comp.factor(temperature, pressure, humidity, material_temperature))
    ratio = p / float(1 << comp.bits)
    return CompensationSummary(
        n=n, n_standard=n_std, growth=g, ratio=ratio, factor=p,
        correction_ppm=(1.0 / (n * g) - 1.0) * 1e6, length=float(length),
        raw_error=length * (n * g - 1.0), weather_error=length * (n / n_std - 1.0),
        material_error=length * (g - 1.0), count_size_in=comp.input_count_size,
        count_size_out=comp.output.count_size)


def rephase_periods_for(speed: float, output: SineOutput, max_frequency: float) -> int:
    """Fewest signal periods k over which to spread the rephasing so the controller's limit holds.

    Parameters
    ----------
    speed : float, m/s
        Homing speed (of the compensated count, i.e. the part at 20 °C).
    output : SineOutput
    max_frequency : float, Hz
        The controller's input limit.

    Returns
    -------
    int
        The smallest k >= 1 with ``f (kN + N − 1)/(kN) · (N + 2)/N <= max_frequency``,
        f = speed / period.

    Notes
    -----
    Renishaw, Laser scale axis referencing Figure 4: in stage 2 the compensator adds v (0 to N − 1) virtual counts to N counts
    of real motion, so the controller sees up to (2N − 1)/N times the real frequency, for
    N counts. Spreading v over kN real counts lowers the factor to (kN + N − 1)/(kN); it cannot
    help once the real motion alone exceeds the limit. The counts reach the controller whole
    (pulse multiplication and the virtual spread each round to a count), so over one period the
    rate can exceed its mean by 2 counts in N: the factor (N + 2)/N is that margin.

    Examples
    --------
    >>> rephase_periods_for(1.9, SineOutput(), 100e3)   # 95 kHz real: 1.9x would be 180 kHz
    23
    """
    n = output.counts_per_period
    f = output.signal_frequency(speed) * (n + 2) / n
    if not f < max_frequency:
        raise InputError(f"homing at {abs(speed) * 60e3:g} mm/min drives the outputs at "
                         f"{output.signal_frequency(speed) / 1e3:.2f} kHz (up to {f / 1e3:.2f} "
                         f"kHz over a period, whole counts), not below the controller's "
                         f"{max_frequency / 1e3:g} kHz before any rephasing: home slower")
    k = int(np.ceil((n - 1) * f / (n * (max_frequency - f))))
    return max(1, k)


@runtime_checkable
class CompensatorUnit(Protocol):
    """What an environmental compensator does in the chain (real unit or simulator).

    Its sensors give a new factor from time to time (``update_sensors``, returning the output
    counts it adds or removes to re-scale the position: the "pulse addition" of Renishaw, Laser scale axis referencing), and it
    turns laser count increments into output count increments (``feed``). The simulator
    :class:`SimulatedCompensatorUnit` implements it; :mod:`axiscal.procedures.referencing` calls the
    same arithmetic in vectorised form (:meth:`Compensator.factor_schedule` then
    :func:`multiply`), which gives identical counts.
    """

    def update_sensors(self, temperature: float, pressure: float, humidity: float,
                       material_temperature: float = REFERENCE_TEMPERATURE) -> int:
        """Read new sensor values (°C, Pa, %RH, °C); return the output counts added (+) or
        removed (−)."""
        ...

    def feed(self, increments) -> np.ndarray:
        """Laser count increments in, output count increments out."""
        ...


class SimulatedCompensatorUnit:
    """The :class:`CompensatorUnit` interface on a :class:`Compensator` and a
    :class:`PulseMultiplier` (a small stateful adapter).

    Examples
    --------
    >>> unit = SimulatedCompensatorUnit(Compensator(), 20.0, 101325.0, 50.0)
    >>> isinstance(unit, CompensatorUnit)
    True
    >>> int(unit.feed([1000]).sum())       # 1000 laser counts of 0.633 µm in 78.125 nm counts
    8100
    """

    def __init__(self, compensator: Compensator, temperature: float = REFERENCE_TEMPERATURE,
                 pressure: float = 101325.0, humidity: float = 50.0,
                 material_temperature: float = REFERENCE_TEMPERATURE) -> None:
        self.compensator = compensator
        self.multiplier = PulseMultiplier(
            compensator.factor(temperature, pressure, humidity, material_temperature),
            compensator.bits)

    def update_sensors(self, temperature: float, pressure: float, humidity: float,
                       material_temperature: float = REFERENCE_TEMPERATURE) -> int:
        return self.multiplier.set_factor(self.compensator.factor(
            temperature, pressure, humidity, material_temperature))

    def feed(self, increments) -> np.ndarray:
        return self.multiplier.feed(increments)
