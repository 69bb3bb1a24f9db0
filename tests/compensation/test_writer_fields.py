"""Every field a controller writer writes keeps to its format's grammar (issue 39).

The hostile values are derived from each writer's ``FIELDS`` (the one shared mechanism,
:func:`axiscal.compensation.controllers._common.check_fields`): a name field gets control
characters, line breaks, the format's own delimiters and 1,000 characters; a number field gets
-1, one past its bounds, 2^63 and 10^20. Each is refused naming the option; no file is written.
"""

import numpy as np
import pytest

from axiscal.compensation.controllers import CONTROLLERS, controller
from axiscal.compensation.controllers._common import Field
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import ControllerLimitError

NAMES = ["X1]=0\nM30\n;[", "X\nCompensation spacing : 1 mm", "X1 ", "X)", "X\x00", "X\r",
         "", "A" * 1000, "X;", "\u202eX"]


def _table(axis="X"):
    return table_from_deviations([0, 100, 200, 300, 400], [2.0, -1.0, 4.0, 3.0, -2.0],
                                 [0.0, -3.0, 2.0, 1.0, -4.0], spacing=25, resolution=1.0,
                                 axis=axis)


def _hostile(field: Field) -> list:
    if field.pattern:
        return NAMES
    return [field.lo - 1, field.hi + 1, -1, 2**63, 10**20, True, "3"]


def _cases():
    out = []
    for name in CONTROLLERS:
        mod = controller(name)
        for option, field in getattr(mod, "FIELDS", {}).items():
            for value in _hostile(field):
                out.append(pytest.param(name, option, value,
                                        id=f"{name}-{option}-{str(value)[:12]!r}"))
    return out


def test_every_writer_declares_its_fields():
    """Every controller with options written into its file declares their grammar."""
    for name in ("siemens-840d", "fanuc", "heidenhain", "linuxcnc", "renishaw-ren"):
        assert controller(name).FIELDS, name
    assert set(controller("siemens-840d").FIELDS) >= {"machine_axis", "input_axis",
                                                       "output_axis", "table_index"}
    assert set(controller("fanuc").FIELDS) >= {"axis_number", "reference_number", "max_number"}


@pytest.mark.parametrize("name, option, value", _cases())
def test_a_hostile_field_is_refused_naming_the_option(name, option, value):
    mod = controller(name)
    write = mod.write_cross_axis if option in ("input_axis", "output_axis", "table_index") \
        else mod.write
    with pytest.raises(ControllerLimitError, match=f"{name}: {option} = "):
        write(_table(), **{option: value})


@pytest.mark.parametrize("name", list(CONTROLLERS))
@pytest.mark.parametrize("axis", ["X\nCompensation spacing : 1 mm", "X1]=0\nM30\n;[",
                                  "X)\n(M30", "X\r\n%"])
def test_an_axis_name_with_a_line_break_adds_no_line(name, axis):
    """Issue 39: ``--axis $'X\\nCompensation spacing : 1 mm'`` added a line to a ``.ren``.

    The table's axis name (from ``--axis`` or a data file's metadata) is written cleaned
    (portable characters) and the source kept in a comment or a note; the file has exactly the
    lines the same table named ``X`` gives."""
    mod = controller(name)
    opts = {"axis": "X"} if name == "heidenhain" else {}
    if name == "heidenhain":   # its axis column takes a letter: refused, not cleaned
        with pytest.raises(ControllerLimitError, match="axis letter"):
            mod.write(_table(axis), **{})
        return
    plain = mod.write(_table("X"), **opts)
    hostile = mod.write(_table(axis), **opts)
    extra = 1 if name in ("siemens-840d", "fanuc", "linuxcnc", "csv") else 0   # the source comment
    assert len(hostile.text.splitlines()) == len(plain.text.splitlines()) + extra
    assert not [ln for ln in hostile.text.splitlines() if ln.lstrip("(;# ").startswith("M30")]
    for line in hostile.text.splitlines():
        assert "\r" not in line and "\x00" not in line
    if name == "renishaw-ren":
        assert any("axis name in the source data" in n for n in hostile.notes)
        assert [ln for ln in hostile.text.splitlines() if ln.startswith("Compensation spacing")
                ] == [ln for ln in plain.text.splitlines() if ln.startswith("Compensation spacing")]


def test_fanuc_axis_number_in_range_is_written():
    """The bounds are not too tight: axis 32 and reference point 89999 - n are tape words."""
    cf = controller("fanuc").write(_table(), axis_number=32)
    assert "N3620A32P" in cf.text
    with pytest.raises(ControllerLimitError, match="axis_number = 33"):
        controller("fanuc").write(_table(), axis_number=33)


def test_siemens_machine_axis_names_of_the_manuals_pass():
    """SINUMERIK machine axis names as the 840D manuals write them: AX1, X1, SP1, MZ_2."""
    for ax in ("AX1", "X1", "SP1", "MZ_2"):
        assert f"$AA_ENC_COMP[0,0,{ax}]" in controller("siemens-840d").write(
            _table(), machine_axis=ax).text
    cf = controller("siemens-840d").write_axes({"AX1": _table(), "AX2": _table()})
    assert "$AA_ENC_COMP[0,0,AX2]" in cf.text
    with pytest.raises(ControllerLimitError, match="machine_axis = 'AX 2'"):
        controller("siemens-840d").write_axes({"AX1": _table(), "AX 2": _table()})


def test_numpy_integers_pass():
    assert "N3620A2P" in controller("fanuc").write(_table(), axis_number=np.int64(2)).text
