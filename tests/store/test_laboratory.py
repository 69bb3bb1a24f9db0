"""The laboratory kept in the history and drift checks kept beside their tests (issue 40,
migration 0006): each change an audit entry (ISO/IEC 17025:2017 §7.5.2), E_VE the range of the
drift check's readings (ISO 230-2:2014 Annex A.5), and the sign-off's uncertainty inputs the
stored test's own, under its drift check's E_VE."""

from __future__ import annotations

from pathlib import Path

import pytest

from axiscal.errors import AxiscalError, InputError
from axiscal.store import open_store
from axiscal.store.corrections import audit
from axiscal.store.laboratory import (add_drift_check, drift_checks, laboratory,
                                      set_laboratory, signoff_config)

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"


@pytest.fixture
def store(db_url):
    """A history on SQLite and on PostgreSQL (migration 0006 on both)."""
    st = open_store(db_url)
    st.add(ECMC.read_bytes(), ECMC.name, machine="MCU1025", date="2026-03-02",
           uncertainty={"resolution": 0.01, "e_ve": 0.3, "e_ve_source": "declared"})
    yield st
    st.close()


def test_laboratory_is_kept_and_every_change_audited(store):
    assert laboratory(store) == {}
    lab = {"company": {"name": "PM GmbH", "address": ["Werkstrasse 1"], "code": "PM"},
           "signatory": [{"name": "B. Signatory", "role": "Head of laboratory"}],
           "uncertainty": {"linear": {"cmc": {"E": 1.0}}}}
    set_laboratory(store, lab, by="eng", reason="laboratory entered")
    assert laboratory(store) == lab
    with pytest.raises(InputError, match="nothing changed"):
        set_laboratory(store, lab, by="eng", reason="again")
    lab2 = {**lab, "company": {**lab["company"], "name": "PM GmbH."}}
    set_laboratory(store, lab2, by="eng2", reason="name as registered")
    a = audit(store)[0]
    assert (a.action, a.by, a.old["company"]["name"], a.new["company"]["name"]) == \
        ("laboratory", "eng2", "PM GmbH", "PM GmbH.")
    with pytest.raises(InputError, match="says who|who makes"):
        set_laboratory(store, lab, by="", reason="x")
    with pytest.raises(InputError, match="is not kept"):
        set_laboratory(store, {"customer": {}}, by="eng", reason="x")


def test_drift_check_gives_e_ve_over_the_stored_inputs(store):
    """E_VE = max − min of the readings: 0.4 − (−0.2) = 0.6 µm (ISO 230-2:2014 Annex A.5,
    as :func:`environmental_variation`'s example). The test's own inputs (resolution 0.01, E_VE
    0.3 declared) are the base; the laboratory's CMC is added; the drift check's E_VE wins."""
    t = store.get(1)
    set_laboratory(store, {"uncertainty": {"resolution": 0.5, "linear": {"cmc": {"E": 1.0}}}},
                   by="eng", reason="CMC")
    assert signoff_config(store, t, {})["uncertainty"]["e_ve"] == 0.3
    d = add_drift_check(store, 1, b"time_s,reading\n0,0.1\n60,0.4\n120,-0.2\n", "dc.csv",
                        by="eng")
    assert (d.e_ve, d.readings) == (0.6, 3) and drift_checks(store, 1) == [d]
    inputs = signoff_config(store, t, {})["uncertainty"]
    assert inputs == {"resolution": 0.01, "e_ve": 0.6, "e_ve_source": "drift check",
                      "linear": {"cmc": {"E": 1.0}}}
    with pytest.raises(InputError, match="given twice"):
        signoff_config(store, t, {}, {"uncertainty": {"e_ve": 1.0}})
    assert audit(store, test_id=1)[0].new["e_ve"] == 0.6
    assert audit(store, test_id=1)[0].old == {"e_ve": 0.3, "e_ve_source": "declared"}
    rec = store.get(1).record()          # the test's one record carries the drift check's E_VE
    assert rec.inputs["e_ve"] == 0.6 and rec.inputs["e_ve_source"] == "drift check"
    from axiscal.report.issue import budget_for

    cfg = signoff_config(store, store.get(1), {})       # the sign-off: the record's inputs
    assert rec.budget.U("E") == budget_for(rec.dataset, rec.evaluation,
                                           {"uncertainty": rec.inputs}).U("E") < 1.0
    assert budget_for(rec.dataset, rec.evaluation, cfg).U("E") == 1.0    # and the lab's CMC
    assert store.get(1).result["quantities"]["E"]["U"] == pytest.approx(rec.budget.U("E"))
    with pytest.raises(AxiscalError, match="at least 2"):
        add_drift_check(store, 1, b"reading\n0.1\n", "one.csv", by="eng")
    assert len(drift_checks(store, 1)) == 1                  # nothing kept of a refusal


def test_only_a_signatory_changes_the_signatories():
    """Review defect 1 (ISO/IEC 17025:2017 §6.2.6 c): the list before the change decides, the
    one kept or, when none is, the server configuration's (its [certificate] signatory too);
    while none is listed anywhere, any account lists the first."""
    from axiscal.errors import NotAuthorisedError
    from axiscal.store.laboratory import check_signatory_change

    new = {"signatory": [{"name": "prep", "role": "Deputy"}]}
    server = {"certificate": {"signatory": "Dr. M. Braun", "signatory_role": "Head"}}
    with pytest.raises(NotAuthorisedError, match=r"only one of them \(Dr. M. Braun\)"):
        check_signatory_change({}, new, "prep", server)
    with pytest.raises(NotAuthorisedError):
        check_signatory_change({"signatory": [{"name": "sig", "role": "Head"}]}, new, "prep")
    check_signatory_change({"signatory": [{"name": "sig", "role": "Head"}]}, new, "SIG")
    check_signatory_change({}, new, "prep")                   # the first list
    check_signatory_change(new, {**new, "company": {"name": "X"}}, "other")   # not the list
