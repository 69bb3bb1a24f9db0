"""Conversions carry the axis (issue 42): a table read from one controller's file, written for
another, keeps its machine axis, measuring system and unit, or is refused naming the loss; the
CLI's --to, the API's write_table and the workbench's download share convert(); a read-back
comparison undoes the reference shift."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.compensation.controllers import CONTROLLERS, controller
from axiscal.compensation.controllers.convert import convert
from axiscal.compensation.readback import compare
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import ControllerLimitError

DATA = Path(__file__).resolve().parents[1] / "data" / "siemens"
EEC, INI = DATA / "AX_EEC.INI", DATA / "INITIAL.INI"
runner = CliRunner()


def _run(*args):
    return runner.invoke(app, [str(a) for a in args])


def _table(axis="X", inch=25.4):
    """Targets 0, 4, 8, 12 inch (101.6 mm apart), points every 2 inch: whole numbers of every
    writer's position unit in mm and in inch."""
    return table_from_deviations(np.arange(4) * 4 * inch, [1.0, -2.0, 3.0, 0.5],
                                 spacing=2 * inch, axis=axis)


#: What each writer needs to be told to write an axis of another controller, and the reader
#: options that read its file back as written.
WRITE = {"siemens-840d": dict(machine_axis="AX2"), "fanuc": dict(axis_number=2, detection_unit=1e-5),
         "linuxcnc": dict(joint=1), "heidenhain": {}, "csv": {}, "renishaw-ren": {}}
READ = {"siemens-840d": {}, "fanuc": dict(axis_number=2, detection_unit=1e-5), "linuxcnc": {}, "heidenhain": {},
        "csv": {}, "renishaw-ren": {}}


def _read_from(name, unit="mm"):
    """A table as read from ``name``'s file (so it carries that file's origin)."""
    mod = controller(name)
    opts = dict(WRITE[name])
    if unit == "inch" and "unit" in mod.write.__code__.co_varnames:
        opts["unit"] = "inch"
    f = mod.write(_table(), **opts)
    ropts = dict(READ[name])
    if name == "linuxcnc":
        ropts["unit"] = opts.get("unit", "mm")
    return mod.parse(f.text, **ropts)


@pytest.mark.parametrize("src", list(CONTROLLERS))
@pytest.mark.parametrize("dst", list(CONTROLLERS))
def test_every_format_into_every_other_keeps_axis_and_unit_or_says_why_not(src, dst):
    """Either the conversion is refused naming the option that places the axis, or it is
    written and reads back to the same corrections at the same positions, the inch unit kept
    where the target writes one."""
    t = _read_from(src, unit="inch")
    o = t.origin
    slot = {"siemens-840d": "machine_axis", "fanuc": "axis_number", "linuxcnc": "joint"}.get(dst)
    if src != dst and slot and o is not None and o.machine_axis:
        with pytest.raises(ControllerLimitError, match=f"give -o {slot}="):
            convert(t, dst)
    opts = {slot: WRITE[dst][slot]} if slot and src != dst else {}
    if dst == "fanuc":
        opts["detection_unit"] = 1e-5                  # 0.254 µm in inch, 0.01 µm in mm
    f = convert(t, dst, **opts)
    mod = controller(dst)
    ropts = dict(READ[dst])
    if dst == "linuxcnc":
        ropts["unit"] = "inch" if o is not None and o.unit == "inch" else "mm"
    back = mod.parse(f.text, **ropts)
    np.testing.assert_allclose(back.positions, t.positions, atol=1e-6)
    shift = back.mean[0] - t.mean[0]          # 840D and Fanuc write zero at the reference point
    tol = 0.5 * max(back.resolution, t.resolution) + 0.06   # the target's counts, 0.1 µm .ren
    np.testing.assert_allclose(back.mean - shift, t.mean, atol=tol)
    if o is not None and o.unit == "inch" and "unit" in mod.write.__code__.co_varnames:
        assert back.origin.unit == "inch", f.text[:200]
    elif o is not None and o.unit == "inch":
        assert any("written in mm" in n for n in f.notes)


def test_840d_table_converted_to_840d_stays_on_its_axis_via_the_cli():
    """Issue 42: ``--read AX_EEC.INI -o machine_axis=AX4 --to siemens-840d`` wrote the A axis's
    table on AX1 (X). It now writes AX4, and a measuring-system-2 table stays [1,…]."""
    r = _run("compensate", "--read", EEC, "--ini", INI, "-o", "machine_axis=AX4",
             "--to", "siemens-840d")
    assert r.exit_code == 0, r.output
    assert "$AA_ENC_COMP[0,0,AX4]=" in r.stdout and "AX1]" not in r.stdout
    r = _run("compensate", "--read", EEC, "-o", "machine_axis=AX1", "-o", "measuring_system=2",
             "--to", "siemens-840d")
    assert r.exit_code == 0, r.output
    assert "$AA_ENC_COMP_STEP[1,AX1]=100" in r.stdout
    r = _run("compensate", "--read", EEC, "-o", "machine_axis=AX1", "-o", "measuring_system=2",
             "--to", "heidenhain")
    assert r.exit_code == 2 and "measuring system 2 of AX1" in r.stderr
    r = _run("compensate", "--read", EEC, "-o", "machine_axis=AX4", "--to", "fanuc")
    assert r.exit_code == 2 and "give -o axis_number=" in r.stderr
    r = _run("compensate", "--read", EEC, "-o", "machine_axis=AX4", "-o", "to.axis_number=4",
             "--to", "fanuc")
    assert r.exit_code == 0, r.output


def test_cli_lists_every_table_and_refuses_only_the_bad_one(tmp_path):
    r = _run("compensate", "--read", EEC, "--ini", INI, "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    kinds = {t["key"]: t["table"]["axis_kind"] for t in d["tables"]}
    assert kinds == {"AX1": "linear", "AX1/2": "linear", "AX2": "linear", "AX3": "linear",
                     "AX4": "rotary", "AX5": "rotary"}
    bad = tmp_path / "AX_EEC.INI"
    bad.write_bytes(EEC.read_bytes().replace(b"MAX[0,AX2]=400", b"MAX[0,AX2]=410"))
    r = _run("compensate", "--read", bad)
    assert r.exit_code == 2
    assert "refused: AX2: (MAX 410" in r.stdout and "AX3 " in r.stdout
    assert r.stderr.strip().endswith("1 of 6 tables refused (listed above); the others were read")


def test_cli_lists_the_nine_cec_tables():
    r = _run("compensate", "--read", DATA / "NC_CEC.INI", "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert [(t["input_axis"], t["output_axis"]) for t in d["tables"]][:2] == [("AX2", "AX3"),
                                                                            ("AX1", "AX3")]
    assert len(d["tables"]) == 9


def test_readback_undoes_the_reference_shift():
    """An 840D table written zero at its reference point (first point, 0 mm) from deviations
    1, −2, 3, 0.5 µm: as it stands every residual is +1 µm (the deviation at 0 mm); undone, the
    residuals are 0 and the shift said."""
    dev = np.array([1.0, -2.0, 3.0, 0.5])
    f = controller("siemens-840d").write(_table())
    back = controller("siemens-840d").parse(f.text)
    rb = compare(back, np.arange(4) * 101.6, dev, "siemens-840d")
    assert rb.shift == pytest.approx(-1.0)
    assert rb.largest_residual == pytest.approx(0.0, abs=1e-6)
    assert "zero at its reference point 0 mm" in rb.note
    plain = compare(back, np.arange(4) * 101.6, dev, "csv")
    assert plain.largest_residual == pytest.approx(1.0) and plain.note == ""


def test_linuxcnc_enable_line_names_the_file_written(tmp_path):
    """Issue 42: ``COMP_FILE = x.comp`` was printed (and returned by the API) whatever name the
    file was written as; [JOINT_n] COMP_FILE must name the file LinuxCNC is to load."""
    from axiscal import api

    out = tmp_path / "x_after_service.txt"
    cf = api.write_table(_table(), "linuxcnc", out)
    assert "[JOINT_0] COMP_FILE = x_after_service.txt" in cf.enable and out.exists()
    assert not any("x.comp" in e for e in cf.enable)
    src = tmp_path / "t.csv"
    src.write_text("# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
                   + "".join(f"{t},{d},{r},{v}\n" for t, v in ((0, 1.0), (100, -2.0), (200, 3.0))
                             for d in "+-" for r in (1, 2)))
    r = _run("compensate", src, "--controller", "linuxcnc", "--spacing", "50", "--out",
             tmp_path / "joint0.comp", "--json")
    assert r.exit_code == 0, r.output
    assert "[JOINT_0] COMP_FILE = joint0.comp" in json.loads(r.stdout)["enable"]
