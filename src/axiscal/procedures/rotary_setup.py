"""The set-up checks of a rotary calibration: the readings taken before the capture, the paper's
thresholds and the bounds on the misalignments they imply (step 1 of
:mod:`axiscal.procedures.rotary_calibration`).

The dial-gauge TIR on the calibrator's mounting ring gives the tilt of the mounting face,
``TIR/(2r)``; the offset of the beam returned by the reflector's rear target at the laser's shutter
gives the laser's misalignment, ``d/(2L)``; the paper's thresholds (TIR < 0.04 mm at 50 mm, return
within 1 mm at 1 m, axes coincident within ±0.5 mm) are checked and the bounds on α and β are
carried into the error budget.

References
----------
Renishaw, Interferometric calibration of rotary axes (set-up and alignment).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from axiscal.errors import InputError
from axiscal.units import ARCSEC, DEG, MM

__all__ = ["SetupCheck", "setup_checks", "TIR_LIMIT", "RETURN_BEAM_LIMIT", "CENTRING_LIMIT",
           "CALIBRATOR_PERPENDICULARITY", "TARGET_ALIGNMENT", "REFLECTOR_TWIST_TOLERANCE",
           "CALIBRATION_STEP", "SDE_LIMIT"]

#: Renishaw, Interferometric calibration of rotary axes: "the TIR should be < 0.04mm at 50mm radius".
TIR_LIMIT = (0.04e-3, 50e-3)
#: Renishaw, Interferometric calibration of rotary axes: "if the laser is placed 1 metre away ... aligned to within 1mm on the laser shutter".
RETURN_BEAM_LIMIT = (1e-3, 1.0)
#: Renishaw, Interferometric calibration of rotary axes: "aligned so that the two axes of rotation are coincident within ±0.5 mm".
CENTRING_LIMIT = 0.5e-3
#: Renishaw, Interferometric calibration of rotary axes: the calibrator's axis "is perpendicular to its mounting face to within ±0.025°".
CALIBRATOR_PERPENDICULARITY = 0.025 * DEG
#: Renishaw, Interferometric calibration of rotary axes: the rear target "is aligned to the XR20's axis of rotation to within ±0.33 milliradians".
TARGET_ALIGNMENT = 0.33e-3
#: Renishaw, Interferometric calibration of rotary axes: retro-reflectors and housing "set during XR20 manufacture to be within ±2.5 milliradians".
REFLECTOR_TWIST_TOLERANCE = 2.5e-3
#: Renishaw, Interferometric calibration of rotary axes: the optics calibration compares the laser with the calibrator "at 0°, +5° and -5°".
CALIBRATION_STEP = 5.0 * DEG
#: Renishaw, Interferometric calibration of rotary axes: sub-divisional error "kept below ±0.25 arcseconds".
SDE_LIMIT = 0.25 * ARCSEC
#: The document the set-up thresholds come from, as warnings name it.
_DOC = "Renishaw, Interferometric calibration of rotary axes"


@dataclass(frozen=True)
class SetupCheck:
    """Set-up readings, the misalignment bounds they imply, and the paper's thresholds.

    Attributes
    ----------
    tir, tir_radius : float, metres
    return_offset, laser_distance : float, metres
    centring : float, metres
    mount_tilt : float, radians
        ``TIR/(2r)``.
    alpha_bound : float, radians
        ``mount_tilt + 0.025°`` (the calibrator's own perpendicularity).
    laser_to_target : float, radians
        ``d/(2L)`` (the returned beam moves twice the angle).
    beta_bound : float, radians
        ``laser_to_target + 0.33 mrad`` (the target's alignment to the axis).
    omega_bound : float, radians
        2.5 mrad (manufacturing tolerance).
    warnings : tuple of str
        One line per threshold exceeded.
    """

    tir: float
    tir_radius: float
    return_offset: float
    laser_distance: float
    centring: float
    mount_tilt: float
    alpha_bound: float
    laser_to_target: float
    beta_bound: float
    omega_bound: float
    warnings: tuple[str, ...]

    @property
    def passed(self) -> bool:
        """True when every reading is within the paper's recommendation."""
        return not self.warnings

    def as_rows(self) -> list[tuple[str, str]]:
        """Readable (name, value) rows for reports."""
        return [
            ("TIR of the mounting ring", f"{self.tir / MM:.4f} mm at {self.tir_radius / MM:g} mm radius"),
            ("mounting face tilt TIR/(2r)", f"{self.mount_tilt * 1e3:.3f} mrad"),
            ("α bound (+0.025° calibrator)", f"{self.alpha_bound * 1e3:.3f} mrad"),
            ("return beam at shutter", f"{self.return_offset / MM:.2f} mm at {self.laser_distance:g} m"),
            ("laser to target d/(2L)", f"{self.laser_to_target * 1e3:.3f} mrad"),
            ("β bound (+0.33 mrad target)", f"{self.beta_bound * 1e3:.3f} mrad"),
            ("ω bound (manufacture)", f"{self.omega_bound * 1e3:.2f} mrad"),
            ("axes offset (centring)", f"{self.centring / MM:.3f} mm"),
            ("checks", "passed" if self.passed else "; ".join(self.warnings)),
        ]

    def __str__(self) -> str:
        return "set-up check:\n" + "\n".join(f"  {k}: {v}" for k, v in self.as_rows())


def setup_checks(tir: float, return_offset: float, centring: float, tir_radius: float = 50e-3,
                 laser_distance: float = 1.0) -> SetupCheck:
    """Translate the set-up readings into bounds on α and β and check the paper's thresholds.

    Parameters
    ----------
    tir : float, metres
        Total indicator reading on the mounting ring over a turn.
    return_offset : float, metres
        Offset of the beam returned by the rear target at the laser's shutter.
    centring : float, metres
        Offset between the calibrator's axis and the axis under test.
    tir_radius, laser_distance : float, metres

    Examples
    --------
    >>> c = setup_checks(0.03e-3, 0.8e-3, 0.2e-3)
    >>> round(c.mount_tilt * 1e3, 3), round(c.laser_to_target * 1e3, 3), c.passed
    (0.3, 0.4, True)
    """
    for name, v in (("tir", tir), ("return_offset", return_offset), ("centring", centring)):
        if not (math.isfinite(v) and v >= 0):
            raise InputError(f"{name}={v!r} m must be a reading >= 0")
    for name, v in (("tir_radius", tir_radius), ("laser_distance", laser_distance)):
        if not v > 0:
            raise InputError(f"{name}={v!r} m must be positive")
    mount = tir / (2.0 * tir_radius)
    laser = return_offset / (2.0 * laser_distance)
    warnings = []
    tir_max = TIR_LIMIT[0] / TIR_LIMIT[1] * tir_radius
    if tir >= tir_max:
        warnings.append(f"TIR {tir / MM:.3f} mm at {tir_radius / MM:g} mm radius: {_DOC} asks for "
                        f"< {tir_max / MM:.3f} mm (0.04 mm at 50 mm)")
    ret_max = RETURN_BEAM_LIMIT[0] / RETURN_BEAM_LIMIT[1] * laser_distance
    if return_offset > ret_max:
        warnings.append(f"returned beam {return_offset / MM:.2f} mm off at {laser_distance:g} m: "
                        f"{_DOC} asks for within {ret_max / MM:.2f} mm (1 mm at 1 m)")
    if centring > CENTRING_LIMIT:
        warnings.append(f"axes {centring / MM:.2f} mm apart: {_DOC} asks for within ±0.5 mm "
                        "(0.25 arcsec with 15 arcsec beam non-parallelism)")
    return SetupCheck(tir, tir_radius, return_offset, laser_distance, centring, mount,
                      mount + CALIBRATOR_PERPENDICULARITY, laser, laser + TARGET_ALIGNMENT,
                      REFLECTOR_TWIST_TOLERANCE, tuple(warnings))
