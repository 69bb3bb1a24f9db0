"""A drift check (ISO 230-2:2014 Annex A.5) kept with a positioning test already in the
workbench (issue 44), through the one field the test's page has for it: the sign-off form's
"Drift check file" (issue 40: the test's own box had a second one). The form posts the file, the
one library call (:func:`axiscal.store.laboratory.add_drift_check`, through
:func:`axiscal.store.kinds.drift_check_record`) keeps it, and the page shows its E_VE as
measured; the stored budget's u_EVE is the command line's for the same files
(``axiscal iso230-2 FILE --drift-check DC``). Refused files: the reason in words at the form,
400, nothing kept."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.web.app import create_app

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
#: A drift check of the test's set-up (µm): E_VE = 0.42 − (−0.18) = 0.60 µm.
DRIFT = b"time_s,reading\n0,0.05\n300,0.42\n600,-0.18\n900,0.11\n"


@pytest.fixture
def bench(tmp_path, monkeypatch):
    (tmp_path / "config.toml").write_text('[certificate]\npaper = "A4"\n', encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "config.toml"))
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'web.sqlite'}"),
                   base_url="http://127.0.0.1")
    c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": c.token, "machine": "MCU1025 bench"},
               files={"file": (ECMC.name, ECMC.read_bytes(), "text/plain")})
    assert r.status_code == 200 and "/tests/1" in str(r.url)
    return c


def _post(c, content: bytes | None, name: str = "drift.csv", test: int = 1, **fields):
    """The sign-off form's "Show the verdict" with a drift-check file."""
    files = {"drift_check": (name, content, "text/csv")} if content is not None else None
    data = {"csrf": c.token, "action": "verdict", "operator": "A. Operator", **fields}
    return c.post(f"/tests/{test}/signoff", data=data, files=files, follow_redirects=False)


def _u_eve(budget: dict) -> dict:
    return next(x for x in budget["contributors"] if x["name"] == "u_EVE")


def test_the_tests_page_has_one_drift_check_field_the_sign_off_forms(bench):
    """One file field named drift_check on the page, inside the sign-off form; the test's
    Drift check box says what is kept and links to that field."""
    page = bench.get("/tests/1").text
    assert len(re.findall(r'type="file" name="drift_check"', page)) == 1
    form = page.split('id="signoff-form"')[1].split("</form>")[0]
    assert 'type="file" name="drift_check"' in form
    box = page.split('id="drift-check"')[1].split("</div>")[0]
    assert 'id="no-drift-check"' in box and 'href="#f-drift_check"' in box
    assert "<form" not in box


def test_a_drift_check_given_on_the_sign_off_form_gives_its_measured_e_ve(bench, tmp_path):
    from axiscal.store.corrections import audit
    from axiscal.store.laboratory import drift_checks

    r = _post(bench, DRIFT)
    assert r.status_code == 200, r.text[-2000:]
    assert "E_VE = 0.6 µm" in r.text.split('id="drift-kept"')[1].split("</p>")[0]
    page = bench.get("/tests/1").text
    block = page.split('id="drift-check"')[1].split("</div>")[0]
    assert "0.6000 µm" in block and "<strong>measured</strong>" in block
    assert "4 readings" in block and "Another drift check" in block
    st = bench.app.state.store
    (kept,) = drift_checks(st, 1)
    assert (kept.filename, kept.readings, kept.by) == ("drift.csv", 4, "A. Operator")
    assert kept.e_ve == pytest.approx(0.60)
    entry = next(a for a in audit(st) if a.action == "drift-check")
    assert entry.new["e_ve"] == 0.6
    stored = json.loads(bench.get("/tests/1/result.json").text)
    assert stored["uncertainty_inputs"]["e_ve_source"] == "drift check"
    # one record, every path: the stored budget's u_EVE is the command line's
    (tmp_path / "drift.csv").write_bytes(DRIFT)
    from axiscal.cli import app

    out = CliRunner().invoke(app, ["iso230-2", str(ECMC), "--drift-check",
                                   str(tmp_path / "drift.csv"), "--json"])
    assert out.exit_code == 0, out.output
    assert _u_eve(stored["result"]["uncertainty_budget"]) == _u_eve(
        json.loads(out.stdout)["uncertainty_budget"])


#: Refused uploads: (file, its name, the form's other fields, the words said at the form).
REFUSED = [
    (b"reading\n0.1\n", "one.csv", {}, "at least 2"),
    (b"reading\n0.1\nabc\n", "text.csv", {}, "abc"),
    (b"", "empty.csv", {}, "empty.csv is empty"),
    (DRIFT, "drift.csv", {"operator": ""}, "give your name"),
]


def test_a_refused_drift_check_is_said_at_the_form_and_nothing_is_kept(bench):
    """A file of one reading, a reading that is not a number, an empty file, no name (the
    no-login workbench: the audit trail records who): 400, the reason at the sign-off form, the
    test's record unchanged, no drift check kept."""
    from axiscal.store.laboratory import drift_checks

    before = bench.get("/tests/1/result.json").text
    for content, name, fields, words in REFUSED:
        r = _post(bench, content, name, **fields)
        assert r.status_code == 400, name
        said = re.search(r'id="signoff-error">(.*?)</div>', r.text, re.S)
        assert said and words in said.group(1), (name, r.text[-2000:])
        assert drift_checks(bench.app.state.store, 1) == []
        assert bench.get("/tests/1/result.json").text == before


def test_a_drift_check_goes_only_with_a_positioning_test(bench, tmp_path):
    """A thermal log's page has no drift-check box or field; a drift check posted with its
    sign-off is refused in the library's words (E_VE is an input of a positioning test's
    budget); the box's old address is gone."""
    import axiscal
    from axiscal.io.thermal import write_thermal_log
    from axiscal.store.laboratory import drift_checks

    log = tmp_path / "linear.csv"
    write_thermal_log(log, axiscal.simulate_thermal("linear", seed=1, interval_s=300.0).log)
    r = bench.post("/upload", data={"csrf": bench.token, "machine": "VMC", "axis": "X"},
                   files={"file": (log.name, log.read_bytes(), "text/csv")})
    assert r.status_code == 200 and "/tests/2" in str(r.url)
    assert 'name="drift_check"' not in r.text and 'id="drift-check"' not in r.text
    r = _post(bench, DRIFT, test=2)
    assert r.status_code == 400
    said = re.search(r'id="signoff-error">(.*?)</div>', r.text, re.S).group(1)
    assert "is a thermal test" in said and "positioning test" in said
    assert drift_checks(bench.app.state.store, 2) == []
    r = bench.post("/tests/1/drift-check", data={"csrf": bench.token},
                   files={"drift_check": ("drift.csv", DRIFT, "text/csv")})
    assert r.status_code in (404, 405)
