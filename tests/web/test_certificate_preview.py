"""Issue 40, defect 6: the test page's certificate preview (DRAFT), the verdict plot of "Show the
verdict" and the report by every standard name what the history keeps (the machine and axis as
corrected, the date and instrument typed at upload, the laboratory), not the data file's names
and the server's configuration alone; the preview is the sign-off's own certificate, so it and
the issued certificate carry the same item fields."""

from __future__ import annotations

import re

from tests.web.test_signoff_history import (DRIFT, JOB_FORM, LAB_FORM, _pdf_lines, _sign,
                                            _value, bench)  # noqa: F401 - the fixture

def test_preview_and_issued_certificate_name_the_item_alike(bench):
    """Laboratory kept on /laboratory, machine and axis renamed in the history, a certificate
    issued: the preview says the history's names (was: "not stated", the file's PV name,
    "[company] name") and carries the same laboratory, machine, serial, axis, date of test and
    instrument as the issued certificate; the verdict plot and the report by every standard
    name the machine and axis as the history does."""
    from axiscal.store.corrections import rename_axis, rename_machine

    st = bench.app.state.store
    r = bench.post("/laboratory", data={"csrf": bench.token, **LAB_FORM, "reason": "set up",
                                        "by": "B. Signatory"}, follow_redirects=False)
    assert r.status_code == 303, r.text[-2000:]
    rename_machine(st, "MCU1025 bench", "ESS test stand", by="A. Operator", reason="site name")
    rename_axis(st, "ESS test stand", "IOC_TEST:AXIS1-POSSET", "X", by="A. Operator",
                reason="the machine's axis letter")

    page = bench.get("/tests/1").text
    form = {k: _value(page, k) for k in ("date", "instrument1_name")}
    verdict = _sign(bench, "verdict", **LAB_FORM, **{**JOB_FORM, **form}).text
    assert "positioning deviations, X axis" in verdict and "AXIS1-POSSET axis" not in verdict
    standards = bench.get("/tests/1/standards.html").text
    assert "ESS test stand" in standards and "IOC_TEST:AXIS1-POSSET" not in standards

    r = _sign(bench, "issue", files={"drift_check": ("drift.csv", DRIFT, "text/csv")},
              **LAB_FORM, **{**JOB_FORM, **form})
    assert r.status_code == 303, r.text[-3000:]
    number = r.headers["location"].split("certificate=")[1].split("#")[0]
    issued = _pdf_lines(st.certificate(number).document)
    preview = _pdf_lines(bench.get("/tests/1/certificate.pdf").content)   # of that sign-off
    seen = " ".join(_section(preview))
    for said in ("Machine ESS MCU1025 (ESS test stand)", "Axis X", "Date of test 2026-03-02",
                 "Encoder IOC_TEST:m0s012-Enc01", LAB_FORM["lab_name"]):
        assert said in seen, (said, seen)
    text = " ".join(preview)
    assert "[company]" not in text and "IOC_TEST:AXIS1" not in text and "DRAFT" in text
    assert _section(preview) == _section(issued)


def _section(lines: list[str]) -> list[str]:
    """The certificate's laboratory, its "Customer and item calibrated" section and date of
    test, the number and date of issue left out (a preview has neither)."""
    start = lines.index("Customer and item calibrated")
    end = next(i for i, ln in enumerate(lines) if ln.startswith("Test conditions"))
    lab = [ln for ln in lines[:start] if ln in (LAB_FORM["lab_name"], "Werkstrasse 1")]
    item = [re.sub(r"Certificate number .*", "", ln) for ln in lines[start + 1:end]]
    date = [m.group(0) for ln in lines if (m := re.search(r"Date of test \S+", ln))]
    inst = [ln for ln in lines if "Encoder IOC_TEST:m0s012-Enc01" in ln]
    return lab + item + date + inst[:1]
