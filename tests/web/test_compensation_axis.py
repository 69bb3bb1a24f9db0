"""The workbench's compensation-table form takes the axis name as ``axiscal compensate --axis``
(issue 31): an ecmc test, whose axis is an EPICS PV name, gives a HEIDENHAIN table once a letter
is typed; a name that is not a letter is refused in one line before anything is stored."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.cli import app as cli
from axiscal.web.app import create_app

#: A real PSI/ESS ecmc ISO 230-2 file (tests/data/ecmc/README.md): axis IOC_TEST:Axis1-PosSet,
#: targets 15 ... 55.8 mm every 10.2 mm, 5 cycles each way.
ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"


@pytest.fixture(scope="module")
def ecmc_site(tmp_path_factory):
    """A workbench with the ecmc test stored (its axis the file's PV name, upper case as the
    history keeps axis names)."""
    d = tmp_path_factory.mktemp("ecmc")
    mp = pytest.MonkeyPatch()
    mp.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
    c = TestClient(create_app(f"sqlite:///{d / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": token, "machine": "MCU1025"},   # the file names none
               files={"file": (ECMC.name, ECMC.read_bytes(), "text/plain")})
    assert r.status_code == 200, r.text[-500:]
    test_id = int(re.search(r"/tests/(\d+)", str(r.url)).group(1))
    yield c, token, test_id, d
    mp.undo()


def _post(c, token, test_id, **fields):
    return c.post(f"/tests/{test_id}/compensation",
                  data={"csrf": token, "controller": "heidenhain", "spacing": "10.2", **fields})


def test_heidenhain_table_with_a_letter_is_the_commands(ecmc_site):
    """Axis X on the page gives, byte for byte, the X.COM that ``axiscal compensate FILE
    --controller heidenhain --axis X`` writes with the settings the page uses (the spacing typed,
    both directions as measured: ``--bidirectional``, corrections not rounded: ``--resolution
    0``); the table is listed under its name and the default is shown beside the field."""
    c, token, test_id, d = ecmc_site
    page = c.get(f"/tests/{test_id}").text
    assert "IOC_TEST:AXIS1-POSSET" in page and 'name="axis"' in page
    assert "default: the test's, IOC_TEST:AXIS1-POSSET" in page
    assert "(as <code>--bidirectional</code>), not rounded (as <code>--resolution 0</code>)" in page
    r = _post(c, token, test_id, axis="X")
    assert r.status_code == 200, r.text[-300:]
    assert 'filename="X.COM"' in r.headers["content-disposition"]
    out = d / "X.COM"
    cli_run = CliRunner().invoke(cli, ["compensate", str(ECMC), "--controller", "heidenhain",
                                       "--axis", "X", "--spacing", "10.2", "--bidirectional",
                                       "--resolution", "0", "--out", str(out)])
    assert cli_run.exit_code == 0, cli_run.output
    assert r.content == out.read_bytes()
    assert r.text.startswith("BEGIN X.COM MM\nNR") and "BACKLASH" in r.text
    assert len(re.findall(r"^\d+\s+\+", r.text, re.M)) == 5          # 15 ... 55.8 mm
    assert "heidenhain: <a" in c.get(f"/tests/{test_id}").text.split('id="tables"')[1]
    assert ">X.COM</a>" in c.get(f"/tests/{test_id}").text


def test_letter_in_either_case_and_other_controllers_take_the_name(ecmc_site):
    """``c`` is written as C (the writer's rule); a csv table takes any name, sanitised by the
    writer as the command does."""
    c, token, test_id, _ = ecmc_site
    r = _post(c, token, test_id, axis="c")
    assert r.status_code == 200 and r.text.startswith("BEGIN C.COM MM")
    r = c.post(f"/tests/{test_id}/compensation", data={"csrf": token, "controller": "csv",
                                                        "spacing": "10.2", "axis": "IOC:m1"})
    assert r.status_code == 200
    assert r.text.splitlines()[1].startswith("# axis=IOC_m1 ")
    assert r.text.splitlines()[2] == "# axis name in the source data: IOC:m1"


@pytest.mark.parametrize("axis, words", [
    ("Q", "axis 'Q' is not an axis letter"),
    ("IOC:m1", "axis 'IOC:m1' is not an axis letter"),
    ("XY", "axis 'XY' is not an axis letter"),
    ("", "the test's axis 'IOC_TEST:AXIS1-POSSET' is not an axis letter"),
])
def test_a_bad_letter_is_refused_in_one_line_and_nothing_stored(ecmc_site, axis, words):
    """The workbench's error page (HTTP 400) says in one line what is wrong and where to type
    the letter; no table is stored."""
    c, token, test_id, _ = ecmc_site
    before = c.get(f"/tests/{test_id}").text.count("/tables/")
    r = _post(c, token, test_id, axis=axis)
    assert r.status_code == 400
    main = r.text.split("<main>")[1] if "<main>" in r.text else r.text
    text = re.sub(r"<[^>]+>", "", main).replace("&#39;", "'").replace("&#34;", '"')
    line = next(x for x in text.splitlines() if "axis letter" in x)
    assert words in line and "type one in the Axis field" in line
    assert "X, Y, Z, A, B, C, U, V, W" in line and "MANUALplus 620" in line
    assert "Traceback" not in r.text and "-o axis" not in r.text
    assert c.get(f"/tests/{test_id}").text.count("/tables/") == before
