"""Every certificate and report a user receives, rendered page by page and checked (issue 28).

What ``make demo`` writes (``axiscal demo --out``: two certificates, the simulation reports, the
index) and the report of every command the README's tour runs with ``--report`` are rendered to
PDF (HTML through WeasyPrint, the same template as ``--report x.pdf``) and then to PNG with
pdftoppm (kept in build/test-artefacts/, see pdf_pages.py). On each:

* no page is more than half empty except the last: the lowest non-white pixel row of the page's
  body (between the running header and footer margins) lies below its middle;
* no code identifier in the text layer (pypdf): no word with an underscore (``servo_mismatch``,
  ``u_E,MACHINE``) and no indexed key (``uncertainty[1]``); a standard's symbols are printed with
  their subscripts, and file names the user gave are left as they are;
* a report that shows a simulation's truth carries the "SIMULATION REPORT" banner on every
  printed page, and a report of measured data does not;
* a certificate's signature block is on the page of its results table (ISO/IEC 17025:2017 §7.8.2.1
  asks for the signatory's identification with the results; issue 28: never alone on a page).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

from pdf_pages import pdf_text, render_pages, used_fraction

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
DPI = 40
BANNER = "SIMULATION REPORT"

#: A word that is code: a letter or digit, an underscore, a letter or digit (``backlash_x``,
#: ``u_EVE``), or a key indexed with brackets (``uncertainty[1]``).
CODE = re.compile(r"\w_\w|\w\[")
#: What a user named: a file (``squareness_L180_x.csv``) or a path.
FILE = re.compile(r"(/|\.(csv|toml|rtx|json|html|pdf|txt|ini|zip|sqlite)\b)")

#: (name, arguments, is a simulation report); {demo}, {tmp}, {ex} are filled in; the report is
#: written to {out}. Inputs made first: the ballbar trace and the volumetric simulation.
COMMANDS = [
    ("ballbar_analyze", "ballbar analyze {tmp}/t.csv --report {out}", False),
    ("squareness_circular", "squareness circular {ex}/squareness_ballbar_150mm.csv --report {out}",
     False),
    ("squareness_diagonal", "squareness diagonal --file {ex}/squareness_diagonal_600x800.csv "
     "--report {out}", False),
    ("squareness_biaxial", "squareness biaxial {ex}/squareness_L180_x.csv "
     "{ex}/squareness_L180_y.csv --config L --orientation 180 --report {out}", False),
    ("squareness_simulate", "squareness simulate --machine 3 --scope global --report {out}", True),
    ("straightness", "straightness {ex}/squareness_L180_x.csv --reference minimum_zone "
     "--report {out}", False),
    ("evaluate_all", "evaluate {demo}/rotary_data.csv --standard all --report {out}", False),
    ("volumetric_map", "volumetric map {tmp}/vol/volumetric.toml --report {out}", True),
    ("motion_simulate", "motion simulate {ex}/motion_indexing_table.toml --report {out}", True),
    ("rotary_budget", "rotary budget --alpha 0.62 --beta 1.23 --omega 2.26 --report {out}", False),
    ("capture", "capture {demo}/run.rtx --plan {demo}/plan.csv --out {tmp}/cap.csv --window 0.5 "
     "--report {out}", False),
    ("compensate_environment", "compensate-environment {demo}/raw.csv --environment "
     "{demo}/env.csv --out {tmp}/env_data.csv --report {out}", False),
    ("scale_home", "scale home {ex}/scale_single.toml --report {out}", True),
    ("scale_gantry", "scale gantry {ex}/scale_gantry.toml --report {out}", True),
    ("compensate_verify", "compensate --verify {ex}/compensation_rotary.toml --report {out}", True),
]
#: What ``axiscal demo`` writes: (file, is a simulation report, is a certificate).
DEMO = [("linear_certificate.pdf", False, True), ("rotary_certificate.pdf", False, True),
        ("linear_report.html", True, False), ("rotary_report.html", True, False),
        ("rotary_calibration_report.html", True, False), ("index.html", False, False)]


def _run(args: str) -> None:
    r = CliRunner().invoke(app, args.split())
    assert r.exit_code == 0, f"axiscal {args}: exit {r.exit_code}: {r.output[-400:]}"


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    """The demo's folder and the inputs the tour's commands read."""
    tmp = tmp_path_factory.mktemp("pages")
    demo = tmp / "demo"
    _run(f"demo --out {demo} --db sqlite:///{tmp / 'history.sqlite'}")
    _run(f"ballbar simulate {EXAMPLES}/ballbar_sim.toml --out {tmp}/t.csv --seed 1")
    _run(f"volumetric simulate --out {tmp}/vol")
    return {"demo": demo, "tmp": tmp, "ex": EXAMPLES}


def _as_pdf(path: Path) -> Path:
    """An HTML report as the PDF it prints to (WeasyPrint, the template's @page rules)."""
    if path.suffix == ".pdf":
        return path
    from axiscal.report.pdf import write_pdf

    return write_pdf(path.read_text("utf-8"), path.with_suffix(".pdf"))


def _check_pages(pdf: Path, name: str, simulation: bool) -> list[str]:
    """The checks every report passes (module docstring); returns the text of each page."""
    pngs = render_pages(pdf, name, dpi=DPI)
    texts = pdf_text(pdf)
    assert len(pngs) == len(texts) >= 1
    fill = [used_fraction(p, dpi=DPI) for p in pngs]
    assert all(f >= 0.5 for f in fill[:-1]), f"{name}: page fill {[round(f, 2) for f in fill]}"
    code = sorted({w for t in texts for w in t.split() if CODE.search(w) and not FILE.search(w)})
    assert not code, f"{name}: code identifiers in the text layer: {code}"
    banner = [BANNER in t for t in texts]
    assert banner == [simulation] * len(texts), f"{name}: simulation banner per page {banner}"
    return texts


@pytest.mark.parametrize("name, args, simulation", COMMANDS, ids=[c[0] for c in COMMANDS])
def test_command_report_pages(inputs, name, args, simulation):
    out = inputs["tmp"] / f"{name}.pdf"
    _run(args.format(out=out, **inputs))
    _check_pages(out, f"page-{name}", simulation)


@pytest.mark.parametrize("file, simulation, certificate", DEMO, ids=[d[0] for d in DEMO])
def test_demo_pages(inputs, file, simulation, certificate):
    texts = _check_pages(_as_pdf(inputs["demo"] / file), f"page-demo-{Path(file).stem}",
                         simulation)
    if certificate:
        results = [i for i, t in enumerate(texts) if re.search(r"Parameter\s+Value", t)]
        signed = [i for i, t in enumerate(texts) if "Authorised by" in t]
        assert results and signed == [results[-1]], (
            f"{file}: results table on pages {[i + 1 for i in results]}, signature on "
            f"{[i + 1 for i in signed]}")


def test_code_pattern_finds_keys_and_spares_file_names():
    """The identifier check itself: what it must catch, and what it must let through."""
    found = [w for w in ("servo_mismatch", "uncertainty[1].clause", "u_E,MACHINE", "|B_i|)",
                         "squareness_L180_x.csv,", "/work/x_y/run.rtx", "uDEVICE", "Bᵢ", "G")
             if CODE.search(w) and not FILE.search(w)]
    assert found == ["servo_mismatch", "uncertainty[1].clause", "u_E,MACHINE", "|B_i|)"]
