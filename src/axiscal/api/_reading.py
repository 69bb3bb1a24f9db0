"""Reading a data file and evaluating it: :func:`read` and :func:`evaluate` of the public API.

``axiscal iso230-2``, ``axiscal evaluate`` and ``axiscal ballbar analyze`` call these two and
print :meth:`axiscal.api.Evaluation.to_dict` for ``--json``.
"""

from __future__ import annotations

from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, Callable, Mapping

from axiscal.api._results import DEFAULT_STANDARD   # the standard applied when none is named

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.api._results import Evaluation, PathLike

__all__ = ["read", "evaluate"]

#: The forms of a positioning evaluation's ``to_dict()``.
FORMS = ("iso230-2", "standards")


def read(path: PathLike | bytes | IO, *, target_unit: str | None = None,
         deviation_unit: str | None = None, kind: str | None = None,
         epics: Mapping[str, Any] | None = None,
         progress: Callable[[int, int], object] | None = None,
         encoding: str | None = None) -> Any:
    """Read any data file axiscal knows into its dataset, the format told by its content.

    Parameters
    ----------
    path : str, Path, bytes or file object
        A positioning test (tidy CSV, axiscal JSON, Renishaw .rtl/.rta, EPICS ecmc or camonitor
        log), a straightness, ballbar, diagonal or five-error CSV: its path, or its content in
        memory: ``bytes`` (UTF-8; errors name ``<bytes>``), a ``str`` holding a line break
        (the file's text; errors name ``<text>``; a ``str`` without one is a path), or a file
        object opened in text or binary (``io.StringIO``, ``open(...)``, an upload; errors
        name its ``name``, else ``<StringIO>`` ...).
    target_unit, deviation_unit : str, optional
        Units of a positioning CSV that does not declare them (mm/deg; um/mm/arcsec).
    kind : str, optional
        ``iso230-2``, ``straightness``, ``ballbar``, ``diagonal`` or ``motion``: read the file
        as this kind instead of telling it from the content (as ``axiscal iso230-2`` and
        ``ballbar analyze`` do).
    epics : mapping, optional
        Options of an EPICS camonitor log (``setpoint_pv``, ``reference_pv``, ``targets``,
        ``reference_scale``, ``reference_offset``, ``window``, ``plan``, ``dwell``; as the
        commands' ``--setpoint-pv`` ...; :func:`axiscal.io.epics.parse_epics`), positioning only.
    progress : callable, optional
        Called with ``(bytes read, file size)`` while a large positioning CSV is streamed.
    encoding : str, optional
        The code page of a Renishaw ``.rtl``/``.rta`` export (a path or ``bytes``): ``cp1250``
        … (:data:`axiscal.io.renishaw.CODE_PAGES`), ``utf-8`` or ``utf-16``, as the commands'
        ``--encoding``; refused for an unknown name, for text already decoded and for any other
        kind of file.

    Returns
    -------
    PositioningDataset, BallbarData, StraightnessData, DiagonalData or MotionErrorData
        The frozen dataset, in the units its file declares.

    Raises
    ------
    axiscal.DataFormatError
        Content that does not parse, naming the file (or ``<bytes>`` ...) and the line. Content
        of no kind axiscal tells is read as a positioning test, whose reader says what is
        wrong (the header it expected), as ``axiscal iso230-2`` does.
    axiscal.MissingFileError
        A path that does not exist or cannot be read.
    """
    from axiscal.report.evaluations import KIND_STANDARD

    if kind is not None and kind not in KIND_STANDARD:
        from axiscal.errors import InputError

        raise InputError(f"kind {kind!r}: one of {', '.join(KIND_STANDARD)}")
    if encoding is not None:
        return _read_encoded(path, encoding, kind, target_unit, deviation_unit, epics)
    memory = in_memory(path)
    return _read(path, memory, kind or _kind_of(path, memory), target_unit, deviation_unit,
                 epics, progress)


def _read_encoded(path, encoding, kind, target_unit, deviation_unit, epics) -> Any:
    """A Renishaw export in the code page ``encoding``: a path, or its bytes."""
    from axiscal.errors import InputError

    if kind not in (None, "iso230-2"):
        raise InputError(f"encoding {encoding!r} is the code page of a Renishaw .rtl/.rta "
                         f"positioning export; a {kind} file is read as UTF-8")
    if isinstance(path, (bytes, bytearray, memoryview)):
        from axiscal.io import detect
        from axiscal.io.renishaw import decode, parse_renishaw

        text, used = decode(bytes(path), encoding, "<bytes>")
        if not detect.looks_like_renishaw(text):
            raise InputError(f"encoding {encoding!r} is the code page of a Renishaw .rtl/.rta "
                             "export; <bytes> is not one")
        return parse_renishaw(text, "<bytes>", target_unit=target_unit,
                              deviation_unit=deviation_unit, encoding=used)
    if not isinstance(path, (str, Path)) or in_memory(path) is not None:
        raise InputError(f"encoding {encoding!r}: give the export's path or its bytes (text "
                         "or a file object is already decoded)")
    from axiscal.io import read_positioning

    return read_positioning(path, target_unit=target_unit, deviation_unit=deviation_unit,
                            epics=dict(epics) if epics else None, encoding=encoding)


def _read(path, memory, kind, target_unit=None, deviation_unit=None, epics=None,
          progress=None) -> Any:
    """:func:`_read_kind`; content of no kind told (``kind`` None) is read as a positioning
    test and its reader's error says so."""
    from axiscal.errors import DataFormatError

    try:
        return _read_kind(path, memory, kind or "iso230-2", target_unit, deviation_unit, epics,
                          progress)
    except DataFormatError as e:
        if kind is not None:
            raise
        raise DataFormatError(f"{e.message} (the content is of no kind axiscal tells, so it was "
                              "read as a positioning test)", e.source, e.line) from None


def in_memory(data: Any) -> tuple[str, str] | None:
    """A data file's content given in memory, as ``(text, source)``; None for a path.

    ``bytes`` (UTF-8) are ``<bytes>``; a ``str`` with a line break is the text itself,
    ``<text>``; a file object (``read()``) is named by its ``name`` where it has one.
    """
    if isinstance(data, (bytes, bytearray, memoryview)):
        return _decoded(bytes(data), "<bytes>"), "<bytes>"
    if isinstance(data, str) and ("\n" in data or "\r" in data):
        return data.removeprefix("\ufeff"), "<text>"
    read_ = getattr(data, "read", None)
    if read_ is None or isinstance(data, (str, Path)):
        return None
    name = getattr(data, "name", None)
    source = str(name) if isinstance(name, (str, Path)) and str(name) else \
        f"<{type(data).__name__}>"
    raw = read_()
    if isinstance(raw, (bytes, bytearray)):
        return _decoded(bytes(raw), source), source
    if not isinstance(raw, str):
        from axiscal.errors import InputError

        raise InputError(f"{source}: read() gave {type(raw).__name__}, not text or bytes")
    return raw.removeprefix("\ufeff"), source


def _decoded(raw: bytes, source: str) -> str:
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        from axiscal.errors import DataFormatError
        from axiscal.io._files import _not_utf8

        raise DataFormatError(_not_utf8(raw, exc.start), source) from None


def _kind_of(path: Any, memory: tuple[str, str] | None) -> str | None:
    """The kind of test the content holds; None when it is of no kind axiscal tells."""
    from axiscal.errors import DataFormatError

    try:
        if memory is not None:
            from axiscal.store.kinds import detect_kind

            return detect_kind(memory[0])
        from axiscal.report.evaluations import kind_of_file

        return kind_of_file(path)
    except DataFormatError as e:
        if e.source is not None:   # not UTF-8, too large ...: the file's own problem
            raise
        return None


def _read_kind(path, memory, kind, target_unit, deviation_unit, epics, progress) -> Any:
    """The dataset of ``kind`` from a path or from ``memory`` (text, source)."""
    epics = dict(epics) if epics else None
    if memory is None:
        if kind == "iso230-2":
            from axiscal.io import read_positioning

            return read_positioning(path, target_unit=target_unit, deviation_unit=deviation_unit,
                                    progress=progress, epics=epics)
        if kind == "ballbar":
            from axiscal.io.ballbar import read_ballbar

            return read_ballbar(path)
        from axiscal.report.evaluations import evaluated_file

        return evaluated_file(path, kind).dataset
    text, source = memory
    if kind == "iso230-2":
        from axiscal.io import parse_positioning

        return parse_positioning(text, source, target_unit=target_unit,
                                 deviation_unit=deviation_unit, epics=epics)
    if kind == "ballbar":
        from axiscal.io.ballbar import parse_ballbar

        return parse_ballbar(text, source=source)
    from axiscal.store.kinds import evaluate_file

    return evaluate_file(text.encode("utf-8"), source, kind).dataset


def _user_config() -> dict:
    from axiscal.io.user_config import load_user_config

    return load_user_config()


def evaluate(data: Any, standard: str = DEFAULT_STANDARD, *,
             tolerances: Mapping[str, float] | None = None,
             rule: str | None = None,
             uncertainty: Mapping[str, float | str] | None = None,
             job: PathLike | Mapping[str, Any] | None = None,
             drift_check: PathLike | None = None,
             full_turn: str = "separate", form: str | None = None,
             feed: float | None = None, plane: str | None = None) -> "Evaluation":
    """Evaluate a dataset (or a data file) by its standard.

    Parameters
    ----------
    data : dataset, Simulation, DataFrame, str, Path, bytes or file object
        What :func:`read` returns, a :class:`Simulation` of :func:`simulate` (its simulated
        test: positioning, rotary calibration, ballbar, five-DOF), a pandas DataFrame of a
        positioning test's readings (:meth:`PositioningDataset.from_dataframe
        <axiscal.datasets.PositioningDataset.from_dataframe>`, units in ``attrs["units"]`` or
        the column names), or what :func:`read` reads (a path, or the content in memory).
    standard : str
        For a positioning test, a key of
        :data:`axiscal.standards.positioning_standards.STANDARDS` (default ``iso230-2:2014``)
        or ``all``. The other kinds have one standard each (ISO 230-1 straightness, ISO 230-4
        ballbar diagnosis, ISO 230-6 diagonal squareness, ISO 230-7 motion errors) and ignore it.
    tolerances : mapping of str to float, optional
        Acceptance tolerances by parameter name in the deviation unit (positioning tests only),
        decided by ISO 14253-1:2017 with U of ISO 230-2:2014 Annex A, as ``--tolerance`` does.
    rule : str, optional
        Decision rule, ``iso14253-1`` (default) or ``simple``.
    uncertainty : mapping, optional
        Inputs of the ISO 230-2:2014 Annex A uncertainty budget by name, over the user
        configuration's and the job file's ``[uncertainty]`` table, as ``--uncertainty
        NAME=VALUE`` (e.g. ``{"e_ve": 0.3}``: the environmental variation error of a drift
        check, Annex A.5). Every input not given is shown as assumed in
        ``to_dict()["uncertainty_budget"]``.
    job : str, Path or mapping, optional
        ISO 230-2:2014: the job file (TOML) over the user configuration, as ``--job``: its
        ``[uncertainty]``, ``[tolerance]``, decision rule and certificate items; or the same
        tables as a dict (read as its TOML text would be).
    drift_check : str or Path, optional
        ISO 230-2:2014: a drift-check file; E_VE of the budget is the range of its readings,
        measured (ISO 230-2:2014 Annex A.5), as ``--drift-check``.
    full_turn : {"separate", "merge"}
        ISO 230-2:2014, a rotary 0-360 deg test: keep 0 and 360 deg as two targets or pool them.
    form : {"iso230-2", "standards"}, optional
        The object of ``to_dict()`` for a positioning test: ``iso230-2`` that of ``axiscal
        iso230-2 --json`` (ISO 230-2:2014 only), ``standards`` that of ``axiscal evaluate
        --standard KEY --json`` (any key). Default: ``iso230-2`` for ISO 230-2:2014, else
        ``standards``.
    feed : float, mm/min, optional
        A ballbar test's feed, over the file's (the servo-mismatch term needs it).
    plane : str, optional
        A ballbar test's plane, ``XY``, ``YZ`` or ``ZX``, over the file's.

    Returns
    -------
    Evaluation
    """
    from axiscal.api._results import Evaluation, Simulation
    from axiscal.datasets import PositioningDataset

    if isinstance(data, Simulation):
        data = _simulated(data)
    elif type(data).__name__ == "DataFrame" and hasattr(data, "columns"):   # pandas, unimported
        data = PositioningDataset.from_dataframe(data)
    memory = in_memory(data)
    if memory is not None or isinstance(data, (str, Path)):
        from axiscal.report.evaluations import evaluated_file

        kind = _kind_of(data, memory)
        if kind is not None and (kind not in ("iso230-2", "ballbar") or (
                kind == "ballbar" and feed is None and plane is None)):
            from axiscal.report.evaluations import record_fields
            from axiscal.store.kinds import inputs_from_config, with_uncertainty

            if memory is None:
                ev = evaluated_file(data, kind)
            else:
                from axiscal.store.kinds import evaluate_file

                ev = evaluate_file(memory[0].encode("utf-8"), memory[1], kind)
            table = inputs_from_config(kind, _user_config(), ev.dataset)
            return Evaluation(**record_fields(with_uncertainty(ev, {**table,
                                                                   **(uncertainty or {})})))
        data = _read(data, memory, kind)
    if isinstance(data, PositioningDataset):
        from axiscal.report.evaluations import positioning_evaluation

        key = standard.strip().lower()
        how = form or ("iso230-2" if key == DEFAULT_STANDARD else "standards")
        if how not in FORMS:
            from axiscal.errors import InputError

            raise InputError(f"form {form!r}: one of {', '.join(FORMS)}")
        if isinstance(job, Mapping):
            from axiscal._schema import loads_toml
            from axiscal.api._config import SOURCE, toml_text

            job = loads_toml(toml_text(job), SOURCE)
        return Evaluation(**positioning_evaluation(
            data, key, dict(tolerances or {}), rule, dict(uncertainty or {}), form=how, job=job,
            drift_check=drift_check, full_turn=full_turn))
    from axiscal.report.evaluations import ballbar_evaluation
    from axiscal.store.kinds import inputs_from_config

    table = inputs_from_config("ballbar", _user_config())
    return Evaluation(**ballbar_evaluation(data, feed=feed, plane=plane,
                                           uncertainty={**table, **(uncertainty or {})}))


def _simulated(sim: Any) -> Any:
    """What :func:`evaluate` evaluates of a simulation: its simulated test's dataset (a
    five-DOF test as the text of its data file, as ``axiscal motion analyze`` reads it)."""
    from axiscal.datasets import PositioningDataset
    from axiscal.errors import InputError
    from axiscal.io.ballbar import BallbarData

    data = sim.dataset
    if isinstance(data, (PositioningDataset, BallbarData)):
        return data
    if sim.kind == "five-dof" and data is not None:
        from axiscal.io.motion import format_motion_errors

        return format_motion_errors(data)
    raise InputError(f"evaluate: a {sim.kind} simulation holds no test a standard evaluates; "
                     "its own result is Simulation.result (and to_dict())")
