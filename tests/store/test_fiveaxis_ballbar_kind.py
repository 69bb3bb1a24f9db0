"""A five-axis ballbar test kept in the history (issue 43; ISO 10791-6:2014 as
axiscal.standards.iso10791_6 reads it): the CSV ``fiveaxis ballbar simulate`` writes (and
``fiveaxis ballbar evaluate`` reads) is one record whose result is, key by key, that command's
``--json`` set-up, on every path (History.add, ``history show --json``, History.evaluation,
axiscal.evaluate, a workbench upload and its page, ``history show --report``); a bad file is
refused with one line and nothing stored."""

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
from axiscal.store.kinds import detect_kind
from axiscal.web.app import create_app

runner = CliRunner()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("bb")
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    cfg["ballbar"] = cfg["ballbar"][:2]
    return fiveaxis.ballbar.simulate(cfg, seed=4, out=folder).files


def _cli(*args) -> dict:
    r = runner.invoke(cli_app, [*map(str, args), "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_the_stored_test_is_the_commands_evaluation_key_by_key(files, tmp_path):
    path = files[0]
    assert detect_kind(path.read_text("utf-8")) == "fiveaxis-ballbar"
    want = _cli("fiveaxis", "ballbar", "evaluate", path)["setups"][0]
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(cli_app, ["history", "add", str(path), "--db", url, "--machine", "5AX",
                                "--axis", "AC"])
    assert r.exit_code == 0 and "fiveaxis-ballbar" in r.output, r.output
    shown = _cli("history", "show", "1", "--db", url)
    assert shown["kind"] == "fiveaxis-ballbar"
    for key, value in want.items():
        assert shown["result"][key] == value, key
    q = shown["quantities"]["range"]
    assert (q["value"], q["U"], q["k"], q["unit"]) == (want["range_um"], want["U_um"], 2.0,
                                                       "um")
    store = open_store(url)
    try:
        ev = axiscal.History(store=store).evaluation(1)
        assert ev.to_dict() == axiscal.evaluate(path).to_dict()
    finally:
        store.close()
    r = runner.invoke(cli_app, ["history", "show", "1", "--db", url, "--report",
                                str(tmp_path / "h.html")])
    assert r.exit_code == 0, r.output
    html = (tmp_path / "h.html").read_text("utf-8")
    assert "Five-axis ballbar test (ISO 10791-6 as axiscal reads it) — 5AX axis AC" in html
    assert f"{want['range_um']:.3f}" in html or f"{want['range_um']:.2f}" in html
    assert "data:image/" in html or "<svg" in html


def test_a_bad_file_is_refused_in_one_line_and_nothing_stored(files, tmp_path):
    good = files[1].read_text("utf-8").splitlines()
    gap = "\n".join(line for line in good if not line.startswith("5,")) + "\n"
    nan = "\n".join(good[:-1] + [re.sub(r",[^,]+$", ",nan", good[-1])]) + "\n"
    store = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    try:
        for text, rule in ((gap, "pose"), (nan, "finite|number")):
            with pytest.raises(DataFormatError, match=rule):
                store.add(text.encode(), "bb.csv", machine="5AX", axis="AC")
        assert store.tests() == []
    finally:
        store.close()


def test_the_workbench_page_shows_the_range_with_u_and_its_budget(files, tmp_path):
    client = TestClient(create_app(f"sqlite:///{tmp_path / 'w.sqlite'}"),
                        base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', client.get("/").text).group(1)
    path = files[1]
    up = client.post("/upload", data={"csrf": token, "machine": "5AX", "axis": "AC"},
                     files={"file": (path.name, path.read_bytes(), "text/csv")},
                     follow_redirects=False)
    assert up.status_code == 303, up.text
    page = client.get(up.headers["location"]).text
    want = _cli("fiveaxis", "ballbar", "evaluate", path)["setups"][0]
    table = page.split('<table id="ballbar-range">')[1].split("</table>")[0]
    assert f"{want['range_um']:.3f}" in table and f"{want['U_um']:.3f}" in table
    budget = page.split('<table id="ballbar-budget">')[1].split("</table>")[0]
    assert all(n in budget for n in ("u_NOISE", "u_GAIN", "u_DRIFT"))
    assert 'id="kind-figure" src="data:image/svg+xml;base64,' in page
