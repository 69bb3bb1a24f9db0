"""A drift check kept with a stored positioning test whose E_VE was declared at upload (issue
40: it was replaced without a word). The measured E_VE replaces the declared one (ISO
230-2:2014 Annex A.5: E_VE is measured by a drift check; the declared value stands in for it),
and it is said where the user acted: ``axiscal history drift-check`` prints it, the workbench's
sign-off form shows it beside its drift-check field; the audit trail keeps both values. A second
drift check replaces a measured E_VE, which was not declared, and says nothing."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.store import open_store
from axiscal.web.app import create_app

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
#: E_VE = 0.42 − (−0.18) = 0.60 µm (the range of the readings, ISO 230-2:2014 Annex A.5).
DRIFT = b"time_s,reading\n0,0.05\n300,0.42\n600,-0.18\n900,0.11\n"
#: E_VE = 0.5 − 0.1 = 0.4 µm.
DRIFT2 = b"reading\n0.1\n0.5\n0.3\n"
SAID = ("E_VE given twice: the drift check's 0.6 µm replaces the declared 0.8 µm (ISO "
        "230-2:2014 Annex A.5")


@pytest.fixture
def url(tmp_path, monkeypatch):
    (tmp_path / "config.toml").write_text('[certificate]\npaper = "A4"\n', encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "config.toml"))
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    st = open_store(url)
    try:
        st.add(ECMC.read_bytes(), ECMC.name, machine="MCU1025 bench",
               uncertainty={"e_ve": 0.8, "resolution": 0.1})
    finally:
        st.close()
    return url


def test_the_command_line_says_the_declared_e_ve_is_replaced(url, tmp_path):
    (tmp_path / "dc.csv").write_bytes(DRIFT)
    (tmp_path / "dc2.csv").write_bytes(DRIFT2)
    r = CliRunner().invoke(app, ["history", "drift-check", "1", str(tmp_path / "dc.csv"),
                                 "--by", "A. Ng", "--db", url])
    assert r.exit_code == 0, r.output
    assert "test 1: drift check dc.csv kept (4 readings), E_VE 0.6 µm" in r.output
    assert SAID in r.output
    st = open_store(url)
    try:
        inputs = st.get(1).result["uncertainty_inputs"]
        assert (inputs["e_ve"], inputs["e_ve_source"]) == (0.6, "drift check")
        from axiscal.store.corrections import audit

        entry = next(a for a in audit(st) if a.action == "drift-check")
        assert entry.old["e_ve"] == 0.8 and entry.new["e_ve"] == 0.6
    finally:
        st.close()
    r = CliRunner().invoke(app, ["history", "drift-check", "1", str(tmp_path / "dc2.csv"),
                                 "--by", "A. Ng", "--db", url, "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["replaced"] is None and d["notice"] == "" and d["e_ve"] == pytest.approx(0.4)
    assert "given twice" not in r.output


def test_a_drift_check_without_a_name_is_refused_in_one_line(url, tmp_path):
    (tmp_path / "dc.csv").write_bytes(DRIFT)
    r = CliRunner().invoke(app, ["history", "drift-check", "1", str(tmp_path / "dc.csv"),
                                 "--by", " ", "--db", url])
    assert r.exit_code == 2 and "--by" in r.output and len(r.output.strip().splitlines()) == 1


def test_the_sign_off_form_says_it_beside_its_drift_check_field(url):
    c = TestClient(create_app(url), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/tests/1/signoff", data={"csrf": token, "action": "verdict",
                                         "operator": "A. Operator"},
               files={"drift_check": ("dc.csv", DRIFT, "text/csv")},
               headers={"HX-Request": "true"})
    assert r.status_code == 200, r.text[-2000:]
    fieldset = r.text.split('id="e-ve"')[1].split("</fieldset>")[0]
    notice = re.search(r'id="drift-notice">(.*?)</p>', fieldset, re.S)
    assert notice and SAID in notice.group(1).replace("&#39;", "'").replace("&#x27;", "'")
