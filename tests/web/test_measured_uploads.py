"""Workbench uploads of a capture (record + plan), of raw readings with an environment log, and
of a history archive (issue 31, "uploads of a capture (record + plan), raw readings +
environment log, and an archive"): the stored test is the one the command line writes, byte for
byte, and its numbers are the command line's; an archive is stored all or nothing."""

from __future__ import annotations

import json
import re
import zipfile
from html import unescape

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.measured import parse_plan_csv
from axiscal.io.rtx import format_rtx
from axiscal.machines.config import axis_from_config
from axiscal.procedures.record_simulation import RecordSettings, simulate_record
from tests.cli.test_cli_measured import AXIS, _write_raw
from tests.store.test_archive_trust import make_archive, rewrite
from tests.web.test_hardening import _client, _csrf, _stored

runner = CliRunner()


def _cli(*args) -> dict:
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def _post(c, path, files, **data):
    return c.post(path, data={"csrf": _csrf(c, "/upload"), **data}, files=files,
                  follow_redirects=False)


def _stored_test(c, r):
    assert r.status_code == 303, unescape(r.text)
    test_id = int(r.headers["location"].split("/tests/")[1].split("?")[0])
    return c.app.state.store.get(test_id)


def _same_numbers(t, cli_json: dict) -> None:
    """The stored parameters equal ``axiscal iso230-2 --json`` of the CLI's file."""
    for k in ("A", "E", "M", "R", "B"):
        assert t.summary.parameters[k][0] == pytest.approx(cli_json[k], abs=1e-9), k


def test_raw_readings_with_an_environment_log_are_stored_as_the_cli_writes_them(tmp_path):
    _write_raw(tmp_path)
    raw, env = tmp_path / "raw.csv", tmp_path / "env.csv"
    done = _cli("compensate-environment", raw, "--environment", env, "--out",
                tmp_path / "d.csv", "--json")
    cli = _cli("iso230-2", tmp_path / "d.csv", "--json")
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {"file": ("raw.csv", raw.read_bytes(), "text/csv"),
                                      "second": ("env.csv", env.read_bytes(), "text/csv")},
              kind="raw", note="after the warm-up")
    t = _stored_test(c, r)
    assert t.raw == (tmp_path / "d.csv").read_bytes()          # the CLI's --out, byte for byte
    _same_numbers(t, cli)
    assert t.summary.machine == "VMC-800" and t.summary.kind == "iso230-2"
    assert t.summary.note.startswith("after the warm-up; from compensate-environment of "
                                     "raw.csv + env.csv: ")
    assert done["applied"] in t.summary.note and "Ciddor (1996)" in t.summary.note
    again = _post(c, "/upload/measured", {"file": ("raw.csv", raw.read_bytes(), "text/csv"),
                                          "second": ("env.csv", env.read_bytes(), "text/csv")},
                  kind="raw", note="typed again")
    assert "stored=again" in again.headers["location"] and _stored(c) == 1
    assert "note=typed+again" in again.headers["location"]       # shown, not dropped


def test_a_capture_of_a_record_and_its_plan_is_stored_as_the_cli_writes_it(tmp_path):
    _cli("plan", "linear", "--length", "800", "--runs", "2", "--dwell", "2", "--csv",
         tmp_path / "plan.csv", "--json")
    plan = parse_plan_csv((tmp_path / "plan.csv").read_text())
    _, x, _ = simulate_record(plan, axis_from_config(AXIS), np.random.default_rng(6),
                              RecordSettings(sample_rate=1000.0))
    rtx = format_rtx(x * 1e6, 1000.0, Axis="X")
    (tmp_path / "run.rtx").write_bytes(rtx)
    found = _cli("capture", tmp_path / "run.rtx", "--plan", tmp_path / "plan.csv", "--out",
                 tmp_path / "d.csv", "--json")
    cli = _cli("iso230-2", tmp_path / "d.csv", "--json")
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {
        "file": ("run.rtx", rtx, "application/octet-stream"),
        "second": ("plan.csv", (tmp_path / "plan.csv").read_bytes(), "text/csv")},
        kind="capture", machine="VMC-800", axis="X")
    t = _stored_test(c, r)
    assert t.raw == (tmp_path / "d.csv").read_bytes()
    _same_numbers(t, cli)
    assert (f"from capture of run.rtx + plan.csv: {found['stops']} stops found, "
            f"{found['measurements']} measurements matched") in t.summary.note
    assert found["measurements"] == plan.targets.size * 4


@pytest.mark.parametrize("kind, files, words", [
    ("capture", {"file": ("run.rtx", b"x", "application/octet-stream")}, "choose the plan"),
    ("raw", {"file": ("raw.zip", b"x", "application/zip")}, "upload a data file ending in .csv"),
    ("both", {"file": ("raw.csv", b"x", "text/csv")}, "kind 'both': capture"),
    ("raw", {"file": ("raw.csv", b"time_s,nothing\n1,2\n", "text/csv")}, "raw.csv"),
])
def test_a_bad_measured_upload_is_one_message_and_stores_nothing(tmp_path, kind, files, words):
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", files, kind=kind, machine="kept")
    assert r.status_code == 400 and words in unescape(r.text), unescape(r.text)
    assert 'value="kept"' in r.text and _stored(c) == 0          # the form kept
    assert "/tmp" not in r.text                                   # no scratch folder named


def test_an_archive_is_imported_all_or_nothing(tmp_path):
    archive = make_archive(tmp_path, 3)
    c = _client(tmp_path)
    with zipfile.ZipFile(archive) as z:
        raws = [n for n in z.namelist() if n.startswith("raw/")]
    broken = rewrite(archive, tmp_path / "broken.zip", drop=(raws[-1],))
    r = _post(c, "/upload/archive", {"archive": ("broken.zip", broken.read_bytes(),
                                                 "application/zip")})
    said = unescape(re.search(r'role="alert">([^<]*)', r.text).group(1))
    assert r.status_code == 400 and said.startswith("broken.zip: history.jsonl line ")
    assert said.endswith("is missing from the archive; nothing was imported")
    assert _stored(c) == 0                                        # nothing of it stored
    r = _post(c, "/upload/archive", {"archive": ("a.zip", archive.read_bytes(),
                                                 "application/zip")})
    assert r.status_code == 200 and "imported 3 tests from a.zip (0 already stored)" in r.text
    assert _stored(c) == 3
    r = _post(c, "/upload/archive", {"archive": ("a.zip", archive.read_bytes(),
                                                 "application/zip")})
    assert "imported 0 tests from a.zip (3 already stored)" in r.text and _stored(c) == 3


def test_archive_uploads_keep_the_guards(tmp_path):
    archive = make_archive(tmp_path, 2)
    c = _client(tmp_path, upload_limit=1000)
    files = {"archive": ("a.zip", archive.read_bytes(), "application/zip")}
    assert archive.stat().st_size > 1000
    assert _post(c, "/upload/archive", files).status_code == 413 and _stored(c) == 0
    r = c.post("/upload/archive", files=files)                    # no CSRF token
    assert r.status_code == 403 and _stored(c) == 0


def test_a_viewer_uploads_nothing(tmp_path, users):
    from tests.web.conftest import log_in

    archive = make_archive(tmp_path, 1)
    c = _client(tmp_path, users_file=users, require_login=True)
    assert log_in(c, "view", "staple battery horse").status_code == 303
    token = _csrf(c, "/")
    for path, files in (("/upload/archive", {"archive": ("a.zip", archive.read_bytes(),
                                                         "application/zip")}),
                        ("/upload/measured", {"file": ("r.csv", b"x", "text/csv")})):
        r = c.post(path, data={"csrf": token, "kind": "raw"}, files=files)
        assert r.status_code == 403 and "your role is viewer" in r.text, path
    assert _stored(c) == 0


def _epics_log(tmp_path):
    """The camonitor log of tests/data/ecmc/mcu1025_fat_sat_ISO230.dat's steps (ecmccfg,
    GPL-3.0; tests/io/test_epics.py builds it) and its plan."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parents[1] / "io"))
    from test_epics import DATA, REF, SP, _ecmc_log, _plan_csv

    ref_ds, text = _ecmc_log(DATA / "mcu1025_fat_sat_ISO230.dat")
    (tmp_path / "axis1.log").write_text(text)
    (tmp_path / "plan.csv").write_text(_plan_csv(ref_ds.targets, ref_ds.n_runs))
    return tmp_path / "axis1.log", SP, REF


def test_an_epics_log_with_its_settings_gives_the_numbers_of_iso230_2(tmp_path):
    """The measured upload of a camonitor log with the settings named as ``axiscal iso230-2
    LOG``'s options: the stored test's A, E, M, R, B are the command's, and every setting not
    given is named in the note with the default that acted."""
    log, sp, ref = _epics_log(tmp_path)
    cli = _cli("iso230-2", log, "--setpoint-pv", sp, "--reference-pv", ref, "--rest-window", 2,
               "--json")
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {"file": ("axis1.log", log.read_bytes(), "text/x-log")},
              kind="epics", machine="MCU1025", axis="X", setpoint_pv=sp, reference_pv=ref,
              rest_window="2")
    t = _stored_test(c, r)
    _same_numbers(t, cli)
    note = t.summary.note
    assert note.startswith(f"from iso230-2 of axis1.log: {cli['notes']}")   # what was found
    for words in ("--targets not given: the setpoint values passed through",
                  "--reference-scale not given: 1 (ecmc's REF_GR)",
                  "--reference-offset not given: 0 (ecmc's REF_OFF)"):
        assert words in note
    assert "--rest-window not given" not in note and "within 2 µm" in note
    page = unescape(c.get(f"/tests/{t.summary.id}").text)
    assert "--reference-scale not given: 1" in page                  # beside the result


def test_an_epics_log_with_its_plan_is_the_capture_of_the_cli(tmp_path, monkeypatch):
    """With the plan: the stored bytes are those ``axiscal capture LOG --plan PLAN --out``
    writes (run where the files are, so the notes name them as the upload does)."""
    log, sp, ref = _epics_log(tmp_path)
    monkeypatch.chdir(tmp_path)
    found = _cli("capture", "axis1.log", "--plan", "plan.csv", "--out", "d.csv",
                 "--setpoint-pv", sp, "--reference-pv", ref, "--json")
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {
        "file": ("axis1.log", log.read_bytes(), "application/octet-stream"),
        "second": ("plan.csv", (tmp_path / "plan.csv").read_bytes(), "text/csv")},
        kind="epics", machine="MCU1025", axis="X", setpoint_pv=sp, reference_pv=ref)
    t = _stored_test(c, r)
    assert t.raw == (tmp_path / "d.csv").read_bytes()                # the CLI's --out
    assert found["notes"] in t.summary.note and "--targets" not in t.summary.note


@pytest.mark.parametrize("settings, words", [
    ({"reference_scale": "two"}, "--reference-scale 'two': give a number"),
    ({"targets": "15,x"}, "--targets '15,x'"),
    ({"setpoint_pv": "IOC:none"}, "PV 'IOC:none' is not in the log"),
])
def test_a_bad_epics_setting_is_one_message_and_stores_nothing(tmp_path, settings, words):
    log, sp, ref = _epics_log(tmp_path)
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {"file": ("axis1.log", log.read_bytes(), "text/plain")},
              kind="epics", machine="kept", **{"setpoint_pv": sp, "reference_pv": ref,
                                               **settings})
    assert r.status_code == 400 and words in unescape(r.text), unescape(r.text)[-400:]
    assert 'value="kept"' in r.text and _stored(c) == 0
    for name, value in settings.items():                             # the settings kept
        assert f'name="{name}" value="{value}"' in unescape(r.text)


@pytest.mark.parametrize("field, value, words", [
    ("targets", "nan,inf", "the targets must be finite numbers"),
    ("targets", "1e308,2e308", "the targets must be finite numbers"),
    ("targets", "0,abc", "give numbers separated by commas"),
    ("rest_window", "-1", "rest window -1: give a band wider than 0"),
    ("rest_window", "1e308", "rest window 1e+308: give a band wider than 0"),
    ("rest_window", "nan", "give a finite number"),
    ("reference_scale", "0", "a non-zero scale"),
    ("reference_offset", "1e308", "an offset within ±1e9"),
])
def test_hostile_epics_settings_are_an_error_page_and_store_nothing(tmp_path, field, value,
                                                                    words):
    """The EPICS settings of the measured upload at their extremes: one error page in the
    workbench's style naming the setting as ``axiscal iso230-2 LOG`` does, nothing stored."""
    log, sp, ref = _epics_log(tmp_path)
    c = _client(tmp_path)
    r = _post(c, "/upload/measured", {"file": ("axis1.log", log.read_bytes(), "text/x-log")},
              kind="epics", machine="MCU1025", axis="X", setpoint_pv=sp, reference_pv=ref,
              **{field: value})
    assert r.status_code == 400 and words in unescape(r.text), unescape(r.text)[-600:]
    assert "Traceback" not in r.text and _stored(c) == 0
