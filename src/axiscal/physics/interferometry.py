"""Laser interferometry: fringes to displacement, dead path, cosine error, angular optics.

Linear optics count one fringe per half wavelength of reflector travel (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 22,
``d = λN/2``); plane-mirror optics pass the beam twice and count one fringe per quarter
wavelength. The angular interferometer of Renishaw, Interferometric calibration of rotary axes (Figure 1) measures the difference ΔL of the
two arms' path lengths to a pair of retro-reflectors a distance S apart and converts it to an
angle by ``θ = arcsin(ΔL / (K·S))``, where K is found by the optics self-calibration at 0°, +5° and
−5° against the reference calibrator (:func:`optics_self_calibration`).

Wavelength in air: this module does not compute the refractive index of air (that is
:mod:`axiscal.physics.air`). Functions take the vacuum wavelength and a refractive index ``n``
as parameters; the default ``n = 1.000271`` is that of standard air (20 °C, 101.325 kPa,
50 %RH, HeNe light) to the nearest 1e-6.

Notes
-----
Renishaw, Interferometric calibration of rotary axes (Figure 1 text) writes that each arm changes by ``S·sin θ``, a total of ``2S·sin θ``,
and then converts with ``arcsin(ΔL/S)``. The two statements agree only if ΔL is the *displacement*
difference of the two reflectors (fringe count × λ/2 already halves the double-pass optical
path) and S is their centre-to-centre spacing: rotating the pair by θ about its midpoint moves one
reflector by ``(S/2)·sin θ`` towards the laser and the other as far away, a difference of
``S·sin θ``. This module uses that consistent reading: ``ΔL = S·sin θ``.

References
----------
Renishaw, Interferometric calibration of rotary axes, "Interferometric angular measurement", "Incorrect retro-reflector
spacing", "Misaligned reflector at datum", "Air refractive index compensation errors",
"Non-parallel beams emerging from the periscope".
Yüksel et al., Position accuracy and repeatability calibration of turn tables, eq. 22.
Renishaw, Laser scale axis referencing: "0.633 microns ... the use of a reflector doubles the sensitivity,
so the effective scale pitch is 0.316 microns".
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Literal

import numpy as np

from axiscal.errors import InputError
from axiscal.units import ARCSEC

__all__ = [
    "HENE_VACUUM_WAVELENGTH",
    "STANDARD_AIR_INDEX",
    "wavelength_in_air",
    "fringes_per_metre",
    "effective_pitch",
    "fringes_to_displacement",
    "dead_path_correction",
    "cosine_error",
    "path_difference",
    "angle_from_path_difference",
    "spacing_error_angle",
    "refraction_angle_error",
    "nonparallel_beam_error",
    "OpticsCalibration",
    "optics_self_calibration",
]

#: Vacuum wavelength of a HeNe laser, metres (632.991 nm).
HENE_VACUUM_WAVELENGTH = 632.991e-9
#: Refractive index of standard air for HeNe light (20 °C, 101.325 kPa, 50 %RH), rounded.
STANDARD_AIR_INDEX = 1.000271

Optics = Literal["linear", "plane_mirror"]
_PASSES = {"linear": 2, "plane_mirror": 4}


def wavelength_in_air(vacuum_wavelength: float = HENE_VACUUM_WAVELENGTH,
                      n: float = STANDARD_AIR_INDEX) -> float:
    """Wavelength in air, metres: ``λ_air = λ_vac / n``.

    Parameters
    ----------
    vacuum_wavelength : float, metres
    n : float, dimensionless
        Refractive index of the air (from :mod:`axiscal.physics.air`; default standard air).

    Returns
    -------
    float, metres

    Notes
    -----
    Definition of the refractive index (NIST, Stone and Zimmerman, eq. 1); Renishaw, Laser scale axis referencing, "wavelength
    compensation".

    Examples
    --------
    >>> round(wavelength_in_air() * 1e9, 3)
    632.82
    """
    _check_positive("vacuum_wavelength", vacuum_wavelength)
    if not 1.0 <= n < 1.01:
        raise InputError(f"refractive index n={n!r} is not in [1, 1.01), the range of air")
    return vacuum_wavelength / n


def effective_pitch(wavelength: float, optics: Optics = "linear") -> float:
    """Displacement per fringe (the effective scale pitch), metres.

    ``λ/2`` for linear optics (a retro-reflector doubles the sensitivity), ``λ/4`` for plane-mirror
    optics.

    Parameters
    ----------
    wavelength : float, metres
    optics : {"linear", "plane_mirror"}

    Returns
    -------
    float, metres per fringe

    Notes
    -----
    Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 22 (d = λN/2) for linear optics; the plane mirror's double pass halves it again.
    Renishaw, Laser scale axis referencing: "0.633 microns ... the use of a reflector doubles the sensitivity, so the effective
    scale pitch is 0.316 microns" (0.3165 µm, written truncated in the paper).

    Examples
    --------
    >>> round(effective_pitch(0.633e-6) * 1e6, 4)
    0.3165
    """
    _check_positive("wavelength", wavelength)
    return wavelength / _passes(optics)


def fringes_per_metre(wavelength: float, optics: Optics = "linear") -> float:
    """Fringes counted per metre of reflector travel, 1/m.

    Parameters
    ----------
    wavelength : float, metres
    optics : {"linear", "plane_mirror"}

    Returns
    -------
    float, 1/m
        ``1 / effective_pitch(wavelength, optics)`` (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 22).
    """
    return 1.0 / effective_pitch(wavelength, optics)


def fringes_to_displacement(fringes, vacuum_wavelength: float = HENE_VACUUM_WAVELENGTH,
                            n: float = STANDARD_AIR_INDEX, optics: Optics = "linear"):
    """Displacement of the reflector from a (fractional) fringe count, metres.

    Parameters
    ----------
    fringes : array_like, fringes (may be fractional after interpolation)
    vacuum_wavelength : float, metres
    n : float
        Refractive index of the air along the beam.
    optics : {"linear", "plane_mirror"}

    Returns
    -------
    ndarray or float, metres
        ``N·λ_air/2`` (linear, Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 22) or ``N·λ_air/4`` (plane mirror).

    Examples
    --------
    >>> round(fringes_to_displacement(1000.0) * 1e6, 4)
    316.4098
    >>> round(fringes_to_displacement(1000.0, optics="plane_mirror") * 1e6, 4)
    158.2049
    """
    pitch = effective_pitch(wavelength_in_air(vacuum_wavelength, n), optics)
    f = np.asarray(fringes, dtype=float)
    out = f * pitch
    return float(out) if out.ndim == 0 else out


def dead_path_correction(measured, dead_path: float, n_datum: float, n_now):
    """Correct a displacement for the dead-path error, metres.

    The dead path is the distance between the interferometer and the reflector at the datum. Its
    air changes from ``n_datum`` to ``n_now`` without the reflector moving; the laser, compensated
    with ``n_now`` only, reads a spurious ``dead_path·(n_now − n_datum)/n_now``.

    Parameters
    ----------
    measured : array_like, metres
        Displacement read by the laser (compensated with ``n_now``).
    dead_path : float, metres
    n_datum, n_now : float or array_like
        Refractive index when the datum was set and at the reading.

    Returns
    -------
    ndarray or float, metres
        ``measured − dead_path·(n_now − n_datum)/n_now``.

    Notes
    -----
    Optical path change = ``n_now·(L_d + d) − n_datum·L_d``; dividing by ``n_now`` gives the
    reading ``d + L_d·(n_now − n_datum)/n_now``.

    Examples
    --------
    >>> # 0.5 m dead path, air 1 K warmer (n falls ~0.95 ppm): the reading is 0.475 µm short
    >>> round(dead_path_correction(0.1, 0.5, 1.000271, 1.000271 - 0.95e-6) * 1e6 - 1e5, 4)
    0.4749
    """
    if dead_path < 0:
        raise InputError(f"dead_path={dead_path!r} m must be >= 0")
    n_now = np.asarray(n_now, dtype=float)
    out = np.asarray(measured, dtype=float) - dead_path * (n_now - n_datum) / n_now
    return float(out) if out.ndim == 0 else out


def cosine_error(length, misalignment):
    """Cosine error of a length measured along a misaligned beam, metres (reading − true).

    Parameters
    ----------
    length : array_like, metres
        True travel along the axis.
    misalignment : array_like, radians
        Angle between the beam and the axis of motion.

    Returns
    -------
    ndarray or float, metres
        ``L·(cos φ − 1)``, always <= 0: the laser reads short.

    Notes
    -----
    The beam measures the projection ``L cos φ`` of the travel on its own direction: the
    cosine error of beam alignment (issue 3; not derived in the source documents, plain geometry).

    Examples
    --------
    >>> round(cosine_error(1.0, 1e-3) * 1e6, 3)   # 1 mrad over 1 m: 0.5 µm short
    -0.5
    """
    out = np.asarray(length, dtype=float) * (np.cos(np.asarray(misalignment, dtype=float)) - 1.0)
    return float(out) if out.ndim == 0 else out


def path_difference(angle, spacing: float):
    """Path (displacement) difference of the two arms of an angular interferometer, metres.

    ``ΔL = S·sin θ`` (see the module notes on Renishaw, Interferometric calibration of rotary axes's factor 2).

    Parameters
    ----------
    angle : array_like, radians
        Rotation of the reflector pair from perpendicular to the beams.
    spacing : float, metres
        True centre-to-centre spacing S of the retro-reflectors.

    Returns
    -------
    float or ndarray, metres

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes, "Interferometric angular measurement" (Figure 1), read as in the module Notes.
    """
    _check_positive("spacing", spacing)
    out = spacing * np.sin(np.asarray(angle, dtype=float))
    return float(out) if out.ndim == 0 else out


def angle_from_path_difference(delta_l, spacing: float, k: float = 1.0):
    """Angle read by an angular interferometer, radians: ``θ = arcsin(ΔL/(K·S))``.

    Parameters
    ----------
    delta_l : array_like, metres
        Path difference ΔL.
    spacing : float, metres
        Nominal spacing S used by the software.
    k : float
        Correction factor K from :func:`optics_self_calibration` (1 before calibration).

    Returns
    -------
    float or ndarray, radians

    Raises
    ------
    InputError
        If ``|ΔL/(K·S)| > 1`` anywhere (no angle has that path difference).

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes, "Incorrect retro-reflector spacing": ``θ = arcsin(ΔL/(K.S))``.

    Examples
    --------
    >>> round(math.degrees(angle_from_path_difference(path_difference(math.radians(1), 0.03), 0.03)), 9)
    1.0
    """
    _check_positive("spacing", spacing)
    _check_positive("k", k)
    ratio = np.asarray(delta_l, dtype=float) / (k * spacing)
    if np.any(np.abs(ratio) > 1.0):
        raise InputError(
            f"path difference {float(np.max(np.abs(delta_l))):.4g} m exceeds K*S = {k * spacing:.4g} m;"
            " |ΔL/(K·S)| must be <= 1"
        )
    out = np.arcsin(ratio)
    return float(out) if out.ndim == 0 else out


def spacing_error_angle(angle, true_spacing: float, nominal_spacing: float):
    """Angular error from converting with the nominal instead of the true spacing, radians.

    Parameters
    ----------
    angle : array_like, radians
        True rotation.
    true_spacing, nominal_spacing : float, metres

    Returns
    -------
    ndarray or float, radians
        ``arcsin(S_true·sin θ / S_nom) − θ``.

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes: 30.1 mm instead of 30.0 mm at 1° gives about ``0.1/30 × 1° = 12 arcsec``.

    Examples
    --------
    >>> round(spacing_error_angle(math.radians(1.0), 30.1e-3, 30.0e-3) / ARCSEC, 1)
    12.0
    """
    return angle_from_path_difference(path_difference(angle, true_spacing), nominal_spacing) - (
        np.asarray(angle, dtype=float) if np.ndim(angle) else float(angle))


def refraction_angle_error(misalignment, delta_n):
    """Change of an angular reading when the air's index changes, radians.

    When the reflector is turned by φ from perpendicular, one arm is ``S·sin φ`` longer than the
    other; an index change Δn changes that arm's optical length by ``Δn·S·sin φ``, read as an angle
    ``Δn·sin φ`` (independent of S).

    Parameters
    ----------
    misalignment : array_like, radians
        Angle φ of the reflector from perpendicular to the beams.
    delta_n : array_like
        Change of the refractive index since the last compensation (about −0.95e-6 per +1 K in
        standard air; take it from :mod:`axiscal.physics.air`).

    Returns
    -------
    float or ndarray, radians

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes, "Air refractive index compensation errors": "a 1 °C change in air temperature, when
    the interferometer and reflector are misaligned by 2.5°, will only introduce a change in
    reading of about 0.05 micro-radians (0.01 arcseconds)".

    Examples
    --------
    >>> round(abs(refraction_angle_error(math.radians(2.5), -0.95e-6)) * 1e6, 3)   # µrad
    0.041
    """
    out = np.asarray(delta_n, dtype=float) * np.sin(np.asarray(misalignment, dtype=float))
    return float(out) if out.ndim == 0 else out


def nonparallel_beam_error(lateral, nonparallelism: float, spacing: float):
    """Angular error from lateral motion of the reflector with non-parallel beams, radians.

    Two beams that diverge by ν convert a lateral shift ``t`` of the reflector (at 90° to the
    beams) into a path difference ``ν·t``, read as the angle ``ν·t/S``.

    Parameters
    ----------
    lateral : array_like, metres
    nonparallelism : float, radians
        Angle between the two beams (Renishaw, Interferometric calibration of rotary axes: within ±15 arcsec).
    spacing : float, metres

    Returns
    -------
    float or ndarray, radians

    Notes
    -----
    Renishaw, Interferometric calibration of rotary axes: ±15 arcsec non-parallelism gives "±0.5 arcseconds for every millimetre of lateral
    motion" (with the 30 mm spacing of Renishaw, Interferometric calibration of rotary axes's example).

    Examples
    --------
    >>> round(nonparallel_beam_error(1e-3, 15 * ARCSEC, 30e-3) / ARCSEC, 2)
    0.5
    """
    _check_positive("spacing", spacing)
    out = np.asarray(lateral, dtype=float) * nonparallelism / spacing
    return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class OpticsCalibration:
    """Result of the angular optics self-calibration.

    Attributes
    ----------
    k : float
        Correction factor K (true/nominal spacing, including the air's index): use it in
        ``θ = arcsin(ΔL/(K·S))``.
    datum_misalignment : float, radians
        Angle of the reflector from perpendicular to the beams when the datum was set; the
        calibrator turns by minus this value and the laser is re-datumed.
    step : float, radians
        The calibration step (5° in Renishaw, Interferometric calibration of rotary axes).
    zero_return : float, radians
        Reading on the return to 0° after the ±step moves, as an angle: drift of the laser or of
        the set-up during the calibration (the two unknowns are fitted exactly from the two
        readings, so this is the only redundancy).
    """

    k: float
    datum_misalignment: float
    step: float
    zero_return: float

    def __str__(self) -> str:
        return (f"optics self-calibration at 0, ±{math.degrees(self.step):.3f}°: K = {self.k:.6f}, "
                f"reflector at datum {self.datum_misalignment / ARCSEC:+.2f} arcsec, "
                f"return to zero {self.zero_return / ARCSEC:+.3f} arcsec")


def optics_self_calibration(delta_l_plus: float, delta_l_minus: float, spacing: float,
                            step: float = math.radians(5.0), step_minus: float | None = None,
                            delta_l_zero: float = 0.0, step_zero: float = 0.0) -> OpticsCalibration:
    """Find K and the reflector's datum misalignment from readings at 0, +step and −step.

    The reference calibrator turns the reflector from the datum by ``step`` and ``step_minus``
    (nominally ±5°; pass the angles its encoder *read*, not the commanded ones: a servo error in
    the steps would otherwise pass straight into the datum misalignment); the laser reports the
    path difference relative to the datum.

    Parameters
    ----------
    delta_l_plus, delta_l_minus : float, metres
        Path difference read at the two steps.
    spacing : float, metres
        Nominal spacing S.
    step : float, radians
        Reference angle of the first step (default +5°, Renishaw, Interferometric calibration of rotary axes).
    step_minus : float, radians, optional
        Reference angle of the second step (default ``-step``).
    delta_l_zero, step_zero : float, metres and radians
        Path difference and reference angle on the return to the datum; their disagreement is
        reported as ``zero_return`` (drift during the calibration).

    Returns
    -------
    OpticsCalibration

    Notes
    -----
    With the reflector turned by φ₀ at the datum and an effective spacing K·S, a step a gives
    ``ΔL = K·S·(sin(φ₀ + a) − sin φ₀) = X·(cos a − 1) + Y·sin a`` with ``X = K·S·sin φ₀`` and
    ``Y = K·S·cos φ₀``. Two steps give a 2×2 linear system for X and Y, hence
    ``φ₀ = atan2(X, Y)`` and ``K = √(X² + Y²)/S``. For symmetric steps ±a this is
    ``tan φ₀ = (ΔL₊+ΔL₋)·sin a / ((ΔL₊−ΔL₋)·(cos a − 1))``. Renishaw, Interferometric calibration of rotary axes, "Incorrect retro-reflector
    spacing" and "Misaligned reflector at datum". Note the sum of the two readings carries φ₀
    with a gain of only ``cos a − 1`` (−0.0038 at 5°): an error δ in a reference step moves φ₀ by
    about ``δ/(2·0.0038)``, 130 times δ.

    Examples
    --------
    >>> s_true, phi0, a = 30.1e-3, 2e-4, math.radians(5)
    >>> dl = lambda x: s_true * (math.sin(phi0 + x) - math.sin(phi0))
    >>> cal = optics_self_calibration(dl(a), dl(-a), 30.0e-3)
    >>> round(cal.k, 9), round(cal.datum_misalignment * 1e4, 9)
    (1.003333333, 2.0)
    """
    _check_positive("spacing", spacing)
    a_p = float(step)
    a_m = -a_p if step_minus is None else float(step_minus)
    for name, v in (("step", a_p), ("step_minus", a_m)):
        if not 0 < abs(v) < math.pi / 4:
            raise InputError(f"calibration {name} {math.degrees(v):g} deg must be within (0, 45) deg")
    if not a_p > 0 > a_m:
        raise InputError(f"calibration steps {math.degrees(a_p):g} and {math.degrees(a_m):g} deg "
                         "must lie either side of the datum (positive, then negative)")
    p, m = float(delta_l_plus), float(delta_l_minus)
    if not p > m:
        raise InputError(
            f"readings at +step ({p:.4g} m) and -step ({m:.4g} m) do not increase with the angle; "
            "check the laser's angular sign or the reflector"
        )
    mat = np.array([[math.cos(a_p) - 1.0, math.sin(a_p)], [math.cos(a_m) - 1.0, math.sin(a_m)]])
    x, y = np.linalg.solve(mat, np.array([p, m]))
    phi0 = math.atan2(x, y)
    ks = math.hypot(x, y)
    ratio = max(-1.0, min(1.0, delta_l_zero / ks + math.sin(phi0)))
    zero_return = math.asin(ratio) - phi0 - step_zero
    return OpticsCalibration(k=float(ks / spacing), datum_misalignment=float(phi0), step=a_p,
                             zero_return=float(zero_return))


def _passes(optics: str) -> int:
    try:
        return _PASSES[optics]
    except KeyError:
        raise InputError(f"optics {optics!r} is not 'linear' or 'plane_mirror'") from None


def _check_positive(name: str, value: float) -> None:
    # numbers.Real takes NumPy scalars too (np.int64, np.float32), not bool
    if not (isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))
            and math.isfinite(value) and value > 0):
        raise InputError(f"{name}={value!r} must be a positive finite number")
