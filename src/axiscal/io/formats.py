"""Every file format axiscal reads and writes (``axiscal formats``).

One entry a format: its name, whether axiscal reads and/or writes it, its extensions, an example
file a user can open (a file of the repository or a command that writes one), and where it is
described (a module docstring, or the public source of a foreign format).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

__all__ = ["FileFormat", "FORMATS"]


@dataclass(frozen=True)
class FileFormat:
    """One format."""

    name: str
    read: bool
    write: bool
    extensions: tuple
    example: str
    described_in: str

    def as_dict(self) -> dict:
        d = asdict(self)
        d["extensions"] = list(self.extensions)
        return d


FORMATS: tuple[FileFormat, ...] = (
    FileFormat("Tidy positioning CSV (ISO 230-2 readings)", True, True, (".csv",),
               "demo-output/linear_data.csv (make demo)", "axiscal.io.csv; README 'File formats'"),
    FileFormat("axiscal positioning JSON", True, True, (".json",),
               "axiscal simulate src/axiscal/data/demo_linear.toml --data x.json",
               "axiscal.io.json"),
    FileFormat("EPICS ecmc ISO 230-2 file", True, True, (".txt", ".ecmc"),
               "tests/io (built to the ecmc description)", "axiscal.io.ecmc"),
    FileFormat("Raw laser readings (uncompensated, with times)", True, False, (".csv",),
               "axiscal.io.measured docstring", "axiscal.io.measured"),
    FileFormat("Environment log (air, pressure, humidity, material sensors)", True, False,
               (".csv", ".json"), "axiscal.io.measured docstring", "axiscal.io.measured"),
    FileFormat("Continuous record (time, reading[, commanded])", True, False, (".csv",),
               "axiscal.io.measured docstring", "axiscal.io.measured"),
    FileFormat("EPICS camonitor log (setpoint and reference PVs)", True, False,
               (".log", ".txt"), "tests/io/test_epics.py builds one from a real ecmc test "
               "(tests/data/ecmc)", "axiscal.io.epics (EPICS Base camonitor, "
               "modules/ca/src/tools/tool_lib.c; real ecmc logs, "
               "github.com/anderssandstrom/ecmc_target_muts_logger)"),
    FileFormat("Renishaw XL-80 dynamic capture", True, False, (".rtx",),
               "tests/io/test_rtx.py builds one to the public description",
               "axiscal.io.rtx (T. Pani, rtx2csv, github.com/TanmayPani/rtx2csv)"),
    FileFormat("Renishaw linear positioning export (HEADER:: … EOF::)", True, True, (".rtl",),
               "tests/io/test_renishaw.py builds them to the public descriptions (no real "
               "public sample found)",
               "axiscal.io.renishaw (a C# writer, Paolico/AxisCorection RtlParser.java, a C++ "
               "and a JavaScript reader; see the module docstring)"),
    FileFormat("Renishaw angular positioning export (deviations in µrad)", True, True, (".rta",),
               "tests/io/test_renishaw.py (no real public sample found)",
               "axiscal.io.renishaw (Read Laser Plot: .rta deviations × 0.2063 = arcsec; shown "
               "in arcsec, --json keeps µrad; --encoding for a code page)"),
    FileFormat("Renishaw .ren compensation export (spacing, start, end, Combined)", True, True,
               (".ren",), "axiscal compensate ... --controller renishaw-ren",
               "axiscal.compensation.controllers.renishaw_ren (a public .REN → Siemens "
               "$AA_ENC_COMP converter)"),
    FileFormat("Test plan", True, True, (".csv",),
               "axiscal plan linear --length 800 --csv plan.csv", "axiscal.io.measured"),
    FileFormat("Straightness trajectory", True, True, (".csv",),
               "examples/squareness_L180_x.csv", "axiscal.io.straightness"),
    FileFormat("Squareness test from two straightness trajectories", True, True, (".toml",),
               "axiscal squareness biaxial examples/squareness_L180_x.csv "
               "examples/squareness_L180_y.csv --inline sq.toml", "axiscal.io.biaxial"),
    FileFormat("Ballbar trace", True, True, (".csv",), "examples/squareness_ballbar_150mm.csv",
               "axiscal.io.ballbar"),
    FileFormat("Multi-point diagonal test", True, True, (".csv",),
               "examples/squareness_diagonal_600x800.csv", "axiscal.io.ballbar"),
    FileFormat("Five motion errors of a rotary axis", True, True, (".csv",),
               "axiscal motion simulate examples/motion_indexing_table.toml --csv m.csv",
               "axiscal.io.motion"),
    FileFormat("Machine, instrument and test configurations", True, False, (".toml",),
               "examples/*.toml, src/axiscal/data/*.toml", "README 'File formats'"),
    FileFormat("Volumetric machine configuration", True, True, (".toml",),
               "axiscal volumetric simulate --out vol", "axiscal.io.volumetric"),
    FileFormat("ISO 230-3 thermal log (time, temperatures, displacements)", True, True, (".csv",),
               "axiscal thermal simulate --test spindle --out s.csv", "axiscal.io.thermal"),
    FileFormat("Drift check (ISO 230-2 Annex A.5 readings)", True, True, (".csv",),
               "axiscal thermal simulate --test drift-check --out dc.csv", "axiscal.io.drift"),
    FileFormat("ISO 230-2 result JSON (for compensation)", True, True, (".json",),
               "axiscal iso230-2 FILE --json > r.json", "axiscal.io.results"),
    FileFormat("Siemens 840D compensation (%_N_AX_EEC_INI, %_N_NC_CEC_INI)", True, True,
               (".ini", ".mpf"), "axiscal compensate demo-output/linear_data.csv --controller "
               "siemens-840d --spacing 10 --out x.ini; tests/data/siemens/archive_layout",
               "axiscal.compensation.controllers (K3; loader .MPF programs; INITIAL.INI with "
               "--ini; checked against a real DMU 85 series start-up archive, "
               "tests/data/siemens/README.md)"),
    FileFormat("Fanuc pitch error parameters", True, True, (".txt",),
               "axiscal compensate ... --controller fanuc", "axiscal.compensation.controllers"),
    FileFormat("Heidenhain .COM and .CMA", True, True, (".com", ".cma"),
               "axiscal compensate ... --controller heidenhain",
               "axiscal.compensation.controllers"),
    FileFormat("LinuxCNC compensation file", True, True, (".txt", ".dat"),
               "axiscal compensate ... --controller linuxcnc",
               "axiscal.compensation.controllers"),
    FileFormat("Compensation table CSV", True, True, (".csv",),
               "axiscal compensate ... --controller csv", "axiscal.compensation.controllers"),
    FileFormat("Calibration history archive", True, True, (".zip",),
               "axiscal history export h.zip", "axiscal.store.archive"),
    FileFormat("Five-axis probing CSV (sphere probed at many rotary poses)", True, True,
               (".csv",), "axiscal fiveaxis simulate --out run (run/1_probing.csv)",
               "axiscal.io.five_axis; README 'File formats'"),
    FileFormat("Five-axis R-test CSV (displacements in the table frame)", True, True,
               (".csv",), "axiscal fiveaxis simulate --out run (run/3_r-test.csv)",
               "axiscal.io.five_axis; README 'File formats'"),
    FileFormat("Five-axis ballbar CSV (a rotary axis moving with the linear axes)", True, True,
               (".csv",), "axiscal fiveaxis ballbar simulate --out bb (bb/1_ballbar.csv)",
               "axiscal.io.five_axis_ballbar; README 'Five-axis ballbar tests'"),
    FileFormat("LinuxCNC trt kinematics pins (halcmd setp lines)", False, True, (".hal",),
               "axiscal fiveaxis compensate run/*.csv --out trt.hal",
               "axiscal.compensation.five_axis"),
    FileFormat("HTML report", False, True, (".html",), "demo-output/linear_report.html",
               "axiscal.report.html"),
    FileFormat("Plot", False, True, (".png", ".svg", ".pdf"), "demo-output/linear_iso230-2.png",
               "axiscal.report"),
)
