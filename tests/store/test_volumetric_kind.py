"""A volumetric test kept in the history (issue 40): a volumetric configuration holding its 21
errors inline (``axiscal volumetric map CONFIG --inline FILE`` writes it from the measured
files) is one record whose result is ``axiscal volumetric map FILE --json``'s object, key by key,
on every path (``history show --json``, History.evaluation, the workbench page), each figure with
the U of :mod:`axiscal.standards.iso230_9_volumetric` (the command's own); ``history show
--report`` writes ``volumetric map --report``'s report under the same heading; a configuration
that names its measured files is refused by ``history add`` with one line, nothing stored.

The machine is the volumetric twin's (``volumetric simulate --points 5``); the figures'
reference is the command itself on the same file."""

from __future__ import annotations

import json
import re

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app as cli_app
from axiscal.store import open_store
from axiscal.web.app import create_app

runner = CliRunner()


def _cli(*args, json_out=True):
    r = runner.invoke(cli_app, [*map(str, args), *(["--json"] if json_out else [])])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout) if json_out else r


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The simulated machine's configuration with its 18 measured files, and the same
    configuration with every error inline."""
    d = tmp_path_factory.mktemp("vol")
    _cli("volumetric", "simulate", "--out", d / "sim", "--points", 5, "--seed", 3)
    _cli("volumetric", "map", d / "sim" / "volumetric.toml", "--inline", d / "vol.toml",
         json_out=False)
    return d / "sim" / "volumetric.toml", d / "vol.toml"


def test_the_inline_file_maps_as_its_measured_files(files):
    """The errors written inline are those the reader took from the files: the same map and
    diagonals to 1e-9 µm (repr of doubles, scaled to mm and µm and back)."""
    named, inline = files
    text = inline.read_text("utf-8")
    assert '"X_EXX.csv"' not in text and "EXX = { positions_mm = [" in text
    a, b = _cli("volumetric", "map", named), _cli("volumetric", "map", inline)
    assert a.keys() == b.keys() and a["machine"] == b["machine"]
    assert b["largest_um"] == pytest.approx(a["largest_um"], abs=1e-9)
    for k in "XYZ":
        assert b["range_um"][k] == pytest.approx(a["range_um"][k], abs=1e-9)
    for x, y in zip(a["diagonals"], b["diagonals"]):
        assert y["range_um"] == pytest.approx(x["range_um"], abs=1e-9)
    assert b["mapped_minus_true_um"] == pytest.approx(a["mapped_minus_true_um"], abs=1e-9)


def test_history_show_json_is_volumetric_map_json_key_by_key(files, tmp_path):
    _, inline = files
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    want = _cli("volumetric", "map", inline)
    added = _cli("history", "add", inline, "--db", url)
    assert (added["kind"], added["machine"], added["axis"]) == ("volumetric", want["machine"],
                                                                "XYZ")
    shown = _cli("history", "show", added["id"], "--db", url)
    result, q = shown["result"], shown["quantities"]
    assert set(want) <= set(result) and len(want) >= 10
    for key in want:                  # machine, chain, largest_um, range_um, diagonals, truth...
        assert result[key] == want[key], key
    assert q["largest"]["value"] == want["largest_um"] and q["largest"]["unit"] == "um"
    for a in "XYZ":
        assert q[f"range_{a}"]["value"] == want["range_um"][a]
    for g in want["diagonals"]:
        assert q[f"diagonal_{g['name']}"]["value"] == g["range_um"]
    assert set(q) == {"largest", "range_X", "range_Y", "range_Z",
                      *(f"diagonal_{g['name']}" for g in want["diagonals"])}
    for name, v in q.items():     # U from iso230_9_volumetric, the same as the command's
        assert v["U"] == want["quantities"][name]["U"] > 0 and v["k"] == 2.0, name
    assert result["uncertainty_budget"] == want["uncertainty_budget"]
    store = open_store(url)
    try:
        ev = axiscal.History(store=store).evaluation(added["id"])
        assert ev.to_dict() == axiscal.evaluate(inline).to_dict()
        assert {k: ev.to_dict()[k] for k in want} == want
    finally:
        store.close()


def _heading(path) -> str:
    return re.search(r"<h1>(.*?)</h1>", path.read_text("utf-8")).group(1)


def test_history_show_report_has_volumetric_maps_heading(files, tmp_path):
    _, inline = files
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    added = _cli("history", "add", inline, "--db", url)
    _cli("history", "show", added["id"], "--db", url, "--report", tmp_path / "h.html",
         json_out=False)
    _cli("volumetric", "map", inline, "--report", tmp_path / "c.html", json_out=False)
    assert _heading(tmp_path / "h.html") == _heading(tmp_path / "c.html") == \
        "Volumetric accuracy — simulated machining centre"
    html = (tmp_path / "h.html").read_text("utf-8")
    assert "Body diagonals (ISO 230-6:2002)" in html and "<svg" in html
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    U = _cli("volumetric", "map", inline)["quantities"]["largest"]["U"]
    for page in (html, (tmp_path / "c.html").read_text("utf-8")):   # the record's U on both
        row = page.split("largest |E|")[1].split("</tr>")[0]
        assert "U (k = 2) [µm]" in page and f">{format_uncertainty(U)}<" in row
        assert "correlation model: scale" in page


def test_a_configuration_naming_its_files_is_refused_with_one_line(files, tmp_path):
    named, _ = files
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(cli_app, ["history", "add", str(named), "--db", url])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert "names files (EXX = 'X_EXX.csv'" in r.output and "--inline" in r.output
    store = open_store(url)
    try:
        assert store.tests() == []
    finally:
        store.close()


def test_the_workbench_page_shows_the_maps_figures(files, tmp_path):
    _, inline = files
    client = TestClient(create_app(f"sqlite:///{tmp_path / 'w.sqlite'}"),
                        base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', client.get("/").text).group(1)
    up = client.post("/upload", data={"csrf": token},
                     files={"file": (inline.name, inline.read_bytes(), "application/toml")},
                     follow_redirects=False)
    assert up.status_code == 303, up.text
    page = client.get(up.headers["location"]).text
    want = _cli("volumetric", "map", inline)
    table = page.split('<table id="volumetric-figures">')[1].split("</table>")[0]
    assert f">{want['largest_um']:.3f}<" in table
    for a in "XYZ":
        row = table.split(f"<td>range_{a}</td>")[1].split("</tr>")[0]
        assert f">{want['range_um'][a]:.3f}<" in row and "<td>µm</td>" in row
    diag = page.split('<table id="volumetric-diagonals">')[1].split("</table>")[0]
    for g in want["diagonals"]:
        row = diag.split(f"<td>diagonal_{g['name']}</td>")[1].split("</tr>")[0]
        assert f">{g['range_um']:.3f}<" in row
    assert 'id="kind-figure" src="data:image/svg+xml;base64,' in page
    assert "ISO/TR 16907:2015" in page
    q = want["quantities"]                     # U beside each figure: the record's, as printed
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    assert f">{format_uncertainty(q['largest']['U'])}</td>" in table
    for a in "XYZ":
        row = table.split(f"<td>range_{a}</td>")[1].split("</tr>")[0]
        assert f">{format_uncertainty(q[f'range_{a}']['U'])}</td>" in row
    for g in want["diagonals"]:
        row = diag.split(f"<td>diagonal_{g['name']}</td>")[1].split("</tr>")[0]
        U = q["diagonal_" + g["name"]]["U"]
        assert f">{format_uncertainty(U)}</td>" in row
    assert 'id="volumetric-budget-inputs"' in page and "correlation model: scale" in page
    # the sign-off is offered (the kind has a budget) and decides with the record's U
    assert 'id="signoff-link"' in page
    tid = re.search(r"/tests/(\d+)", up.headers["location"]).group(1)
    assert 'id="signoff-form"' in page and 'name="tol_largest"' in page
    assert 'name="tol_diagonal_PPP"' in page
    r = client.post(f"/tests/{tid}/signoff", data={"csrf": token, "action": "verdict",
                                                 "tol_largest": "100"})
    assert r.status_code == 200, r.text[-800:]
    verdicts = re.search(r'<table id="verdicts">.*?<tbody>(.*?)</tbody>', r.text, re.S).group(1)
    assert f'<td class="num">{format_uncertainty(q["largest"]["U"])}</td>' in verdicts
    assert "conformance proven" in verdicts


def test_an_inline_error_s_own_u_is_the_budget_s(files):
    """``U`` in an inline error's table (its unit, k = 2: here EXX in µm, ECX in µrad) is used
    over the class's input and listed as given (iso230_9_volumetric); a negative U is refused
    in one line naming the error."""
    from axiscal.errors import ConfigError
    from axiscal.store.kinds import evaluate_file, with_uncertainty

    _, inline = files
    text = inline.read_text("utf-8")
    own = re.sub(r'^(EXX = \{.*?), unit = "um" \}$', r'\1, unit = "um", U = 6.0 }', text,
                 flags=re.M)
    own = re.sub(r'^(ECX = \{.*?), unit = "urad" \}$', r'\1, unit = "urad", U = 9.0 }', own,
                 flags=re.M)
    assert own.count("U = ") == 2
    plain = with_uncertainty(evaluate_file(text.encode(), "vol.toml"), {}).budget
    mine = with_uncertainty(evaluate_file(own.encode(), "vol.toml"), {}).budget
    given = {i.name: (i.value, i.unit, i.assumed) for i in mine.inputs if i.name in ("EXX", "ECX")}
    assert given == {"EXX": (pytest.approx(6.0), "µm", False),
                     "ECX": (pytest.approx(9.0), "µrad", False)}
    assert mine.U("range_X") > plain.U("range_X")
    bad = own.replace("U = 6.0", "U = -1.0")
    with pytest.raises(ConfigError, match=r"\[errors\] EXX U = -1.0") as e:
        evaluate_file(bad.encode(), "vol.toml")
    assert "\n" not in str(e.value)
