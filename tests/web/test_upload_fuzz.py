"""The command line's corpus of malformed files (tests/cli/_fuzz_cases.py: truncated, hostile
header numbers, swapped units and columns, every class of stray byte, empty, 100,000 nested
brackets, a 1 MB header line) posted through the workbench's upload form (issue 31).

Each mutated file either is refused with an error page of the workbench and nothing stored, or,
when ``axiscal history add`` (the same library call on the command line) takes it too, stored
once; the two front ends never disagree, and no upload answers with a trace or a 500."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from axiscal.cli import app as cli
from axiscal.web.app import create_app
from tests.cli._fuzz_cases import _variants

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _bases() -> dict:
    from tests.web.conftest import positioning_file

    return {"positioning.csv": positioning_file(),
            "ballbar.csv": (EXAMPLES / "squareness_ballbar_150mm.csv").read_bytes(),
            "straightness.csv": (EXAMPLES / "squareness_L180_x.csv").read_bytes()}


@pytest.mark.parametrize("name", sorted(_bases()))
def test_malformed_files_through_the_upload_form(tmp_path, name):
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'web.sqlite'}"),
                   base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/plan").text).group(1)
    store = c.app.state.store
    variants = _variants(name, _bases()[name])
    assert len(variants) >= 15
    refused, seen = 0, {_bases()[name]}
    for what, data in variants.items():
        if data in seen:                     # a mutation that changed nothing: stored already
            continue
        seen.add(data)
        before = len(store.tests(limit=10_000))
        r = c.post("/upload", data={"csrf": token, "machine": "M", "axis": "X"},
                   files={"file": (name, data, "text/csv")}, follow_redirects=False)
        f = tmp_path / name
        f.write_bytes(data)
        line = CliRunner().invoke(cli, ["history", "add", str(f), "--machine", "M", "--axis",
                                        "X", "--db", f"sqlite:///{tmp_path / 'cli.sqlite'}"])
        after = len(store.tests(limit=10_000))
        if line.exit_code == 0:
            assert r.status_code == 303 and after == before + 1, what
            continue
        refused += 1
        assert r.status_code in (400, 413), (what, r.status_code)
        assert 'role="alert"' in r.text and "Traceback" not in r.text, what
        assert after == before, f"{what}: stored although refused"
    assert refused >= len(variants) // 2
