"""Monte Carlo check of the ISO 230-2 Annex A budget (JCGM 101:2008, GUM Supplement 1).

Kept apart from :mod:`axiscal.standards.iso230_9` on purpose: it is written from the physics of
the measurement (the laser's scale error, the cosine error as the square of an angle, the
product of α and the temperature), not from the budget's contributors, so that agreement of the
two is an independent check.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.iso230_9 import (
    COVERAGE_FACTOR,
    DISTANCE_PARAMETERS,
    SCATTER_PARAMETERS,
    LinearInputs,
)

__all__ = ["MonteCarlo", "monte_carlo_linear"]


@dataclass(frozen=True)
class MonteCarlo:
    """Result of the Monte Carlo check (JCGM 101:2008), per parameter, deviation unit.

    Attributes
    ----------
    trials : int
    u : mapping of str to float
        Standard deviation of the simulated error of each parameter.
    expanded : mapping of str to float
        k·u, comparable with the budget's U.
    interval95 : mapping of str to float
        Half-width of the probabilistically symmetric 95 % coverage interval.
    """

    trials: int
    u: Mapping[str, float]
    expanded: Mapping[str, float]
    interval95: Mapping[str, float] = field(default_factory=dict)


def monte_carlo_linear(
    travel_mm: float,
    inputs: LinearInputs,
    rng: np.random.Generator,
    trials: int = 200_000,
    unit: str = "um",
    k: float = COVERAGE_FACTOR,
) -> MonteCarlo:
    """Propagate the input distributions through the measurement model by Monte Carlo.

    The model is written from the physics, not from the budget: the error of a distance over
    the travel L is

        δ = L·ε_laser − L·θ²/2 + L·[(α + δα)(ΔT + δT + δT_pos) − α·ΔT] + reading + drift

    with ε_laser ~ N(0, a/k_cal) (an encoder reference: L·ε ~ U(±a·L), no beam so no θ),
    θ ~ U(−d/L, d/L) (the cosine error is quadratic in the angle,
    not rectangular), δα ~ U(±a_α), δT ~ U(±a_T), δT_pos ~ U(±a_P), reading ~ U(±r/2), drift ~
    U(±E_VE/2) (E_VE not given: 0, as the budget leaves it out); ΔT = T − 20 °C enters with its
    sign, so the product term is kept whole (T not stated: the shop range's end farthest from
    20 °C, as the budget takes it). For R
    and B only the reading and the drift act.

    Parameters
    ----------
    travel_mm : float, mm
    inputs : LinearInputs
    rng : numpy.random.Generator
    trials : int
    unit : str
    k : float

    Returns
    -------
    MonteCarlo
    """
    i = inputs
    n = int(trials)
    if n < 1000:
        raise InputError(f"Monte Carlo trials = {trials!r}: use at least 1000 (GUM S1 §7.2)")
    L = travel_mm * 1e3
    a_alpha = i.alpha_halfwidth
    dT = (i.material_temperature - 20.0 if i.material_temperature is not None
          else i.temperature_deviation)   # not stated: the shop range's end farthest from 20 °C
    if i.reference == "encoder":   # a ± bound of the scale, no beam
        device = rng.uniform(-1.0, 1.0, n) * i.encoder_accuracy * 1e-6 * L
        cosine = np.zeros(n)
    else:
        device = rng.normal(0.0, i.laser_accuracy_ppm * 1e-6 / i.laser_accuracy_k, n) * L
        theta = rng.uniform(-1.0, 1.0, n) * (i.beam_offset * 1e3 / L)
        cosine = -L * theta**2 / 2
    alpha = i.expansion_coefficient + rng.uniform(-a_alpha, a_alpha, n)
    temp = (
        dT
        + rng.uniform(-i.temperature_halfwidth, i.temperature_halfwidth, n)
        + rng.uniform(-i.sensor_position_halfwidth, i.sensor_position_halfwidth, n)
    )
    thermal = L * (alpha * temp - i.expansion_coefficient * dT)
    reading = rng.uniform(-i.resolution / 2, i.resolution / 2, n)
    e_ve = 0.0 if i.e_ve is None else i.e_ve   # not given: left out, as the budget does
    drift = rng.uniform(-e_ve / 2, e_ve / 2, n)
    to_unit = {"um": 1.0, "mm": 1e-3, "nm": 1e3}[unit]
    dist = (device + cosine + thermal + reading + drift) * to_unit
    scat = (reading + drift) * to_unit
    u, half = {}, {}
    for names, sample in ((DISTANCE_PARAMETERS, dist), (SCATTER_PARAMETERS, scat)):
        sd = float(np.std(sample, ddof=1))
        lo, hi = np.quantile(sample, [0.025, 0.975])
        for p in names:
            u[p] = sd
            half[p] = float(hi - lo) / 2
    return MonteCarlo(n, u, {p: k * v for p, v in u.items()}, half)
