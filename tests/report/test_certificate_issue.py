"""Issuing a certificate (issue 28): each mandatory item of ISO/IEC 17025:2017 §7.8.2.1 and
§7.8.4.1 missing gives a DRAFT naming it, an overdue instrument gives a DRAFT, a test dated after
the date of issue is refused, a name no font can print is refused, the certificate's statements
and layout (long and Chinese names) on the rendered PDF."""

from __future__ import annotations

import copy
import tomllib
from importlib import resources

import pytest

from axiscal.errors import AxiscalError
from axiscal.procedures.positioning import simulate_from_config
from axiscal.report.issue import write_certificate
from axiscal.store import open_store
from tests.report.certificate_jobs import COMPLETE

from pdf_pages import pdf_text, render_pages, used_fraction

TOL = {"E": 25.0, "R": 8.0}


@pytest.fixture(scope="module")
def linear():
    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_linear.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    from axiscal.io.csv import format_positioning_csv

    return sim.dataset, sim.result, format_positioning_csv(sim.dataset).encode()


def _without(path: str, value=None):
    """COMPLETE with ``table.key`` removed (or set to ``value``)."""
    cfg = copy.deepcopy(COMPLETE)
    table, _, key = path.partition(".")
    if not key:
        del cfg[table]
    elif value is None:
        del cfg[table][key]
    else:
        cfg[table][key] = value
    return cfg


def _issue(tmp_path, linear, cfg, name="c.html", note="", **kw):
    ds, result, raw = linear
    store = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    o = write_certificate(tmp_path / name, ds, result, cfg, raw, kw.pop("tol", TOL), store=store,
                          filename="x.csv", today="2026-11-24", config_note=note, **kw)
    return o, store


def _instrument(**kw):
    cfg = copy.deepcopy(COMPLETE)
    cfg["instrument"] = [{**cfg["instrument"][0], **kw}]
    return cfg


@pytest.mark.parametrize("cfg, note, named", [
    (_without("company.name"), "", "laboratory identity"),
    (_without("company.address"), "", "laboratory identity"),
    (_without("company.name", "Your Calibration Company Ltd"), "", "still the template"),
    (_without("company"), "AXISCAL_CONFIG names /x/none.toml, which does not exist",
     "laboratory identity: AXISCAL_CONFIG names /x/none.toml, which does not exist"),
    (_without("company"), "the user configuration /x/c.toml is empty", "is empty"),
    (_without("customer.name"), "", "customer name"),
    (_without("customer.address"), "", "customer address"),
    (_without("machine.maker"), "", "maker of the machine"),
    (_without("machine.model"), "", "model of the machine"),
    (_without("machine.serial"), "", "serial number of the machine"),
    (_without("machine.location"), "", "location of the calibration"),
    (_without("conditions.date"), "", "date of calibration"),
    (_without("conditions.air_temperature"), "", "air temperature during the test, measured"),
    (_without("conditions.material_temperature"), "", "material temperature during the test"),
    (_without("instrument"), "", "instruments used, with their calibration certificates"),
    (_instrument(certificate="..."), "", "calibration certificate number of the instrument"),
    (_instrument(due="YYYY-MM-DD"), "", "calibration due date of the instrument"),
    (_instrument(due="2020-01-01"), "", "due 2020-01-01, overdue on the date of calibration"),
    (_without("uncertainty.e_ve"), "", "environmental variation error"),
    (_without("certificate.specification"), "", "source of the specification"),
    (_without("certificate.signatory"), "", "name of the person authorising"),
    (_without("certificate.signatory_role"), "", "role of the person authorising"),
])
def test_each_missing_item_makes_a_draft_naming_it(tmp_path, linear, cfg, note, named):
    """ISO/IEC 17025:2017 §7.8.2.1 (b, c, e, f, h, i, o), §7.8.4.1 (a, c), §7.8.6.2: one item
    missing -> a DRAFT (title "not a certificate", no number taken) naming it; nothing else
    missing."""
    o, store = _issue(tmp_path, linear, cfg, note=note)
    assert o.draft and o.number == "" and store.certificates() == []
    assert len(o.missing) == 1 and named in o.missing[0], o.missing
    html = o.path.read_text()
    assert "DRAFT — not a certificate" in html and 'class="watermark"' in html


def test_without_a_register_there_is_no_number(tmp_path, linear):
    """§7.8.2.1 b: the number comes from the register only; without one (the workbench's
    download) the complete page is still a DRAFT, naming the number."""
    ds, result, raw = linear
    o = write_certificate(tmp_path / "c.html", ds, result, COMPLETE, raw, TOL, today="2026-11-24")
    assert o.draft and len(o.missing) == 1 and o.missing[0].startswith("certificate number")


def test_a_job_may_carry_the_laboratory(tmp_path, linear):
    """The user configuration absent but the laboratory given (a job file): issued."""
    o, _ = _issue(tmp_path, linear, COMPLETE, note="no user configuration at /x/config.toml")
    assert not o.draft


def test_no_statement_of_conformity_needs_no_specification(tmp_path, linear):
    """§7.8.6.2 asks for the specification only when a verdict is given."""
    o, _ = _issue(tmp_path, linear, _without("certificate.specification"), tol={})
    assert not o.draft and o.number == "PM-2026-00001"


def test_complete_certificate_is_issued_with_its_statements(tmp_path, linear):
    o, store = _issue(tmp_path, linear, COMPLETE)
    assert not o.draft and o.missing == () and o.number == "PM-2026-00001"
    html = o.path.read_text()
    assert "Calibration certificate — positioning of the X axis" in html
    assert "DRAFT" not in html and 'class="watermark"' not in html
    for s in ("metrologically traceable to the SI through the calibration certificates of the "
              "instruments used: Laser interferometer (certificate C-77, due 2027-04-30)",
              "The results relate only to the item calibrated.",
              "This certificate shall not be reproduced except in full without the written "
              "approval of the laboratory.", "against the specification: Contract 4711. Decision rule",
              "Assumptions and deviations", "— End of certificate —",
              "Authorised by: Dr. M. Braun, Head of laboratory"):
        assert s in html, s
    rec = store.certificate(o.number)
    assert rec.document == o.path.read_bytes() and rec.media_type == "text/html"


def test_job_tolerances_are_marked_as_supplied_by_the_customer(tmp_path, linear):
    job = tmp_path / "job.toml"
    job.write_text("[tolerance]\nE = 25\n")
    cfg = {**COMPLETE, "tolerance": {"E": 25.0}}
    o, _ = _issue(tmp_path, linear, cfg, job=job, tol={"R": 8.0})
    html = o.path.read_text()
    assert "<td>25 *</td>" in html and "<td>8</td>" in html
    assert "* Supplied by the customer (job file)." in html
    assert "Contract 4711 (supplied by the customer)" in html


def test_test_dated_after_the_date_of_issue_is_refused(tmp_path, linear):
    cfg = _without("conditions.date", "2026-12-01")
    with pytest.raises(AxiscalError, match="date of test 2026-12-01 is after the date of issue "
                                           "2026-11-24"):
        _issue(tmp_path, linear, cfg)
    assert not (tmp_path / "c.html").exists()


def test_a_name_no_font_can_print_is_refused(tmp_path, linear):
    """An Egyptian hieroglyph is in neither DejaVu Sans nor Noto Sans CJK: refused by name, not
    printed as an empty box."""
    cfg = _without("customer.name", "Pharao \U00013000 Ltd")
    with pytest.raises(AxiscalError, match=r"\[customer\] name: the character .* \(U\+13000, EGYPTIAN"):
        _issue(tmp_path, linear, cfg)
    assert not (tmp_path / "c.html").exists()


def test_long_and_chinese_names_wrap_and_render(tmp_path, linear):
    """A 200-character customer name wraps in its cell (no blank page, no page but the last
    under half full) and a Chinese name is drawn by Noto Sans CJK (it is in the text layer;
    the pages were looked at in build/test-artefacts)."""
    name = ("长城精密机械有限公司 Example Machining AG and Sons " * 6)[:200]
    o, _ = _issue(tmp_path, linear, _without("customer.name", name), name="c.pdf")
    assert not o.draft
    texts = pdf_text(o.path)
    joined = "".join("".join(t.split()) for t in texts)
    assert "长城精密机械有限公司" in joined
    assert "".join(name.split()) in joined
    pngs = render_pages(o.path, "certificate_long_cjk_name")
    fractions = [used_fraction(p) for p in pngs]
    assert all(f >= 0.5 for f in fractions[:-1]), fractions
    last = texts[-1]
    assert "Results" in last and "Authorised by" in last and "End of certificate" in last


def test_draft_pdf_is_marked_on_every_page(tmp_path, linear):
    o, _ = _issue(tmp_path, linear, _without("certificate.signatory"), name="d.pdf")
    texts = pdf_text(o.path)
    assert all("DRAFT" in t for t in texts) and "not a certificate" in texts[0]
    render_pages(o.path, "certificate_draft")


@pytest.mark.parametrize("paper", ["A4", "Letter"])
def test_rotary_certificate_keeps_its_signature_with_the_results(tmp_path, paper):
    """The rotary certificate (14 result rows with the closures) on A4 and Letter with a
    200-character customer name: no page but the last under half full, and the results, the
    signatory and the end mark on the last page together (issue 28: page 4 once held only the
    signature lines)."""
    from axiscal.io.csv import format_positioning_csv

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("demo_rotary.toml").read_text())
    sim = simulate_from_config(cfg, seed=1)
    c = _without("customer.name", ("Rundtisch-Prüfstand GmbH & Co. KG " * 7)[:200])
    c["uncertainty"] = {"e_ve": 0.1}
    c["certificate"]["paper"] = paper
    rotary = (sim.dataset, sim.result, format_positioning_csv(sim.dataset).encode())
    o, _ = _issue(tmp_path, rotary, c, name="r.pdf", tol={"E": 12.0, "R": 6.0})
    assert not o.draft
    texts = pdf_text(o.path)
    assert all(k in texts[-1] for k in ("Results", "Authorised by", "End of certificate"))
    fractions = [used_fraction(p) for p in render_pages(o.path, f"certificate_rotary_long_name_{paper}")]
    assert all(f >= 0.5 for f in fractions[:-1]), fractions


def test_prepared_by_one_approved_by_an_authorised_signatory(tmp_path, linear):
    """Issue 38: whoever ran the command issued. A certificate is prepared by one person and
    issued when one of the laboratory's authorised signatories ([[signatory]] name, role)
    approves it; both are printed and kept in the register."""
    cfg = copy.deepcopy(COMPLETE)
    cfg["signatory"] = [{"name": "Dr. M. Braun", "role": "Head of laboratory"},
                        {"name": "K. Weber", "role": "Deputy head of laboratory"}]
    o, store = _issue(tmp_path, linear, cfg, approved_by="K. Weber")
    assert not o.draft, o.missing
    html = o.path.read_text()
    assert "Prepared by J. Keller; issue approved by K. Weber." in html
    assert "Authorised by: K. Weber, Deputy head of laboratory" in html
    r = store.certificate(o.number)
    assert (r.prepared_by, r.approved_by, r.approved_role) == (
        "J. Keller", "K. Weber", "Deputy head of laboratory")


@pytest.mark.parametrize("approver, prepared, named", [
    ("J. Keller", "", "'J. Keller' is not one of the laboratory's (Dr. M. Braun"),
    ("Dr. M. Braun", "Dr. M. Braun", "approval by a second person: Dr. M. Braun prepared"),
])
def test_an_approval_that_is_not_an_authorised_signatorys_is_a_draft(tmp_path, linear, approver,
                                                                     prepared, named):
    """An approver not on the laboratory's list, or the preparer approving their own
    certificate: a DRAFT naming it, no number, nothing in the register."""
    o, store = _issue(tmp_path, linear, COMPLETE, approved_by=approver, prepared_by=prepared)
    assert o.draft and any(named in m for m in o.missing), o.missing
    assert store.certificates() == []


def test_laser_conditions_and_the_datas_origin_are_printed(tmp_path, linear):
    """Issue 38: air pressure and humidity could not be entered; α showed 'not stated' while the
    budget assumed 11.5 µm/(m·K); the sensors' place, 'referred to 20 °C' and who took the
    readings were not said."""
    cfg = copy.deepcopy(COMPLETE)
    cfg["conditions"].update(air_pressure=101100, humidity=45, referred_to_20=True,
                             material_sensors="two sensors on the X scale, at 200 and 600 mm")
    o, _ = _issue(tmp_path, linear, cfg)
    html = o.path.read_text()
    for text in ("101100", ">45<", "two sensors on the X scale, at 200 and 600 mm",
                 "Deviations referred to 20 °C (ISO 1)</td><td>yes",
                 "the laboratory&#x27;s instrument"):
        assert text in html, text
    assert "11.5 (assumed: steel" in html or "11.5 (taken from the data file" in html
    assert "interval" not in html.lower()          # §7.8.4.3: no calibration interval advised
    bad = copy.deepcopy(COMPLETE)
    bad["conditions"]["humidity"] = 140
    with pytest.raises(AxiscalError, match="humidity = 140: a number from 0 to 100"):
        _issue(tmp_path, linear, bad, name="bad.html")


def test_readings_of_the_customers_control_system_are_marked(tmp_path):
    """The ESS ecmc file: its reference is the machine's encoder read by ecmc, so the readings
    are the customer's (ISO/IEC 17025:2017 §7.8.2.2), said in the conditions and statements."""
    from pathlib import Path

    from axiscal.io.ecmc import read_ecmc
    from axiscal.standards.iso230_2 import evaluate

    path = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
    ds = read_ecmc(path)
    o, _ = _issue(tmp_path, (ds, evaluate(ds), path.read_bytes()), COMPLETE, tol={"R": 210.0})
    html = o.path.read_text()
    assert "the customer&#x27;s own system (data supplied by the customer)" in html
    assert "supplied by the customer (ISO/IEC 17025:2017 §7.8.2.2)" in html
    assert "CONFORMS" not in html and "NOT PROVEN" in html       # R = 204.76 ± 150 vs 210
    assert "<td>205</td><td>150</td>" in html                    # value to U's last digit
    assert "simulated" not in html.lower()            # a real file's certificate says none


def test_one_identity_of_the_item_in_title_plot_and_identification(tmp_path, linear):
    """Issue 38: the plot's title said "VMC-800 (simulated)" where the certificate said "Example
    VMC-800", and a job's [machine] axis was refused. One identity: the job's machine, serial,
    axis and location in the identification, the title and the figure's title."""
    cfg = copy.deepcopy(COMPLETE)
    cfg["machine"]["axis"] = "Y1"
    o, _ = _issue(tmp_path, linear, cfg)
    html = o.path.read_text()
    assert "positioning of the Y1 axis" in html
    assert "Example Machining AG, hall 2" in html
    from axiscal.report.certificate import _figure_title, item_identity, certificate_info

    item = item_identity(linear[0], certificate_info(cfg))
    assert item == {"Machine": "Example VMC-800", "Serial number": "VMC8-0042",
                    "Location": "Example Machining AG, hall 2", "Axis": "Y1"}
    assert _figure_title(item) == ("Positioning deviation, ISO 230-2:2014 — Example VMC-800, "
                                   "serial VMC8-0042, axis Y1")
    assert "simulated" not in _figure_title(item)


def _stored_axis_test(store, seed: int, date: str, slope: float):
    """A linear X-axis test of machine M-1 on ``date``: deviations ``slope`` µm/mm along the
    travel plus noise (a compensated axis has a small slope)."""
    import numpy as np

    from axiscal.datasets import Metadata, PositioningDataset
    from axiscal.io.csv import format_positioning_csv

    rng = np.random.default_rng(seed)
    t = np.linspace(0, 800, 9)
    up = slope * t[:, None] + rng.normal(0, 0.4, (9, 5))
    ds = PositioningDataset("linear", t, up, up - 0.8, "mm", "um",
                            Metadata(machine="M-1", axis="X", date=date))
    return store.add(format_positioning_csv(ds).encode(), f"x-{date}.csv").id


def test_as_found_and_as_left_from_two_stored_tests(tmp_path):
    """Issue 38 (ISO/IEC 17025:2017 §7.8.4.1 d): a compensated axis's certificate reports the
    test before compensation and the one after, each with its U and verdict against the same
    tolerance; the register keeps both tests; a pair of another axis or in the wrong order is
    refused."""
    from axiscal.report.issue import write_as_found_as_left

    store = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    found = _stored_axis_test(store, 1, "2026-11-18", 0.03)     # E about 24 µm
    left = _stored_axis_test(store, 2, "2026-11-20", 0.001)     # E about 2 µm
    o = write_as_found_as_left(tmp_path / "c.html", store, found, left, COMPLETE, {"E": 10.0},
                               today="2026-11-24")
    assert not o.draft, o.missing
    html = o.path.read_text()
    assert "positioning of the X axis, as found and as left" in html
    assert "Results as found, before adjustment (test of 2026-11-18)" in html
    assert "Results as left, after adjustment" in html
    assert "As found: non-conformance proven; as left: conformance proven." in html
    r = store.certificate(o.number)
    assert (r.test_id, r.as_found_test_id) == (left, found)
    assert f"(as found: test {found})" in str(r)
    with pytest.raises(AxiscalError, match="is after test"):
        write_as_found_as_left(tmp_path / "d.html", store, left, found, COMPLETE, {"E": 10.0},
                               today="2026-11-24")
    other = store.add(store.get(left).raw.replace(b"M-1", b"M-2"), "m2.csv").id
    with pytest.raises(AxiscalError, match="as found and as left are one axis"):
        write_as_found_as_left(tmp_path / "e.html", store, found, other, COMPLETE, {"E": 10.0},
                               today="2026-11-24")


def test_names_corrected_in_the_history_reach_the_certificate(tmp_path):
    """Issue 38: names corrected in the history never reached a certificate. An axis renamed
    in the history (X -> X1) is the certificate's axis where the job names none."""
    from axiscal.report.issue import write_certificate
    from axiscal.store.corrections import rename_axis, rename_machine

    store = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    left = _stored_axis_test(store, 2, "2026-11-20", 0.001)
    rename_axis(store, "M-1", "X", "X1", by="QA", reason="the customer calls it X1")
    rename_machine(store, "M-1", "Press line 4 mill", by="QA", reason="customer's name")
    cfg = copy.deepcopy(COMPLETE)
    del cfg["machine"]["maker"], cfg["machine"]["model"]
    t = store.get(left)
    ev = t.evaluate_again()
    o = write_certificate(tmp_path / "c.html", ev.dataset, ev.evaluation, cfg, t.raw,
                          {"E": 10.0}, store=store, filename="x.csv", today="2026-11-24")
    html = o.path.read_text()
    assert "positioning of the X1 axis" in html and "Press line 4 mill" in html
    assert any("maker of the machine" in m for m in o.missing)   # still a DRAFT: no maker
