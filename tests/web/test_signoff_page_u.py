"""Review defect 8: the test page's U is the certificate's. After a certificate issued with the
laboratory's CMC (E = 1.0 µm, A = 1.0 µm: ILAC-P14:09/2020 §5.4, a U is never below the CMC) and
a drift check, every U of the page's parameter table equals the U the certificate prints, field by
field; before the issue, the page already shows the U the certificate would state."""

from __future__ import annotations

import re

from tests.web.test_signoff_history import (DRIFT, JOB_FORM, LAB_FORM, _pdf_lines, _sign,
                                            bench)  # noqa: F401 - the fixture

__all__ = ["bench"]


def _page_u(page: str) -> dict:
    """parameter key -> U text of the page's parameter table."""
    body = re.search(r'<table id="parameters">.*?<tbody>(.*?)</tbody>', page, re.S).group(1)
    out = {}
    for row in re.findall(r"<tr[^>]*>(.*?)</tr>", body, re.S):
        key = re.search(r'title="([^" ]+)', row)
        cells = re.findall(r'<td class="num">([^<]*)</td>', row)
        if key and len(cells) >= 2:
            out[key.group(1)] = cells[1].strip()
    return out


def test_page_u_is_the_certificates_field_by_field(bench):
    """Issued with CMC E = A = 1.0 µm and a drift check (E_VE 0.60 µm): the page's U of every
    parameter the certificate lists (its results rows: symbol, value, U) is the printed U; E
    and A are the CMC (1.0), which the page left out before (0.83 there)."""
    from axiscal.report.labels import name as quantity_name

    st = bench.app.state.store
    r = _sign(bench, "issue", files={"drift_check": ("drift.csv", DRIFT, "text/csv")},
              **LAB_FORM, **JOB_FORM)
    assert r.status_code == 303, r.text[-2000:]
    lines = _pdf_lines(st.certificate(st.certificates()[0].number).document)
    results = lines[lines.index("Results") + 1:]
    printed = {ln.split()[0]: ln.split()[2] for ln in results
               if len(ln.split()) > 2 and re.fullmatch(r"-?[\d.]+", ln.split()[1])}
    page = _page_u(bench.get("/tests/1").text)
    assert page["E"] == "1.0" and page["A"] == "1.0"     # the CMC, as the certificate prints
    compared = {k: (u, printed[quantity_name(k, "XY")]) for k, u in page.items()
                if quantity_name(k, "XY") in printed}
    assert len(compared) >= 10, (page, printed)
    assert all(a == b for a, b in compared.values()), compared
