"""Ballbar diagnosis: every machine error a circular test separates, with its share and advice.

The clockwise and counter-clockwise runs of a circular test (ISO 230-4:2005) are fitted together
by linear least squares on a model of the radial deviation ``Δr(φ)`` (φ counter-clockwise from the
first axis, ``s = +1`` CCW, ``-1`` CW, ``v`` the feed, ``R`` the radius). Each term's first-order
effect on ``Δr = δx cos φ + δy sin φ`` (Renishaw, Calibration of machine squareness, Method 4,
"isolate the squareness error from ... backlash, servo, scale mismatch, cyclic, straightness
errors"; Chapman, Calibration of machine squareness):

* centre and radius: ``1, cos φ, sin φ`` (and ``±`` half of them: a shift between the runs);
* scale mismatch ``δx = e_x x, δy = e_y y``: ``(R/2)(e_x - e_y) cos 2φ``;
* squareness ``δx = -θ y``: ``-(θR/2) sin 2φ``;
* servo mismatch ``δx = -τ_x ẋ, δy = -τ_y ẏ``: ``s (v Δτ / 2) sin 2φ`` with ``Δτ = τ_x - τ_y``;
* backlash ``δx = (b_x/2) sign v_x`` (approach side): ``(1/2) s_x cos φ``, ``(1/2) s_y sin φ``;
* lateral play ``δy = (l_x/2) sign v_x``: ``(1/2) s_x sin φ``; ``l_y`` alike;
* straightness ``δy = c_x (x/R)²`` (a bow over ±R): ``c_x cos²φ sin φ``; ``c_y`` alike;
* reversal spike ``δx = h e^{-u/d}`` after a reversal: ``h |cos φ| e^{-Rα/d}``, α the travel
  angle since the reversal;
* cyclic error ``δx = A sin(2π x/p + ϑ)``: ``cos φ · [sin, cos](2π R cos φ / p)``.

``s_x = -s·sign(sin φ)`` is the sign of X's velocity (approach side on the reversal point itself,
:func:`axiscal.standards.iso230_4._backlash_basis`). The non-linear parameters (decay length ``d``,
pitch ``p``) are chosen by a grid search on the fit residual. Stick-slip is the peak-to-valley of
the residual near the reversal points (axis velocity under 10 % of the feed) beyond that of the
rest of the path; vibration is the largest line of the residual's amplitude spectrum against time
(feed known). The residual after every modelled term is reported so a user sees what the model
does not explain. ISO 230-4 G, H, F come from :func:`~axiscal.standards.iso230_4.evaluate_circular`.

What the simpler model folds in: the ISO 230-4 two-direction fit
(:func:`~axiscal.standards.iso230_4.evaluate_circular`) has the centre, radius, shift, scale,
squareness and backlash columns only, a subset of this model's columns on the same rows. Both are
linear least squares, so each ISO 230-4 coefficient is this model's coefficient plus, for every
term the ISO 230-4 model lacks, that term's coefficient times the ISO 230-4 regression of its
column (``(AᵀA)⁻¹ Aᵀ t``, A the ISO 230-4 columns); the residual adds nothing (it is orthogonal
to every column). :class:`FoldedError` gives that split for squareness, scale mismatch and the
backlash of each axis; servo mismatch (``s sin 2φ``, a sign change with the direction like the
backlash) is the usual one.

Servo mismatch: an axis whose position loop has gain ``K`` follows ``τ = 1/K`` behind its command
(first-order loop, steady state); with ``ẋ = -s v sin φ``, ``ẏ = s v cos φ`` the radial effect
is ``s v (τ_x - τ_y) sin φ cos φ``, which changes sign with the direction (squareness does not).

References
----------
ISO 230-4:2005 §3 and Annex A (interpretation of circular test plots). Renishaw (M.A.V. Chapman),
Calibration of machine squareness, Method 4 (Chapman, Calibration of machine squareness).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError
from axiscal.standards.iso230_4 import (CircularResult, _common, _harmonics, evaluate_circular,
                                        block_product, normal_equations,
                                        velocity_signs)

__all__ = ["BallbarDiagnosis", "DiagnosisTerm", "FoldedError", "diagnose", "ADVICE"]

#: What a service engineer does about each term (ISO 230-4:2005 Annex A; ballbar practice).
ADVICE = {
    "squareness": "re-square the axes (gib/column alignment) or enter a squareness compensation",
    "scale_mismatch": "check the scale/pitch compensation of both axes against a laser "
                      "(ISO 230-2) and the machine temperature",
    "servo_mismatch": "match the position-loop gains (kv) of the two axes in the controller",
    "backlash_x": "adjust the X ball-screw preload/nut or enter backlash compensation",
    "backlash_y": "adjust the Y ball-screw preload/nut or enter backlash compensation",
    "lateral_play_x": "check the X guideways and gibs for play",
    "lateral_play_y": "check the Y guideways and gibs for play",
    "straightness_x": "check X guideway straightness (levelling, wear)",
    "straightness_y": "check Y guideway straightness (levelling, wear)",
    "reversal_spike_x": "tune the X reversal (friction) compensation or check X lubrication",
    "reversal_spike_y": "tune the Y reversal (friction) compensation or check Y lubrication",
    "cyclic_x": "check the X ball screw/encoder for pitch-periodic error",
    "cyclic_y": "check the Y ball screw/encoder for pitch-periodic error",
    "stick_slip": "check way lubrication and friction near reversals",
    "vibration": "look for a source at the reported frequency (spindle, fan, loop tuning)",
    "residual": "errors the model does not explain: inspect the polar plot",
}

_DECAYS = np.geomspace(0.05e-3, 5e-3, 9)      # candidate spike decay lengths, m


@dataclass(frozen=True)
class DiagnosisTerm:
    """One diagnosed term: value (in ``unit``), its peak-to-valley on Δr (m) and share of G."""

    key: str
    value: float
    unit: str
    ptp: float
    share: float
    advice: str


@dataclass(frozen=True)
class FoldedError:
    """A figure of the ISO 230-4 fit that folds other errors in (module docstring).

    Attributes
    ----------
    quantity : str
        ``squareness``, ``scale_mismatch``, ``backlash_x`` or ``backlash_y``.
    label : str
        The quantity as a reader names it (``backlash X``).
    unit : str
        ``µm`` or ``µm/m``.
    iso230_4, diagnosis : float
        The value by the ISO 230-4 fit and by the full diagnosis, in ``unit``.
    parts : tuple of (str, str, float)
        Each term the ISO 230-4 fit lacks (its ranking key, its label with the plane's axis
        letter) with what it adds to ``iso230_4`` (``unit``), largest first; they sum to
        ``iso230_4 - diagnosis`` (the residual adds nothing).
    material : bool
        The difference moves the radial deviation by more than the residual the diagnosis
        leaves (rms, at least 1 nm): a separation the readings resolve, so it is stated.
    """

    quantity: str
    label: str
    unit: str
    iso230_4: float
    diagnosis: float
    parts: tuple[tuple[str, str, float], ...]
    material: bool

    def as_dict(self) -> dict:
        """JSON: the quantity, unit, both values, the difference and every folded term."""
        return {"quantity": self.quantity, "unit": self.unit, "iso230_4": self.iso230_4,
                "diagnosis": self.diagnosis, "difference": self.iso230_4 - self.diagnosis,
                "folded": {k: v for k, _, v in self.parts}, "material": self.material,
                "statement": str(self)}

    def __str__(self) -> str:
        diff = self.iso230_4 - self.diagnosis
        big = [p for p in self.parts if abs(p[2]) >= FOLD_SHARE * abs(diff)] or \
            list(self.parts[:1])
        rest = [p[2] for p in self.parts[len(big):] if abs(p[2]) >= 5e-4]   # shown as ≠ 0
        names = ", ".join(f"{label} {v:+.3f} {self.unit}" for _, label, v in big)
        if rest:
            names += f" ({len(rest)} smaller {'terms' if len(rest) > 1 else 'term'} " \
                     f"{sum(rest):+.3f} {self.unit})"
        return (f"{self.label} {self.iso230_4:+.3f} {self.unit} by the ISO 230-4 fit folds in "
                f"{names}; the full diagnosis gives {self.diagnosis:+.3f} {self.unit}")


#: A folded term is named in the statement when it holds at least this share of the difference.
FOLD_SHARE = 0.1


@dataclass(frozen=True)
class BallbarDiagnosis:
    """The diagnosis of a circular test (module docstring); lengths in m, ratios in m/m.

    Attributes
    ----------
    circular : CircularResult
        ISO 230-4 G, H, F and the basic squareness diagnosis.
    values : dict
        Every term in its JSON unit, keys carrying the unit (``squareness_um_per_m`` ...).
    terms : tuple of DiagnosisTerm
        Ranked, largest effect on the circularity first.
    residual_rms, residual_ptp : float, m
        What the model leaves.
    warnings : tuple of str
    folded : tuple of FoldedError
        What the ISO 230-4 fit of ``circular`` folds into its squareness, scale mismatch and
        backlash, against this diagnosis.
    """

    circular: CircularResult
    values: dict
    terms: tuple[DiagnosisTerm, ...]
    residual_rms: float
    residual_ptp: float
    feed: float | None
    warnings: tuple[str, ...] = field(default=())
    folded: tuple[FoldedError, ...] = field(default=())

    def as_dict(self) -> dict:
        """JSON numbers: µm, µm/m, ms, Hz, mm; the ranking with shares in %."""
        d = dict(self.values)
        d.update({"residual_rms_um": self.residual_rms * 1e6,
                  "residual_ptp_um": self.residual_ptp * 1e6,
                  "feed_mm_per_min": None if self.feed is None else self.feed * 6e4,
                  "iso230_4": {**self.circular.as_dict(),
                               "folded": [f.as_dict() for f in self.folded]},
                  "ranking": [{"term": t.key, "value": t.value, "unit": t.unit,
                               "effect_um": t.ptp * 1e6, "share_percent": t.share * 100,
                               "advice": t.advice} for t in self.terms],
                  "warnings": list(self.warnings)})
        return d

    def __str__(self) -> str:
        return self.text()

    def text(self, name=None) -> str:
        """The diagnosis as a ranked table for a person.

        ``name(key, axes)`` names each term: the commands pass the reports' labels
        (:func:`axiscal.report.labels.quantity`); by default the key in words with the plane's
        axes (``backlash_x`` → ``backlash X``), never the code key.
        """
        c = self.circular
        axes = c.squareness.axes
        names = [(name or _words)(t.key, axes) for t in self.terms]
        w = max([19, *map(len, names)])
        lines = [f"ballbar diagnosis R = {c.radius * 1e3:g} mm over {c.arc_deg:.0f}°"
                 + ("" if self.feed is None else f", feed {self.feed * 6e4:g} mm/min"),
                 f"  ISO 230-4:2005 §3: G ccw {_um(c.G_ccw)}, G cw {_um(c.G_cw)}, "
                 f"H {_um(c.H)}, F max {_um(c.F_max)}, F min {_um(c.F_min)}",
                 *self.folded_lines(),
                 f"  rank  {'term':<{w}}  value            effect   share  advice"]
        for i, (t, n) in enumerate(zip(self.terms, names), 1):
            lines.append(f"  {i:>4}  {n:<{w}} {t.value:>+9.3f} {t.unit:<6} "
                         f"{t.ptp * 1e6:>7.3f} µm {t.share * 100:>5.0f} %  {t.advice}")
        lines.append(f"  residual after the model: {self.residual_rms * 1e6:.3f} µm rms, "
                     f"{self.residual_ptp * 1e6:.3f} µm peak-to-valley")
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines)

    def folded_lines(self) -> list[str]:
        """The statements of :attr:`folded` whose difference the readings resolve."""
        return [f"  {f}" for f in self.folded if f.material]


def _words(key: str, axes) -> str:
    """A term's key in words with the plane's axes: ``backlash_x`` → ``backlash X``."""
    return " ".join({"x": axes[0], "y": axes[1]}.get(p, p) for p in key.split("_"))


def diagnose(runs, radius: float, *, feed: float | None = None,
             axes: tuple[str, str] = ("X", "Y"), datum: str = "") -> BallbarDiagnosis:
    """Diagnose a circular test from its CCW and CW runs.

    Parameters
    ----------
    runs : sequence of CircularRun
        One CCW and one CW run (full circle or an arc of at least 220°).
    radius : float, m
    feed : float or None, m/s
        Contouring feed; servo mismatch (ms) and vibration (Hz) need it.
    axes : (str, str)
        The plane's axes (keys keep ``x`` and ``y`` for the first and second axis).
    datum : str
        Datum axis of the ISO 230-1 sign of the squareness (default the first axis).

    Returns
    -------
    BallbarDiagnosis

    Raises
    ------
    InputError
        Not one run of each direction, an arc under 220°, a bad radius or feed.

    Examples
    --------
    >>> from axiscal.standards.iso230_4 import CircularRun
    >>> phi = np.radians(np.arange(0, 360, 0.5))
    >>> dr = -(20e-6 * 0.1 / 2) * np.sin(2 * phi)         # 20 µm/m squareness, R = 100 mm
    >>> d = diagnose([CircularRun(phi, dr, "ccw"), CircularRun(phi, dr, "cw")], 0.1)
    >>> round(d.values["squareness_um_per_m"], 6), d.terms[0].key
    (20.0, 'squareness')
    """
    runs = list(runs)
    if len(runs) != 2 or {r.direction for r in runs} != {"ccw", "cw"}:
        raise InputError("the diagnosis needs one CCW and one CW run")
    if feed is not None and not (math.isfinite(feed) and feed > 0):
        raise InputError(f"feed={feed!r} m/s: must be positive")
    circ = evaluate_circular(runs, radius, axes=axes, datum=datum)
    by = {r.direction: r for r in runs}
    phi, ccw, cw = _common(by["ccw"], by["cw"], circ.arc_deg)
    y = np.concatenate([ccw, cw])
    fit = _fit(phi, y, radius)
    return _assemble(circ, phi, y, fit, radius, feed, axes)


# --- the fit -------------------------------------------------------------------------------------

_LINEAR = ("centre_r", "centre_x", "centre_y", "scale", "square", "shift_r", "shift_x",
           "shift_y", "servo", "backlash_x", "backlash_y", "lateral_x", "lateral_y",
           "straight_x", "straight_y", "spike_x", "spike_y")


def _columns(phi: np.ndarray, radius: float) -> np.ndarray:
    """Design matrix of both runs (CCW rows then CW rows): the 15 fixed columns of _LINEAR, then
    the X spike column for each of _DECAYS, then the Y spike column for each. Column-major, each
    column filled in place (the sines and cosines are the same for both runs)."""
    n, nd = phi.size, _DECAYS.size
    c, s = np.cos(phi), np.sin(phi)
    h = _harmonics(phi)
    m = np.empty((2 * n, 15 + 2 * nd), order="F")
    rate = -radius / _DECAYS
    for k, sense in enumerate((1.0, -1.0)):
        blk = m[k * n:(k + 1) * n]
        sx, sy = velocity_signs(s, c, sense)
        blk[:, :5] = h
        blk[:, 5:8] = sense * 0.5 * h[:, :3]
        blk[:, 8] = sense * 0.5 * h[:, 4]
        blk[:, 9], blk[:, 10] = 0.5 * sx * c, 0.5 * sy * s        # = _backlash_basis
        blk[:, 11], blk[:, 12] = 0.5 * sx * s, 0.5 * sy * c
        blk[:, 13], blk[:, 14] = c * c * s, s * s * c
        ax = np.mod(sense * phi, np.pi)                 # travel angle since the X reversal
        ay = np.mod(sense * (phi - np.pi / 2), np.pi)   # ... since the Y reversal
        for col, travel, weight in ((15, ax, np.abs(c)), (15 + nd, ay, np.abs(s))):
            spikes = blk[:, col:col + nd]                   # filled in place
            np.multiply.outer(travel, rate, out=spikes)
            np.exp(spikes, out=spikes)
            spikes *= weight[:, None]
    return m


@dataclass(frozen=True)
class _Fit:
    coef: dict
    decay: tuple[float, float]
    cyclic: dict
    model: dict          # term -> its Δr contribution on the stacked rows
    residual: np.ndarray
    observable: dict
    gram: np.ndarray     # AᵀA of the final columns (_LINEAR, then the 4 cyclic columns)
    c: np.ndarray        # their coefficients


def _fit(phi, y, radius) -> _Fit:
    """Linear terms by least squares, the spike decays by a coordinate search on the normal
    equations of all candidate columns (one product, then 15+2 column systems per candidate);
    the final system with the cyclic columns is bordered onto the same product."""
    m = _columns(phi, radius)
    nf, nd = 15, _DECAYS.size
    gram, rhs = normal_equations(m, y)
    yy = float(np.einsum("i,i", y, y))          # not BLAS ddot: no threads woken
    pick = [nf + nd // 2, nf + nd + nd // 2]
    for axis in (0, 1, 0, 1):
        best = None
        for j in range(nd):
            idx = list(range(nf)) + pick
            idx[nf + axis] = nf + axis * nd + j
            c = np.linalg.lstsq(gram[np.ix_(idx, idx)], rhs[idx], rcond=None)[0]
            sse = yy - float(c @ rhs[idx])
            if best is None or sse < best[0] - 1e-18 * yy:
                best = (sse, idx[nf:], c)
        pick = best[1]
    sel = list(range(nf)) + pick
    a = m[:, sel]
    decay = (float(_DECAYS[pick[0] - nf]), float(_DECAYS[pick[1] - nf - nd]))
    cyc_cols, cyclic = _cyclic(phi, y - block_product(a, best[2]), radius)
    cc, cross = normal_equations(cyc_cols, a)
    cy = normal_equations(cyc_cols, y)[1]
    g = np.block([[gram[np.ix_(sel, sel)], cross.T], [cross, cc]])
    c = np.linalg.lstsq(g, np.concatenate([rhs[sel], cy]), rcond=None)[0]
    model = {k: a[:, i] * c[i] for i, k in enumerate(_LINEAR)}
    model["cyclic_x"] = block_product(cyc_cols[:, :2], c[-4:-2])
    model["cyclic_y"] = block_product(cyc_cols[:, 2:], c[-2:])
    cyclic["x_amp"] = float(math.hypot(*c[-4:-2]))
    cyclic["y_amp"] = float(math.hypot(*c[-2:]))
    norms = np.sqrt(np.diag(g) / len(y))
    observable = {k: bool(norms[i] > 1e-3) for i, k in enumerate(_LINEAR)}
    residual = y - block_product(a, c[:-4]) - model["cyclic_x"] - model["cyclic_y"]
    return _Fit(dict(zip(_LINEAR, map(float, c))), decay, cyclic, model, residual, observable,
                g, c)


def _cyclic(phi, res, radius):
    """Pitch of each axis's cyclic error: grid search of the projections of the mean residual of
    the two runs (a cyclic error of position is the same in both directions).

    The search only ranks the candidate pitches, so it runs in single precision (5x faster sines
    here; a rounding of 1e-4 rad moves a pick by at most one step of the fine grid, where the
    power is flat); the columns of the chosen pitch are then formed in double precision."""
    n = phi.size
    mean = 0.5 * (res[:n] + res[n:])
    dphi = 2 * np.pi / max(n, 8)
    pitches = np.geomspace(max(8 * radius * dphi, radius / 200), radius / 2, 48)
    cols, out = [], {}
    for name, w in (("x", np.cos(phi)), ("y", np.sin(phi))):
        peak = float(np.max(np.abs(mean))) or 1.0   # ranking is scale-free: no float32 underflow
        w32, mean32 = w.astype(np.float32), (mean / peak).astype(np.float32)
        i = int(np.argmax(_cyclic_power(pitches, w32, mean32, radius)))
        fine = np.geomspace(pitches[max(i - 1, 0)], pitches[min(i + 1, pitches.size - 1)], 24)
        pitch = float(fine[int(np.argmax(_cyclic_power(fine, w32, mean32, radius)))])
        out[f"{name}_pitch"] = pitch
        arg = 2 * np.pi * radius / pitch * w
        cols += [np.tile(w * np.sin(arg), 2), np.tile(w * np.cos(arg), 2)]
    return np.column_stack(cols), out


def _cyclic_power(pitches, w, mean, radius):
    """Power of the mean residual projected on w·sin and w·cos of each pitch's phase 2πr·w/p,
    in the precision of ``w`` and ``mean``."""
    arg = (2 * np.pi * radius / pitches).astype(w.dtype)[:, None] * w[None, :]
    sn = np.sin(arg)
    sn *= w
    cs = np.cos(arg, out=arg)                   # in place: two arrays of pitches × readings
    cs *= w
    ss = np.einsum("ij,ij->i", sn, sn)          # einsum, not BLAS: no threads woken
    return np.einsum("ij,j->i", sn, mean) ** 2 / ss + \
        np.einsum("ij,j->i", cs, mean) ** 2 / (np.einsum("i,i", w, w) - ss)   # sin² + cos² = 1


# --- the result ----------------------------------------------------------------------------------

def _assemble(circ, phi, y, fit: _Fit, radius, feed, axes) -> BallbarDiagnosis:
    c, warnings = fit.coef, []
    v = {"squareness_um_per_m": -2 * c["square"] / radius * 1e6,
         "scale_mismatch_um_per_m": 2 * c["scale"] / radius * 1e6,
         "backlash_x_um": c["backlash_x"] * 1e6, "backlash_y_um": c["backlash_y"] * 1e6,
         "lateral_play_x_um": c["lateral_x"] * 1e6, "lateral_play_y_um": c["lateral_y"] * 1e6,
         "straightness_x_um": c["straight_x"] * 1e6, "straightness_y_um": c["straight_y"] * 1e6,
         "reversal_spike_x_um": c["spike_x"] * 1e6, "reversal_spike_y_um": c["spike_y"] * 1e6,
         "reversal_spike_x_decay_mm": fit.decay[0] * 1e3,
         "reversal_spike_y_decay_mm": fit.decay[1] * 1e3,
         "cyclic_x_um": fit.cyclic["x_amp"] * 1e6, "cyclic_x_pitch_mm": fit.cyclic["x_pitch"] * 1e3,
         "cyclic_y_um": fit.cyclic["y_amp"] * 1e6, "cyclic_y_pitch_mm": fit.cyclic["y_pitch"] * 1e3,
         "servo_mismatch_ms": None, "servo_term_um": c["servo"] * 1e6}
    if feed is not None:
        v["servo_mismatch_ms"] = c["servo"] / feed * 1e3   # column s sin 2φ / 2: coef v Δτ
    else:
        warnings.append("no feed given: servo mismatch stays a length (the servo term, µm), "
                        "not ms, and vibration has no frequency")
    for k in ("spike_x", "spike_y", "backlash_x", "backlash_y"):
        if not fit.observable[k]:
            warnings.append(f"{k}: its reversal point lies outside the arc; not observable")
    stick, vib = _stick_slip(phi, fit.residual), _vibration(phi, fit.residual, radius, feed)
    v.update({"stick_slip_um": stick * 1e6, "vibration_um": vib[1] * 1e6,
              "vibration_hz": vib[0]})
    terms = _rank(fit, circ, v, stick, vib[1])
    res = fit.residual
    rms = float(np.sqrt(np.mean(res**2)))
    return BallbarDiagnosis(circ, v, terms, rms, float(np.ptp(res)), feed,
                            tuple(warnings) + circ.warnings,
                            _folded(circ, fit, v, radius, axes, rms))


#: Columns of the ISO 230-4 two-direction fit among _LINEAR (centre, radius, shift, scale,
#: squareness, backlash); the others, and the four cyclic columns, are what it lacks.
_ISO_COLUMNS = (0, 1, 2, 3, 4, 5, 6, 7, 9, 10)
_FOLDED = (  # quantity, ISO column, value key, unit, its value per unit of the column's
    # coefficient at radius R (as _assemble), the ISO 230-4 value from the CircularResult
    ("squareness", 4, "squareness_um_per_m", "µm/m", lambda R: -2 / R * 1e6,
     lambda r: r.squareness.um_per_m),
    ("scale_mismatch", 3, "scale_mismatch_um_per_m", "µm/m", lambda R: 2 / R * 1e6,
     lambda r: r.scale_mismatch * 1e6),
    ("backlash_x", 9, "backlash_x_um", "µm", lambda R: 1e6, lambda r: r.backlash_x * 1e6),
    ("backlash_y", 10, "backlash_y_um", "µm", lambda R: 1e6, lambda r: r.backlash_y * 1e6),
)


def _folded(circ, fit: _Fit, v, radius, axes, rms) -> tuple[FoldedError, ...]:
    """What the ISO 230-4 fit folds into each of its figures (module docstring): the regression
    of every column it lacks on its own columns, times that column's coefficient."""
    iso = list(_ISO_COLUMNS)
    other = [i for i in range(fit.c.size) if i not in _ISO_COLUMNS]
    g = fit.gram
    x = np.linalg.lstsq(g[np.ix_(iso, iso)], g[np.ix_(iso, other)], rcond=None)[0] * fit.c[other]
    names = [_RANK_KEY[_LINEAR[i]] if i < len(_LINEAR) else f"cyclic_{'xxyy'[i - len(_LINEAR)]}"
             for i in other]
    out = []
    for quantity, col, vkey, unit, per_coef, iso_value in _FOLDED:
        parts: dict[str, float] = {}
        for name, amount in zip(names, x[iso.index(col)] * per_coef(radius)):
            parts[name] = parts.get(name, 0.0) + float(amount)
        full = v[vkey]
        effect = abs(iso_value(circ) - full) * 1e-6 * (1.0 if unit == "µm" else radius)  # m
        out.append(FoldedError(
            quantity, _axis_label(quantity, axes), unit, float(iso_value(circ)), float(full),
            tuple(sorted(((k, _axis_label(k, axes), a) for k, a in parts.items()),
                         key=lambda p: -abs(p[2]))),
            bool(effect > max(rms, 1e-9))))
    return tuple(out)


def _axis_label(key: str, axes) -> str:
    """``backlash_x`` -> ``backlash X`` (the plane's axis letters), ``servo_mismatch`` ->
    ``servo mismatch``."""
    for suffix, axis in (("_x", axes[0]), ("_y", axes[1])):
        if key.endswith(suffix):
            return f"{key[:-2].replace('_', ' ')} {axis}"
    return key.replace("_", " ")


_TERMS = (  # ranking key, model parts, value key, unit
    ("squareness", ("square",), "squareness_um_per_m", "µm/m"),
    ("scale_mismatch", ("scale",), "scale_mismatch_um_per_m", "µm/m"),
    ("servo_mismatch", ("servo",), "servo_mismatch_ms", "ms"),
    ("backlash_x", ("backlash_x",), "backlash_x_um", "µm"),
    ("backlash_y", ("backlash_y",), "backlash_y_um", "µm"),
    ("lateral_play_x", ("lateral_x",), "lateral_play_x_um", "µm"),
    ("lateral_play_y", ("lateral_y",), "lateral_play_y_um", "µm"),
    ("straightness_x", ("straight_x",), "straightness_x_um", "µm"),
    ("straightness_y", ("straight_y",), "straightness_y_um", "µm"),
    ("reversal_spike_x", ("spike_x",), "reversal_spike_x_um", "µm"),
    ("reversal_spike_y", ("spike_y",), "reversal_spike_y_um", "µm"),
    ("cyclic_x", ("cyclic_x",), "cyclic_x_um", "µm"),
    ("cyclic_y", ("cyclic_y",), "cyclic_y_um", "µm"),
)


#: The ranking key of each model part (``servo`` -> ``servo_mismatch``).
_RANK_KEY = {p: key for key, parts, _, _ in _TERMS for p in parts}


def _rank(fit, circ, v, stick, vib_amp) -> tuple[DiagnosisTerm, ...]:
    g = max(x for x in (circ.G_ccw, circ.G_cw, 1e-12) if x is not None)
    out = []
    for key, parts, vkey, unit in _TERMS:
        ptp = float(np.ptp(sum(fit.model[p] for p in parts)))
        value = v[vkey]
        if value is None:
            value, unit = v["servo_term_um"], "µm"
        out.append(DiagnosisTerm(key, float(value), unit, ptp, ptp / g, ADVICE[key]))
    out.append(DiagnosisTerm("stick_slip", stick * 1e6, "µm", stick, stick / g,
                             ADVICE["stick_slip"]))
    out.append(DiagnosisTerm("vibration", vib_amp * 1e6, "µm", 2 * vib_amp, 2 * vib_amp / g,
                             ADVICE["vibration"]))
    rp = float(np.ptp(fit.residual))
    out.append(DiagnosisTerm("residual", rp * 1e6, "µm", rp, rp / g, ADVICE["residual"]))
    return tuple(sorted(out, key=lambda t: -t.ptp))


def _stick_slip(phi, res) -> float:
    """Residual peak-to-valley near reversals (|sin| or |cos| < 0.1) beyond the rest's."""
    p2 = np.concatenate([phi, phi])
    near = (np.abs(np.sin(p2)) < 0.1) | (np.abs(np.cos(p2)) < 0.1)
    if near.sum() < 2 or (~near).sum() < 2:
        return 0.0
    return float(max(0.0, np.ptp(res[near]) - np.ptp(res[~near])))


def _vibration(phi, res, radius, feed) -> tuple[float | None, float]:
    """Largest line of the residual's amplitude spectrum (CCW run, uniform angle grid)."""
    n = phi.size
    r = res[:n] - res[:n].mean()
    if n < 16:
        return None, 0.0
    spec = 2 * np.abs(np.fft.rfft(r)) / n
    spec[:5] = 0.0                                  # harmonics up to 4/rev are modelled terms
    i = int(np.argmax(spec))
    span = abs(phi[-1] - phi[0]) * n / max(n - 1, 1) * radius   # path length of the run, m
    hz = None if feed is None else float(i * feed / span)
    return hz, float(spec[i])


def _um(v):
    return "—" if v is None else f"{v * 1e6:.3f} µm"
