"""An ISO 230-3:2020 thermal test kept in the history (issue 44): a thermal log is one record
whose figures are those of ``axiscal thermal evaluate --json`` on the same file, field by field
(value, U with k = 2, unit, clause), on every path (History.add, ``history show --json``,
History.evaluation, a workbench upload and its page); ``history show --report`` writes
``thermal evaluate --report``'s report; a damaged log (a gap, time going backwards) is refused
by ``history add`` with one line, exit 2, and nothing stored.

The logs are the thermal twin's (``thermal simulate``, 5-minute samples: the longest interval
a log may have, which keeps the test fast); the figures' reference is the command itself."""

from __future__ import annotations

import json
import re

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app as cli_app
from axiscal.errors import DataFormatError
from axiscal.io.thermal import write_thermal_log
from axiscal.store import open_store
from axiscal.web.app import create_app

runner = CliRunner()
#: The store's ASCII names of the figures' display units (``thermal evaluate`` writes µ).
ASCII = {"µm": "um", "µrad": "urad", "K": "K", "µm/m": "um/m", "h": "h"}


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("thermal")
    out = {}
    for test in ("linear", "spindle"):
        sim = axiscal.simulate_thermal(test, seed=1, interval_s=300.0)
        out[test] = folder / f"{test}.csv"
        write_thermal_log(out[test], sim.log)
    return out


def _cli(*args) -> dict:
    r = runner.invoke(cli_app, [*map(str, args), "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


@pytest.mark.parametrize("test", ["linear", "spindle"])
def test_the_stored_test_is_thermal_evaluate_of_the_file_field_by_field(logs, tmp_path, test):
    path = logs[test]
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    want = _cli("thermal", "evaluate", path)
    added = _cli("history", "add", path, "--db", url, "--machine", "VMC", "--axis", "X")
    assert added["kind"] == "thermal"
    shown = _cli("history", "show", added["id"], "--db", url)
    result, q = shown["result"], shown["quantities"]
    for key in want:                                     # test, clause, duration_h, figures...
        assert result[key] == want[key], key
    assert len(want["figures"]) >= 13
    for f in want["figures"]:
        assert q[f["name"]]["value"] == f["value"] and q[f["name"]]["U"] == f["U"], f["name"]
        assert q[f["name"]]["unit"] == ASCII[f["unit"]] and q[f["name"]]["k"] == 2.0
    store = open_store(url)
    try:
        ev = axiscal.History(store=store).evaluation(added["id"])
        assert ev.to_dict() == axiscal.evaluate(path).to_dict()
        assert {k: ev.to_dict()[k] for k in want} == want
    finally:
        store.close()


def test_history_show_report_is_thermal_evaluates_report(logs, tmp_path):
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    added = _cli("history", "add", logs["linear"], "--db", url, "--machine", "VMC")
    r = runner.invoke(cli_app, ["history", "show", str(added["id"]), "--db", url,
                                "--report", str(tmp_path / "r.html")])
    assert r.exit_code == 0, r.output
    html = (tmp_path / "r.html").read_text("utf-8")
    assert "Thermal effects (ISO 230-3) — VMC axis X" in html
    for f in _cli("thermal", "evaluate", logs["linear"])["figures"][:3]:
        assert f["label"] in html
    assert "<svg" in html or "data:image" in html


def _damaged(path, how: str) -> str:
    lines = path.read_text("utf-8").splitlines()
    i = next(n for n, s in enumerate(lines) if s.startswith("time_s"))
    if how == "gap":
        lines = lines[:i + 5] + lines[i + 8:]
    else:                                                # time going backwards
        lines = lines[:i + 5] + [lines[i + 7], lines[i + 6]] + lines[i + 8:]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("how, says", [("gap", "a gap of"), ("back", "time goes backwards")])
def test_a_damaged_log_is_refused_with_one_line_and_nothing_stored(logs, tmp_path, how, says):
    bad = tmp_path / f"{how}.csv"
    bad.write_text(_damaged(logs["linear"], how), "utf-8")
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(cli_app, ["history", "add", str(bad), "--db", url, "--machine", "VMC"])
    assert r.exit_code == 2 and says in r.output
    assert len(r.output.strip().splitlines()) == 1 and "Traceback" not in r.output
    store = open_store(url)
    try:
        with pytest.raises(DataFormatError, match=says):
            store.add(bad.read_bytes(), bad.name, machine="VMC", axis="X")
        assert store.tests() == []
    finally:
        store.close()


def test_the_workbench_page_shows_the_figures_with_units_and_the_plot(logs, tmp_path):
    client = TestClient(create_app(f"sqlite:///{tmp_path / 'w.sqlite'}"),
                        base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', client.get("/").text).group(1)
    path = logs["spindle"]
    up = client.post("/upload", data={"csrf": token, "machine": "VMC", "axis": "Z"},
                     files={"file": (path.name, path.read_bytes(), "text/csv")},
                     follow_redirects=False)
    assert up.status_code == 303, up.text
    page = client.get(up.headers["location"]).text
    table = page.split('<table id="thermal-figures">')[1].split("</table>")[0]
    want = _cli("thermal", "evaluate", path)["figures"]
    for f in want:
        row = table.split(f"<td>{f['name']}</td>")[1].split("</tr>")[0]
        assert f">{f['value']:.3f}<" in row and f">{f['U']:.3f}<" in row, f["name"]
        assert f"<td>{f['unit']}</td>" in row and f["clause"] in row
    assert {"µm", "µrad", "K"} <= {f["unit"] for f in want}
    assert 'id="kind-figure" src="data:image/svg+xml;base64,' in page
    assert "ISO 230-3:2020 Clause 6" in page
