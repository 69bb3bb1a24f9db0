"""A certificate for every kind of stored test that has an uncertainty budget (issue 40): the
figures it states are the stored record's, field by field (value, U, k), each value rounded to
the last digit of its U (ILAC-P14:09/2020 §5.3), decided by ISO 14253-1:2017 against the
tolerance given; a kind without a budget is refused in one line naming why.

The files are the project's own generators (the diagonal of tests/store/test_paths_agree.py,
the thermal twin, the five-axis twin); the references are the stored records themselves
(one record, every path: the certificate recomputes nothing)."""

from __future__ import annotations

import copy
import json
import tomllib
from importlib import resources
from pathlib import Path

import pytest

import axiscal
from axiscal.errors import InputError
from axiscal.report.kind_certificate import certificate_record, write_kind_certificate
from axiscal.standards.uncertainty_reporting import format_uncertainty, format_value
from axiscal.store import open_store
from tests.report.certificate_jobs import KIND_COMPLETE as COMPLETE

DIAGONAL = ("# length_x_mm=600 length_y_mm=800\ndiagonal,position,error\n"
            "D1,100,0.6\nD1,500,3.0\nD1,1000,6.0\nD2,100,-0.3\nD2,500,-1.5\nD2,1000,-3.0\n")

STRAIGHTNESS = ("# position_unit=mm deviation_unit=um axis=X direction=Y\nposition,deviation\n"
                "0,0\n100,1\n200,3\n300,2\n")

MOTION = Path(__file__).resolve().parents[2] / "examples" / "motion_indexing_table_3runs.csv"

BALLBAR = ("# radius_mm=100\nangle,direction,deviation\n"
           + "".join(f"{a},{d},{0.001 * (a % 7):.4f}\n" for d in ("ccw", "cw")
                     for a in range(0, 360, 10)))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    from axiscal.io.thermal import write_thermal_log

    folder = tmp_path_factory.mktemp("kinds")
    out = {"diagonal": folder / "diagonal.csv"}
    out["diagonal"].write_text(DIAGONAL)
    sim = axiscal.simulate_thermal("linear", seed=1, interval_s=300.0)
    out["thermal"] = folder / "thermal.csv"
    write_thermal_log(out["thermal"], sim.log)
    from axiscal.api import fiveaxis

    cfg = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                        .read_text("utf-8"))
    cfg["setup"] = cfg["setup"][0:1]
    out["fiveaxis"] = fiveaxis.simulate(cfg, seed=3, out=folder).files[0]
    out["ballbar"] = folder / "ballbar.csv"
    out["ballbar"].write_text(BALLBAR)
    whole = tomllib.loads(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")
                          .read_text("utf-8"))
    fiveaxis.ballbar.simulate(dict(whole, ballbar=whole["ballbar"][:1]), seed=3,
                              out=folder / "bb")
    out["fiveaxis-ballbar"] = folder / "bb" / "1_ballbar.csv"
    out["motion"] = MOTION             # the shipped three-run five-DOF file (ISO 230-7)
    out["straightness"] = folder / "straightness.csv"
    out["straightness"].write_text(STRAIGHTNESS)
    out["squareness"] = folder / "squareness.toml"      # squareness biaxial --inline's file
    out["squareness"].write_text(_biaxial_file())
    out["volumetric"] = _volumetric_inline(folder)
    return out


def _biaxial_file() -> str:
    """The examples' two trajectories (L set-up at 180°) as one squareness test file."""
    from pathlib import Path

    from axiscal.io.biaxial import biaxial_test, format_biaxial_test
    from axiscal.io.straightness import read_straightness

    ex = Path(__file__).resolve().parents[2] / "examples"
    return format_biaxial_test(biaxial_test(read_straightness(ex / "squareness_L180_x.csv"),
                                            read_straightness(ex / "squareness_L180_y.csv"),
                                            orientation=180))


def _volumetric_inline(folder):
    """The volumetric twin's configuration with every error inline (the file ``history add``
    keeps), as tests/store/test_volumetric_kind.py makes it."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    for args in (["volumetric", "simulate", "--out", str(folder / "vol"), "--points", "5",
                  "--seed", "3"],
                 ["volumetric", "map", str(folder / "vol" / "volumetric.toml"), "--inline",
                  str(folder / "vol.toml")]):
        r = CliRunner().invoke(app, args)
        assert r.exit_code == 0, r.output
    return folder / "vol.toml"


def _stored(tmp_path, path):
    st = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    added = st.add(path.read_bytes(), path.name, machine="VMC", axis="X")
    return st, st.get(added.id)


@pytest.mark.parametrize("kind", ["diagonal", "thermal", "fiveaxis", "ballbar",
                                  "fiveaxis-ballbar", "motion", "squareness", "volumetric",
                                  "straightness"])
def test_the_certificate_states_the_stored_record_field_by_field(files, tmp_path, kind):
    """Value, U and k of every figure are the stored record's (``history show --json``'s
    ``quantities``); the printed value has U's last digit (ILAC-P14:09/2020 §5.3)."""
    st, t = _stored(tmp_path, files[kind])
    ev = t.record()
    assert ev.kind == kind
    stored = t.result["quantities"]
    rec = certificate_record(ev)
    assert rec.figures and rec.overall is None
    for f in rec.figures:
        q = stored[f.name]
        assert (f.value, f.U, f.k, f.unit) == (q["value"], q["U"], q["k"], q["unit"]), f.name
        assert f.U_text == format_uncertainty(q["U"])
        assert f.value_text == format_value(q["value"], q["U"])
    assert {f.name for f in rec.figures} == {n for n, q in stored.items()
                                             if q["U"] is not None and q["value"] is not None}
    assert rec.inputs, "the budget's inputs are listed"
    assert all(v.strip() for row in rec.inputs for v in row[:2]), rec.inputs


def test_a_diagonal_certificate_is_issued_with_its_verdict(files, tmp_path):
    """Squareness (D1 − D2)·D0/(2XY) of ISO 230-6:2002 §4 with D0 = 1000 mm, X = 600, Y =
    800 mm: errors growing along each diagonal to 6 and −3 µm at 1000 mm give
    9·1000/(2·600·800) = 9.375 µm/m; against 20 µm/m
    with its U (about 0.7 µm/m, ISO/TR 230-9) conformance is proven (ISO 14253-1:2017 §5.2)
    and the register numbers the certificate. Its E_VE is declared (0.5 µm): without it the
    certificate is a DRAFT (review defect 3, never "0 µm assumed")."""
    from axiscal.store.kinds import with_uncertainty

    st, t = _stored(tmp_path, files["diagonal"])
    bare = write_kind_certificate(tmp_path / "d.html", t.record(), copy.deepcopy(COMPLETE),
                                  t.raw, {"squareness": 20.0}, store=st, today="2026-11-25",
                                  prepared_by="J. Keller", draft_document=False)
    assert [m[:5] for m in bare.missing] == ["E_VE,"] and not bare.number
    ev = with_uncertainty(t.record(), {**t.record().inputs, "e_ve": 0.5})
    sq = ev.parameters["squareness"][0]
    assert sq == pytest.approx(9.375, abs=1e-6)
    out = write_kind_certificate(tmp_path / "c.html", ev, copy.deepcopy(COMPLETE), t.raw,
                                 {"squareness": 20.0}, store=st, filename=t.summary.filename,
                                 today="2026-11-25", prepared_by="J. Keller")
    assert out.missing == () and out.number.startswith("PM-2026-")
    assert out.decisions[0].outcome.value == "conformance proven"
    page = (tmp_path / "c.html").read_text()
    f = certificate_record(ev, {"squareness": 20.0}).figures[0]
    assert f"<td>{f.value_text}</td><td>{f.U_text}</td><td>2</td>" in page
    assert "Contract 4711" in page and out.number in page
    assert st.certificate(out.number).test_id == t.summary.id


def test_a_motion_certificate_is_issued_with_its_verdicts(files, tmp_path):
    """The shipped three-run five-DOF file (ISO 230-7:2015 §3): radial Y total 7.19 µm with U
    about 0.19 µm (:mod:`axiscal.standards.iso230_7_uncertainty`, defaults) against 10 µm is
    conformance proven; tilt Y total 15.86 arcsec, U about 0.42, against 15 arcsec is
    non-conformance proven; the synchronous radial Y value of three runs, 2.2 µm with U about
    3.4 µm (the run-to-run scatter of the mean), against 5 µm is in the uncertainty zone
    (ISO 14253-1:2017 §5.2-5.3). Issued and numbered; each figure's row is the record's."""
    st, t = _stored(tmp_path, files["motion"])
    ev = t.record()
    tol = {"radial_Y_total": 10.0, "tilt_Y_total": 15.0, "radial_Y_synchronous": 5.0}
    out = write_kind_certificate(tmp_path / "m.html", ev, copy.deepcopy(COMPLETE), t.raw, tol,
                                 store=st, filename=t.summary.filename, today="2026-11-25",
                                 prepared_by="J. Keller")
    assert out.missing == () and out.number.startswith("PM-2026-")
    got = {d.parameter: d.outcome.value for d in out.decisions}
    assert got == {"radial_Y_total": "conformance proven",
                   "tilt_Y_total": "non-conformance proven",
                   "radial_Y_synchronous": "uncertainty zone"}
    page = (tmp_path / "m.html").read_text()
    figs = {f.name: f for f in certificate_record(ev, tol).figures}
    f = figs["radial_Y_total"]
    assert (f.value_text, f.U_text) == ("7.19", "0.19")
    assert f"<td>{f.value_text}</td><td>{f.U_text}</td><td>2</td>" in page
    assert "Radial Y error motion, total (radial_Y_total)" in page
    assert "resolution of δy (radial Y)" in page and "run-to-run scatter s of δy" in page
    assert st.certificate(out.number).test_id == t.summary.id


def test_a_missing_item_makes_a_draft_and_a_bad_tolerance_is_refused(files, tmp_path):
    st, t = _stored(tmp_path, files["thermal"])
    cfg = copy.deepcopy(COMPLETE)
    del cfg["customer"]["address"]
    out = write_kind_certificate(tmp_path / "d.html", t.record(), cfg, t.raw, store=st,
                                 prepared_by="J. Keller", draft_document=False)
    assert out.draft and out.missing == ("customer address ([customer] address)",)
    with pytest.raises(InputError, match="not a parameter of this result"):
        certificate_record(t.record(), {"R_up": 3.0})
    with pytest.raises(InputError, match="a positive number"):
        certificate_record(t.record(), {next(iter(t.record().parameters)): -1.0})


def _without_budget(monkeypatch, kind: str) -> None:
    """``kind`` made a kind without an uncertainty budget (:func:`axiscal.store.kinds.
    budget_of` makes none for it), so the refusal is tested whichever kinds lack one today."""
    from axiscal.store import kinds

    made = kinds.budget_of
    monkeypatch.setattr(kinds, "budget_of", lambda k, *a: None if k == kind else made(k, *a))


def test_a_kind_without_a_budget_is_refused_in_one_line(files, tmp_path, monkeypatch):
    _without_budget(monkeypatch, "straightness")
    st, t = _stored(tmp_path, files["straightness"])
    assert t.record().budget is None
    with pytest.raises(InputError) as e:
        write_kind_certificate(tmp_path / "x.html", t.record(), COMPLETE, t.raw, store=st)
    assert str(e.value).startswith("no uncertainty budget for straightness tests in axiscal: ")
    assert "\n" not in str(e.value)
    assert not (tmp_path / "x.html").exists() and st.certificates(test_id=t.summary.id) == []


def test_a_straightness_certificate_is_issued_on_the_command_line(files, tmp_path):
    """ISO 230-1:2012 straightness of 0, 1, 3, 2 µm at 0..300 mm: least squares 1.8 µm
    (the line 0.3 + 0.8·x/100 mm µm leaves −0.3, −0.1, 1.1, −0.7 µm), with U by
    standards/iso230_9_straightness.py; ``axiscal certificate issue ID`` with every item
    given (E_VE declared: without it the certificate is a DRAFT, never E_VE = 0) numbers it
    (not a DRAFT) and states each figure as the stored record holds it with that E_VE."""
    from typer.testing import CliRunner

    from axiscal.cli import app as cli_app
    from tests.report.pdf_pages import pdf_text

    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    st = open_store(url)
    tid = st.add(files["straightness"].read_bytes(), "straightness.csv", machine="VMC").id
    job = tmp_path / "job.toml"
    job.write_text(_toml({**COMPLETE, "uncertainty": {"e_ve": 0.5}}))    # E_VE declared
    out = tmp_path / "straightness.pdf"
    r = CliRunner().invoke(cli_app, ["certificate", "issue", str(tid), "--db", url, "--job",
                                     str(job), "--tolerance", "straightness=20",
                                     "--prepared-by", "J. Keller", "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["number"].startswith("PM-2026-") and got["test_id"] == tid
    text = " ".join(" ".join(pdf_text(out)).split())
    assert "DRAFT" not in text and got["number"] in text
    from axiscal.store.kinds import with_uncertainty

    stored = st.get(tid).record()      # the certificate's record: its budget with E_VE 0.5 µm
    rec = certificate_record(with_uncertainty(stored, {**stored.inputs, "e_ve": 0.5}),
                             {"straightness": 20.0})
    assert {f.name for f in rec.figures} == {"straightness", "straightness_min_zone", "slope"}
    f = next(f for f in rec.figures if f.name == "straightness")
    assert f.value == pytest.approx(1.8, abs=1e-9) and f.verdict == "conformance proven"
    assert f"{f.value_text} {f.U_text} 2 µm 20" in text, text[-2000:]
    assert "reading noise σ of one reading" in text and "measured: the spread" in text


def _toml(cfg: dict) -> str:
    """A job file of ``cfg`` (tables of strings, numbers and lists of them)."""
    def val(v):
        return json.dumps(v, ensure_ascii=False)
    out = []
    for table, body in cfg.items():
        rows = body if isinstance(body, list) else [body]
        for row in rows:
            out.append(f"[[{table}]]" if isinstance(body, list) else f"[{table}]")
            out += [f"{k} = {val(v)}" for k, v in row.items()]
    return "\n".join(out) + "\n"


def test_certificate_issue_on_the_command_line(files, tmp_path, monkeypatch):
    """``axiscal certificate issue ID``: a diagonal test numbered by the register, its
    squareness and U in the document; a test of a kind without a budget (straightness made one,
    :func:`_without_budget`) refused in one line, exit 2, nothing issued."""
    _without_budget(monkeypatch, "straightness")
    from typer.testing import CliRunner

    from axiscal.cli import app as cli_app

    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    st = open_store(url)
    d = st.add(files["diagonal"].read_bytes(), "diagonal.csv", machine="VMC").id
    b = st.add(files["straightness"].read_bytes(), "straightness.csv", machine="VMC").id
    job = tmp_path / "job.toml"
    job.write_text(_toml({**COMPLETE, "uncertainty": {"e_ve": 0.5}}))    # E_VE declared
    runner = CliRunner()
    r = runner.invoke(cli_app, ["certificate", "issue", str(d), "--db", url, "--job", str(job),
                                "--tolerance", "squareness=20", "--prepared-by", "J. Keller",
                                "--out", str(tmp_path / "sq.html"), "--json"])
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["test_id"] == d and got["number"].startswith("PM-2026-")
    from axiscal.store.kinds import with_uncertainty

    rec = with_uncertainty(st.get(d).record(), {**st.get(d).record().inputs, "e_ve": 0.5})
    f = certificate_record(rec, {"squareness": 20.0}).figures[0]
    assert f"<td>{f.value_text}</td><td>{f.U_text}</td>" in (tmp_path / "sq.html").read_text()
    fix = tmp_path / "fix.toml"
    fix.write_text('[customer]\nname = "Example Machining GmbH"\n')
    r = runner.invoke(cli_app, ["certificate", "reissue", got["number"], "--db", url,
                                "--reason", "customer renamed", "--job", str(fix),
                                "--out", str(tmp_path / "sq2.html"), "--json"])
    assert r.exit_code == 0, r.output
    again = json.loads(r.stdout)
    assert again["replaces"] == got["number"] and again["test_id"] == d
    assert {"what": "[customer] name", "old": "Example Machining AG",
            "new": "Example Machining GmbH"} in again["changes"]
    assert "This certificate replaces certificate" in (tmp_path / "sq2.html").read_text()
    r = runner.invoke(cli_app, ["certificate", "issue", str(b), "--db", url, "--job", str(job),
                                "--out", str(tmp_path / "bb.html")])
    assert r.exit_code == 2
    assert r.output.strip().splitlines() == [
        "axiscal: error: no uncertainty budget for straightness tests in axiscal: a certificate "
        "states "
        "each result with its expanded uncertainty U (ILAC-P14:09/2020 §5; ISO 14253-1:2017 "
        "§5), so this test gets none"]
    assert not (tmp_path / "bb.html").exists()
    r = runner.invoke(cli_app, ["certificate", "issue", str(d), "--db", url, "--job", str(job),
                                "--tolerance", "E=20", "--out", str(tmp_path / "e.html")])
    assert r.exit_code == 2 and "tolerance for 'E': not a parameter of this result; use one " \
        "of squareness" in r.output and not (tmp_path / "e.html").exists()


def test_certificate_issue_of_a_motion_test_on_the_command_line(files, tmp_path):
    """``axiscal certificate issue ID`` of a stored five-motion-error test: numbered, each
    decided figure's value and U as the record's; a tolerance that is no figure is refused."""
    from typer.testing import CliRunner

    from axiscal.cli import app as cli_app

    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    st = open_store(url)
    m = st.add(files["motion"].read_bytes(), "motion.csv", machine="HSD-200RT", axis="C").id
    job = tmp_path / "job.toml"
    job.write_text(_toml(COMPLETE))
    runner = CliRunner()
    r = runner.invoke(cli_app, ["certificate", "issue", str(m), "--db", url, "--job", str(job),
                                "--tolerance", "axial_total=10", "--prepared-by", "J. Keller",
                                "--out", str(tmp_path / "m.html"), "--json"])
    assert r.exit_code == 0, r.output
    got = json.loads(r.stdout)
    assert got["test_id"] == m and got["number"].startswith("PM-2026-")
    f = {g.name: g for g in certificate_record(st.get(m).record(),
                                               {"axial_total": 10.0}).figures}["axial_total"]
    assert f"<td>{f.value_text}</td><td>{f.U_text}</td>" in (tmp_path / "m.html").read_text()
    r = runner.invoke(cli_app, ["certificate", "issue", str(m), "--db", url, "--job", str(job),
                                "--tolerance", "ez_total=20", "--out", str(tmp_path / "e.html")])
    assert r.exit_code == 2 and "tolerance for 'ez_total': not a parameter of this result" \
        in r.output and not (tmp_path / "e.html").exists()
