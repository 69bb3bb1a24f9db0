"""In-memory entry points of the public API (issue 37): ``axiscal.read`` of bytes, text or a file
object, ``PositioningDataset.from_dataframe``, ``axiscal.evaluate`` of a simulation, and every
exception at the package's top. The same numbers as from the file, and errors that name the
source (``<bytes>``, the file object's name) and the line, as the command line does."""

from __future__ import annotations

import io
import re
from pathlib import Path

import pytest

import axiscal
from axiscal.datasets import PositioningDataset

ROOT = Path(__file__).resolve().parents[1]
ECMC = ROOT / "tests" / "data" / "ecmc" / "sls_fat_sat_ISO230.dat"
STRAIGHTNESS = ROOT / "examples" / "squareness_L180_x.csv"
BALLBAR = ROOT / "examples" / "squareness_ballbar_150mm.csv"
DEMO_LINEAR = ROOT / "src" / "axiscal" / "data" / "demo_linear.toml"
BAD_HEADER = "targets,dir,run,dev\n0,+,1,0.1\n"


def _same(a, b) -> bool:
    """The same readings (the ``source`` a dataset keeps names where it came from)."""
    import dataclasses

    import numpy as np

    if hasattr(a, "equals"):
        return a.equals(b)
    with np.printoptions(threshold=10**9, floatmode="unique"):
        return repr(dataclasses.replace(a, source=b.source)) == repr(b)


@pytest.mark.parametrize("path", [ECMC, STRAIGHTNESS, BALLBAR], ids=lambda p: p.name)
def test_read_of_bytes_text_and_file_objects_equals_read_of_the_path(path):
    """A real file (ecmc: tests/data/ecmc/README.md; the examples' straightness and ballbar
    files) read from memory in every form gives the dataset read from its path."""
    from_path = axiscal.read(path)
    raw = path.read_bytes()
    with open(path, "rb") as binary, open(path, encoding="utf-8") as text:
        forms = [raw, bytearray(raw), raw.decode("utf-8"), io.BytesIO(raw),
                 io.StringIO(raw.decode("utf-8")), binary, text]
        for form in forms:
            assert _same(axiscal.read(form), from_path), type(form).__name__


def test_read_errors_name_the_source_and_the_line(tmp_path):
    """``axiscal.read("bad.csv")`` names the file, the line and the header it expected, as
    ``axiscal iso230-2 bad.csv`` does (not "not a data file the history knows"); from memory the
    source is ``<bytes>``, ``<StringIO>`` or the file object's name."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    bad = tmp_path / "bad.csv"
    bad.write_text(BAD_HEADER)
    with pytest.raises(axiscal.DataFormatError) as e:
        axiscal.read(bad)
    assert str(e.value).startswith(f"{bad}:1: header 'targets,dir,run,dev' must name")
    assert e.value.source == str(bad) and e.value.line == 1
    cli = CliRunner().invoke(app, ["iso230-2", str(bad)])
    assert cli.exit_code == 2 and e.value.message.split(" (the content")[0] in cli.stderr
    with pytest.raises(axiscal.DataFormatError, match=r"^<bytes>:1: header"):
        axiscal.read(BAD_HEADER.encode())
    with pytest.raises(axiscal.DataFormatError, match=r"^<StringIO>:1: header"):
        axiscal.read(io.StringIO(BAD_HEADER))
    with pytest.raises(axiscal.DataFormatError, match=re.escape(f"{bad}:1: header")):
        with open(bad, "rb") as fh:
            axiscal.read(fh)
    bad_row = "# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n0,+,1,x\n"
    with pytest.raises(axiscal.DataFormatError, match=r"^<text>:3: "):
        axiscal.read(bad_row)
    with pytest.raises(axiscal.DataFormatError, match=r"^<bytes>: not UTF-8 text"):
        axiscal.read(b"\xff\xfe\x00bad")
    with pytest.raises(axiscal.MissingFileError, match="no-such.csv: no such file"):
        axiscal.read(tmp_path / "no-such.csv")


def _tidy_frame(ds):
    import pandas as pd

    frame = pd.DataFrame(ds.records(), columns=["target", "direction", "run", "deviation"])
    return frame


def test_from_dataframe_round_trips_a_real_test():
    """The ecmc test's readings as a tidy DataFrame (units in ``attrs``, in the column names,
    or as arguments) build the same dataset."""
    pytest.importorskip("pandas")
    ds = axiscal.read(ECMC)
    frame = _tidy_frame(ds)
    units = {"target_unit": ds.target_unit, "deviation_unit": ds.deviation_unit}
    built = PositioningDataset.from_dataframe(frame, metadata=ds.metadata, **units)
    assert built.equals(ds)
    frame.attrs["units"] = {"target": ds.target_unit, "deviation": ds.deviation_unit}
    assert PositioningDataset.from_dataframe(frame, metadata=ds.metadata).equals(ds)
    named = _tidy_frame(ds).rename(columns={"target": f"target [{ds.target_unit}]",
                                            "deviation": f"deviation_{ds.deviation_unit}"})
    assert PositioningDataset.from_dataframe(named, metadata=ds.metadata).equals(ds)
    mine = _tidy_frame(ds).rename(columns={"target": "pos", "deviation": "err"})
    assert PositioningDataset.from_dataframe(
        mine, columns={"target": "pos", "deviation": "err"}, metadata=ds.metadata,
        **units).equals(ds)
    assert axiscal.evaluate(built).to_dict()["E"] == axiscal.evaluate(ECMC).to_dict()["E"]
    assert axiscal.evaluate(frame).to_dict()["E"] == axiscal.evaluate(ECMC).to_dict()["E"]


def test_from_dataframe_refuses_naming_the_problem():
    pytest.importorskip("pandas")
    import pandas as pd

    frame = pd.DataFrame({"target": [0, 0, 100, 100], "direction": ["+", "-", "+", "-"],
                          "run": [1, 1, 1, 1], "deviation": [0.1, 0.2, 0.3, 0.4]})
    with pytest.raises(axiscal.InputError, match="no target unit: give target_unit="):
        PositioningDataset.from_dataframe(frame)
    with pytest.raises(axiscal.DataFormatError, match="<DataFrame>: no 'run' column"):
        PositioningDataset.from_dataframe(frame.drop(columns="run"), target_unit="mm",
                                          deviation_unit="um")
    odd = frame.assign(direction=["+", "sideways", "+", "-"])
    with pytest.raises(axiscal.DataFormatError, match="<DataFrame>: row 1: direction 'sideways'"):
        PositioningDataset.from_dataframe(odd, target_unit="mm", deviation_unit="um")
    twice = frame.assign(direction=["+", "+", "+", "-"], target=[0, 0, 100, 100])
    with pytest.raises(axiscal.DataFormatError, match="two readings for target 0"):
        PositioningDataset.from_dataframe(twice, target_unit="mm", deviation_unit="um")
    with pytest.raises(axiscal.UnitError):
        PositioningDataset.from_dataframe(frame, target_unit="parsec", deviation_unit="um")
    rotary = PositioningDataset.from_dataframe(frame, target_unit="deg", deviation_unit="arcsec")
    assert rotary.axis_kind.value == "rotary"


def test_evaluate_of_a_simulation_and_of_bytes():
    """``evaluate(simulation)`` is ``evaluate(simulation.dataset)``; ``evaluate(bytes)`` is
    ``evaluate(path)``; a simulation that holds no test is refused saying where its result is."""
    sim = axiscal.simulate(DEMO_LINEAR, seed=1)
    assert axiscal.evaluate(sim).to_dict() == axiscal.evaluate(sim.dataset).to_dict()
    assert axiscal.evaluate(sim).to_dict()["E"] == pytest.approx(sim.to_dict()["E"], rel=1e-12)
    assert axiscal.evaluate(ECMC.read_bytes()).to_dict() == axiscal.evaluate(ECMC).to_dict()
    straight = axiscal.evaluate(io.StringIO(STRAIGHTNESS.read_text()))
    assert straight.kind == "straightness"
    assert straight.to_dict() == axiscal.evaluate(STRAIGHTNESS).to_dict()


def test_evaluate_of_a_simulation_without_a_test_is_refused():
    homing = axiscal.simulate(ROOT / "examples" / "scale_single.toml", seed=1)
    with pytest.raises(axiscal.InputError, match="scale-homing simulation holds no test"):
        axiscal.evaluate(homing)


def test_every_library_exception_is_at_the_top():
    """Each public exception class defined in the library (not the front ends; a private
    ``_Name`` is caught inside its module) is ``axiscal.<Name>``,
    the same class as in its module."""
    import axiscal.errors as errors

    defined = set()
    for p in (ROOT / "src" / "axiscal").rglob("*.py"):
        if {"web", "cli"} & set(p.relative_to(ROOT / "src" / "axiscal").parts):
            continue
        defined |= set(re.findall(r"^class ([A-Za-z]\w*)\([^)]*(?:Error|AxiscalError)[^)]*\):",
                                  p.read_text("utf-8"), re.MULTILINE))
    assert defined | {"AxiscalError"} == set(errors.ERRORS)   # AxiscalError(Exception)
    for name in errors.ERRORS:
        cls = getattr(axiscal, name)
        assert cls is getattr(errors, name) and issubclass(cls, errors.AxiscalError)
        assert name in axiscal.__all__
    from axiscal.store.database import NotFoundError, StoreError

    assert StoreError is axiscal.StoreError and NotFoundError is axiscal.NotFoundError
