"""Issue 40, defects 3 (its rendering) and 7: a customer's certificate speaks the certificate's
own words. An assumed input of a ballbar or diagonal budget says "assumed" once; how an input is
set is said in words (the laboratory's uncertainty input, by its label), never a configuration
file's ``[squareness_uncertainty] e_ve`` (whose underscores were printed as subscripts); an
amendment lists each change by the label the certificate prints ("Machine: A → B")."""

from __future__ import annotations

import copy
import re

import pytest

from axiscal.report.certificate import _changes
from axiscal.report.kind_certificate import write_kind_certificate
from tests.report.test_kind_certificate import COMPLETE, _stored, files  # noqa: F401


@pytest.mark.parametrize("kind", ["ballbar", "diagonal"])
def test_budget_notes_are_in_words(files, tmp_path, kind):  # noqa: F811
    st, t = _stored(tmp_path, files[kind])
    from axiscal.store.kinds import with_uncertainty

    cfg = copy.deepcopy(COMPLETE)
    rec = t.record()          # E_VE declared (the diagonal's budget reads it; none is an item)
    rec = with_uncertainty(rec, {**rec.inputs, "e_ve": 0.5}) if kind == "diagonal" else rec
    write_kind_certificate(tmp_path / "c.html", rec, cfg, t.raw, {}, store=None,
                           filename=t.summary.filename, today="2026-11-25")
    page = (tmp_path / "c.html").read_text()
    text = re.sub(r"<[^>]+>", "", page)
    assert "assumed: assumed:" not in text and "assumed:" in text
    for code in ("_uncertainty]", "<sub>uncertainty</sub>", "<sub>ppm</sub>", "axiscal config",
                 "user configuration", "--uncertainty"):
        assert code not in page, code


def test_amendment_lists_changes_by_the_certificates_labels():
    html = _changes([{"what": "[machine] name", "old": "MCU1025 stand",
                      "new": "ESS MCU1025 test stand"},
                     {"what": "[company] name", "old": "PM", "new": "PM GmbH"},
                     {"what": "[customer] address", "old": "Werkstr. 5; 12345 Berlin",
                      "new": "Werkstr. 7; 12345 Berlin"},
                     {"what": "[[instrument]] 1 due", "old": "2026-01-01", "new": "2027-01-01"},
                     {"what": "[uncertainty] linear", "old": '{"cmc": {"E": 1.0}}',
                      "new": '{"cmc": {"E": 1.2}}'},
                     {"what": "U(E)", "old": "1.0", "new": "1.1"}])
    assert "<li>Machine: MCU1025 stand → ESS MCU1025 test stand</li>" in html
    assert "<li>Laboratory: PM → PM GmbH</li>" in html
    assert "<li>Customer address: Werkstr. 5; 12345 Berlin → Werkstr. 7; 12345 Berlin</li>" \
        in html
    assert "<li>Instrument 1: calibration due: 2026-01-01 → 2027-01-01</li>" in html
    assert "<li>U(E): 1.0 → 1.1</li>" in html
    assert "<li>Uncertainty inputs of linear axes: CMC: E: 1 → CMC: E: 1.2</li>" in html
    assert "[" not in html
