"""Compensation tables of the public API: :func:`compensation_table` and :func:`write_table`.

``axiscal compensate SOURCE --controller NAME`` calls these two.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.api._results import PathLike

__all__ = ["compensation_table", "write_table"]


def compensation_table(source: Any, spacing: float | None = None, *,
                       bidirectional: bool = False, resolution: float = 0.1,
                       start: float | None = None, end: float | None = None,
                       extrapolation: str = "hold", home: float | None = None,
                       axis: str = "", encoding: str | None = None) -> Any:
    """A compensation table from the mean deviations of a positioning test.

    Parameters
    ----------
    source : Evaluation, str or Path
        An ISO 230-2:2014 :class:`Evaluation`, a positioning data file, or the JSON
        ``axiscal iso230-2 --json`` printed.
    spacing : float, mm or deg, optional
        Distance between table points (default: the mean target spacing, as the CLI).
    bidirectional : bool
        Separate tables for the two directions.
    resolution : float, um or arcsec
        Corrections rounded to this step (default 0.1, as ``axiscal compensate``).
    start, end, home : float, mm or deg, optional
        First and last table point, reference position (default: the targets' ends, the start).
    extrapolation : {"hold", "linear"}
        Beyond the measured targets.
    axis : str
        Axis name written in the table (default: the file's).
    encoding : str, optional
        The code page of a Renishaw export given as ``source`` (``cp1250`` …, as
        ``axiscal compensate --encoding``); refused for an :class:`Evaluation` (already read).

    Returns
    -------
    axiscal.compensation.tables.CompensationTable
    """
    from axiscal.api._results import Evaluation
    from axiscal.compensation.tables import table_from_result

    if isinstance(source, Evaluation):
        if encoding is not None:
            from axiscal.errors import InputError

            raise InputError(f"encoding {encoding!r}: the Evaluation given is already read; "
                             "give the export's path")
        result, file_axis = source.result, getattr(source.dataset.metadata, "axis", "")
    else:
        from axiscal.io.results import load_mean_deviations

        result, file_axis = load_mean_deviations(source, encoding=encoding)
    if spacing is None:
        t = result.targets
        spacing = float((t[-1] - t[0]) / (len(t) - 1))
    how: Any = extrapolation     # checked by table_from_result: "hold" or "linear"
    return table_from_result(result, spacing, start=start, end=end, bidirectional=bidirectional,
                             resolution=resolution, extrapolation=how, reference=home,
                             axis=axis or file_axis)


def write_table(table: Any, controller: str, path: PathLike | None = None, *,
                travel: tuple[float, float] | None = None, **options: Any) -> Any:
    """Write a compensation table in a controller's format.

    Parameters
    ----------
    table : CompensationTable
        From :func:`compensation_table`, or read from a controller file: then it is written for
        the machine axis, measuring system and unit it was read from, and a conversion that
        would lose one is refused naming it
        (:func:`axiscal.compensation.controllers.convert.convert`).
    controller : str
        ``siemens-840d``, ``fanuc``, ``heidenhain``, ``linuxcnc``, ``csv`` or ``renishaw-ren``.
    path : str or Path, optional
        Where to write the file (its companion files, e.g. Heidenhain's .CMA, go beside it);
        None writes nothing.
    travel : (float, float), mm or deg, optional
        The axis's travel, low and high (``--travel``): the table must lie inside it.
    **options
        The writer's format options (``machine_axis``, ``detection_unit`` ...).

    Returns
    -------
    axiscal.compensation.controllers.ControllerFile
        ``text``, ``extra_files``, ``enable`` (what the controller must be told) and ``notes``.
    """
    from axiscal.compensation.controllers.convert import convert

    cf = convert(table, controller, travel, **options)
    if path is not None:
        cf = cf.written_as(Path(path).name)     # COMP_FILE = the name written
        from axiscal.io._files import write_text_atomic

        write_text_atomic(path, cf.text)
        for name, text in cf.extra_files.items():
            write_text_atomic(Path(path).parent / name, text)
    return cf
