"""The calibration certificate of a positioning test: PDF pages, text layer, verdicts, layout.

Every certificate is rendered to PNG in build/test-artefacts/ (see pdf_pages.py) and was looked at.
"""

import re
import tomllib
from importlib import resources

import pytest

from axiscal.procedures.positioning import simulate_from_config
from axiscal.report.certificate import certificate_info, positioning_certificate
from axiscal.standards.iso14253_1 import RULE_TEXT, Rule, decide_all
from axiscal.standards.iso230_9 import positioning_budget

from pdf_pages import page_sizes_mm, pdf_text, render_pages, used_fraction

CONFIG = {
    "company": {"name": "Precision Metrology GmbH", "address": ["Messweg 12", "70565 Stuttgart"]},
    "operator": {"name": "J. Keller"},
    "customer": {"name": "Example Machining AG", "address": ["Industriestr. 4", "Esslingen"]},
    "machine": {
        "maker": "Example",
        "model": "VMC-800",
        "serial": "VMC8-0042",
        "location": "Hall 2",
    },
    "conditions": {
        "measuring_line": "100 mm above the table centre",
        "feed": "2000 mm/min",
        "dwell": "4 s",
    },
    "instrument": [
        {
            "name": "Laser interferometer",
            "serial": "L-1",
            "certificate": "C-77",
            "due": "2027-04-30",
        }
    ],
    "certificate": {"approver": "Dr. M. Braun"},  # the older name of [certificate] signatory
}
#: A measured material temperature: the budget then holds no shop-temperature range (issue 28).
MEASURED = {"e_ve": 0.8, "e_ve_source": "drift check", "material_temperature": 20.2}


@pytest.fixture(scope="module")
def linear():
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    return sim.dataset, sim.result


def _certificate(ds, result, tolerances, rule=Rule.ISO_14253_1, paper="A4", uncertainty=None):
    budget = positioning_budget(
        ds, result, MEASURED if uncertainty is None else uncertainty
    )
    decisions = decide_all(result.parameters(), budget, tolerances, rule)
    info = certificate_info(
        {**CONFIG, "certificate": {**CONFIG["certificate"], "paper": paper}},
        number="AXC-TEST-0001",
        issued="2026-11-23",
    )
    return positioning_certificate(ds, result, budget, info, decisions, RULE_TEXT[rule]), budget


@pytest.mark.parametrize("paper, size", [("A4", (210, 297)), ("Letter", (215.9, 279.4))])
def test_pdf_pages_text_and_layout(linear, tmp_path, paper, size):
    """The PDF on A4 and US Letter: every page that size and numbered "page n of N"; the text
    layer holds the overall verdict, each U and the certificate number; no page but the last is
    more than half empty (measured on the pdftoppm rendering). B = 3.42 µm: its U (0.97 µm)
    holds the sampling of the means since issue 38, so B is toleranced at 5 µm, not 4."""
    ds, result = linear
    rep, budget = _certificate(ds, result, {"E": 15, "R": 8, "A": 20, "B": 5}, paper=paper)
    pdf = rep.write(tmp_path / "cert.pdf")
    texts = pdf_text(pdf)
    n = len(texts)
    assert 2 <= n <= 4
    for w, h in page_sizes_mm(pdf):
        assert (w, h) == pytest.approx(size, abs=0.5)
    for i, t in enumerate(texts, 1):
        assert f"page {i} of {n}" in t
        assert "AXC-TEST-0001" in t
    text = "\n".join(texts)
    assert "Overall verdict: CONFORMS" in text
    for p in ("E", "R", "A", "B"):
        assert budget.U_text(p) in text
    assert "ISO 14253-1:2017" in text and "Precision Metrology GmbH" in text
    assert "VMC8-0042" in text and "Laser interferometer" in text and "2027-04-30" in text
    pngs = render_pages(pdf, f"certificate_linear_{paper}")
    assert len(pngs) == n
    fractions = [used_fraction(p) for p in pngs]
    assert all(f >= 0.5 for f in fractions[:-1]), fractions


def test_certificate_shows_no_truth_and_no_internal_references(linear, tmp_path):
    """A customer certificate of simulated data shows the measurement only: no truth table, no
    "seed 00x" references, no simulation banner."""
    ds, result = linear
    html = _certificate(ds, result, {"E": 15})[0].html()
    for word in ("seed 00", "truth", "Truth", "SIMULATION REPORT"):
        assert word not in html, word


@pytest.mark.parametrize(
    "tolerances, rule, headline, cell",
    [
        ({"E": 12.5}, Rule.ISO_14253_1, "NOT PROVEN", "ZONE"),  # E = 11.92, U ≈ 2.4
        ({"E": 12.5}, Rule.SIMPLE, "CONFORMS", "PASS"),
        ({"E": 9.0}, Rule.ISO_14253_1, "DOES NOT CONFORM", "FAIL"),  # 11.92 − 2.4 > 9
        ({"E": 11.0}, Rule.ISO_14253_1, "NOT PROVEN", "ZONE"),
        ({"E": 11.0}, Rule.SIMPLE, "DOES NOT CONFORM", "FAIL"),
    ],
)
def test_verdict_and_rule_are_stated(linear, tolerances, rule, headline, cell):
    ds, result = linear
    html = _certificate(ds, result, tolerances, rule)[0].html()
    assert f"Overall verdict: {headline}" in html
    assert f">{cell}</span>" in html
    assert RULE_TEXT[rule] in html


def test_unknown_conditions_are_said_plainly(linear):
    """ISO 230-2 asks the report to state the test conditions: what the data does not hold is
    written as not stated, never left out."""
    ds, result = linear
    html = _certificate(ds, result, {}, uncertainty={"e_ve": 0.8})[0].html()
    assert "not stated in the data file" in html  # the demo data carries no date
    assert "Material temperature (°C)</td><td>not stated" in html
    assert "No tolerance given" in html
    assert "Assumptions and deviations" in html and "assumed, not given" in html


def test_certificate_info_refuses_unknown_keys():
    from axiscal.errors import ConfigError

    with pytest.raises(ConfigError, match="unknown table"):
        certificate_info({"compnay": {}})
    with pytest.raises(ConfigError, match="unknown key"):
        certificate_info({"machine": {"serial_no": "1"}})
    with pytest.raises(ConfigError, match="A4 or Letter"):
        certificate_info({"certificate": {"paper": "A3"}})


def test_certificate_is_a_pure_function(linear):
    """Same inputs, same page (but for the generation time in the footer): a history store can
    regenerate it."""
    ds, result = linear
    strip = lambda h: re.sub(r"on \d{4}-\d\d-\d\d \d\d:\d\d UTC", "", h)  # noqa: E731
    assert strip(_certificate(ds, result, {"E": 15})[0].html()) == strip(
        _certificate(ds, result, {"E": 15})[0].html()
    )


def test_rotary_certificate_pdf(tmp_path):
    """The rotary positioning test (demo turntable): U in arcsec from the calibrator and
    Renishaw eq. 1, verdicts, page numbers, page fill."""
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_rotary.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    rep, budget = _certificate(sim.dataset, sim.result, {"E": 12, "R": 6}, uncertainty={})
    assert budget.unit == "arcsec" and 0.5 < budget.U("E") < 2.0
    pdf = rep.write(tmp_path / "rotary.pdf")
    texts = pdf_text(pdf)
    assert all(f"page {i} of {len(texts)}" in t for i, t in enumerate(texts, 1))
    text = "\n".join(texts)
    assert "Overall verdict: CONFORMS" in text and budget.U_text("E") in text
    assert "not applicable (rotary axis)" in text and "Renishaw" in text
    fractions = [used_fraction(p) for p in render_pages(pdf, "certificate_rotary_A4")]
    assert all(f >= 0.5 for f in fractions[:-1]), fractions


def test_simulation_report_pdf_is_marked_on_every_page(tmp_path):
    """A simulation report (truth shown) says so on every printed page."""
    from axiscal.report.simulation_views import add_truth_section
    from axiscal.report.html import positioning_report

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    rep = positioning_report(sim.dataset, sim.result)
    rep.simulation = True
    add_truth_section(rep, sim)
    pdf = rep.write(tmp_path / "sim.pdf")
    texts = pdf_text(pdf)
    assert all("SIMULATION REPORT" in t for t in texts) and "truth" in "\n".join(texts)
    render_pages(pdf, "simulation_report_linear_A4")


def test_targets_are_right_aligned_like_the_other_numbers(linear):
    """The per-target table's first column holds numbers: right-aligned (the issue's layout rule),
    while the label column of the metadata tables stays left beside its values."""
    css = _certificate(*linear, {})[0].html()
    assert "table.targets td:first-child, table.targets th:first-child { text-align: right; }" in css
    assert "table.kv td { text-align: left; }" in css
    assert re.search(r'class="targets[" ]', css)   # "targets long": it may continue overleaf
