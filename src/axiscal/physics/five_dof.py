"""Equations of the five-DOF rotary-axis measuring system of Optics Express 2018, Five-DOF motion errors of a rotary axis (eqs. 1-9).

The sensitive unit (two corner-cube retro-reflectors RR1 and RR2, a beam-splitting film BS1 on half
of RR1's base) sits on a reference rotary axis that counter-rotates on the target axis. Two
parallel beams (separation ``h``) run along X over the working distance ``l``:

* PSD1 behind L1 (focal length ``f1``) is an autocollimator on BS1: angles εz, εy (eqs. 1-3);
* QD1 and QD2 see the retro-reflected beams: radial δy and axial δz (eqs. 4-5), tilt εx (eq. 6);
* PSD2 behind L2 (``f2``) sees the return of RR2 and so the beam's angular drift (eq. 7), which
  corrects the others (eqs. 8-9).

All functions are pure and work element-wise on arrays: metres and radians in and out.

Sign choice for the ± of eqs. 8-9 (the paper leaves it open)
------------------------------------------------------------
The geometry of :mod:`axiscal.instruments.five_dof` fixes the detector senses so that eqs. 1, 2, 4,
5 and 7 hold exactly as printed, with Δβ, Δγ the Y and Z components of the outgoing beam's unit
direction (its angle towards +Y and +Z). A ray traced through that geometry gives

* ``ΔY_PSD1 = 2 f1 εz − f1 Δβ`` and ``ΔZ_PSD1 = 2 f1 εy + f1 Δγ``: a plane mirror returns a
  beam tilted by Δβ at −Δβ about the reversed axis, so the drift looks like a mirror tilt of
  **Δβ/2**, not Δβ. Hence ``εz = ΔY_PSD1/(2 f1) + Δβ/2`` and ``εy = ΔZ_PSD1/(2 f1) − Δγ/2``.
  Seed eq. 8 prints ``± Δβ``; with Δβ defined by eq. 7 that over-corrects by Δβ/2 (the truth test
  of the instrument shows it), so the factor 1/2 is used here.
* ``ΔY_QD = 2 δy − 2 l Δβ``: the angular drift (pivot at the measurement unit, where the QDs
  are) displaces the incoming beam by ``l Δβ`` at the reflector, and the corner cube returns it
  displaced by as much again. Hence ``δy = ΔY_QD/2 + l Δβ`` and ``δz = ΔZ_QD/2 + l Δγ``: the
  ``+`` sign of eq. 9, with the paper's magnitude.

References
----------
Optics Express 2018, Five-DOF motion errors of a rotary axis, "Method for simultaneous measurement of five DOF motion errors of a
rotary axis using a single-mode fiber-coupled laser", section 2, eqs. 1-9, and section 3
("Measurement resolution").

Examples
--------
>>> from axiscal.units import ARCSEC
>>> round(angular_resolution(0.5e-6, 0.200) / ARCSEC, 3)
0.258
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.units import ARCSEC, UM

__all__ = [
    "DRIFT_ANGLE_FACTOR",
    "autocollimation_angle",
    "positioning_error",
    "retroreflector_displacement",
    "tilt_from_quadrants",
    "beam_drift",
    "compensate_angle",
    "compensate_displacement",
    "angular_resolution",
    "tilt_x_resolution",
    "displacement_resolution",
    "Resolutions",
    "resolutions",
]

#: Coefficient of the drift angle in the corrected autocollimation angle (see module Notes).
DRIFT_ANGLE_FACTOR = 0.5


def autocollimation_angle(spot_shift, f):
    """Mirror angle from a spot shift on a PSD behind a lens: ``Δ/(2f)`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 1, 2).

    Parameters
    ----------
    spot_shift : array_like, metres
        Change in position of the spot (ΔY_PSD1 for εz, ΔZ_PSD1 for εy).
    f : float, metres
        Focal length of the lens L1.

    Returns
    -------
    ndarray, radians

    Examples
    --------
    >>> float(autocollimation_angle(2e-6, 0.2))
    5e-06
    """
    _positive("f", f)
    return np.asarray(spot_shift, dtype=float) / (2.0 * f)


def positioning_error(spot_shift_y, f, theta_ref, theta):
    """Angular positioning error over the full circle: ``ΔY/(2f1) + θref − θ`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eq. 3).

    Parameters
    ----------
    spot_shift_y : array_like, metres
        ΔY_PSD1 (drift-corrected, if wanted, through :func:`compensate_angle` afterwards).
    f : float, metres
        Focal length f1.
    theta_ref : array_like, radians
        Angle the reference rotary axis turned back (read by its encoder), positive in the
        sense opposite to the target axis.
    theta : array_like, radians
        Nominal (commanded) angle of the target axis.

    Returns
    -------
    ndarray, radians

    Examples
    --------
    >>> float(positioning_error(0.0, 0.2, 1.0 + 1e-5, 1.0))  # doctest: +ELLIPSIS
    1.0000000000...e-05
    """
    return autocollimation_angle(spot_shift_y, f) + np.asarray(theta_ref, float) - np.asarray(theta, float)


def retroreflector_displacement(spot_shift):
    """Lateral displacement of a corner cube from the return spot shift: ``Δ/2`` (eqs. 4, 5).

    Parameters
    ----------
    spot_shift : array_like, metres

    Returns
    -------
    ndarray, metres
    """
    return 0.5 * np.asarray(spot_shift, dtype=float)


def tilt_from_quadrants(dz_qd1, dz_qd2, h):
    """Tilt motion about X: ``εx = (ΔZ_QD1 − ΔZ_QD2) / (2h)`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eq. 6).

    Parameters
    ----------
    dz_qd1, dz_qd2 : array_like, metres
        Z spot shifts on QD1 and QD2.
    h : float, metres
        Separation of the centres of the reflectors RR1 and RR2 (along Y).

    Returns
    -------
    ndarray, radians

    Examples
    --------
    >>> float(tilt_from_quadrants(0.3e-6, -0.3e-6, 0.03))
    1e-05
    """
    _positive("h", h)
    return (np.asarray(dz_qd1, float) - np.asarray(dz_qd2, float)) / (2.0 * h)


def beam_drift(spot_shift, f):
    """Angular drift of the beam from PSD2: ``Δβ = ΔY_PSD2/f2``, ``Δγ = ΔZ_PSD2/f2`` (eq. 7).

    Parameters
    ----------
    spot_shift : array_like, metres
    f : float, metres
        Focal length f2 of L2.

    Returns
    -------
    ndarray, radians
    """
    _positive("f", f)
    return np.asarray(spot_shift, dtype=float) / f


def compensate_angle(angle, drift, sign):
    """Drift-corrected autocollimation angle: ``angle + sign · Δ/2`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eq. 8, see Notes).

    Parameters
    ----------
    angle : array_like, radians
        εz or εy from eqs. 1-3.
    drift : array_like, radians
        Δβ (for εz) or Δγ (for εy) from eq. 7.
    sign : {+1, -1}
        +1 for εz with Δβ, −1 for εy with Δγ in the geometry of
        :mod:`axiscal.instruments.five_dof`.

    Returns
    -------
    ndarray, radians

    Notes
    -----
    The coefficient is :data:`DRIFT_ANGLE_FACTOR` = 1/2, not the 1 printed in eq. 8: the module
    docstring derives it.
    """
    _sign(sign)
    return np.asarray(angle, float) + sign * DRIFT_ANGLE_FACTOR * np.asarray(drift, float)


def compensate_displacement(displacement, drift, l):
    """Drift-corrected displacement: ``δ + l·Δ`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eq. 9 with the ``+`` sign).

    Parameters
    ----------
    displacement : array_like, metres
        δy or δz from eqs. 4-5.
    drift : array_like, radians
        Δβ (for δy) or Δγ (for δz).
    l : float, metres
        Working distance from the measurement unit (drift pivot and QD plane) to the reflectors.

    Returns
    -------
    ndarray, metres

    Notes
    -----
    Optics Express 2018, Five-DOF motion errors of a rotary axis eq. 9 with the ``+`` sign derived in the module docstring.
    """
    if not l >= 0:
        raise InputError(f"working distance l = {l!r} m must be >= 0")
    return np.asarray(displacement, float) + l * np.asarray(drift, float)


def angular_resolution(psd_resolution, f):
    """Resolution of εz and εy: ``r_PSD / (2 f)`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 1-2, section 3).

    Parameters
    ----------
    psd_resolution : float, metres
    f : float, metres

    Returns
    -------
    float, radians
    """
    return float(autocollimation_angle(psd_resolution, f))


def tilt_x_resolution(qd_resolution, h):
    """Resolution of εx: ``r_QD / (2 h)`` (eq. 6 with one QD changing by its resolution).

    Parameters
    ----------
    qd_resolution : float, metres
    h : float, metres

    Returns
    -------
    float, radians
    """
    return float(tilt_from_quadrants(qd_resolution, 0.0, h))


def displacement_resolution(qd_resolution):
    """Resolution of δy and δz: ``r_QD / 2`` (Optics Express 2018, Five-DOF motion errors of a rotary axis eqs. 4-5).

    Parameters
    ----------
    qd_resolution : float, metres

    Returns
    -------
    float, metres
    """
    return float(retroreflector_displacement(qd_resolution))


@dataclass(frozen=True)
class Resolutions:
    """Resolutions of the five measured errors, from the parts (SI units).

    Attributes
    ----------
    angular : float, radians
        εz and εy (PSD1 behind L1).
    tilt_x : float, radians
        εx (QD1 and QD2 at separation h).
    displacement : float, metres
        δy and δz (QD1, QD2).
    """

    angular: float
    tilt_x: float
    displacement: float

    def __str__(self) -> str:
        return (f"resolution: εz, εy {self.angular / ARCSEC:.3f} arcsec; εx {self.tilt_x / ARCSEC:.3f} "
                f"arcsec; δy, δz {self.displacement / UM:.3f} µm")


def resolutions(f1, h, psd_resolution, qd_resolution) -> Resolutions:
    """The three resolutions of Optics Express 2018, Five-DOF motion errors of a rotary axis section 3 from the focal length, h and detectors.

    Parameters
    ----------
    f1 : float, metres
    h : float, metres
    psd_resolution, qd_resolution : float, metres

    Returns
    -------
    Resolutions
        Radians and metres (Optics Express 2018, Five-DOF motion errors of a rotary axis section 3: 0.26 arcsec, 0.27 arcsec, 0.04 µm).

    Examples
    --------
    >>> print(resolutions(0.2, 0.03, 0.5e-6, 0.08e-6))
    resolution: εz, εy 0.258 arcsec; εx 0.275 arcsec; δy, δz 0.040 µm
    """
    for name, v in (("psd_resolution", psd_resolution), ("qd_resolution", qd_resolution)):
        _positive(name, v)
    return Resolutions(angular_resolution(psd_resolution, f1), tilt_x_resolution(qd_resolution, h),
                       displacement_resolution(qd_resolution))


def _positive(name: str, value) -> None:
    if not (np.isscalar(value) and np.isfinite(value) and value > 0):
        raise InputError(f"{name} = {value!r} must be a positive finite number (metres)")


def _sign(sign) -> None:
    if sign not in (1, -1):
        raise InputError(f"sign = {sign!r} must be +1 or -1")
