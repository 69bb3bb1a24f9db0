"""The identified location errors of a table-table machine in LinuxCNC's terms: the HAL pins of
``xyzac-trt-kins`` / ``xyzbc-trt-kins`` and the joints' ``HOME_OFFSET``, and a neutral table.

What the pins hold (LinuxCNC 2.9, ``src/emc/kinematics/trtfuncs.c``, ``xyzacKinematicsForward``
and ``xyzbcKinematicsForward``):

* ``x-rot-point``, ``y-rot-point``: X, Y of the C axis at A = 0 (B = 0): E_X0C, E_Y0C are added;
* xyzac: the A axis is at Y = ``y-rot-point + y-offset``, Z = ``z-rot-point + z-offset``
  (+ ``tool-offset``); so ``y-offset`` takes E_Y0A minus the change of ``y-rot-point``, and
  ``z-offset`` takes E_Z0A (``z-rot-point`` is kept: only the sum counts; ``x-offset`` is unused);
* xyzbc: the B axis is at X = ``x-rot-point + x-offset``, Z = ``z-rot-point + z-offset``;
  ``x-offset`` takes E_X0B minus the change of ``x-rot-point``, ``z-offset`` takes E_Z0B.

All in the machine's linear unit (mm here), the sign of the machine frame: a pin is the position
of the axis line, so a positive location error (the line further along +X, +Y, +Z) adds to it.
The zero position of the tilting axis (identified as E_A0A+E_A0C, the convention of
:mod:`axiscal.standards.location_errors`) goes to the joint's ``[JOINT_n]HOME_OFFSET``: with the
table turning right-handed by the commanded angle (LinuxCNC's trt sign), a commanded ``a`` reaches
``a + E``; after homing the joint reads ``HOME_OFFSET`` at the switch, so ``HOME_OFFSET`` grows by
``E`` (degrees) and the joint then reads the angle the table really has. E_C0C is not seen by the
set-ups (the C zero is the set-up's) and is left as it is. The orientation errors (E_B0A, E_C0A,
E_B0C for A/C; E_A0B, E_C0B, E_A0C for B/C) have no pin: they are listed as not held by any pin
and corrected through LinuxCNC's external offsets of X, Y, Z by axiscal's HAL component
``axiscal_trtcomp.py`` (package data; LinuxCNC documentation, "External Axis Offsets"), which
reads the commanded world pose and asks for ``o = R_nomᵀ (T_act p − T_nom p)``: the table point
``p`` moved to where the identified axis lines (``T_act``: the pins' lines with the identified
orientation errors) put it, expressed in the world frame, which turns with the table (the
component's docstring). :attr:`TrtCorrection.external_offsets` holds the two sets of lines it
reads (``trtcomp.json``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import InputError
from axiscal.physics.rotary_location import Geometry

__all__ = ["TrtCorrection", "trt_correction", "nominal_pins", "corrected_geometry", "corrected_machine",
           "Verification", "verify_on_twin", "Explained", "explain_range", "noise_maps",
           "EXPLAINED_WITHIN", "NOISE_DRAWS"]

#: How close the measured range after the correction must come to the range expected from the
#: unmodelled errors plus the noise for it to count as explained, m (issue 43, Must show: 1 µm).
EXPLAINED_WITHIN = 1e-6

#: Monte Carlo draws of the noise in :func:`explain_range` (the mean's own scatter is then
#: about 0.3 % of the range's spread).
NOISE_DRAWS = 4000


@dataclass(frozen=True)
class TrtCorrection:
    """New values of LinuxCNC trt kinematics parameters (mm, degrees).

    Attributes
    ----------
    component : str
        ``"xyzac-trt-kins"`` or ``"xyzbc-trt-kins"``.
    pins : dict of str to (float, float)
        HAL pin -> (value before, value after), mm.
    home_offset : dict of str to float
        Joint axis letter -> change of ``HOME_OFFSET``, degrees.
    not_held : dict of str to float
        Location errors no parameter holds -> value (µrad).
    sources : dict of str to str
        Each pin or offset -> the location error(s) it takes.
    external_offsets : dict or None
        What ``axiscal_trtcomp.py`` reads (``trtcomp.json``): ``tilt`` and the ``nominal`` and
        ``actual`` lines, each ``{"tilt": [point mm, unit direction, zero deg], "c": [...]}``;
        None when no orientation error was identified.
    """

    component: str
    pins: dict
    home_offset: dict
    not_held: dict
    sources: dict
    external_offsets: dict | None = None

    def hal(self) -> str:
        """``setp`` lines for halcmd (idle, rotary axes at 0), with the convention as comments."""
        lines = [f"# {self.component}: location errors identified by axiscal (ISO 230-1 names);",
                 "# the table turns right-handed by the commanded angle (LinuxCNC trt sign)."]
        for pin, (old, new) in self.pins.items():
            lines.append(f"setp {self.component}.{pin} {new:.6f}    # was {old:.6f} mm; "
                         f"{self.sources[pin]}")
        for axis, d in self.home_offset.items():
            lines.append(f"# [JOINT of {axis}] HOME_OFFSET += {d:+.6f} deg ({self.sources[axis]})")
        for name, v in self.not_held.items():
            lines.append(f"# not held by any pin: {name} = {v:+.2f} urad"
                         + (" (external offsets: axiscal_trtcomp.hal, trtcomp.json)"
                            if self.external_offsets else ""))
        return "\n".join(lines).replace("\u2212", "-") + "\n"   # halcmd reads ASCII

    def neutral_table(self) -> list[dict]:
        """One row per parameter: ``parameter``, ``before``, ``after``, ``unit``, ``takes``."""
        rows = [{"parameter": f"{self.component}.{p}", "before": o, "after": n, "unit": "mm",
                 "takes": self.sources[p]} for p, (o, n) in self.pins.items()]
        rows += [{"parameter": f"HOME_OFFSET of {a}", "before": None, "after": d,
                  "unit": "deg (change)", "takes": self.sources[a]}
                 for a, d in self.home_offset.items()]
        rows += [{"parameter": "(none)", "before": None, "after": v, "unit": "µrad",
                  "takes": n} for n, v in self.not_held.items()]
        return rows

    def table_csv(self) -> str:
        """The neutral table as CSV (``parameter,before,after,unit,takes``)."""
        out = ["parameter,before,after,unit,takes"]
        for r in self.neutral_table():
            cells = ["" if r[k] is None else (f"{r[k]:.6f}" if isinstance(r[k], float)
                                              else str(r[k]))
                     for k in ("parameter", "before", "after", "unit", "takes")]
            out.append(",".join(cells))
        return "\n".join(out) + "\n"

    def to_dict(self) -> dict:
        return {"component": self.component,
                "pins_mm": {p: {"before": o, "after": n} for p, (o, n) in self.pins.items()},
                "home_offset_change_deg": dict(self.home_offset),
                "not_held_urad": dict(self.not_held), "sources": dict(self.sources),
                "external_offsets": self.external_offsets}


def nominal_pins(geometry: Geometry, z_rot_point: float = 0.0) -> dict:
    """The trt pins (mm) that hold the nominal ``geometry`` (m), ``z-rot-point`` as given (m):
    what the controller holds before a correction (module docstring)."""
    if geometry.head:
        raise InputError("a spindle head: LinuxCNC's trt pins are for table-table machines "
                         "(its 5axiskins holds only pivot-length); no pin values are given")
    cx, cy = geometry.c_position
    t1, tz = geometry.tilt_position
    pins = {"x-rot-point": cx * 1e3, "y-rot-point": cy * 1e3, "z-rot-point": z_rot_point * 1e3,
            "z-offset": (tz - z_rot_point) * 1e3}
    if geometry.tilt == "A":
        pins["y-offset"] = (t1 - cy) * 1e3
    else:
        pins["x-offset"] = (t1 - cx) * 1e3
    return pins


def trt_correction(geometry: Geometry, result, z_rot_point: float = 0.0) -> TrtCorrection:
    """The pins that put the identified location errors right (module docstring).

    Parameters
    ----------
    geometry : Geometry
        The nominal geometry the controller holds now (m).
    result : LocationIdentification
    z_rot_point : float, m
        The ``z-rot-point`` pin as set now (kept).

    Raises
    ------
    InputError
        A location error a pin needs was not identified.
    """
    if geometry.head:
        raise InputError("a spindle head: LinuxCNC's trt pins are for table-table machines "
                         "(its 5axiskins holds only pivot-length); no pin values are given")
    got = {e.name: e.value for e in result.errors}
    t = geometry.tilt
    need = ("E_X0C", "E_Y0C") + (("E_Y0A", "E_Z0A") if t == "A" else ("E_X0B", "E_Z0B"))
    missing = [n for n in need if n not in got]
    if missing:
        raise InputError(f"{', '.join(missing)} not identified: no pin value can be given for "
                         "them; measure with a plan that sees them (axiscal fiveaxis plan)")
    mm = 1e3
    cx, cy = geometry.c_position
    t1, tz = geometry.tilt_position
    before = nominal_pins(geometry, z_rot_point)
    xr, yr = cx + got["E_X0C"], cy + got["E_Y0C"]
    pins = {"x-rot-point": (before["x-rot-point"], xr * mm),
            "y-rot-point": (before["y-rot-point"], yr * mm)}
    sources = {"x-rot-point": "E_X0C", "y-rot-point": "E_Y0C"}
    if t == "A":
        pins["y-offset"] = (before["y-offset"], (t1 + got["E_Y0A"] - yr) * mm)
        sources["y-offset"] = "E_Y0A − E_Y0C"
        pins["z-offset"] = (before["z-offset"], (tz + got["E_Z0A"] - z_rot_point) * mm)
        sources["z-offset"] = "E_Z0A"
        tilts = ("E_B0A", "E_C0A", "E_B0C")
    else:
        pins["x-offset"] = (before["x-offset"], (t1 + got["E_X0B"] - xr) * mm)
        sources["x-offset"] = "E_X0B − E_X0C"
        pins["z-offset"] = (before["z-offset"], (tz + got["E_Z0B"] - z_rot_point) * mm)
        sources["z-offset"] = "E_Z0B"
        tilts = ("E_A0B", "E_C0B", "E_A0C")
    zero = f"E_{t}0{t}+E_{t}0C"
    home = {t: got[zero] * 180.0 / 3.141592653589793} if zero in got else {}
    sources[t] = zero
    not_held = {n: got[n] * 1e6 for n in tilts if n in got}
    corr = TrtCorrection(f"xyz{t.lower()}c-trt-kins", pins, home, not_held, sources)
    if not not_held:
        return corr
    from dataclasses import replace

    after = corrected_geometry(geometry, corr)
    lines = lambda e: dict(zip(("tilt", "c"), (  # noqa: E731 - the two lines in mm, deg
        [(q * 1e3).tolist(), u.tolist(), z * 180.0 / 3.141592653589793]
        for q, u, z in after.lines(e))))
    eo = {"tilt": t, "unit": "mm, deg", "nominal": lines({}),
          "actual": lines({n: got[n] for n in tilts if n in got})}
    return replace(corr, external_offsets=eo)


def corrected_geometry(geometry: Geometry, correction: TrtCorrection) -> Geometry:
    """The nominal geometry the controller holds after the correction (m): the pins' sums."""
    p = {k: v[1] * 1e-3 for k, v in correction.pins.items()}
    c = (p["x-rot-point"], p["y-rot-point"])
    zt = geometry.tilt_position[1] + (correction.pins["z-offset"][1]
                                      - correction.pins["z-offset"][0]) * 1e-3
    t1 = p["y-rot-point"] + p["y-offset"] if geometry.tilt == "A" else \
        p["x-rot-point"] + p["x-offset"]
    return Geometry(geometry.tilt, (t1, zt), c)


@dataclass(frozen=True)
class Explained:
    """What a set-up's range after the correction is expected to be: the unmodelled errors the
    twin holds plus the instruments' noise (:func:`explain_range`), m.

    Attributes
    ----------
    unmodelled : float, m
        The range without noise (the deviations the correction leaves on the twin).
    expected : float, m
        Mean of the range of (unmodelled deviations + noise) over the noise draws.
    low, high : float, m
        Its 2.5 % and 97.5 % quantiles: 95 % of measurements fall between them.
    draws : int
        Monte Carlo draws.
    """

    unmodelled: float
    expected: float
    low: float
    high: float
    draws: int

    @property
    def noise(self) -> float:
        """What the noise adds to the range on average, m: ``expected − unmodelled``."""
        return self.expected - self.unmodelled

    def explains(self, after: float) -> bool:
        """True when a measured range ``after`` (m) is within :data:`EXPLAINED_WITHIN` of
        :attr:`expected`."""
        return abs(after - self.expected) <= EXPLAINED_WITHIN

    def to_dict(self, after: float) -> dict:
        return {"unmodelled_um": self.unmodelled * 1e6, "noise_um": self.noise * 1e6,
                "expected_um": self.expected * 1e6,
                "interval_95_um": [self.low * 1e6, self.high * 1e6],
                "unexplained_um": (after - self.expected) * 1e6,
                "within_95": bool(self.low <= after <= self.high),
                "explained": self.explains(after), "draws": self.draws}

    def describe(self, after: float) -> str:
        return (f"left {after * 1e6:.2f} µm = {self.unmodelled * 1e6:.2f} µm unmodelled + noise "
                f"{(after - self.unmodelled) * 1e6:.2f} µm; expected "
                f"{self.expected * 1e6:.2f} µm ({self.unmodelled * 1e6:.2f} + "
                f"{self.noise * 1e6:.2f} from the noise), 95 % within "
                f"{self.low * 1e6:.2f}–{self.high * 1e6:.2f} µm"
                + ("" if self.explains(after) else
                   f"; NOT explained within {EXPLAINED_WITHIN * 1e6:g} µm"))


def noise_maps(machine, setup) -> tuple[np.ndarray, float]:
    """How the instrument's noise enters each deviation of a set-up, to first order.

    Parameters
    ----------
    machine : FiveAxisMachine
        Its nominal geometry turns a probed centre into the table frame.
    setup : PlannedSetUp

    Returns
    -------
    maps : numpy.ndarray, shape (poses, 3, k)
        ``δ_p = σ maps[p] z`` with ``z`` k independent standard normal draws: the deviation's
        error at pose ``p`` (table frame).
    sigma : float, m
        The instrument's noise (one touch, one sensor reading).

    Notes
    -----
    Probing: each of the k touches is off by ``ε_i`` along its travel (the simulated probe's
    model), the fitted centre by ``G ε`` (:func:`~axiscal.standards.sphere_fit.centre_sensitivity`
    with the touch directions, machine frame), turned into the table frame with the pose's
    nominal angles: ``maps[p] = R_p G``. R-test: the three sensors read ``s = N Δ + ε``, the
    instrument gives ``Δ = N⁻¹ s`` (Weikert 2004), so ``maps[p] = N⁻¹`` (table frame already;
    the gains' calibration error, of order 1e-3, is left out). The twin's random axis errors
    (repeatability), where its axes have them, are not in the maps.
    """
    from axiscal.physics.rotary_location import machine_to_table
    from axiscal.procedures.five_axis import PROBING
    from axiscal.standards.sphere_fit import centre_sensitivity

    inst = setup.instrument
    poses = len(setup.tilt_angle)
    if setup.kind != PROBING:
        n_inv = np.linalg.inv(np.asarray(inst.directions, float))
        return np.broadcast_to(n_inv, (poses, 3, 3)).copy(), float(inst.noise)
    g = centre_sensitivity(np.asarray(inst.directions, float))
    out = []
    for a, c in zip(setup.tilt_angle, setup.c_angle):
        rows = machine_to_table(machine.geometry, {}, a, c, np.eye(3)) \
            - machine_to_table(machine.geometry, {}, a, c, np.zeros(3))   # row j: R e_j
        out.append(rows.T @ g)
    return np.array(out), float(inst.noise)


def explain_range(unmodelled, maps, sigma: float, rng: np.random.Generator,
                  draws: int = NOISE_DRAWS) -> Explained:
    """The range a set-up is expected to show: its noise-free deviations plus the noise.

    Parameters
    ----------
    unmodelled : array_like, shape (poses, 3), m
        The set-up's deviations without noise (table frame).
    maps : array_like, shape (poses, 3, k)
    sigma : float, m
        From :func:`noise_maps`.
    rng : numpy.random.Generator
        Draws the Monte Carlo samples.
    draws : int

    Returns
    -------
    Explained

    Notes
    -----
    The range ``max_xyz ptp_p(v_p)`` is not additive: noise of standard deviation ``s`` on
    ``P`` poses widens a range by about the expected range of ``P`` normal draws (for 12 poses
    ``3.26 s``; Tippett's table of the mean range) less what the noise-free spread already
    covers. Its distribution has no closed form for correlated, unequal errors, so it is
    sampled: ``v_p = u_p + σ maps[p] z``, ``z ~ N(0, I)`` (JCGM 101:2008, the propagation of
    distributions by a Monte Carlo method, 5.9 and 7.7 for the coverage interval), ``draws``
    times; the mean and the 2.5 % and 97.5 % quantiles of the sampled ranges are returned.
    """
    u = np.asarray(unmodelled, float)
    m = np.asarray(maps, float)
    z = rng.standard_normal((m.shape[0], m.shape[2], draws))
    v = u[:, :, None] + sigma * (m @ z)                   # (poses, 3, draws)
    r = np.ptp(v, axis=0).max(axis=0)
    low, high = np.quantile(r, [0.025, 0.975])
    return Explained(float(np.ptp(u, axis=0).max()), float(r.mean()), float(low), float(high),
                     int(draws))


@dataclass(frozen=True)
class Verification:
    """Sphere-centre (R-test) deviation range of each set-up before and after the correction, m.

    The range of a set-up is the largest peak-to-valley, over X, Y and Z, of the sphere centres
    seen through the controller's kinematics in the table frame (probing), or of the R-test's
    displacements: what a perfect machine would show as 0. ``after_unmodelled`` is the range
    after the correction on the twin without noise: what the errors the correction cannot hold
    leave (the twin's truth; the rest of ``after`` is the instruments' noise). ``explained``
    (:class:`Explained`, one per set-up) says what ``after`` is expected to be from those
    unmodelled deviations plus the instruments' noise (:func:`explain_range`), and whether the
    measured ``after`` is within :data:`EXPLAINED_WITHIN` of it (issue 43, Must show).
    """

    labels: tuple[str, ...]
    before: tuple[float, ...]
    after: tuple[float, ...]
    after_unmodelled: tuple[float, ...] = ()
    explained: tuple[Explained, ...] = ()

    @property
    def reduction(self) -> tuple[float, ...]:
        return tuple(1.0 - a / b if b > 0 else 0.0 for a, b in zip(self.after, self.before))

    def to_dict(self) -> dict:
        left = self.after_unmodelled or (None,) * len(self.labels)
        why = self.explained or (None,) * len(self.labels)
        return {"setups": [{"label": n, "before_um": b * 1e6, "after_um": a * 1e6,
                            "reduction": r,
                            "after_unmodelled_um": None if u is None else u * 1e6,
                            "explained": None if e is None else e.to_dict(a)}
                           for n, b, a, r, u, e in
                           zip(self.labels, self.before, self.after, self.reduction, left, why)]}

    def __str__(self) -> str:
        left = self.after_unmodelled or (None,) * len(self.labels)
        why = self.explained or (None,) * len(self.labels)
        return "\n".join(f"  {n}: range {b * 1e6:.2f} µm before, {a * 1e6:.2f} µm after "
                         f"({r:.1%} less)" + ("" if u is None or e is not None else
                                              f"; without noise {u * 1e6:.2f} µm after")
                         + ("" if e is None else f"; {e.describe(a)}")
                         for n, b, a, r, u, e in
                         zip(self.labels, self.before, self.after, self.reduction, left, why))


def corrected_machine(machine, correction: TrtCorrection):
    """The twin as its controller sees it after the correction: the same physical axis lines,
    the corrected nominal geometry, the zero of the tilting axis shifted by HOME_OFFSET and, with
    the external offsets, the orientation errors less those the offsets correct (to first order
    in the small angles: the offsets put the table point where the identified lines have it)."""
    from dataclasses import replace

    g0, g1 = machine.geometry, corrected_geometry(machine.geometry, correction)
    t = g0.tilt
    e = dict(machine.errors)
    e["E_X0C"] = e.get("E_X0C", 0.0) + g0.c_position[0] - g1.c_position[0]
    e["E_Y0C"] = e.get("E_Y0C", 0.0) + g0.c_position[1] - g1.c_position[1]
    first = "E_Y0A" if t == "A" else "E_X0B"
    e[first] = e.get(first, 0.0) + g0.tilt_position[0] - g1.tilt_position[0]
    e[f"E_Z0{t}"] = e.get(f"E_Z0{t}", 0.0) + g0.tilt_position[1] - g1.tilt_position[1]
    e[f"E_{t}0{t}"] = e.get(f"E_{t}0{t}", 0.0) - correction.home_offset.get(t, 0.0) \
        * 3.141592653589793 / 180.0
    if correction.external_offsets:
        for n, v in correction.not_held.items():
            e[n] = e.get(n, 0.0) - v * 1e-6
    return replace(machine, geometry=g1, errors=e)


def verify_on_twin(machine, plan, correction: TrtCorrection, seed: int = 7) -> Verification:
    """Measure the plan on the twin before and after the correction (same noise draws) and
    compare the deviation ranges (twin only: the controller is the twin's nominal geometry);
    what is left after is explained by the noise-free deviations and the instruments' noise
    (:func:`explain_range`, its draws seeded by ``seed``)."""
    from axiscal.procedures.five_axis import measure

    after_machine = corrected_machine(machine, correction)
    devs = []
    for m, rng in ((machine, np.random.default_rng(seed)),
                   (after_machine, np.random.default_rng(seed)), (after_machine, None)):
        devs.append([_deviations(m, r) for r in measure(m, plan, rng)])
    ranges = [tuple(float(np.ptp(v, axis=0).max()) for v in d) for d in devs]
    rng = np.random.default_rng([seed, 43])
    why = tuple(explain_range(u, *noise_maps(after_machine, s), rng)
                for u, s in zip(devs[2], plan.setups))
    return Verification(tuple(s.label for s in plan.setups), *ranges, why)


def _deviations(machine, record) -> np.ndarray:
    from axiscal.physics.rotary_location import machine_to_table

    if record.kind == "probing":
        c = record.setup().values
        return machine_to_table(machine.geometry, {}, record.tilt_angle, record.c_angle, c)
    return np.asarray(record.displacement, float)
