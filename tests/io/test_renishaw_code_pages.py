"""Renishaw exports in Windows code pages (``--encoding``) and ``.rta`` results in µrad beside
the arcsec shown (issue 42).

Renishaw's software runs on Windows and writes the PC's ANSI code page: a Polish "Łódź" in the
USER-TEXT is the cp1250 bytes A3 F3 64 9F, read as cp1252 they are "£ódŸ". The ``.rta``
deviations are µrad (Read Laser Plot multiplies them by 0.2063 for arcsec: 1″ = π/648000 rad =
4.8481 µrad, ISO 80000-3)."""

from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from axiscal import api
from axiscal.cli import app
from axiscal.errors import AxiscalError, InputError
from axiscal.io.renishaw import decode, encode, format_rtl, parse_rtl

from test_renishaw import renishaw_text

T = [0.0, 45.0, 90.0, 135.0]
UP1, DN1 = [4.8481, 2.0, -1.0, 3.5], [5.0, 2.5, -0.5, 4.0]
RUNS = [UP1, DN1, [v + 0.3 for v in UP1], [v - 0.2 for v in DN1]]
USER = {"Machine": "Drehtisch Łódź", "Axis": "C", "TITLE": "nach Wartung"}
run = CliRunner().invoke


@pytest.fixture
def rta(tmp_path):
    path = tmp_path / "c.rta"
    path.write_bytes(renishaw_text("rta", T, RUNS, user=USER).encode("cp1250"))
    return path


def test_code_page_given_on_the_command_line_reaches_the_reader(rta):
    assert rta.read_bytes().count(b"\xa3\xf3d\x9f") == 1          # Łódź in cp1250
    default = run(app, ["iso230-2", str(rta), "--json"])
    given = run(app, ["iso230-2", str(rta), "--json", "--encoding", "cp1250"])
    assert default.exit_code == given.exit_code == 0
    assert '"machine": "Drehtisch £ódŸ"' in default.output       # Windows-1252 by default
    assert '"machine": "Drehtisch Łódź"' in given.output
    assert "read as windows-1250 text" in given.output
    ev = run(app, ["evaluate", str(rta), "-s", "iso230-2:2014", "--encoding", "windows-1250"])
    assert ev.exit_code == 0, ev.output


def test_unknown_code_page_or_a_file_that_is_no_export_refused_in_one_line(rta, tmp_path):
    bad = run(app, ["iso230-2", str(rta), "--encoding", "cp9999"])
    assert bad.exit_code == 2 and "encoding 'cp9999': one of utf-8, utf-16, cp1252" in bad.output
    csv = tmp_path / "x.csv"
    csv.write_text("# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
                   "0,+,1,1\n10,+,1,2\n0,+,2,1\n10,+,2,2\n", encoding="utf-8")
    no = run(app, ["iso230-2", str(csv), "--encoding", "cp1250"])
    assert no.exit_code == 2 and "is not one (axiscal reads its other files as UTF-8)" in no.output
    with pytest.raises(InputError, match="is not one"):
        api.read(csv.read_bytes(), encoding="cp1250")
    assert api.read(rta.read_bytes(), encoding="cp1250").metadata.machine == "Drehtisch Łódź"
    with pytest.raises(InputError, match="already decoded"):
        api.read(rta.read_text(encoding="cp1250"), encoding="cp1250")


def test_history_with_a_code_page_it_would_not_reread_alike_is_refused(rta, tmp_path):
    r = run(app, ["iso230-2", str(rta), "--encoding", "cp1250", "--history", "--db",
                  f"sqlite:///{tmp_path / 'h.db'}"])
    assert r.exit_code == 2 and "re-reads it without --encoding cp1250" in r.output
    assert not (tmp_path / "h.db").exists() or "stored as" not in r.output


def test_compensate_reads_its_source_in_the_code_page_and_refuses_it_unused(rta):
    ok = run(app, ["compensate", str(rta), "--encoding", "cp1250", "-c", "csv"])
    assert ok.exit_code == 0 and "axis C" in ok.output
    unused = run(app, ["compensate", "--verify", "x.toml", "--encoding", "cp1250"])
    assert unused.exit_code == 2 and "--verify does not use --encoding" in unused.output


def test_the_writer_takes_the_code_page_and_reads_back():
    """``simulate --data x.rtl --encoding`` writes the export as the Windows program would."""
    ds = parse_rtl(renishaw_text("rtl", [0.0, 100.0], [[1.0, 2.0], [1.5, 2.5]], user=USER))
    raw = encode(format_rtl(ds), "cp1250")
    assert b"\xa3\xf3d\x9f" in raw and decode(raw, "cp1250")[0] == format_rtl(ds)
    assert parse_rtl(decode(raw, "cp1250")[0]).metadata.machine == "Drehtisch Łódź"
    with pytest.raises(InputError, match="'Ł' .* is not in windows-1252"):
        encode(format_rtl(ds), "cp1252")
    assert encode("x", "utf-16").startswith(b"\xff\xfe")


def test_simulate_writes_the_export_in_the_code_page(tmp_path):
    out = tmp_path / "s.rtl"
    r = run(app, ["simulate", "src/axiscal/data/demo_linear.toml", "--data", str(out),
                  "--encoding", "utf-16"])
    assert r.exit_code == 0 and out.read_bytes().startswith(b"\xff\xfe")
    assert api.read(out).n_targets > 2
    csv = run(app, ["simulate", "src/axiscal/data/demo_linear.toml", "--data",
                    str(tmp_path / "s.csv"), "--encoding", "cp1250"])
    assert csv.exit_code == 2 and "s.csv is written as UTF-8: drop --encoding" in csv.output
    assert not (tmp_path / "s.csv").exists()


def test_rta_results_in_arcsec_with_the_files_microradians_kept_in_json(rta):
    """Every deviation parameter of the ``--json`` is also given in µrad, the file's unit, and
    each is the arcsec value × 4.8481 (ISO 80000-3: 1″ = π/648000 rad)."""
    d = __import__("json").loads(run(app, ["iso230-2", str(rta), "--json"]).output)
    assert d["unit"] == "arcsec"
    block = d["in_file_unit"]
    assert block["deviation_unit"] == "urad" and block["source"] == "the .rta file's unit"
    k = math.pi / 648000 * 1e6
    assert k == pytest.approx(4.8481, abs=1e-4)
    for name in ("A", "E", "M", "R", "B"):
        assert block["parameters"][name] == pytest.approx(d[name] * k, rel=1e-12)
    # E↑ of run values 4.8481 … −1.0 µrad (+0.3 on run 2): the largest minus the smallest mean
    assert block["parameters"]["E_up"] == pytest.approx(4.8481 + 0.15 - (-1.0 + 0.15), abs=1e-9)
    lin = api.evaluate(api.read(rta, deviation_unit="urad")).to_dict()
    assert "in_file_unit" not in lin and lin["unit"] == "urad"


def test_encode_and_decode_raise_only_axiscal_errors():
    for name in ("", "latin-1", "utf-32", "cp65001"):
        with pytest.raises(AxiscalError):
            encode("x", name)


def test_rta_microradians_kept_by_every_standard_of_evaluate(rta):
    """``evaluate -s all --json``: each standard evaluated has its deviation parameters in µrad
    too, each the arcsec value × 4.8481."""
    d = __import__("json").loads(run(app, ["evaluate", str(rta), "-s", "all", "--json"]).output)
    block = d["in_file_unit"]
    assert block["deviation_unit"] == "urad"
    k = math.pi / 648000 * 1e6
    evaluated = [s for s in d["standards"] if s["evaluated"]]
    assert len(evaluated) >= 3 and set(block["standards"]) == {s["standard"] for s in evaluated}
    for s in evaluated:
        for name, p in s["parameters"].items():
            if p["unit"] == "arcsec" and p["value"] is not None:
                assert block["standards"][s["standard"]][name] == pytest.approx(p["value"] * k)
