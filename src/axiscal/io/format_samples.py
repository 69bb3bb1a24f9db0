"""A small sample of each file format, written by axiscal's own writer (the file-format page).

The documentation's file-format page (``docs/_generate.py``) shows, for each format of
:data:`axiscal.io.formats.FORMATS` that has an entry in :data:`SAMPLES`, the columns it holds
and a sample written by the code that writes the format, so the page cannot show a layout the
program does not write. The samples are of a made-up three-target test, not of a machine.
"""

from __future__ import annotations

from typing import Callable

__all__ = ["SAMPLES", "COLUMNS", "sample"]


def _dataset():
    from axiscal.datasets import Metadata, PositioningDataset

    return PositioningDataset.from_arrays(
        "linear", [0.0, 100.0, 200.0], [[1.2, 1.4], [2.0, 2.3], [0.4, 0.1]],
        [[-0.8, -0.6], [0.1, 0.3], [-1.5, -1.2]], "mm", "um",
        metadata=Metadata(machine="VMC-800", axis="X", date="2026-01-15"))


def _positioning_csv() -> str:
    from axiscal.io.csv import format_positioning_csv

    return format_positioning_csv(_dataset())


def _positioning_json() -> str:
    from axiscal.io.json import format_positioning_json

    return format_positioning_json(_dataset())


def _ecmc() -> str:
    from axiscal.io.ecmc import format_ecmc

    return format_ecmc(_dataset())


def _rtl() -> str:
    from axiscal.io.renishaw import format_rtl

    return format_rtl(_dataset())


def _straightness() -> str:
    import numpy as np

    from axiscal.io.straightness import StraightnessData, format_straightness

    return format_straightness(StraightnessData(np.array([0.0, 0.2, 0.4]),
                                                np.array([0.0, 1.5e-6, 0.8e-6]),
                                                axis="X", direction="Y"))


def _biaxial() -> str:
    """Two three-point trajectories (X read along Y, Y along X) as one squareness test."""
    import numpy as np

    from axiscal.io.biaxial import biaxial_test, format_biaxial_test
    from axiscal.io.straightness import StraightnessData

    p = np.array([0.0, 0.2, 0.4])
    return format_biaxial_test(biaxial_test(
        StraightnessData(p, np.array([0.0, 1.5e-6, 0.8e-6]), "X", "Y", source="x.csv"),
        StraightnessData(p, np.array([0.0, -2e-6, -4e-6]), "Y", "X", source="y.csv"),
        machine="VMC-800"))


def _table(controller: str) -> Callable[[], str]:
    def write() -> str:
        from axiscal.compensation.controllers import controller as module
        from axiscal.compensation.tables import table_from_result
        from axiscal.standards.iso230_2 import evaluate

        table = table_from_result(evaluate(_dataset()), 100.0, axis="X")
        return module(controller).write(table).text
    return write


#: A sample writer per format name of :data:`axiscal.io.formats.FORMATS`.
SAMPLES: dict[str, Callable[[], str]] = {
    "Tidy positioning CSV (ISO 230-2 readings)": _positioning_csv,
    "axiscal positioning JSON": _positioning_json,
    "EPICS ecmc ISO 230-2 file": _ecmc,
    "Renishaw linear positioning export (HEADER:: … EOF::)": _rtl,
    "Straightness trajectory": _straightness,
    "Squareness test from two straightness trajectories": _biaxial,
    "Siemens 840D compensation (%_N_AX_EEC_INI, %_N_NC_CEC_INI)": _table("siemens-840d"),
    "Fanuc pitch error parameters": _table("fanuc"),
    "Heidenhain .COM and .CMA": _table("heidenhain"),
    "LinuxCNC compensation file": _table("linuxcnc"),
    "Compensation table CSV": _table("csv"),
    "Renishaw .ren compensation export (spacing, start, end, Combined)": _table("renishaw-ren"),
}

#: The columns of the CSV formats a user writes by hand, with their units.
COLUMNS: dict[str, str] = {
    "Tidy positioning CSV (ISO 230-2 readings)":
        "``target`` (target position, ``target_unit``: mm or deg), ``direction`` (``+``/``-``), "
        "``run`` (1, 2 ...), ``deviation`` (measured minus target, ``deviation_unit``: µm or "
        "arcsec); units and metadata in ``# key=value`` comment lines before the header.",
    "Straightness trajectory": "``position`` (mm) and ``deviation`` (µm) along the axis; "
                               "the axis and the direction of the deviation in comments.",
    "Ballbar trace": "``angle`` (deg), ``direction`` (``ccw``/``cw``), ``deviation`` (µm, of "
                     "the radius); radius, feed and plane in comments.",
    "Multi-point diagonal test": "``diagonal`` (``D1``/``D2``), ``position`` (mm), "
                                 "``error`` (µm); the X and Y travels in comments.",
    "Five motion errors of a rotary axis": "``run``, ``angle_deg`` and one column per "
                                           "motion (µm or arcsec, in the header's names).",
    "Test plan": "``step``, ``target`` (mm or deg), ``direction``, ``run``: the moves a "
                 "controller program makes (``axiscal plan``).",
}


def sample(name: str) -> str | None:
    """The sample of format ``name`` written by axiscal's writer (None: no sample kept)."""
    make = SAMPLES.get(name)
    return None if make is None else make()
