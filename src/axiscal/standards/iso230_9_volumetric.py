"""Uncertainty of a volumetric map's figures from the uncertainty of its 21 geometric errors.

The volumetric error of :func:`axiscal.standards.volumetric.volumetric_error` (ISO/TR
16907:2015 rigid-body model; Schwenke et al. 2008, eq. 3) is *linear* in the error motions'
values and the three squareness errors, so the law of propagation of uncertainty (JCGM
100:2008 §5.1.2 eq. 10; §5.2.2 eq. 13 with correlated inputs) is exact for it, and every
sensitivity coefficient is the model itself evaluated with one input alone (superposition of a
linear model: no second implementation of the chain, no truncation).

The inputs
----------
Each error motion measured along its axis has an expanded uncertainty U (k = 2) of its values
*relative to the reference point* ``c`` through which the measuring lines passed (the model
takes every function relative to ``c``, so its value there is exactly zero and carries none):

- positioning ``EXX``, ``EYY``, ``EZZ`` (ISO 230-2 tests): U = a + b·L, L = |u − c| the
  distance from the reference point (µm and µm/m);
- straightness ``EYX`` … (ISO 230-1 §3.4): U in µm;
- angular ``EAX`` … (pitch, yaw, roll): U in µrad (1 arcsec = 4.848 µrad; the configuration's
  inline angles are arcsec by default and µrad as ``volumetric map --inline`` writes them: the
  model holds radians, this table µrad);
- squareness ``xy``, ``yz``, ``zx``: U in µm/m, as the configuration's ``[squareness]``.

An inline error of the configuration may carry its own ``U`` (same unit as its values, k = 2):
it is used over the class's (the measurement's own statement wins over a default).

The correlation model (input ``correlation``)
---------------------------------------------
A figure that is a range is a difference of the error at two grid points, and each error
function acts on both: GUM §5.2 (correlated inputs). Two models are offered:

- ``scale`` (default): each function's measurement error is one error of shape along its axis,
  fully correlated from point to point: a linear ramp through ``c`` reaching the function's
  standard uncertainty at the end of the travel farthest from ``c`` (a scale or slope error,
  as a laser's wavelength or gain error, or an optics' misalignment, gives). Two points on the
  same side of ``c`` move together and a common part cancels in their difference; two points on
  opposite sides move apart.
- ``independent``: the error at each position along the axis is independent of the error at
  any other position (correlation 0), and the same at the same position (correlation 1: the
  reading is one): reading noise and short-period set-up effects.

Either model is stated in the budget's method and notes. The squareness is one number: always
common to both points.

The figures
-----------
``largest`` = |E(p*)| at the grid point p* where it is largest: δ|E| = (E/|E|)·δE(p*);
``range_A`` = E_A(p_max) − E_A(p_min) at the grid points that attain the maximum and the
minimum; ``diagonal_NAME`` = (E(p_a) − E(p_b))·e, the range along a body diagonal of direction
e (ISO 230-6:2002; its start's error cancels). The locus (p*, p_max, p_min, p_a, p_b) is held
fixed: the first-order propagation of JCGM 100:2008 §5.1.2 about the measured values; an input
that moves the extreme to another point is not followed (a maximum is not differentiable there).

Not included (a note says so): error motions not measured (taken as zero by the map), the
rigid-body model's own error (ISO/TR 16907:2015: non-rigid effects), the grid's sampling of the
volume and the tool offset's uncertainty.

References
----------
ISO/TR 16907:2015, Machine tools — Numerical compensation of geometric errors.
ISO 230-1:2012, Test code for machine tools — Part 1 (the error motions and their notation).
ISO 230-6:2002, Test code for machine tools — Part 6: Determination of positioning accuracy on
body and face diagonals. ISO/TR 230-9:2005, Part 9: Estimation of measurement uncertainty for
machine tool tests according to series ISO 230, basic equations (k = 2). JCGM 100:2008 (GUM)
§5.1.2, §5.2.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Mapping

import numpy as np

from axiscal.errors import ConfigError
from axiscal.standards.iso230_9 import Contributor, combine
from axiscal.standards.iso230_9_inputs import BudgetInput
from axiscal.standards.volumetric import (AXES, ERROR_NAMES, PAIRS, ErrorFunction,
                                          GeometricErrors, volumetric_error)

__all__ = ["VOLUMETRIC_INPUTS", "CORRELATIONS", "error_class", "volumetric_budget"]

#: key -> (label, unit, default, basis of the default). Every default is an assumption, marked
#: so on every budget that takes it: set each from the measurements' own budgets.
VOLUMETRIC_INPUTS = {
    "positioning_a": ("U (k = 2) of a positioning error, constant part a", "µm", 0.5,
                      "a laser interferometer's reading and set-up"),
    "positioning_b": ("U (k = 2) of a positioning error, length part b", "µm/m", 2.0,
                      "a laser's wavelength (0.5 µm/m) and the material temperature "
                      "known to ±0.1 K (1.2 µm/m for steel)"),
    "straightness": ("U (k = 2) of a straightness error", "µm", 1.0,
                     "straightness optics of a laser interferometer"),
    "angular": ("U (k = 2) of an angular error", "µrad", 2.0,
                "angular optics of a laser interferometer (about 0.4 arcsec)"),
    "squareness": ("U (k = 2) of a squareness error", "µm/m", 2.0,
                   "a squareness measured by ISO 230-1 with a calibrated reference"),
    "k": ("coverage factor", "", 2.0, "ISO/TR 230-9:2005: k = 2"),
}
#: The correlation models (module docstring) by the input ``correlation``.
CORRELATIONS = {
    "scale": "each error function's uncertainty fully correlated along its axis (a linear "
             "scale error through the reference point, its U at the far end of the travel)",
    "independent": "each error function's uncertainty independent from position to position "
                   "(the same at the same position)",
}
#: How a user sets an input.
SET_WITH = "[volumetric_uncertainty] {key} in the user configuration"
#: Coverage factor of the inputs' U (as certificates state them).
_K_IN = 2.0
#: Contributor symbols by error class.
_CLASSES = {"positioning": "u_POS", "straightness": "u_STR", "angular": "u_ANG",
            "squareness": "u_SQ"}
_CLAUSE = ("ISO/TR 16907:2015 rigid-body model; JCGM 100:2008 §5.1.2, §5.2 (sensitivity by the "
           "model)")
#: Amplitude of a unit input (m or rad): small against the model's limit, exact (linear model).
_UNIT = 1e-6
#: A figure's u_c at most this (µm) is no U: no measured error acts on it.
_NONE = 1e-9


def error_class(name: str) -> str:
    """``positioning``, ``straightness``, ``angular`` or ``squareness`` of an error's name.

    >>> [error_class(n) for n in ("EXX", "EYX", "ECZ", "xy")]
    ['positioning', 'straightness', 'angular', 'squareness']
    """
    if name in PAIRS:
        return "squareness"
    if name[1] in "ABC":
        return "angular"
    return "positioning" if name[1] == name[2] else "straightness"


def volumetric_budget(errors: GeometricErrors, vmap, diagonals=(),
                      table: Mapping[str, object] | None = None,
                      given: Mapping[str, float] | None = None):
    """The uncertainty of a volumetric map's figures from the U of its geometric errors.

    Parameters
    ----------
    errors : GeometricErrors
        The 21 errors the map was made from.
    vmap : VolumetricMap
        The map (:func:`~axiscal.standards.volumetric.map_volume`): its grid, error field and
        tool offset (reused, not recomputed).
    diagonals : sequence of BodyDiagonal
        The body diagonals (:func:`~axiscal.standards.volumetric.body_diagonals`) at the same
        tool offset.
    table : mapping, optional
        The user configuration's ``[volumetric_uncertainty]`` table: keys of
        :data:`VOLUMETRIC_INPUTS` (each in its unit, U with k = 2) and ``correlation``
        (``scale`` or ``independent``, :data:`CORRELATIONS`); absent inputs take the defaults,
        marked assumed.
    given : mapping of str to float, optional
        U (k = 2, SI: m or rad) of single error motions stated in the configuration itself
        (``U`` of an inline error); used over the class's input.

    Returns
    -------
    UncertaintyBudget
        Unit ``um``; parameters ``largest``, ``range_X``, ``range_Y``, ``range_Z`` and
        ``diagonal_<name>`` as :func:`axiscal.store.kinds.evaluate_file` names them (a figure
        no measured error acts on has no U, a note says so; U = 0 is never stated); one
        contributor per figure and error class (``u_POS,range_X`` …), its basis each error's
        share.

    Raises
    ------
    ConfigError
        A key that is no input, a value that is not a finite number ≥ 0 (k > 0), or a
        correlation that is neither model.

    Notes
    -----
    A figure F = Σ_j w_j·E(p_j) over its points p_j (weights ±1 on one component, or the
    direction of |E| or of a diagonal). For an error function f with standard uncertainty u(s)
    at position s of its axis and the model's response R(p) to a unit ramp
    r(s) = (s − c)/L_far of f alone (L_far the distance from c to the farther end of the
    travel), c_j = w_j·R(p_j) is exact (linear model). JCGM 100:2008 §5.2.2 eq. 13:

    - scale (r = 1 between all points): u_f(F) = |Σ_j c_j|·u(L_far);
    - independent: u_f(F)² = Σ_s (Σ_{j: s_j = s} c_j / r(s_j))²·u(s)², the points grouped by
      their position s_j along f's axis (r = 1 within a group, 0 between groups);
    - squareness θ: u_θ(F) = |Σ_j w_j·R_θ(p_j)|·u(θ) for a unit θ.

    u_c(F)² = Σ_f u_f(F)² (the functions measured independently), U = k·u_c.

    Examples
    --------
    Only EXX measured, X travel 0-100 mm, reference at 50 mm, U = 1 µm constant (a = 1, b = 0),
    the squareness's U 0 (its U acts even where no squareness is given): the range of E_X is
    E_X(100) − E_X(0).

    >>> from axiscal.standards.volumetric import KinematicChain, map_volume
    >>> f = ErrorFunction([0.0, 0.1], [0.0, 10e-6])
    >>> e = GeometricErrors(KinematicChain.parse("X Y | Z"), {"EXX": f}, {},
    ...                     [0.05, 0.05, -0.05], [0, 0, 0],
    ...                     {"X": (0.0, 0.1), "Y": (0.0, 0.1), "Z": (-0.1, 0.0)})
    >>> m = map_volume(e, 11)
    >>> t = {"positioning_a": 1.0, "positioning_b": 0.0, "squareness": 0.0}
    >>> b = volumetric_budget(e, m, (), {**t, "correlation": "independent"})
    >>> round(b.U("range_X"), 6), b.U("range_Y"), round(b.U("largest"), 6)
    (1.414214, None, 1.000000)
    >>> round(volumetric_budget(e, m, (), {**t, "correlation": "scale"}).U("range_X"), 6)
    2.000000

    By hand: u = U/2 = 0.5 µm at each end. Independent (two positions): u_c = √(0.5² + 0.5²),
    U = 2·0.7071 = 1.4142 µm. Scale: the ramp is +0.5 µm at 100 mm and −0.5 µm at 0, both
    100 % correlated: u_c = 0.5 + 0.5 = 1.0, U = 2.0 µm. The largest |E| (5 µm at an end) moves
    with E_X there: U = 2·0.5 = 1.0 µm. E_Y is untouched by EXX: no U is stated (not U = 0).
    """
    v, correlation = _inputs(table)
    given = dict(given or {})
    points, figures = _figures(vmap, diagonals)
    c = errors.reference
    t = vmap.tool_offset
    shares: dict[str, dict[str, float]] = {f: {} for f in figures}
    for name in ERROR_NAMES + PAIRS:
        if name in ERROR_NAMES and name not in errors.functions:
            continue                                  # not measured: taken as zero, said
        response, ratio, spread = _response(errors, name, points, t)
        for fig, (idx, w) in figures.items():
            cj = np.einsum("ij,ij->j", w, response[:, idx])      # c_j = w_j·R(p_j), m per unit
            if name in PAIRS:
                u_f = abs(cj.sum()) * _u(name, v, given, 0.0)
            elif correlation == "scale":
                u_f = abs(cj.sum()) * _u(name, v, given, spread[0])
            else:
                u_f = _independent(cj, ratio[idx], points[AXES.index(name[2]), idx] - c[
                    AXES.index(name[2])], name, v, given)
            shares[fig][name] = u_f / _UNIT * 1e6             # µm
    contributors = []
    for fig, by in shares.items():
        for cls, symbol in _CLASSES.items():
            names = [n for n in by if error_class(n) == cls]
            if not names:
                continue
            u = math.sqrt(sum(by[n] ** 2 for n in names))
            basis = "√Σ of " + ", ".join(f"{n} {by[n]:.3g}" for n in names) + " µm"
            contributors.append(Contributor(f"{symbol},{fig}", f"{cls} errors on {fig}", u,
                                            "normal", _CLAUSE, basis, (fig,)))
    inputs = tuple(BudgetInput(key, label, v[key], unit, key not in (table or {}),
                               SET_WITH.format(key=key),
                               rule if key not in (table or {}) else "")   # given
                   for key, (label, unit, _, rule) in VOLUMETRIC_INPUTS.items())
    inputs += tuple(BudgetInput(n, f"U (k = 2) of {n}", given[n] * (1e6), "µrad" if n[1] in "ABC"
                                else "µm", False, f"U of [errors] {n} in the volumetric "
                                "configuration", "given in the volumetric configuration")
                    for n in ERROR_NAMES if n in given and n in errors.functions)
    # printed on reports and certificates: words, no configuration key (each input's key is
    # its set_with, on the workbench and in the JSON)
    other = next(m for m in CORRELATIONS if m != correlation)
    notes = (f"correlation model: {correlation}: {CORRELATIONS[correlation]}; the other model, "
             f"{other}, is chosen by the correlation input of the user configuration's "
             "volumetric uncertainty table",
             "the locus of each figure (the grid point of the largest |E|, the points of each "
             "range) held fixed: first-order propagation, JCGM 100:2008 §5.1.2")
    assumed = [f"{i.label} {i.value:g} {i.unit}".strip() for i in inputs
               if i.assumed and i.name != "k"]
    if assumed:
        notes += ("assumed (set each in the user configuration's volumetric uncertainty "
                  "table): " + "; ".join(assumed),)
    if errors.missing:
        notes += (f"not measured, taken as zero, so not in U: {', '.join(errors.missing)}",)
    covered = tuple(f for f, by in shares.items() if math.fsum(u * u for u in by.values())
                    > _NONE ** 2)
    if len(covered) < len(figures):       # U = 0 is never stated (only unmeasured errors act)
        notes += ("no U for " + ", ".join(_words(f) for f in figures if f not in covered)
                  + ": none of the measured errors acts on it",)
    notes += ("not included: the rigid-body model's own error (non-rigid effects), the grid's "
              "sampling of the volume, the tool offset's uncertainty",)
    return replace(combine(contributors, "um", v["k"], covered, notes), inputs=inputs,
                   method=f"ISO/TR 16907:2015 model, GUM §5.1.2/§5.2 with sensitivity "
                          f"coefficients by the model; correlation model: {correlation}")


# -- helpers ---------------------------------------------------------------------------------
def _words(figure: str) -> str:
    """A figure's key in words (``range_X``: the range along X)."""
    if figure == "largest":
        return "the largest |E|"
    kind, name = figure.split("_", 1)
    return f"the range along {name}" if kind == "range" else f"the range along diagonal {name}"


def _inputs(table) -> tuple[dict, str]:
    """The inputs' values (defaults for the absent) and the correlation model, checked."""
    from axiscal.standards.iso230_9_entry import checked_table

    table = checked_table(table, VOLUMETRIC_INPUTS, "[volumetric_uncertainty]",
                          extra=("correlation",))
    correlation = table.pop("correlation", "scale")
    if correlation not in CORRELATIONS:
        raise ConfigError(f"[volumetric_uncertainty] correlation = {correlation!r:.40}: "
                          f"use {' or '.join(CORRELATIONS)}")
    return ({key: float(table.get(key, d)) for key, (_, _, d, _) in VOLUMETRIC_INPUTS.items()},
            correlation)


def _figures(vmap, diagonals):
    """The points every figure is formed at (3, m), and per figure its point indices and
    weights (3, n): F = Σ_j w_j·E(p_j)."""
    pts, figures = [], {}

    def add(p) -> int:
        pts.append(np.asarray(p, dtype=float))
        return len(pts) - 1

    grid = vmap.grid

    def at(flat: int, field) -> np.ndarray:
        idx = np.unravel_index(flat, field.shape)
        return np.array([g[i] for g, i in zip(grid, idx)])

    mag = vmap.magnitude
    top = int(np.argmax(mag))
    e_top = vmap.error.reshape(3, -1)[:, top]
    if np.linalg.norm(e_top) > 0:
        figures["largest"] = ([add(at(top, mag))], (e_top / np.linalg.norm(e_top))[:, None])
    for i, a in enumerate(AXES):
        comp = vmap.error[i]
        w = np.zeros((3, 2))
        w[i] = (1.0, -1.0)
        figures[f"range_{a}"] = ([add(at(int(np.argmax(comp)), comp)),
                                  add(at(int(np.argmin(comp)), comp))], w)
    for d in diagonals:
        span = d.end - d.start
        e = span / np.linalg.norm(span)
        ends = [int(np.argmax(d.deviation)), int(np.argmin(d.deviation))]
        p = [d.start + span * (d.distance[j] / d.distance[-1]) for j in ends]
        figures[f"diagonal_{d.name}"] = ([add(p[0]), add(p[1])], np.stack([e, -e], axis=1))
    return np.stack(pts, axis=1), figures


def _response(errors: GeometricErrors, name: str, points: np.ndarray, tool_offset):
    """The model's error at ``points`` (3, m) with input ``name`` alone at unit amplitude
    (:data:`_UNIT` m or rad): a ramp through the reference point reaching it at the far end of
    the travel, or a squareness of it; with the ramp's value at each point's position and the
    ramp's reach L_far (m). The model is linear: this response is its sensitivity, exactly."""
    c = errors.reference
    if name in PAIRS:
        alone = GeometricErrors(errors.chain, {}, {name: _UNIT}, c,
                                errors.measured_tool_offset, errors.travel)
        return volumetric_error(alone, *points, tool_offset), None, (0.0,)
    i = AXES.index(name[2])
    lo, hi = errors.travel[name[2]]
    far = max(hi - c[i], c[i] - lo)
    s = np.array([min(lo, c[i]), max(hi, c[i])])
    ramp = ErrorFunction(s, _UNIT * (s - c[i]) / far, "unit ramp")
    alone = GeometricErrors(errors.chain, {name: ramp}, {}, c, errors.measured_tool_offset,
                            errors.travel)
    ratio = (points[i] - c[i]) / far
    return volumetric_error(alone, *points, tool_offset), ratio, (far,)


def _u(name: str, v: dict, given: dict, distance: float) -> float:
    """Standard uncertainty (m or rad) of error ``name``'s value at ``distance`` (m) from the
    reference point: its own U if the configuration gives one, else its class's."""
    if name in given:
        return given[name] / _K_IN
    cls = error_class(name)
    if cls == "positioning":
        U = (v["positioning_a"] + v["positioning_b"] * distance) * 1e-6
    else:
        U = v[cls] * 1e-6                  # µm, µrad and µm/m: 1e-6 to m, rad and m/m
    return U / _K_IN


def _independent(cj, ratio, offsets, name, v, given) -> float:
    """u (m) of a figure from one error function whose errors are independent from position to
    position: the points grouped by their position along the axis (the same reading)."""
    total, done = 0.0, np.zeros(len(cj), bool)
    for j in range(len(cj)):
        if done[j]:
            continue
        same = np.isclose(offsets, offsets[j], rtol=0.0, atol=1e-12)
        done |= same
        if abs(offsets[j]) <= 1e-12:
            continue                        # at the reference point: the value is zero exactly
        c = float(np.sum(cj[same] / ratio[same]))
        total += (c * _u(name, v, given, abs(float(offsets[j])))) ** 2
    return math.sqrt(total)
