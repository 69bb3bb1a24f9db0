"""Render HTML reports to PNG with headless Chromium, so a person can look at them.

Usage: ``python tools/screenshot.py FOLDER_OR_FILE [...]`` writes ``<name>.png`` beside each
``.html``. Used by ``make shots``; needs Debian's ``chromium`` (the Makefile installs it).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--hide-scrollbars"]


def shoot(html: Path, width: int = 1200, height: int = 2400) -> Path:
    """Screenshot one page; returns the PNG path."""
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        raise SystemExit("tools/screenshot.py: chromium is not installed (make shots installs it)")
    png = html.parent / (html.stem + ".page.png")
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run([exe, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}",
                        f"--screenshot={png}", html.resolve().as_uri()],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=120)
    return png


def main(args: list[str]) -> int:
    pages = []
    for a in args or ["demo-output"]:
        p = Path(a)
        pages.extend(sorted(p.glob("*.html")) if p.is_dir() else [p])
    for page in pages:
        print(f"wrote {shoot(page)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
