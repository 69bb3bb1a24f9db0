"""Issue 40, review defects 1 and 5: with accounts, a certificate is the act of two accounts
(ISO/IEC 17025:2017 §7.8.2.1 o: the person(s) authorising the report identified; §6.2.5, §6.2.6
c: authorised personnel). Only a signatory changes the signatory list (audit-trailed with the
account); the preparer is the account that saved the sign-off for approval, not a name typed on
the form; the approver is another account, a signatory, who issues what was saved."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.web.conftest import log_in
from tests.web.conftest import positioning_file as data_file
from tests.web.test_signoff import JOB, LAB

SIGNATORIES = '[[signatory]]\nname = "sig"\nrole = "Head of metrology"\n' \
              '[[signatory]]\nname = "sig2"\nrole = "Deputy"\n'
PASSWORD = "correct horse battery"


@pytest.fixture
def bench(tmp_path, monkeypatch):
    """Accounts prep (an engineer, not a signatory) and sig (an engineer and one of the
    laboratory's signatories, sig and sig2); test 1 uploaded by prep."""
    from axiscal.web.security import UserFile

    cfg = tmp_path / "config.toml"
    cfg.write_text(LAB + SIGNATORIES, encoding="utf-8")
    monkeypatch.setenv("AXISCAL_CONFIG", str(cfg))
    users = UserFile.load(tmp_path / "users.toml")
    for name in ("prep", "sig"):
        users.add(name, "engineer", PASSWORD)
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", tmp_path / "users.toml",
                              require_login=True), base_url="http://127.0.0.1")
    _as(c, "prep")
    c.post("/upload", data={"csrf": c.token}, files={"file": ("x.csv", data_file(), "text/csv")})
    return c


def _as(c, name: str) -> None:
    c.cookies.clear()
    assert log_in(c, name, PASSWORD).status_code == 303
    c.token = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)


def _sign(c, action, **fields):
    return c.post("/tests/1/signoff", data={"csrf": c.token, "action": action, **fields},
                  follow_redirects=False)


def _lab(c, signatories: str, reason: str = "deputy added"):
    return c.post("/laboratory", data={"csrf": c.token, "lab_name": "Präzision Messtechnik GmbH",
                                       "lab_code": "PM", "lab_signatories": signatories,
                                       "reason": reason}, follow_redirects=False)


def test_only_a_signatory_changes_the_signatory_list(bench):
    """Defect 1's first step: prep (not a signatory) adds itself on /laboratory and through the
    sign-off form: 403 / refused, the list unchanged; sig (a signatory) adds a deputy: kept, the
    audit entry by sig."""
    from axiscal.store.corrections import audit
    from axiscal.store.laboratory import laboratory

    st = bench.app.state.store
    r = _lab(bench, "sig, Head of metrology\nprep, Deputy")
    assert r.status_code == 403 and "only one of them (sig, sig2)" in r.text
    assert laboratory(st) == {}
    r = _sign(bench, "verdict", lab_signatories="prep, Deputy", tol_E="30", **JOB)
    assert "only one of them (sig, sig2)" in r.text
    assert laboratory(st) == {}
    _as(bench, "sig")
    assert _lab(bench, "sig, Head of metrology\nsig2, Deputy\nprep, Deputy").status_code == 303
    assert [s["name"] for s in laboratory(st)["signatory"]] == ["sig", "sig2", "prep"]
    entry = next(a for a in audit(st) if a.action == "laboratory")
    assert entry.by == "sig"


def test_the_preparer_saves_and_another_signatory_issues_what_was_saved(bench):
    """Defects 1 and 5: sig, a signatory, saves a form itself and presses Issue: "prepared by
    one account and approved by another", the form's signatory fields (a name typed) not read;
    prep presses Issue: not issued, and the page tells it to save for approval (no "Authorised
    signatories" item, no "not one of" fault); prep saves: an audit entry, the test page says
    "awaiting approval by a signatory"; sig opens the test and finds the form as saved, a
    changed form is not prep's; sig issues prep's: the register keeps prep (the account, not
    the operator typed) as preparer, sig as approver."""
    from axiscal.store.corrections import audit

    st = bench.app.state.store
    form = {**JOB, "operator": "A. Other", "tol_E": "30"}
    _as(bench, "sig")
    alone = {**form, "signatory": "sig2", "signatory_role": "Deputy"}
    assert _sign(bench, "save", **alone).status_code == 200
    assert "prepared by one account and approved by another" in _sign(bench, "issue",
                                                                       **alone).text
    assert st.certificates() == []
    _as(bench, "prep")
    r = _sign(bench, "issue", **form)
    assert r.status_code == 200 and 'id="draft"' in r.text
    draft = r.text[r.text.index('id="draft"'):r.text.index("</ul>", r.text.index('id="draft"'))]
    assert 'href="#f-save_for_approval">Save for approval</a>' in draft
    assert "you (prep) are not one of the laboratory" in draft
    assert "Authorised signatories" not in draft and "Approver" not in draft
    assert st.certificates() == []
    r = _sign(bench, "save", **form)
    assert r.status_code == 200 and 'id="saved-for-approval"' in r.text
    saved = next(a for a in audit(st) if a.action == "signoff-saved")
    assert saved.by == "prep" and saved.new["values"]["customer_name"] == JOB["customer_name"]
    page = bench.get("/tests/1").text
    assert "awaiting approval by a signatory" in page

    _as(bench, "sig")
    page = bench.get("/tests/1").text
    assert 'name="customer_name" value="Example Machining AG"' in page
    assert 'name="tol_E" value="30"' in page and "Saved for approval by prep" in page
    r = _sign(bench, "issue", **{**form, "tol_E": "20"})         # changed: sig prepared it
    assert r.status_code == 200 and "the form differs from what prep saved" in r.text
    r = _sign(bench, "issue", **form)
    assert r.status_code == 303, r.text[-2000:]
    rec = st.certificates()[0]
    assert (rec.prepared_by, rec.approved_by, rec.approved_role) == ("prep", "sig",
                                                                     "Head of metrology")
    assert "awaiting approval" not in bench.get("/tests/1").text
