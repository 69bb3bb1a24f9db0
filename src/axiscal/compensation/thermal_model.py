"""A thermal model fitted to ISO 230-3 tests, and SINUMERIK's temperature compensation from it.

The model
---------
Each drift quantity c of a test (:func:`axiscal.standards.iso230_3.drift_series`: X, Y, Z, A, B
of the spindle test; P1, P2, G of the linear test; X, Y, Z of the ETVE test) is a linear function
of the measured temperatures, each seen through a first-order lag::

    d_c(t) = Σ_j k_c,j (L_τj[T_s(j)](t) − 20 °C)        L_τ:  τ dL/dt = T − L,  L(0) = T(0)

a sum of terms j, each a sensor s(j) seen through a lag τ_j (τ = 0: the temperature itself; a
sensor may give two terms). The lag
stands for the heat's way from the sensor to the structure that moves (a casting slower than
its bearings); a short one also gives a lead, T − L_τ[T] ≈ τ dT/dt, for a sensor that sees its
node late (a sensor on a housing outside the bearings). The same
first-order form as the twin's nodes (``machines/thermal.py``) and as the lumped models of
Mayr et al., "Thermal issues in machine tools", CIRP Annals 61/2 (2012) (its review of
compensation by models of measured temperatures). A test's drift is known only relative to its
start, so the fit is on differences from the first sample (no intercept): ``d_c(t) − d_c(0) =
Σ_j k_c,j (L_j(t) − L_j(0))``, ordinary least squares over every fit run's samples (each run
relative to its own start). The absolute form above takes the state
with every sensor at 20 °C as zero error (ISO 1): the twin's; a real machine's geometric
calibration holds at its own temperatures, which shift the reference.

Choice and validation: the sensors and their lags are chosen from :data:`LAG_CANDIDATES` by
forward selection (a sensor enters when it lowers the validation cost by more than 2 %), then
each lag refined, on the RMS error of a **validation run not used for the fit**; a third run used for neither (the
"test" run), when given, is the unseen run the model is judged on. Reported: the residual RMS on
each run, the largest error as a share of that run's drift range, and each coefficient's
standard uncertainty from the fit (σ²(XᵀX)⁻¹; the residuals are autocorrelated, so this
understates it: the validation RMS is the honest uncertainty of a prediction).

SINUMERIK
---------
SINUMERIK 840D sl Function Manual *Extended Functions*, K3 "Compensation", temperature
compensation: MD32750 ``$MA_TEMP_COMP_TYPE`` (bit 0 position-independent, bit 1
position-dependent: 3 for both); per axis the compensation value::

    ΔK_x = K0 + tanβ · (P_x − P0)

with SD43900 ``$SA_TEMP_COMP_ABS_VALUE`` = K0 (mm), SD43910 ``$SA_TEMP_COMP_SLOPE`` = tanβ
(dimensionless), SD43920 ``$SA_TEMP_COMP_REF_POSITION`` = P0 (mm), written cyclically by the PLC
or synchronized actions from the temperatures; MD32760 ``$MA_COMP_ADD_VELO_FACTOR`` limits how
fast the compensation may change. From a linear-axis model (P1, P2)::

    P0 = P1,   K0(T) = d_P1(T),   tanβ(T) = (d_P2(T) − d_P1(T)) / (P2 − P1)

each a linear function of the lagged temperatures with the coefficients reported (mm/K and 1/K).
Sign (axiscal's reading, and why): ΔK is written as the axis's thermal **error** (actual −
commanded, the laser's reading of the deviation), not as the correction. The K3 text defines ΔK
as the "approximated error line": its figure plots the error curve of the axis at temperature T
against the position, the deviation up, and calls tanβ "the gradient of the approximated error
line" (SINUMERIK 840D sl Function Manual *Extended Functions*, 03/2013, 6FC5397-1BP40-3BA1, K3
§4.2 "Temperature compensation", p. 225, "Error curve characteristic" and "Compensation
equation"); its worked example takes P0, K0 and tanβ(T) from the measured error curves (p. 230,
"Specifying parameters"); the SINUMERIK 840C manual's same function labels that axis "Error
(comp. value)" (Installation Instructions 09.95, §12.19.4 "Temperature compensation TC",
p. 12-188): the compensation value is the error, which the control then removes. The same sign
as SINUMERIK's EEC tables, for which K3 says it plainly ("a positive compensation value causes
the machine axis to move in the negative direction"; ``compensation/controllers/
siemens_840d.py``). The K3 pages read do not state the direction of the temperature
compensation's motion in words: check the sign on the machine with one small K0 before use.
Outside the function: the tilts A and B and every drift across the axis (Y or Z drift while X
moves); SINUMERIK's temperature compensation corrects an axis along itself only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError, one_line
from axiscal.standards.iso230_3 import drift_series
from axiscal.standards.iso230_3_data import ThermalLog

__all__ = ["ThermalModel", "RunScore", "SinumerikTemperatureCompensation", "fit_thermal_model",
           "CompensationCheck", "verify_on_twin",
           "lagged", "sinumerik_compensation", "LAG_CANDIDATES", "REFERENCE_C"]

#: Candidate lags, s (1 min to 160 min, about doubling: short ones let T − L stand for the rate
#: of change, a lead over a sensor that lags its node; long ones for castings).
MAX_TERMS = 8
LAG_CANDIDATES = (0.0, 60.0, 120.0, 300.0, 600.0, 1200.0, 2400.0, 4800.0, 9600.0)
REFERENCE_C = 20.0


def lagged(temperature, time, tau: float) -> np.ndarray:
    """A temperature seen through a first-order lag τ (s), °C: τ dL/dt = T − L, L(0) = T(0),
    integrated exactly with T held over each interval at its value at the interval's end (what a
    PLC filtering each new reading computes).

    Examples
    --------
    >>> t = np.arange(0, 3601, 60.0)
    >>> round(float(lagged(np.where(t > 0, 21.0, 20.0), t, 600.0)[10]), 4)   # 1 - e^-1 after τ
    20.6321
    """
    T = np.asarray(temperature, dtype=float)
    if tau <= 0:
        return T.copy()
    decay = np.exp(-np.diff(np.asarray(time, dtype=float)) / tau)
    out = np.empty_like(T)
    x = out[0] = T[0]
    for k in range(T.size - 1):
        x = T[k + 1] + (x - T[k + 1]) * decay[k]
        out[k + 1] = x
    return out


@dataclass(frozen=True)
class RunScore:
    """How the model does on one run.

    Attributes
    ----------
    role : {"fit", "validation", "test"}
    source : str
    rms : dict of str to float, m or rad
    max_error : dict of str to float
    drift_range : dict of str to float
        Range of the measured drift on that run.
    """

    role: str
    source: str
    rms: dict[str, float]
    max_error: dict[str, float]
    drift_range: dict[str, float]

    def share(self, channel: str) -> float:
        """Largest error as a share of the run's drift range."""
        r = self.drift_range[channel]
        return float("inf") if r == 0 else self.max_error[channel] / r


@dataclass(frozen=True)
class ThermalModel:
    """A fitted thermal model (module docstring).

    Attributes
    ----------
    test : str
    sensors : tuple of str
        The sensor of each term (a sensor may appear twice).
    lags : tuple of float, s
        The lag of each term.
    channels : tuple of str
    coefficients : dict of str to tuple of float
        Per channel, k_j in m/K (rad/K for A and B), one per term.
    coefficient_u : dict of str to tuple of float
        Their standard uncertainties from the fit (an understatement, module docstring).
    scores : tuple of RunScore
    targets : tuple of float or None, m
        The linear test's P1 and P2.
    axis : str
    """

    test: str
    sensors: tuple[str, ...]
    lags: tuple[float, ...]
    channels: tuple[str, ...]
    coefficients: dict[str, tuple[float, ...]]
    coefficient_u: dict[str, tuple[float, ...]]
    scores: tuple[RunScore, ...]
    targets: tuple[float, float] | None = None
    axis: str = ""

    def features(self, log: ThermalLog) -> np.ndarray:
        """The lagged temperatures of ``log`` minus 20 °C, shape (n, sensors)."""
        missing = [s for s in self.sensors if s not in log.temperatures]
        if missing:
            raise InputError(f"{log.source}: no temperature {one_line(repr(missing[0]), 60)}; the model uses "
                             f"{', '.join(self.sensors)}")
        return _features(log, self.sensors, self.lags)

    def predict(self, log: ThermalLog, relative: bool = True) -> dict[str, np.ndarray]:
        """Each channel's predicted drift over ``log`` (relative to its start by default)."""
        f = self.features(log)
        if relative:
            f = f - f[0]
        return {c: f @ np.asarray(self.coefficients[c]) for c in self.channels}

    def score(self, log: ThermalLog, role: str) -> RunScore:
        """RMS and largest error of the model on ``log``."""
        return _score(self, log, role)

    def to_dict(self) -> dict:
        """The documented JSON object of ``axiscal thermal model --json`` (µm/K, µrad/K, min)."""
        def unit(c):
            return "µrad" if c in ("A", "B") else "µm"
        return {
            "test": self.test, "axis": self.axis,
            "targets_mm": None if self.targets is None else [p * 1e3 for p in self.targets],
            "sensors": list(self.sensors), "lags_min": [tau / 60 for tau in self.lags],
            "reference_C": REFERENCE_C,
            "coefficients": {c: {"unit": f"{unit(c)}/K",
                                 "values": [round(k * 1e6, 9) for k in self.coefficients[c]],
                                 "u": [round(k * 1e6, 9) for k in self.coefficient_u[c]]}
                             for c in self.channels},
            "scores": [{"role": s.role, "source": s.source,
                        "rms": {c: round(v * 1e6, 6) for c, v in s.rms.items()},
                        "max_error": {c: round(v * 1e6, 6) for c, v in s.max_error.items()},
                        "drift_range": {c: round(v * 1e6, 6) for c, v in s.drift_range.items()},
                        "max_error_share_of_range": {c: round(s.share(c), 6) for c in s.rms}}
                       for s in self.scores],
        }

    def __str__(self) -> str:
        lines = [f"thermal model of the {self.test} test; lags: "
                 + ", ".join(f"{s} {tau / 60:g} min" for s, tau in zip(self.sensors, self.lags))]
        for s in self.scores:
            lines.append(f"  {s.role} run ({s.source}): " + "; ".join(
                f"{c} rms {s.rms[c] * 1e6:.3g}, max {s.max_error[c] * 1e6:.3g} of range "
                f"{s.drift_range[c] * 1e6:.3g} ({100 * s.share(c):.0f} %)" for c in self.channels))
        return "\n".join(lines)


def fit_thermal_model(fit, validation: ThermalLog, test: ThermalLog | None = None,
                      *, sensors: tuple[str, ...] | None = None,
                      channels: tuple[str, ...] | None = None,
                      candidates: tuple[float, ...] = LAG_CANDIDATES) -> ThermalModel:
    """Fit the model on ``fit``, choose its lags on ``validation``, judge it on ``test``.

    Parameters
    ----------
    fit : ThermalLog or sequence of ThermalLog
        The run(s) fitted (different loads and times of day make a model that generalises: the
        room's share is learnt only from runs over which the room changed).
    validation : ThermalLog
        A run of the same test, not fitted, on which the terms are chosen.
    test : ThermalLog, optional
        A third run, used for neither fit nor choice.
    sensors : tuple of str, optional
        Temperatures to use (default: those in every run).
    channels : tuple of str, optional
        Drift quantities to model (default: all of the test's).
    candidates : tuple of float, s

    Returns
    -------
    ThermalModel
    """
    fits = [fit] if isinstance(fit, ThermalLog) else list(fit)
    if not fits:
        raise InputError("no run to fit")
    runs = fits + [validation] + ([test] if test is not None else [])
    if len({r.test for r in runs}) != 1:
        raise InputError("the runs of a thermal model must be of one test; got "
                         + ", ".join(r.test for r in runs))
    common = set.intersection(*(set(r.temperatures) for r in runs))
    fit = fits[0]
    sensors = tuple(sensors) if sensors else tuple(s for s in fit.temperatures if s in common)
    if not sensors or not set(sensors) <= common:
        raise InputError(f"sensors {one_line(', '.join(sensors), 80) or 'none'}: each must be in "
                         f"every run (common: {one_line(', '.join(sorted(common)), 200) or 'none'})")
    known = tuple(drift_series(fit))
    channels = tuple(channels) if channels else known
    if not set(channels) <= set(known):
        raise InputError(f"channels {one_line(', '.join(channels), 80)}: the {fit.test} test "
                         f"has {', '.join(known)}")
    if fit.test == "linear" and any(r.targets != fit.targets for r in runs):
        raise InputError("the linear runs must share their targets P1 and P2")
    best = _select(fits, validation, sensors, channels, candidates)
    scores = tuple(best.score(f, "fit") for f in fits) + (best.score(validation, "validation"),)
    if test is not None:
        scores += (best.score(test, "test"),)
    return ThermalModel(best.test, best.sensors, best.lags, best.channels, best.coefficients,
                        best.coefficient_u, scores, fit.targets, fit.axis)


@dataclass(frozen=True)
class SinumerikTemperatureCompensation:
    """SINUMERIK's temperature compensation of one axis from a linear-axis model (module
    docstring).

    Attributes
    ----------
    axis : str
    p0 : float, m
        SD43920 TEMP_COMP_REF_POSITION.
    sensors : tuple of str
    lags : tuple of float, s
        The PLC feeds each temperature through this first-order lag.
    k0 : tuple of float, m/K
        K0 = Σ k0_i (L_i − 20 °C): SD43900 TEMP_COMP_ABS_VALUE.
    slope : tuple of float, 1/K
        tanβ = Σ slope_i (L_i − 20 °C): SD43910 TEMP_COMP_SLOPE.
    """

    axis: str
    p0: float
    sensors: tuple[str, ...]
    lags: tuple[float, ...]
    k0: tuple[float, ...]
    slope: tuple[float, ...]

    def values(self, lagged_temperatures) -> tuple[float, float]:
        """(K0 in m, tanβ) for lagged temperatures (°C), one per sensor."""
        x = np.asarray(lagged_temperatures, dtype=float) - REFERENCE_C
        return float(x @ np.asarray(self.k0)), float(x @ np.asarray(self.slope))

    def error(self, position, lagged_temperatures) -> float:
        """ΔK at ``position`` (m): K0 + tanβ (P − P0), m."""
        k0, tb = self.values(lagged_temperatures)
        return k0 + tb * (np.asarray(position, dtype=float) - self.p0)

    def to_dict(self) -> dict:
        """The documented JSON object of ``axiscal thermal compensate --json``."""
        return {
            "controller": "SINUMERIK 840D sl (K3 temperature compensation)",
            "axis": self.axis,
            "MD32750 $MA_TEMP_COMP_TYPE": 3,
            "SD43920 $SA_TEMP_COMP_REF_POSITION": {"value": round(self.p0 * 1e3, 6), "unit": "mm"},
            "SD43900 $SA_TEMP_COMP_ABS_VALUE": {
                "formula": "K0 = sum_i k0_i * (L_i - 20 °C)", "unit": "mm",
                "k0_mm_per_K": [round(k * 1e3, 12) for k in self.k0]},
            "SD43910 $SA_TEMP_COMP_SLOPE": {
                "formula": "tanβ = sum_i s_i * (L_i - 20 °C)", "unit": "1 (mm/mm)",
                "s_per_K": [float(f"{k:.6g}") for k in self.slope]},
            "sensors": list(self.sensors),
            "lags_min": [tau / 60 for tau in self.lags],
            "lag": "L_i: the temperature through a first-order lag, tau dL/dt = T - L",
            "sign": "the value is the error (actual - commanded): K3's 'approximated error "
                    "line' (840D sl Extended Functions 03/2013, K3 4.2, p. 225), the sign of "
                    "axiscal's EEC tables; check it on the machine with one small K0",
            "outside": "tilts and drifts across the axis are outside this function",
        }

    def to_text(self, machine_axis: str = "AX1") -> str:
        """The machine and setting data as a SINUMERIK assignment file (``;`` comments): MD32750
        and SD43920 fixed, SD43900 and SD43910 at their value with every sensor at 20 °C (0),
        and, as comments, K0(T) and tanβ(T) for the PLC (or synchronized actions) to write
        cyclically (K3 §4.2; module docstring for the sign).

        Examples
        --------
        >>> c = SinumerikTemperatureCompensation("X", 0.04, ("T",), (600.0,), (-1e-6,), (1e-5,))
        >>> print(c.to_text().splitlines()[-4])
        $MA_TEMP_COMP_TYPE[AX1]=3
        """
        ax = one_line(machine_axis, 20)
        lines = [f"; axiscal: SINUMERIK temperature compensation of axis {self.axis} (K3 4.2, "
                 "840D sl Function Manual Extended Functions)",
                 "; from a thermal model fitted to ISO 230-3:2020 Clause 7 runs",
                 "; dK = K0 + tan(beta) * (Px - P0); dK is the error line (actual - commanded)",
                 "; the PLC writes cyclically, from each temperature seen through its lag",
                 ";   L_i(t): tau_i dL_i/dt = T_i - L_i",
                 ";   SD43900 $SA_TEMP_COMP_ABS_VALUE = sum k0_i (L_i - 20 C)  [mm]",
                 ";   SD43910 $SA_TEMP_COMP_SLOPE     = sum s_i  (L_i - 20 C)  [1]"]
        for sensor, tau, k, b in zip(self.sensors, self.lags, self.k0, self.slope):
            lines.append(f";   {one_line(sensor, 40)}: tau {tau:g} s, k0 {k * 1e3:.9g} mm/K, "
                         f"s {b:.9g} 1/K")
        lines += ["; MD32760 $MA_COMP_ADD_VELO_FACTOR limits how fast dK may change",
                  "; tilts and drifts across the axis are outside this function",
                  f"$MA_TEMP_COMP_TYPE[{ax}]=3",
                  f"$SA_TEMP_COMP_REF_POSITION[{ax}]={self.p0 * 1e3:.6f}",
                  f"$SA_TEMP_COMP_ABS_VALUE[{ax}]=0",
                  f"$SA_TEMP_COMP_SLOPE[{ax}]=0"]
        return "\n".join(lines) + "\n"

    def __str__(self) -> str:
        rows = [f"SINUMERIK temperature compensation, axis {self.axis}: MD32750 = 3, "
                f"SD43920 P0 = {self.p0 * 1e3:.3f} mm"]
        for s, tau, k, b in zip(self.sensors, self.lags, self.k0, self.slope):
            rows.append(f"  {s} (lag {tau / 60:g} min): K0 {k * 1e3 * 1e3:+.4g} µm/K, "
                        f"tanβ {b * 1e6:+.4g} µm/m/K")
        rows.append("  tilts and drifts across the axis are outside this function")
        return "\n".join(rows)


def sinumerik_compensation(model: ThermalModel) -> SinumerikTemperatureCompensation:
    """SINUMERIK's K0(T), tanβ(T) and P0 from a linear-axis model (module docstring)."""
    if model.test != "linear" or not {"P1", "P2"} <= set(model.channels):
        raise InputError("SINUMERIK's temperature compensation is made from a linear-axis "
                         "model with P1 and P2 (thermal model of the linear test)")
    p1, p2 = model.targets
    c1, c2 = np.asarray(model.coefficients["P1"]), np.asarray(model.coefficients["P2"])
    return SinumerikTemperatureCompensation(model.axis, p1, model.sensors, model.lags,
                                            tuple(c1.tolist()), tuple(((c2 - c1) / (p2 - p1)).tolist()))


def _select(fit, validation, sensors, channels, candidates) -> ThermalModel:
    """Forward selection of terms (sensor, lag) by the validation cost, then the lags refined.

    A term enters when it lowers the validation cost by more than 2 %; a sensor may enter twice
    with different lags (a lead and a slow casting). Nearly collinear sensors (a housing and the
    casting it sits on) would otherwise trade wild coefficients that fit one run and fail the
    next. At most :data:`MAX_TERMS` terms."""
    terms: list[tuple[str, float]] = []
    best, best_cost = None, np.inf
    while len(terms) < MAX_TERMS:
        scored = []
        for s in sensors:
            for tau in candidates:
                if (s, tau) in terms:
                    continue
                trial = terms + [(s, tau)]
                m = _trial(fit, trial, channels)
                scored.append((_cost(m, validation), trial, m))
        if not scored:
            break
        cost, trial, m = min(scored, key=lambda x: x[0])
        if not cost < best_cost * 0.98:
            break
        terms, best, best_cost = trial, m, cost
    for _ in range(2):   # refine each term's lag with the others fixed
        for i in range(len(terms)):
            for tau in candidates:
                trial = terms.copy()
                trial[i] = (terms[i][0], tau)
                if len(set(trial)) < len(trial):
                    continue
                m = _trial(fit, trial, channels)
                c = _cost(m, validation)
                if c < best_cost * (1 - 1e-9):
                    terms, best, best_cost = trial, m, c
    if best is None:
        raise InputError("no temperature term improves the prediction of the validation run; "
                         "the drift does not follow the logged temperatures")
    return best


def _trial(fits, terms, channels) -> ThermalModel:
    sensors, lags = tuple(t[0] for t in terms), tuple(t[1] for t in terms)
    x = np.vstack([(f := _features(r, sensors, lags)) - f[0] for r in fits])
    series = [drift_series(r) for r in fits]
    fit = fits[0]
    coef, cu = {}, {}
    n, p = x.shape
    if n <= p:
        raise InputError(f"{fit.source}: {n} samples for {p} temperatures; too few to fit")
    for c in channels:
        y = np.concatenate([d[c] - d[c][0] for d in series])
        k, *_ = np.linalg.lstsq(x, y, rcond=None)
        r = y - x @ k
        s2 = float(r @ r) / (n - p)
        cov = s2 * np.linalg.pinv(x.T @ x)
        coef[c] = tuple(float(v) for v in k)
        cu[c] = tuple(float(np.sqrt(max(v, 0.0))) for v in np.diag(cov))
    return ThermalModel(fit.test, tuple(sensors), tuple(lags), tuple(channels), coef, cu, (),
                        fit.targets, fit.axis)


def _features(log, sensors, lags):
    """One column per term: the sensor's temperature through its lag (τ = 0: itself)."""
    return np.column_stack([lagged(log.temperatures[s], log.time, tau) - REFERENCE_C
                            for s, tau in zip(sensors, lags)])


def _cost(model: ThermalModel, log: ThermalLog) -> float:
    """Sum over channels of the validation RMS over the channel's drift range."""
    s = _score(model, log, "validation")
    return sum(s.rms[c] / max(s.drift_range[c], 1e-12) for c in model.channels)


def _score(model: ThermalModel, log: ThermalLog, role: str) -> RunScore:
    pred = model.predict(log)
    series = drift_series(log)
    rms, mx, rng = {}, {}, {}
    for c in model.channels:
        y = series[c] - series[c][0]
        e = y - pred[c]
        rms[c] = float(np.sqrt(np.mean(e ** 2)))
        mx[c] = float(np.max(np.abs(e)))
        rng[c] = float(np.ptp(y))
    return RunScore(role, log.source, rms, mx, rng)


@dataclass(frozen=True)
class CompensationCheck:
    """A linear-axis test on the twin run twice with one thermal history (one seed): without
    and with the temperature compensation applied.

    Attributes
    ----------
    before, after : dict of str to float, m
        The largest drift while running at P1 and P2 (ISO 230-3:2020 Clause 7), signed.
    reduction : dict of str to float
        1 − |after| / |before| per target.
    """

    before: dict[str, float]
    after: dict[str, float]
    reduction: dict[str, float]

    def to_dict(self) -> dict:
        return {"before_um": {k: round(v * 1e6, 6) for k, v in self.before.items()},
                "after_um": {k: round(v * 1e6, 6) for k, v in self.after.items()},
                "reduction": {k: round(v, 6) for k, v in self.reduction.items()}}

    def __str__(self) -> str:
        return "verified on the twin: " + "; ".join(
            f"largest drift at {k} {self.before[k] * 1e6:.3g} µm → {self.after[k] * 1e6:.3g} µm "
            f"({100 * self.reduction[k]:.0f} % less)" for k in self.before)


def verify_on_twin(twin, plan, comp: SinumerikTemperatureCompensation,
                   seed: int) -> CompensationCheck:
    """Run ``plan`` (a linear test) on ``twin`` and apply ``comp`` as the controller would: from
    the logged (noisy) temperatures through the terms' lags, causally, ΔK(P, t) subtracted from
    the positioning error at each target (ΔK is the error, module docstring). Both runs share
    the seed, so the thermal history and the noise are the same. The controller's rate limit
    (MD32760) and its cycle are not modelled: the value acts at each sample."""
    from dataclasses import replace

    from axiscal.procedures.thermal import simulate_thermal
    from axiscal.standards.iso230_3 import evaluate_linear

    if plan.test != "linear" or plan.axis.upper() != comp.axis.upper():
        raise InputError(f"verification runs a linear test of axis {comp.axis}")
    log = simulate_thermal(twin, plan, np.random.default_rng(seed)).log
    temps = np.column_stack([lagged(log.temperatures[s], log.time, tau)
                             for s, tau in zip(comp.sensors, comp.lags)])
    k0 = (temps - REFERENCE_C) @ np.asarray(comp.k0)
    slope = (temps - REFERENCE_C) @ np.asarray(comp.slope)
    d = dict(log.displacements)
    for name, p in zip(("P1", "P2"), log.targets):
        d[name] = d[name] - (k0 + slope * (p - comp.p0))
    before, after = evaluate_linear(log), evaluate_linear(replace(log, displacements=d))
    b = {k: before[f"delta_{k}_max_run"].value for k in ("P1", "P2")}
    a = {k: after[f"delta_{k}_max_run"].value for k in ("P1", "P2")}
    return CompensationCheck(b, a, {k: 1 - abs(a[k]) / abs(b[k]) if b[k] else 0.0 for k in b})
