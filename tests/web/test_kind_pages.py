"""Every kind of test the history stores has a page with its figure and labelled numbers, the
numbers of the command a user runs on the same file (``--json``, written with three decimals as
the page writes them); and the rough edges of issue 31: the plan form keeps its choices, stored
compensation tables download again, the trend's axis is in dates with the predicted crossing
drawn, every axis's trend link works, µm never "um"."""

from __future__ import annotations

import base64
import html
import json
import re
from pathlib import Path

import numpy as np
import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.cli import app as cli_app
from axiscal.web.app import create_app

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
runner = CliRunner()


def _cli(*args) -> dict:
    res = runner.invoke(cli_app, [*map(str, args), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _n(v) -> str:
    """A number as the page writes it (three decimals; web/kind_pages.py)."""
    return "—" if v is None else f"{v:.3f}"


def _table(page: str, table_id: str) -> list[list[str]]:
    body = page.split(f'<table id="{table_id}">')[1].split("</table>")[0]
    body = body.split("<tbody>")[1]
    return [[html.unescape(re.sub(r"<[^>]+>", "", c)).strip()
             for c in re.findall(r"<td[^>]*>(.*?)</td>", row, re.S)]
            for row in re.findall(r"<tr>(.*?)</tr>", body, re.S)]


def _motion_file(folder: Path) -> Path:
    from axiscal.io.motion import MotionErrorData, format_motion_errors

    rng = np.random.default_rng(31)
    theta = np.radians(np.arange(0, 360, 15.0))
    arrays = {c: rng.normal(0, 1e-6, (2, theta.size)) for c in ("ez", "ey", "ex", "dy", "dz")}
    p = folder / "motion.csv"
    p.write_text(format_motion_errors(MotionErrorData(theta=theta, title="table", **arrays)))
    return p


def _ballbar_file(folder: Path) -> Path:
    """A circular test with a servo lag (3 ms at 1000 mm/min), 20 µm/m squareness, 15 µm/m
    scale mismatch and 5 / -3 µm backlash, by ``Δr = δx cos φ + δy sin φ`` (Renishaw,
    "Calibration of machine squareness", Method 4): the ISO 230-4 fit folds the servo lag into
    its backlash, which the page must state."""
    from axiscal.io.ballbar import BallbarData, format_ballbar
    from axiscal.standards.iso230_4 import CircularRun

    rng = np.random.default_rng(3)
    n, radius, feed = 360, 0.1, 1000 / 6e4
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    sq, ex, bx, by, tau = 20e-6, 15e-6, 5e-6, -3e-6, 3e-3
    runs = []
    for direction, s in (("ccw", 1.0), ("cw", -1.0)):
        c, si = np.cos(phi), np.sin(phi)
        sx = np.where(np.abs(si) < 1e-9, np.sign(c), -s * np.sign(si))
        sy = np.where(np.abs(c) < 1e-9, np.sign(si), s * np.sign(c))
        dx = ex * radius * c - sq * radius * si + bx / 2 * sx + tau * s * feed * si
        runs.append(CircularRun(phi, dx * c + by / 2 * sy * si + rng.normal(0, 1e-8, n),
                                direction))
    p = folder / "servo_lag.csv"
    p.write_text(format_ballbar(BallbarData(radius, tuple(runs), ("X", "Y"), feed=feed)))
    return p


def _one_direction(folder: Path) -> Path:
    """The example ballbar test with its CW run left out."""
    lines = (EXAMPLES / "squareness_ballbar_150mm.csv").read_text().splitlines()
    p = folder / "ccw_only.csv"
    p.write_text("\n".join(x for x in lines if ",cw," not in x) + "\n")
    return p


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """A workbench with one test of every kind (ids in the order of ``files``)."""
    d = tmp_path_factory.mktemp("kinds")
    mp = pytest.MonkeyPatch()
    mp.setenv("AXISCAL_CONFIG", str(d / "none.toml"))
    c = TestClient(create_app(f"sqlite:///{d / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    files = {"ballbar": (_ballbar_file(d), ""),
             "straightness": (EXAMPLES / "squareness_L180_x.csv", ""),
             "diagonal": (EXAMPLES / "squareness_diagonal_600x800.csv", ""),
             "motion": (_motion_file(d), "C"),
             "one direction": (_one_direction(d), "")}
    pages = {}
    for kind, (path, axis) in files.items():
        r = c.post("/upload", data={"csrf": token, "machine": "DMU 50", "axis": axis},
                   files={"file": (path.name, path.read_bytes(), "text/csv")})
        assert r.status_code == 200 and "/tests/" in str(r.url), r.text[-500:]
        pages[kind] = r.text
    yield c, token, files, pages
    mp.undo()


def _figure_is_svg(page: str) -> None:
    src = re.search(r'<img id="kind-figure" src="data:image/svg\+xml;base64,([^"]+)"', page)
    assert src, "no figure"
    assert b"<svg" in base64.b64decode(src.group(1))


def test_ballbar_page_shows_the_diagnosis_of_ballbar_analyze(site):
    """Polar plot, ISO 230-4:2005 §3 figures, the ranked diagnosis with advice and the folded
    statements: the numbers and the order of ``ballbar analyze --json`` on the same file."""
    _, _, files, pages = site
    page = pages["ballbar"]
    j = _cli("ballbar", "analyze", files["ballbar"][0])
    _figure_is_svg(page)
    iso = dict((r[0], r[1]) for r in _table(page, "iso230-4"))
    for name, key in (("G ccw", "G_ccw_um"), ("G cw", "G_cw_um"), ("H", "H_um"),
                      ("F max", "F_max_um"), ("F min", "F_min_um")):
        assert iso[name] == _n(j["iso230_4"][key]), name
    assert iso["residual after the model, rms"] == _n(j["residual_rms_um"])
    ranked = _table(page, "diagnosis")
    assert len(ranked) == len(j["ranking"]) > 5
    for row, term in zip(ranked, j["ranking"]):
        assert row[2] == _n(term["value"]) and row[3] == term["unit"]
        assert row[4] == _n(term["effect_um"]) and row[5] == f"{term['share_percent']:.1f}"
        assert row[6] == term["advice"]
    assert ranked[0][1] == "Servo mismatch" and ranked[0][3] == "ms"   # by name, in ms
    assert float(ranked[0][2]) == pytest.approx(3.0, abs=0.01)        # the injected 3 ms lag
    fit = {r[0]: r[1] for r in _table(page, "iso230-4-fit")}
    assert fit["squareness"] == _n(j["iso230_4"]["squareness"]["um_per_m"])
    assert fit["backlash X"] == _n(j["iso230_4"]["backlash_x_um"])
    folded = [f["statement"] for f in j["iso230_4"]["folded"] if f["material"]]
    shown = re.findall(r"<li>(.*?)</li>", page.split('id="folded"')[1].split("</ul>")[0])
    assert [html.unescape(s) for s in shown] == folded and len(folded) == 3
    assert "backlash X -20.934 µm by the ISO 230-4 fit folds in servo mismatch" in folded[1]
    for w in j["warnings"]:
        assert html.escape(w, quote=True) in page or w in html.unescape(page)
    assert "e-06" not in page and "e-08" not in page


def test_one_direction_ballbar_page_has_the_iso230_4_figures(site):
    """One direction: no diagnosis, the ISO 230-4 evaluation of ``squareness circular``."""
    _, _, files, pages = site
    page = pages["one direction"]
    j = _cli("squareness", "circular", files["one direction"][0])
    _figure_is_svg(page)
    rows = {r[0]: r[1] for r in _table(page, "iso230-4")}
    assert rows["G ccw"] == _n(j["G_ccw_um"]) and rows["H"] == _n(j["H_um"])
    assert rows["squareness"] == _n(j["squareness"]["um_per_m"])
    assert 'id="diagnosis"' not in page


def test_straightness_page_in_labelled_units(site):
    """Both reference lines of ISO 230-1:2012 §3.4.8/§3.4.9 in µm and µm/m, each figure with
    its U (k = 2), as ``axiscal straightness --json`` (the stored record's budget,
    standards/iso230_9_straightness.py); no unlabelled SI (the page once showed 9.997e-06)."""
    _, _, files, pages = site
    page = pages["straightness"]
    out = _cli("straightness", files["straightness"][0])
    j, U = out["methods"], out["uncertainty_budget"]["U_display"]
    _figure_is_svg(page)
    assert ("<th>straightness [µm]</th><th>U (k = 2) [µm]</th><th>slope [µm/m]</th>"
            "<th>U (k = 2) [µm/m]</th>") in page
    rows = _table(page, "straightness")
    assert rows[0][1:] == [_n(j["least_squares"]["straightness_um"]), U["straightness"],
                           _n(j["least_squares"]["slope_um_per_m"]), U["slope"]]
    assert rows[1][1:] == [_n(j["minimum_zone"]["straightness_um"]),
                           U["straightness_min_zone"],
                           _n(j["minimum_zone"]["slope_um_per_m"]), "—"]
    budget = _table(page, "budget")
    assert [r[0] for r in budget] == [c["name"] for c in
                                      out["uncertainty_budget"]["contributors"]]
    inputs = {r[0]: r[1:3] for r in _table(page, "budget-inputs")}
    assert inputs["reading noise σ of one reading"][1] == "measured"
    assert 'id="budget-notes"' in page
    assert "e-06" not in page and "e-08" not in page


def test_diagonal_page_as_squareness_diagonal(site):
    _, _, files, pages = site
    page = pages["diagonal"]
    j = _cli("squareness", "diagonal", "--file", files["diagonal"][0])
    _figure_is_svg(page)
    rows = _table(page, "diagonal")
    assert rows[0] == ["squareness", _n(j["squareness"]["um_per_m"]), "µm/m"]
    assert rows[1] == ["squareness", _n(j["squareness"]["arcsec"]), "arcsec"]
    assert rows[6][1:] == [_n(j["error_d1_um"]), "µm"] and rows[7][1:] == [_n(j["error_d2_um"]),
                                                                          "µm"]
    _page_U_is_the_cli_U(page, j)


def _page_U_is_the_cli_U(page: str, j: dict) -> None:
    """The page's U (k = 2), contributors and inputs are those ``squareness diagonal --json``
    prints (ISO/TR 230-9 budget of :func:`axiscal.standards.iso230_9_geometry.diagonal_budget`);
    U written as the command line writes it (two significant digits, rounded up)."""
    from axiscal.standards.iso230_9 import format_uncertainty

    rows = _table(page, "diagonal")
    assert rows[2] == ["U (k = 2) of the squareness", format_uncertainty(j["U_um_per_m"]),
                       "µm/m"]
    budget = _table(page, "budget")
    assert [(r[0], r[2]) for r in budget] == [(c["name"], f'{c["u_um_per_m"]:.3g}')
                                              for c in j["uncertainty"]]
    assert all(r[5] for r in budget)                                  # every clause named
    inputs = {r[0]: r[1:3] for r in _table(page, "budget-inputs")}
    assert inputs["X travel"] == ["0.6 m", "measured"]       # from the data file
    assert 'id="budget-notes"' in page


def test_diagonal_page_U_follows_the_user_configuration(tmp_path, monkeypatch):
    """With ``[squareness_uncertainty]`` inputs declared (laser 2 ppm, E_VE 1 µm), the page's
    U is the command line's U under the same configuration, and the declared inputs are shown
    given, not assumed; the undeclared D0 uncertainty stays assumed, in words."""
    cfg = tmp_path / "config.toml"
    cfg.write_text("[squareness_uncertainty]\nlaser_ppm = 2.0\ne_ve = 1.0\n")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    f = EXAMPLES / "squareness_diagonal_600x800.csv"
    j = _cli("squareness", "diagonal", "--file", f)
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": token, "machine": "DMU 50"},
               files={"file": (f.name, f.read_bytes(), "text/csv")})
    assert r.status_code == 200 and "/tests/" in str(r.url)
    _page_U_is_the_cli_U(r.text, j)
    inputs = {row[0]: row[1:3] for row in _table(r.text, "budget-inputs")}
    assert inputs["laser accuracy (k = 2)"] == ["2 ppm", "given"]
    assert inputs["environmental variation error E_VE"] == ["1 µm", "given"]
    notes = html.unescape(r.text.split('id="budget-notes">')[1].split("</p>")[0])
    assert "assumed: standard uncertainty of the diagonal length D0 10 µm" in notes
    assert "laser accuracy" not in notes
    assert j["U_um_per_m"] > 2 * 0.737       # 2 ppm and E_VE move U well above the defaults'


def test_motion_page_as_motion_analyze(site):
    """ISO 230-7 error motion values: ``motion analyze --json`` (µm and arcsec), with the plot."""
    _, _, files, pages = site
    page = pages["motion"]
    j = _cli("motion", "analyze", files["motion"][0])["iso230_7"]["motions"]
    _figure_is_svg(page)
    rows = _table(page, "motion")
    assert [r[0] for r in rows] == [m["name"] for m in j]
    for row, m in zip(rows, j):
        assert row[1:8:2] == [_n(m["total"]), _n(m["synchronous"]), _n(m["asynchronous"]),
                              _n(m["fundamental"])]
        assert row[9] == ("µm" if m["unit"] == "um" else m["unit"])


def test_every_axis_has_a_working_trend_link(site):
    """The "trend of E" link of an XY ballbar axis led to an error page: each axis's link now
    follows its key parameter, and every one answers."""
    c = site[0]
    page = c.get("/machines/DMU 50").text
    links = [html.unescape(u) for u in re.findall(r'href="(/trend\?[^"]+)"', page)]
    assert any("axis=XY" in u and "parameter=squareness" in u for u in links)
    assert len(links) == 3                            # XY, X and C
    for u in links:
        r = c.get(u)
        assert r.status_code == 200, u
        assert " um" not in r.text.split("<main>")[1], u


def _positioning(date: str, offset: float) -> bytes:
    from axiscal.datasets import Metadata, PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(int(offset * 10))
    t = np.linspace(0, 800, 9)
    up = rng.normal(1.0, 0.3, (9, 5)) + t[:, None] * offset / 800
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 2.0, "mm", "um",
        Metadata(machine="VMC", axis="X", date=date))).encode()


def test_stored_tables_download_and_trend_in_dates(site):
    """A table written from a test is listed with a link and downloads as written; the trend's
    x axis is dates (seconds since 1970, UTC) and the predicted crossing is a point on the
    tolerance at the crossing date of :func:`axiscal.store.trend`."""
    import datetime as dt

    c, token, _, _ = site
    ids = []
    for date, offset in (("2024-01-10", 2.0), ("2025-01-10", 4.0), ("2026-01-10", 6.0)):
        r = c.post("/upload", data={"csrf": token},
                   files={"file": (f"{date}.csv", _positioning(date, offset), "text/csv")})
        ids.append(int(re.search(r"/tests/(\d+)", str(r.url)).group(1)))
    written = c.post(f"/tests/{ids[0]}/compensation", data={"csrf": token,
                                                            "controller": "linuxcnc",
                                                            "spacing": "100"})
    assert written.status_code == 200
    page = c.get(f"/tests/{ids[0]}").text
    link = re.search(rf'href="(/tests/{ids[0]}/tables/1)"', page)
    assert link, "the stored table has no link"
    again = c.get(link.group(1))
    assert again.status_code == 200 and again.text == written.text
    assert "attachment" in again.headers["content-disposition"]
    assert c.get(f"/tests/{ids[0]}/tables/2").status_code == 404

    from axiscal.store import trend

    page = c.get("/trend", params={"machine": "VMC", "axis": "X", "parameter": "E",
                                   "tolerance": "30"}).text
    spec = json.loads(html.unescape(re.search(r'id="trend-plot">(.*?)</script>', page,
                                              re.S).group(1)))
    tr = trend(c.app.state.store, "VMC", "X", "E", 30.0)
    assert tr.crossing is not None and spec["x_time"] is True
    firsts = [dt.datetime.fromtimestamp(x, dt.timezone.utc).date() for x in spec["x"][:3]]
    assert firsts == [dt.date(2024, 1, 10), dt.date(2025, 1, 10), dt.date(2026, 1, 10)]
    cross = next(s for s in spec["series"] if s["label"].startswith("predicted crossing"))
    k = [i for i, v in enumerate(cross["values"]) if v is not None]
    assert len(k) == 1 and cross["values"][k[0]] == 30.0
    assert spec["x"][k[0]] == pytest.approx(
        tr.crossing.replace(tzinfo=dt.timezone.utc).timestamp())
    fitted = next(s for s in spec["series"] if s["label"] == "fitted drift")
    assert fitted["values"][k[0]] == pytest.approx(30.0, abs=1e-6)   # the line reaches it there
    assert "years since" not in page and " um" not in page.split("<main>")[1]


def test_plan_form_keeps_rotary(tmp_path):
    """After a rotary plan the form still says rotary, so pressing again plans degrees."""
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/plan").text).group(1)
    r = c.post("/plan", data={"csrf": token, "kind": "rotary", "travel": "360", "step": "45"})
    assert r.status_code == 200 and "deg" in r.text
    assert '<option value="rotary" selected>' in r.text
    assert '<option value="linear" selected>' not in r.text
    r = c.post("/plan", data={"csrf": token, "kind": "linear", "travel": "800"})
    assert '<option value="linear" selected>' in r.text


def _h1(html_text: str) -> str:
    return html.unescape(re.search(r"<h1>(.*?)</h1>", html_text, re.S).group(1))


def test_every_kind_has_the_report_of_history_show(site, tmp_path):
    """Issue 40: each test page links a report, and it is the report ``axiscal history show ID
    --report`` writes (one call, :meth:`axiscal.api.History.report`): the same heading, which
    names the machine and axis kept in the history, and the same figures."""
    from axiscal import api

    c, _, files, _ = site
    for kind in files:
        tid = next(t.id for t in c.app.state.store.tests(machine="DMU 50")
                   if t.filename == files[kind][0].name)
        page = c.get(f"/tests/{tid}").text
        assert f'href="/tests/{tid}/report.html"' in page, kind
        r = c.get(f"/tests/{tid}/report.html")
        assert r.status_code == 200 and "attachment" in r.headers["content-disposition"], kind
        path = api.History(store=c.app.state.store).report(tid, tmp_path / f"{tid}.html")
        assert _h1(r.text) == _h1(path.read_text()), kind
        assert "DMU 50" in _h1(r.text), kind


def test_squareness_from_two_straightness_tests_equals_squareness_biaxial(site):
    """A straightness test's page offers the other axis's straightness tests; the squareness
    page gives ``axiscal squareness biaxial X Y --json``'s squareness and U (ISO 230-1:2012
    §3.6.7; ISO/TR 230-9), and its report downloads."""
    c, token, _, _ = site
    y = EXAMPLES / "squareness_L180_y.csv"
    r = c.post("/upload", data={"csrf": token, "machine": "DMU 50"},
               files={"file": (y.name, y.read_bytes(), "text/csv")})
    second = int(str(r.url).split("/tests/")[1].split("?")[0])
    first = next(t.id for t in c.app.state.store.tests(machine="DMU 50", axis="X")
                 if t.kind == "straightness")
    page = c.get(f"/tests/{first}").text
    assert 'id="squareness-with"' in page and f'<option value="{second}">' in page
    j = _cli("squareness", "biaxial", EXAMPLES / "squareness_L180_x.csv", y, "--orientation",
             "180")
    q = {"first": first, "second": second, "config": "L", "orientation": 180}
    page = c.get("/squareness", params=q)
    assert page.status_code == 200
    shown = re.search(r'id="squareness-value">([^<]+)<', page.text).group(1)
    assert shown == f"{j['squareness']['um_per_m']:+.2f}"
    from axiscal.standards.iso230_9 import format_uncertainty

    assert f"U (k = 2) = {format_uncertainty(j['U_um_per_m'])}" in page.text
    rep = c.get("/squareness/report.html", params=q)
    assert rep.status_code == 200 and "Squareness, bi-axial L 180°" in rep.text
    # entered from the Y test: the command's order, X the datum, the same sign (issue 40)
    from_y = c.get("/squareness", params={**q, "first": second, "second": first})
    assert re.search(r'id="squareness-value">([^<]+)<', from_y.text).group(1) == shown
    assert f"Squareness XY from tests {first} and {second}" in from_y.text
    same = c.get("/squareness", params={**q, "second": first})
    assert same.status_code == 400 and "with itself" in same.text


def test_compensation_from_the_page_lists_the_table_and_the_cli_notes(site):
    """Written from the page (htmx), the answer carries what ``axiscal compensate`` prints
    (:meth:`ControllerFile.summary`: reference point, the 840D backlash machine datum as a value,
    the shift to zero at the reference point) and the tables list, swapped in without reload."""
    from axiscal.compensation.controllers.convert import convert
    from axiscal.compensation.tables import table_from_result

    c, token = site[0], site[1]
    r = c.post("/upload", data={"csrf": token},
               files={"file": ("comp.csv", _positioning("2024-03-03", 2.5), "text/csv")})
    tid = int(str(r.url).split("/tests/")[1].split("?")[0])
    r = c.post(f"/tests/{tid}/compensation", headers={"HX-Request": "true"},
               data={"csrf": token, "controller": "siemens-840d", "spacing": "100"})
    assert r.status_code == 200 and "<html" not in r.text
    ev = c.app.state.store.get(tid).evaluate_again()
    f = convert(table_from_result(ev.evaluation, 100.0, axis="X", bidirectional=True),
                "siemens-840d")
    summary = html.unescape(re.search(r'id="compensation-summary">(.*?)</pre>', r.text,
                                      re.S).group(1))
    assert summary.splitlines() == f.summary()
    assert any("$MA_BACKLASH" in s and " mm" in s for s in f.summary())
    assert any("zero at the reference point" in s for s in f.summary())
    assert 'hx-swap-oob="true"' in r.text and f'/tests/{tid}/tables/1"' in r.text
    bad = c.post(f"/tests/{tid}/compensation", headers={"HX-Request": "true"},
                 data={"csrf": token, "controller": "siemens-840d", "spacing": "-1"})
    assert 'role="alert"' in bad.text and "spacing" in bad.text
