"""A five-axis kinematics test kept in the history (issue 43): a probing or R-test CSV that
states its machine's nominal geometry is one record whose numbers are those of ``axiscal
fiveaxis identify --json`` on the same file (value and U, ISO 230-1 names), on every path
(History.add, ``history show --json``, History.evaluation, axiscal.evaluate, a workbench upload
and its page); a file without the geometry is refused with one line and nothing stored."""

from __future__ import annotations

import json
import re
import tomllib
from importlib import resources

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import axiscal
from axiscal.api import fiveaxis
from axiscal.cli import app as cli_app
from axiscal.errors import DataFormatError
from axiscal.store import open_store
from axiscal.web.app import create_app

runner = CliRunner()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    cfg["setup"] = cfg["setup"][0:1] + cfg["setup"][2:]       # one sphere and the R-test
    folder = tmp_path_factory.mktemp("fiveaxis")
    return fiveaxis.simulate(cfg, seed=3, out=folder).files


def _cli(*args) -> dict:
    r = runner.invoke(cli_app, [*map(str, args), "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


@pytest.mark.parametrize("which", [0, 1])
def test_the_stored_test_is_the_identification_of_the_file(files, tmp_path, which):
    path = files[which]
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    want = {e["name"]: (e["value"], e["U"]) for e in
            _cli("fiveaxis", "identify", path)["errors"]}   # the shipped A/C example's geometry
    store = open_store(url)
    try:
        added = store.add(path.read_bytes(), path.name, machine="5AX", axis="AC")
        rec = store.get(added.id)
        assert rec.summary.kind == "fiveaxis"
        q = rec.result["quantities"]
        assert {n: (q[n]["value"], q[n]["U"]) for n in want} == want
        assert {q[n]["unit"] for n in want} == {"um", "urad"} and q["E_X0C"]["k"] == 2.0
        assert "E_C0C" in [u["name"] for u in rec.result["unidentified"]]
        shown = _cli("history", "show", added.id, "--db", url)
        assert shown["quantities"] == q
        ev = axiscal.History(store=store).evaluation(added.id)
        assert ev.to_dict() == axiscal.evaluate(path).to_dict()
    finally:
        store.close()


def test_a_file_without_the_machine_geometry_is_refused_and_nothing_stored(files, tmp_path):
    text = "\n".join(line for line in files[0].read_text("utf-8").splitlines()
                     if "_position_mm" not in line) + "\n"
    store = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    try:
        with pytest.raises(DataFormatError, match="states its machine's nominal geometry"):
            store.add(text.encode(), "probing.csv", machine="5AX", axis="AC")
        one = text.replace("# sphere_radius_mm", "# c_position_mm = 0, 0\n# sphere_radius_mm")
        with pytest.raises(DataFormatError, match="c_position_mm without tilt_position_mm"):
            store.add(one.encode(), "probing.csv", machine="5AX", axis="AC")
        assert store.tests() == []
    finally:
        store.close()


def test_the_workbench_page_shows_the_errors_in_iso_names_with_u(files, tmp_path):
    client = TestClient(create_app(f"sqlite:///{tmp_path / 'w.sqlite'}"),
                        base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', client.get("/").text).group(1)
    path = files[0]
    up = client.post("/upload", data={"csrf": token, "machine": "5AX", "axis": "AC"},
                     files={"file": (path.name, path.read_bytes(), "text/csv")},
                     follow_redirects=False)
    assert up.status_code == 303, up.text
    page = client.get(up.headers["location"]).text
    table = page.split('<table id="location-errors">')[1].split("</table>")[0]
    want = _cli("fiveaxis", "identify", path)["errors"]
    for e in want:
        assert f"<td>{e['name']}</td>" in table and f"{e['value']:+.3f}" in table
        assert f"{e['U']:.3f}" in table
    assert "E_C0C" in page.split('<table id="unidentified">')[1].split("</table>")[0]
    assert 'id="kind-figure" src="data:image/svg+xml;base64,' in page


def test_its_report_from_the_history_is_the_identifications(files, tmp_path):
    """``history show ID --report`` (the workbench's Report link, :meth:`History.report`) of a
    five-axis test writes ``fiveaxis identify --report``'s report of the same file (its values
    with U), titled with the names the history keeps; it raised KeyError before."""
    path = files[1]
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    store = open_store(url)
    try:
        added = store.add(path.read_bytes(), path.name, machine="5AX", axis="AC")
    finally:
        store.close()
    r = runner.invoke(cli_app, ["history", "show", str(added.id), "--db", url, "--report",
                                str(tmp_path / "h.html")])
    assert r.exit_code == 0, r.output
    r = runner.invoke(cli_app, ["fiveaxis", "identify", str(path), "--report",
                                str(tmp_path / "c.html")])
    assert r.exit_code == 0, r.output
    stored, cli = ((tmp_path / n).read_text("utf-8") for n in ("h.html", "c.html"))
    assert "Five-axis location errors (ISO 230-1 / ISO 230-7) — 5AX axis AC" in stored
    rows = re.compile(r"<tr><td>(E<sub>[A-Z0-9]+</sub>[^<]*)</td><td>([^<]+)</td><td>([^<]+)</td>")
    assert rows.findall(stored) and rows.findall(stored) == rows.findall(cli)
