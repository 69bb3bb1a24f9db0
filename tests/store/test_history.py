"""The calibration history (issue 13): storing, showing again, duplicates, compare, trend, archive,
on SQLite and PostgreSQL."""

from __future__ import annotations

import datetime as dt
import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.errors import AxiscalError
from axiscal.io.csv import format_positioning_csv
from axiscal.io.squareness_examples import example_files
from axiscal.standards.iso230_2 import evaluate
from axiscal.store import NotFoundError, open_store, trend
from axiscal.store.analysis import compare_tests, fit_trend
from axiscal.store.archive import export_history, import_history
from axiscal.store.kinds import jsonable


def _dataset(rng, n_targets=5, runs=5, machine="VMC-800", axis="X", date="2025-03-01",
             offset=0.0):
    t = np.sort(rng.choice(800_000, n_targets, replace=False)) / 1000.0
    up = rng.normal(offset, 2.0, (n_targets, runs))
    down = up - 3.0 + rng.normal(0, 0.5, (n_targets, runs))
    return PositioningDataset("linear", t, up, down, "mm", "um",
                              Metadata(machine=machine, axis=axis, date=date))


def _raw(ds) -> bytes:
    return format_positioning_csv(ds).encode()


def _evaluated(raw: bytes):
    """The evaluation a user gets from the file itself (``axiscal iso230-2 FILE``)."""
    from axiscal.io import parse_positioning

    return evaluate(parse_positioning(raw.decode(), "x.csv"))


def test_store_and_show_again_gives_the_same_numbers(db_url):
    """A stored ISO 230-2 test evaluated again from the stored bytes equals the evaluation of the
    original file, every parameter and every per-target value, bit for bit; the bytes are kept
    exactly."""
    raw = _raw(_dataset(np.random.default_rng(1)))
    s = open_store(db_url)
    r = s.add(raw, "x.csv")
    assert (r.duplicate, r.kind, r.machine, r.axis) == (False, "iso230-2", "VMC-800", "X")
    stored = s.get(r.id)
    direct = _evaluated(raw)
    again = stored.evaluate_again()
    assert stored.raw == raw
    for name, value in direct.parameters().items():
        if value is not None:
            assert stored.summary.parameters[name][0] == value          # exact
            assert again.parameters[name][0] == value
    assert again.result == json.loads(json.dumps(jsonable(direct)))
    # what is stored is that evaluation with the record's quantities, inputs and budget
    assert {k: v for k, v in stored.result.items() if k in again.result} == again.result
    assert set(stored.result) - set(again.result) == {
        "schema_version", "quantities", "uncertainty_inputs", "uncertainty_budget"}
    assert stored.result["quantities"]["E"]["U"] == stored.record().budget.U("E") > 0
    assert stored.summary.tested_at == dt.datetime(2025, 3, 1) and stored.summary.date_known


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 12), runs=st.integers(2, 6))
def test_round_trip_property(tmp_path, seed, n, runs):
    """Any positioning dataset stored and read back evaluates to the same parameters (SQLite)."""
    raw = _raw(_dataset(np.random.default_rng(seed), n, runs))
    s = open_store(f"sqlite:///{tmp_path / f'h{seed}.sqlite'}")
    r = s.add(raw, "x.csv")
    direct = {k: v for k, v in _evaluated(raw).parameters().items() if v is not None}
    # and every other standard axiscal evaluates, as KEY:NAME (issue 16: history for any standard)
    from axiscal.io import parse_positioning
    from axiscal.standards import positioning_standards as ps

    for std, res in ps.evaluate_all(parse_positioning(raw.decode(), "x.csv")):
        if std.key != "iso230-2:2014" and not isinstance(res, str):
            direct.update({f"{std.key}:{k}": v for k, (v, _, _) in res.parameters().items()
                           if v is not None})
    assert {"jis-b6192:R", "vdi3441:Pa", "iso230-2:1988:R_up"} <= set(direct)
    assert {k: v for k, (v, _) in s.get(r.id).evaluate_again().parameters.items()} == direct
    s.close()


@pytest.mark.parametrize("name", sorted(example_files()))
def test_every_kind_round_trips(db_url, name):
    """Straightness, ballbar and diagonal files (the project's example files) stored and shown
    again give the same parameters."""
    text = example_files()[name]
    s = open_store(db_url)
    r = s.add(text.encode(), name, machine="VMC-800", axis="X" if "_x" in name else None)
    t = s.get(r.id)
    assert t.evaluate_again().parameters == t.summary.parameters


def test_motion_kind_round_trips(db_url):
    from axiscal.io.motion import MotionErrorData, format_motion_errors

    rng = np.random.default_rng(3)
    theta = np.radians(np.arange(0, 360, 30.0))
    arrays = {c: rng.normal(0, 1e-6, (2, theta.size)) for c in ("ez", "ey", "ex", "dy", "dz")}
    text = format_motion_errors(MotionErrorData(theta=theta, title="table", **arrays))
    s = open_store(db_url)
    r = s.add(text.encode(), "motion.csv", machine="Table", axis="C")
    assert r.kind == "motion"
    assert s.get(r.id).evaluate_again().parameters == s.get(r.id).summary.parameters


def test_the_same_file_twice_is_a_duplicate(db_url):
    s = open_store(db_url)
    raw = _raw(_dataset(np.random.default_rng(2)))
    first = s.add(raw, "a.csv")
    second = s.add(raw, "renamed.csv", machine="another name")
    assert second.duplicate and second.id == first.id
    assert len(s.tests()) == 1


def test_a_file_that_fails_leaves_nothing(db_url):
    s = open_store(db_url)
    with pytest.raises(AxiscalError):
        s.add(b"target,direction,run,deviation\n0,+,1,abc\n", "bad.csv", machine="M", axis="X")
    with pytest.raises(AxiscalError, match="does not name the machine"):
        s.add(_raw(_dataset(np.random.default_rng(4), machine="")), "x.csv")
    assert s.tests() == [] and s.machines() == []


def test_listing_filters_and_order(db_url):
    s = open_store(db_url)
    rng = np.random.default_rng(5)
    for m, a, d in (("M1", "X", "2024-01-01"), ("M1", "Y", "2024-02-01"), ("M2", "X", "2025-01-01"),
                    ("M1", "X", "2025-06-01")):
        s.add(_raw(_dataset(rng, machine=m, axis=a, date=d)), f"{m}{a}{d}.csv")
    rows = s.tests(machine="M1", axis="x")
    assert [t.tested_at.year for t in rows] == [2025, 2024]            # newest first
    assert len(s.tests(since=dt.datetime(2024, 12, 31))) == 2
    ms = {m.name: m for m in s.machines()}
    assert ms["M1"].axes == ("X", "Y") and ms["M1"].tests == 3
    with pytest.raises(NotFoundError):
        s.get(999)


def test_compare_before_and_after(db_url):
    """Every parameter and the per-target change of the mean bidirectional deviation."""
    rng = np.random.default_rng(6)
    before = _dataset(rng)
    after = PositioningDataset("linear", before.targets, before.up - 2.0, before.down - 2.0,
                               "mm", "um", Metadata(machine="VMC-800", axis="X", date="2025-04-01"))
    s = open_store(db_url)
    a, b = s.add(_raw(before), "b.csv").id, s.add(_raw(after), "a.csv").id
    c = compare_tests(s.get(a), s.get(b))
    np.testing.assert_allclose(c.difference, -2.0, atol=1e-9)
    rows = {n: (x, y, d) for n, x, y, d, _ in c.rows}
    assert rows["R"][2] == pytest.approx(0.0, abs=1e-9)         # a shift changes no R
    assert rows["B_mean"][2] == pytest.approx(0.0, abs=1e-9)


def test_trend_against_numpy_and_the_gum():
    """Drift = numpy.polyfit slope; crossing date t* = t̄ + (T − a)/b; u(t*) by the GUM law of
    propagation (JCGM 100:2008 eq. 13) with u(a), u(b) of ISO/TS 28037 clause 6."""
    rng = np.random.default_rng(7)
    dates = [dt.datetime(2020, 1, 1) + dt.timedelta(days=91 * k) for k in range(12)]
    years = np.array([(d - dates[0]).days / 365.25 for d in dates])
    values = 5.0 + 0.8 * years + rng.normal(0, 0.2, years.size)
    t = fit_trend("E", dates, values, "um", tolerance=10.0)
    b, a0 = np.polyfit(years, values, 1)
    assert t.drift == pytest.approx(b, rel=1e-12)
    res = values - (a0 + b * years)
    s2 = (res ** 2).sum() / (years.size - 2)
    ub = np.sqrt(s2 / ((years - years.mean()) ** 2).sum())
    assert t.u_drift == pytest.approx(ub, rel=1e-12)
    tc = (10.0 - a0) / b
    assert (t.crossing - dates[0]).days / 365.25 == pytest.approx(tc, abs=2 / 365.25)
    assert t.recalibrate_by < t.crossing
    flat = fit_trend("E", dates, np.full(12, 5.0) + rng.normal(0, 0.1, 12) * 0, "um", 10.0)
    assert flat.crossing is None
    assert fit_trend("E", dates[:2], values[:2], "um", 10.0).drift is None


def test_trend_from_the_store(db_url):
    s = open_store(db_url)
    rng = np.random.default_rng(8)
    for k in range(4):
        s.add(_raw(_dataset(rng, date=f"202{k}-05-01", offset=1.5 * k)), f"{k}.csv")
    tr = trend(s, "VMC-800", "x", "E", tolerance=30.0)
    assert len(tr.values) == 4 and tr.drift > 0
    with pytest.raises(NotFoundError):
        trend(s, "VMC-800", "X", "nothing")


def test_export_import_between_databases(tmp_path, pg_server):
    """An archive exported from SQLite imports into PostgreSQL with the same tests; importing it
    again adds nothing."""
    from tests.store.conftest import _fresh_pg_database

    src = open_store(f"sqlite:///{tmp_path / 'a.sqlite'}")
    rng = np.random.default_rng(9)
    for k in range(3):
        src.add(_raw(_dataset(rng, date=f"202{k}-01-01")), f"{k}.csv", note=f"n{k}",
                tables=(("csv", f"t{k}.csv", "position,correction\n"),))
    assert export_history(src, tmp_path / "h.zip") == 3
    dst = open_store(_fresh_pg_database(pg_server))
    assert import_history(dst, tmp_path / "h.zip") == (3, 0)
    assert import_history(dst, tmp_path / "h.zip") == (0, 3)
    a = sorted((t.tested_at, t.parameters["E"], t.note) for t in src.tests())
    b = sorted((t.tested_at, t.parameters["E"], t.note) for t in dst.tests())
    assert a == b
    assert dst.get(dst.tests()[0].id).tables[0][0] == "csv"
