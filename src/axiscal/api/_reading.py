"""Reading a data file and evaluating it: :func:`read` and :func:`evaluate` of the public API.

``axiscal iso230-2``, ``axiscal evaluate`` and ``axiscal ballbar analyze`` call these two and
print :meth:`axiscal.api.Evaluation.to_dict` for ``--json``.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping

from axiscal.api._results import DEFAULT_STANDARD   # the standard applied when none is named

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.api._results import Evaluation, PathLike

__all__ = ["read", "evaluate"]

#: The forms of a positioning evaluation's ``to_dict()``.
FORMS = ("iso230-2", "standards")


def read(path: PathLike, *, target_unit: str | None = None,
         deviation_unit: str | None = None, kind: str | None = None,
         epics: Mapping[str, Any] | None = None,
         progress: Callable[[int, int], object] | None = None) -> Any:
    """Read any data file axiscal knows into its dataset, the format told by its content.

    Parameters
    ----------
    path : str or Path
        A positioning test (tidy CSV, axiscal JSON, Renishaw .rtl/.rta, EPICS ecmc or camonitor
        log), a straightness, ballbar, diagonal or five-error CSV.
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

    Returns
    -------
    PositioningDataset, BallbarData, StraightnessData, DiagonalData or MotionErrorData
        The frozen dataset, in the units its file declares.

    Raises
    ------
    axiscal.errors.DataFormatError
        A file of no kind axiscal knows, or one that does not parse.
    """
    from axiscal.report.evaluations import KIND_STANDARD, evaluated_file, kind_of_file

    if kind is not None and kind not in KIND_STANDARD:
        from axiscal.errors import InputError

        raise InputError(f"kind {kind!r}: one of {', '.join(KIND_STANDARD)}")
    kind = kind or kind_of_file(path)
    if kind == "iso230-2":
        from axiscal.io import read_positioning

        return read_positioning(path, target_unit=target_unit, deviation_unit=deviation_unit,
                                progress=progress, epics=dict(epics) if epics else None)
    if kind == "ballbar":
        from axiscal.io.ballbar import read_ballbar

        return read_ballbar(path)
    return evaluated_file(path, kind).dataset


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
    data : dataset or str or Path
        What :func:`read` returns, or a path to read.
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
    from axiscal.api._results import Evaluation
    from axiscal.datasets import PositioningDataset

    if isinstance(data, (str, Path)):
        from axiscal.report.evaluations import KIND_STANDARD, evaluated_file, kind_of_file

        kind = kind_of_file(data)
        if kind not in ("iso230-2", "ballbar") or (kind == "ballbar" and feed is None
                                                   and plane is None):
            from axiscal.report.evaluations import record_fields
            from axiscal.store.kinds import inputs_from_config, with_uncertainty

            ev = evaluated_file(data, kind)
            table = inputs_from_config(kind, _user_config(), ev.dataset)
            return Evaluation(**record_fields(with_uncertainty(ev, {**table,
                                                                   **(uncertainty or {})})))
        data = read(data, kind=kind)
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

    return Evaluation(**ballbar_evaluation(data, feed=feed, plane=plane))
