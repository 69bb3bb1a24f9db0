"""One file of a squareness test from two straightness trajectories (TOML): both trajectories
and every option of ``axiscal squareness biaxial``, so a calibration history keeps the test as
one file (kind ``squareness``) and evaluates it again to the same numbers.

Format
------
Written by ``axiscal squareness biaxial X.csv Y.csv --inline FILE.toml`` and by the
workbench's "Keep as a test"; three tables, no other::

    # axiscal squareness from two straightness trajectories, every reading inline
    [biaxial]
    machine = "VMC-800"            # optional ("": the history's --machine names it)
    config = "L"                   # L, T or + (Chapman, Calibration of machine squareness)
    orientation = 180              # degrees clockwise: 0, 90, 180 or 270
    prism_error_arcsec = 0.0       # the square's angle error in orientation 0, |e| <= 3600
    reference = "least_squares"    # least_squares, end_point or minimum_zone (ISO 230-1)
    datum = ""                     # datum axis of the ISO 230-1 sign ("": the first axis)
    square = "optics"              # reference square of the budget: optics, square, reversal

    [first]                        # the first axis's trajectory, deviations along the second
    source = "squareness_L180_x.csv"
    sha256 = "9f2c..."             # of the straightness file's bytes ("" if not known)
    axis = "X"
    direction = "Y"
    position_unit = "mm"           # the units the file was written in (for display)
    deviation_unit = "um"
    positions_m = [-0.4, -0.35, ...]
    deviations_m = [1.0018078e-05, ...]

    [second]                       # the same keys: the second axis's trajectory

The readings are in metres, SI as the core holds them, each written as Python's shortest
``repr`` of the double: read back they are the same doubles bit for bit, so the squareness, its
U and every figure are those of the two straightness files (a scaled unit, mm or µm, would
round the last bit). TOML rather than two files or a CSV with sections: one self-contained file
the history stores as it stores a volumetric configuration, whose options are named keys a
reader sees and a parser checks (an unknown key, table or option is refused).

Limits: at most 1 MiB (:data:`axiscal._schema.MAX_TOML_BYTES`, about 20,000 readings in all);
each trajectory at least 2 readings at two positions, as many positions as deviations, every
number finite and within ±1e12 m; names without control characters.

:func:`read_biaxial_test` wraps :func:`parse_biaxial_test`; :func:`format_biaxial_test` writes
the format; :meth:`BiaxialTest.evaluate` is the one evaluation
(:func:`axiscal.standards.squareness_biaxial.evaluate_biaxial`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from axiscal.errors import DataFormatError
from axiscal.io.straightness import StraightnessData

__all__ = ["BiaxialTest", "biaxial_test", "parse_biaxial_test", "read_biaxial_test",
           "format_biaxial_test", "ORIENTATIONS", "REFERENCES", "MAX_PRISM_ARCSEC"]

#: The equipment's orientations, degrees clockwise (Chapman, Calibration of machine squareness).
ORIENTATIONS = (0, 90, 180, 270)
#: Reference lines of ISO 230-1:2012 §3.4.
REFERENCES = ("least_squares", "end_point", "minimum_zone")
#: Largest angle error of a square taken, arcsec (1°: a square, not a protractor).
MAX_PRISM_ARCSEC = 3600.0
#: Largest magnitude of a position or deviation, m.
MAX_METRES = 1e12

_OPTIONS = {"machine", "config", "orientation", "prism_error_arcsec", "reference", "datum",
            "square"}
_TRAJECTORY = {"source", "sha256", "axis", "direction", "position_unit", "deviation_unit",
               "positions_m", "deviations_m"}
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]")


@dataclass(frozen=True, eq=False)
class BiaxialTest:
    """A squareness test from two straightness trajectories: the readings and the options.

    Attributes
    ----------
    one, two : StraightnessData
        The first axis's trajectory (deviations along the second) and the second's; m.
    config : {"L", "T", "+"}
    orientation : {0, 90, 180, 270}, degrees
    prism_error : float, arcsec
        The square's angle error in orientation 0.
    reference : {"least_squares", "end_point", "minimum_zone"}
    datum : str
        Datum axis of the ISO 230-1 sign ("": the first axis).
    square : {"optics", "square", "reversal"}
        Reference square of the uncertainty budget.
    machine : str
        The machine's name ("": not stated).
    sha256 : (str, str)
        SHA-256 of each straightness file's bytes ("": not known).
    """

    one: StraightnessData
    two: StraightnessData
    config: str = "L"
    orientation: int = 0
    prism_error: float = 0.0
    reference: str = "least_squares"
    datum: str = ""
    square: str = "optics"
    machine: str = ""
    sha256: tuple = ("", "")

    def evaluate(self, inputs=None):
        """The squareness with its U (the ``[squareness_uncertainty]`` ``inputs``): the one
        call of ``axiscal squareness biaxial``
        (:func:`~axiscal.standards.squareness_biaxial.evaluate_biaxial`)."""
        from axiscal.standards.squareness_biaxial import evaluate_biaxial

        return evaluate_biaxial(self.one, self.two, config=self.config,
                                orientation=self.orientation, prism_error=self.prism_error,
                                reference=self.reference, datum=self.datum,
                                square=self.square, inputs=inputs)

    @property
    def title(self) -> str:
        """``Bi-axial L 180°``, as the command's figure and report head it."""
        return f"Bi-axial {self.config} {self.orientation}°"


def biaxial_test(one: StraightnessData, two: StraightnessData, *, config: str = "L",
                 orientation: int = 0, prism_error: float = 0.0,
                 reference: str = "least_squares", datum: str = "", square: str = "optics",
                 machine: str = "", sha256: tuple = ("", ""),
                 source: str = "<options>") -> BiaxialTest:
    """A :class:`BiaxialTest` with its options checked as :func:`parse_biaxial_test` checks a
    file's (the one check: what is written can be read).

    Raises
    ------
    DataFormatError
        An option outside its choices or range, a trajectory outside the format's limits.
    """
    from axiscal.standards.squareness_biaxial import CONFIGS, SQUARES

    config = config.upper() if isinstance(config, str) else config
    _choice(config, CONFIGS, "config", source)
    if isinstance(orientation, bool) or orientation not in ORIENTATIONS:
        raise DataFormatError(f"[biaxial] orientation {orientation!r:.20}: one of 0, 90, 180 "
                              "or 270 (degrees clockwise)", source)
    if (isinstance(prism_error, bool) or not isinstance(prism_error, (int, float))
            or not abs(prism_error) <= MAX_PRISM_ARCSEC):
        raise DataFormatError(f"[biaxial] prism_error_arcsec {prism_error!r:.20}: a finite "
                              f"number of arcsec within ±{MAX_PRISM_ARCSEC:g}", source)
    _choice(reference, REFERENCES, "reference", source)
    _choice(square, SQUARES, "square", source)
    for key, value in (("machine", machine), ("datum", datum)):
        _text(value, f"[biaxial] {key}", source)
    if datum and datum.upper() not in (one.axis or "X", two.axis or "Y"):
        raise DataFormatError(f"[biaxial] datum {datum!r:.20}: one of the two axes "
                              f"({one.axis or 'X'}, {two.axis or 'Y'}) or empty", source)
    for name, data, digest in (("first", one, sha256[0]), ("second", two, sha256[1])):
        _trajectory_checked(data, digest, name, source)
    return BiaxialTest(one, two, config, int(orientation), float(prism_error), reference,
                       datum, square, machine, (sha256[0], sha256[1]))


def read_biaxial_test(path) -> BiaxialTest:
    """Read a squareness test file; see :func:`parse_biaxial_test`."""
    from axiscal.io._files import read_text

    return parse_biaxial_test(read_text(path), source=str(path))


def parse_biaxial_test(text: str, source: str = "<text>") -> BiaxialTest:
    """Parse the TOML of a squareness test from two straightness trajectories.

    Raises
    ------
    DataFormatError, ConfigError
        Not TOML, a table or key not of the format, a missing one, an option outside its
        choices, a trajectory whose positions and deviations differ in number, a number not
        finite; one line each, naming the table and key.

    Examples
    --------
    >>> from axiscal.io.straightness import parse_straightness
    >>> x = parse_straightness("# axis=X direction=Y\\nposition,deviation\\n0,0\\n500,1\\n")
    >>> y = parse_straightness("# axis=Y direction=X\\nposition,deviation\\n0,0\\n500,2\\n")
    >>> t = parse_biaxial_test(format_biaxial_test(biaxial_test(x, y, orientation=90)))
    >>> t.orientation, t.one.deviations.tolist() == x.deviations.tolist()
    (90, True)
    >>> parse_biaxial_test(format_biaxial_test(biaxial_test(x, y)).replace(
    ...     "positions_m = [0.0, 0.5]", "positions_m = [0.0]"), "sq.toml")
    Traceback (most recent call last):
    ...
    axiscal.errors.DataFormatError: sq.toml: [first] 1 positions_m and 2 deviations_m: a reading is a position and its deviation
    """
    from axiscal._schema import loads_toml

    doc = loads_toml(text, source)
    extra = sorted(set(doc) - {"biaxial", "first", "second"})
    if extra:
        raise DataFormatError(f"[{extra[0]}] is not a table of a squareness test file (its "
                              "tables: [biaxial], [first], [second])", source)
    for table in ("biaxial", "first", "second"):
        if not isinstance(doc.get(table), dict):
            raise DataFormatError(f"no [{table}] table: a squareness test file holds "
                                  "[biaxial], [first] and [second]", source)
    opts = doc["biaxial"]
    _known(opts, _OPTIONS, "biaxial", source)
    for key in ("config", "orientation", "reference", "square"):
        if key not in opts:
            raise DataFormatError(f"[biaxial] has no {key}", source)
    one, digest_one = _trajectory(doc["first"], "first", source)
    two, digest_two = _trajectory(doc["second"], "second", source)
    for key in ("config", "reference", "square", "machine", "datum"):
        _text(opts.get(key, ""), f"[biaxial] {key}", source)
    return biaxial_test(one, two, config=opts["config"], orientation=opts["orientation"],
                        prism_error=opts.get("prism_error_arcsec", 0.0),
                        reference=opts["reference"], datum=opts.get("datum", ""),
                        square=opts["square"], machine=opts.get("machine", ""),
                        sha256=(digest_one, digest_two), source=source)


def format_biaxial_test(test: BiaxialTest) -> str:
    """The TOML text of ``test`` (the format above): each reading as the shortest ``repr`` of
    its double, so :func:`parse_biaxial_test` gives the same doubles."""
    import json

    lines = ["# axiscal squareness from two straightness trajectories, every reading inline",
             "# (axiscal squareness biaxial --inline; ISO 230-1:2012 §3.6.7). Readings in m.",
             "", "[biaxial]"]
    opts = {"machine": test.machine, "config": test.config, "orientation": test.orientation,
            "prism_error_arcsec": float(test.prism_error), "reference": test.reference,
            "datum": test.datum, "square": test.square}
    lines += [f"{k} = {json.dumps(v) if isinstance(v, str) else repr(v)}"
              for k, v in opts.items()]
    for name, data, digest in (("first", test.one, test.sha256[0]),
                               ("second", test.two, test.sha256[1])):
        lines += ["", f"[{name}]"]
        for key, value in (("source", _name(data.source)), ("sha256", digest),
                           ("axis", data.axis), ("direction", data.direction),
                           ("position_unit", data.position_unit),
                           ("deviation_unit", data.deviation_unit)):
            lines.append(f"{key} = {json.dumps(value)}")
        lines.append("positions_m = [" + ", ".join(repr(float(v)) for v in data.positions) + "]")
        lines.append("deviations_m = [" + ", ".join(repr(float(v)) for v in data.deviations)
                     + "]")
    return "\n".join(lines) + "\n"


# -- helpers ---------------------------------------------------------------------------------
def _name(source: str) -> str:
    """A file's name without its folders (the file kept names where it came from, not where
    it was on the disk)."""
    return str(source).replace("\\", "/").rsplit("/", 1)[-1]


def _known(table: dict, keys: set, name: str, source: str) -> None:
    extra = sorted(set(table) - keys)
    if extra:
        raise DataFormatError(f"[{name}] {extra[0]!r:.40}: not a key of a squareness test file "
                              f"(keys: {', '.join(sorted(keys))})", source)


def _choice(value, choices, key: str, source: str) -> None:
    if not isinstance(value, str) or value not in choices:
        raise DataFormatError(f"[biaxial] {key} {value!r:.30}: one of {', '.join(choices)}",
                              source)


def _text(value, what: str, source: str) -> None:
    if not isinstance(value, str):
        raise DataFormatError(f"{what} {value!r:.30}: a string", source)
    if _CONTROL.search(value) or len(value) > 300:
        raise DataFormatError(f"{what}: at most 300 characters, no control characters", source)


def _trajectory(t: dict, name: str, source: str) -> tuple[StraightnessData, str]:
    """The ``[first]`` or ``[second]`` table as a trajectory and its file's SHA-256."""
    from axiscal.io._tidy import length_factor

    _known(t, _TRAJECTORY, name, source)
    for key in ("positions_m", "deviations_m"):
        if key not in t:
            raise DataFormatError(f"[{name}] has no {key}", source)
        values = t[key]
        if not isinstance(values, list) or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            raise DataFormatError(f"[{name}] {key}: a list of numbers (m)", source)
    for key in _TRAJECTORY - {"positions_m", "deviations_m"}:
        _text(t.get(key, ""), f"[{name}] {key}", source)
    pu, du = t.get("position_unit", "mm"), t.get("deviation_unit", "um")
    length_factor(pu, "position_unit", source)          # a unit the straightness reader knows
    length_factor(du, "deviation_unit", source)
    if len(t["positions_m"]) != len(t["deviations_m"]):
        raise DataFormatError(f"[{name}] {len(t['positions_m'])} positions_m and "
                              f"{len(t['deviations_m'])} deviations_m: a reading is a position "
                              "and its deviation", source)
    data = StraightnessData(np.array(t["positions_m"], dtype=float),
                            np.array(t["deviations_m"], dtype=float),
                            t.get("axis", "").upper(), t.get("direction", "").upper(), pu, du,
                            t.get("source", "") or f"{source} [{name}]")
    return data, t.get("sha256", "")


def _trajectory_checked(data: StraightnessData, digest, name: str, source: str) -> None:
    """The format's limits on one trajectory (what :func:`parse_biaxial_test` takes)."""
    pos, dev = np.asarray(data.positions, float), np.asarray(data.deviations, float)
    if pos.shape != dev.shape or pos.ndim != 1:
        raise DataFormatError(f"[{name}] {pos.size} positions and {dev.size} deviations: a "
                              "reading is a position and its deviation", source)
    for key, values in (("positions_m", pos), ("deviations_m", dev)):
        bad = np.flatnonzero(~(np.abs(values) <= MAX_METRES))
        if bad.size:
            value = float(values[bad[0]])
            raise DataFormatError(f"[{name}] {key}[{bad[0]}] = {value!r}: a finite number of "
                                  f"metres within ±{MAX_METRES:g}", source)
    if pos.size < 2 or np.ptp(pos) == 0:
        raise DataFormatError(f"[{name}] {pos.size} reading(s) at {np.unique(pos).size} "
                              "position(s): a straightness needs readings at two positions at "
                              "least", source)
    if not (isinstance(digest, str) and (digest == "" or re.fullmatch(r"[0-9a-f]{64}", digest))):
        raise DataFormatError(f"[{name}] sha256 {digest!r:.20}: 64 lower-case hex digits or "
                              "empty", source)
    for key in ("axis", "direction"):
        value = getattr(data, key)
        if value and not re.fullmatch(r"[A-Z][A-Z0-9]{0,7}", value):
            raise DataFormatError(f"[{name}] {key} {value!r:.20}: an axis name (X, Y, Z ...)",
                                  source)
