"""Every ``-o`` option of ``axiscal compensate`` reaches the file written, or is refused naming
why (issue 42: "options that reach a reader but not its writer" — ``-o machine_axis=AX4`` with
``--to siemens-840d`` used to choose the table read and leave the writer at AX1).

Each writer option of each controller (the keyword arguments of ``controllers.<name>.write``;
:func:`test_the_cases_cover_every_writer_option` keeps the list complete) is given twice:
writing a table from measurements (``compensate SOURCE -c NAME -o KEY=VALUE``) and converting a
table read from a file (``compensate --read T.csv --to NAME -o to.KEY=VALUE``, the writer's
prefix). Either the file (or the enable line the command prints for it) shows the value, or the
command refuses in one line naming the option's rule (a limit such as MD38000, a spacing that
does not fit the position unit).
"""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.compensation.controllers import controller

SOURCE = """# target_unit=mm deviation_unit=um
target,direction,run,deviation
""" + "".join(f"{t},{d},{r},{v}\n" for r, (up, dn) in enumerate(
    [([1.0, 2.0, 3.5, 2.5, 4.0], [1.4, 2.6, 3.9, 3.1, 4.4]),
     ([1.2, 2.2, 3.3, 2.7, 4.2], [1.6, 2.4, 4.1, 3.3, 4.2])], 1)
    for d, vals in (("+", up), ("-", dn)) for t, v in zip((0, 25, 50, 75, 100), vals))

INCH = ("--spacing", "25.4")      # a spacing the inch position units hold (0.001 inch, 0.0254 mm)

#: (controller, KEY=VALUE, extra arguments, --out name, where, what): ``where`` is ``file`` (the
#: file written holds ``what``), ``said`` (the enable line printed for it says ``what``) or
#: ``refused`` (exit 2, the one line says ``what``).
CASES = [
    ("siemens-840d", "machine_axis=AX4", (), "T.INI", "file", "$AA_ENC_COMP[0,1,AX4]="),
    ("siemens-840d", "measuring_system=2", (), "T.INI", "file", "$AA_ENC_COMP_STEP[1,AX1]="),
    ("siemens-840d", "unit=inch", INCH, "T.INI", "file", "$MN_SCALING_SYSTEM_IS_METRIC = 0"),
    ("siemens-840d", "zero_ends=true", (), "T.INI", "file", "$AA_ENC_COMP[0,4,AX1]=0.0\n"),
    ("siemens-840d", "zero_at_reference=false", (), "T.INI", "file",
     "$AA_ENC_COMP[0,0,AX1]=0.0013"),
    ("siemens-840d", "max_points=3", (), "T.INI", "refused", "at most 3"),
    ("siemens-840d", "position_resolution=7", (), "T.INI", "refused", "position unit 7 mm"),
    ("fanuc", "axis_number=3", (), "T.TXT", "file", "N3620A3P"),
    ("fanuc", "reference_number=5", (), "T.TXT", "file", "N3620A1P5"),
    ("fanuc", "detection_unit=0.0001", (), "T.TXT", "file", "1 COUNT = 0.0001 MM"),
    ("fanuc", "magnification=2", (), "T.TXT", "file", "N3623A1P2"),
    ("fanuc", "unit=inch", INCH, "T.TXT", "file", "INCH"),
    ("fanuc", "max_number=3", (), "T.TXT", "refused", "point numbers; the format allows at most 4"),
    ("heidenhain", "axis=Z", (), "Z.COM", "file", "AXISPOS       Z"),
    ("heidenhain", "driving_axis=Y", (), "XY.COM", "file", "BEGIN XY.COM"),
    ("heidenhain", "unit=inch", INCH, "X.COM", "file", "BEGIN X.COM INCH"),
    ("heidenhain", "power_of_two=true", (), "X.COM", "refused", "not a power of two"),
    ("heidenhain", "max_points=3", (), "X.COM", "refused", "at most 3"),
    ("heidenhain", "position_resolution=7", (), "X.COM", "refused", "position unit 7 mm"),
    ("linuxcnc", "joint=2", (), "x.comp", "said", "[JOINT_2] COMP_FILE = x.comp"),
    ("linuxcnc", "file_type=0", (), "x.comp", "file", "25.000000 25.002"),
    ("linuxcnc", "unit=inch", (), "x.comp", "file", "0.9842520 "),
    ("linuxcnc", "max_points=3", (), "x.comp", "refused", "at most 3"),
    ("renishaw-ren", "max_points=3", (), "T.REN", "refused", "at most 3"),
    ("csv", "max_points=3", (), "T.csv", "refused", "unknown option(s) max_points; allowed: none"),
    ("fanuc", "machine_axis=AX4", (), "T.TXT", "refused",
     "unknown option(s) machine_axis; allowed: axis_number"),
]


def _ids(case):
    return f"{case[0]}-{case[1].split('=')[0]}"


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("opts")
    (d / "src.csv").write_text(SOURCE, encoding="utf-8")
    r = CliRunner().invoke(app, ["compensate", str(d / "src.csv"), "-c", "csv", "--out",
                                 str(d / "table.csv")])
    assert r.exit_code == 0, r.output
    return d


def _check(r, out: Path, where: str, what: str) -> None:
    if where == "refused":
        assert r.exit_code == 2, r.output
        assert what in r.output and "Traceback" not in r.output
        assert not out.exists(), "nothing written when refused"
        return
    assert r.exit_code == 0, r.output
    text = out.read_text(encoding="utf-8")
    assert what in (text if where == "file" else r.output), (text, r.output)


@pytest.mark.parametrize("case", CASES, ids=_ids)
def test_option_reaches_the_file_written_from_measurements(case, files, tmp_path):
    name, option, extra, out, where, what = case
    r = CliRunner().invoke(app, ["compensate", str(files / "src.csv"), "-c", name, "-o", option,
                                 *extra, "--out", str(tmp_path / out)])
    _check(r, tmp_path / out, where, what)


@pytest.mark.parametrize("case", CASES, ids=_ids)
def test_option_reaches_the_file_of_a_conversion(case, files, tmp_path):
    """The same option, for the writer of ``--to`` (``to.KEY``), on a table read from a file."""
    name, option, extra, out, where, what = case
    source = files / "table.csv"
    if extra:               # the inch cases: a table read at the spacing the inch units hold
        source = tmp_path / "inch.csv"
        CliRunner().invoke(app, ["compensate", str(files / "src.csv"), "-c", "csv", *extra,
                                 "--out", str(source)])
    r = CliRunner().invoke(app, ["compensate", "--read", str(source), "--to", name, "-o",
                                 f"to.{option}", "--out", str(tmp_path / out)])
    _check(r, tmp_path / out, where, what)


def test_the_cases_cover_every_writer_option():
    """Every keyword option of every writer has a case (a new option needs one)."""
    covered = {(c[0], c[1].split("=")[0]) for c in CASES}
    for name in ("siemens-840d", "fanuc", "heidenhain", "linuxcnc", "csv", "renishaw-ren"):
        params = inspect.signature(controller(name).write).parameters
        for p in params.values():
            if p.kind is inspect.Parameter.KEYWORD_ONLY:
                assert (name, p.name) in covered, f"{name}: -o {p.name} has no case"


def test_a_writer_option_without_to_and_an_option_no_side_takes_are_refused(files, tmp_path):
    run = CliRunner().invoke
    no_to = run(app, ["compensate", "--read", str(files / "table.csv"), "-o", "to.joint=2"])
    assert no_to.exit_code == 2 and "options for the writer need --to NAME" in no_to.output
    neither = run(app, ["compensate", "--read", str(files / "table.csv"), "--to", "linuxcnc",
                        "-o", "bogus=1", "--out", str(tmp_path / "x.comp")])
    assert neither.exit_code == 2 and "bogus" in neither.output
    assert not (tmp_path / "x.comp").exists()


#: What each format's file shows for ``--axis C --home 50 --bidirectional`` (the table's own
#: options): the axis name, the reference (or, where the format holds none, the note saying
#: so) and both directions (a second column, a backlash, or the mean reversal said).
FORMATS = [
    ("siemens-840d", "T.INI", "; axiscal: axis C,", "$AA_ENC_COMP[0,2,AX1]=0.0\n",
     "MD32450 $MA_BACKLASH[0,AX1] = 0.00044 mm"),
    ("fanuc", "T.TXT", "AXIS C,", "(REFERENCE POSITION 50 MM AT POINT 2)", "N3626A1P"),
    ("heidenhain", "C.COM", "AXISPOS       C", "a heidenhain file holds no reference position",
     "BACKLASH"),
    ("linuxcnc", "x.comp", "# axiscal: axis C", "a linuxcnc file holds no reference position",
     "0.000000 -0.001100 -0.001500"),
    ("csv", "T.csv", "axis=C", "reference_index=2", "bidirectional=true"),
    ("renishaw-ren", "T.REN", "Axis : C", "a renishaw-ren file holds no reference position",
     "Mean reversal : -0.000440 mm"),
]


@pytest.mark.parametrize("name,out,axis,home,both", FORMATS, ids=[f[0] for f in FORMATS])
def test_axis_home_and_both_directions_reach_every_format(name, out, axis, home, both, files,
                                                          tmp_path):
    r = CliRunner().invoke(app, ["compensate", str(files / "src.csv"), "-c", name, "--axis",
                                 "C", "--home", "50", "--bidirectional", "--out",
                                 str(tmp_path / out)])
    assert r.exit_code == 0, r.output
    shown = (tmp_path / out).read_text(encoding="utf-8") + r.output
    for what in (axis, home, both):
        assert what in shown, what
