"""Helpers of the PDF tests: text layer (pypdf), page images (pdftoppm) and how full a page is.

Every rendered page is kept as a PNG in ``build/test-artefacts/`` (or ``$AXISCAL_ARTEFACTS``) so a
person can look at what a customer receives.
"""

import os
import subprocess
from pathlib import Path

import numpy as np

ARTEFACTS = Path(
    os.environ.get(
        "AXISCAL_ARTEFACTS", Path(__file__).resolve().parents[2] / "build" / "test-artefacts"
    )
)
MM = 72 / 25.4  # points per millimetre


def pdf_text(path) -> list[str]:
    """The text layer of each page."""
    from pypdf import PdfReader

    return [p.extract_text() for p in PdfReader(str(path)).pages]


def page_sizes_mm(path) -> list[tuple[float, float]]:
    from pypdf import PdfReader

    return [
        (float(p.mediabox.width) / MM, float(p.mediabox.height) / MM)
        for p in PdfReader(str(path)).pages
    ]


def render_pages(path, name: str, dpi: int = 60) -> list[Path]:
    """Render every page with pdftoppm into the artefact folder; returns the PNG paths."""
    ARTEFACTS.mkdir(parents=True, exist_ok=True)
    prefix = ARTEFACTS / name
    for old in ARTEFACTS.glob(f"{name}-*.png"):
        old.unlink()
    subprocess.run(["pdftoppm", "-png", "-r", str(dpi), str(path), str(prefix)], check=True)
    return sorted(ARTEFACTS.glob(f"{name}-*.png"), key=lambda p: int(p.stem.rsplit("-", 1)[1]))


def used_fraction(png: Path, top_mm: float = 16.0, bottom_mm: float = 15.0, dpi: int = 60) -> float:
    """Fraction of the page's body (between the running header and footer margins) that holds
    content: from the body's top to the lowest non-white pixel row."""
    from PIL import Image

    img = np.asarray(Image.open(png).convert("L"), dtype=float)
    px = dpi / 25.4
    body = img[int(top_mm * px) : img.shape[0] - int(bottom_mm * px)]
    rows = np.nonzero((body < 200).any(axis=1))[0]
    return 0.0 if rows.size == 0 else float(rows[-1] + 1) / body.shape[0]
