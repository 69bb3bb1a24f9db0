"""After ``make docs``: every gallery example ran and drew at least one figure.

sphinx-gallery saves the figures of ``gallery/plot_NAME.py`` as
``auto_examples/images/sphx_glr_plot_NAME_001.png`` (``_002`` ...) and embeds them in
``_build/html/auto_examples/plot_NAME.html``. Exit code 1, naming the examples, if one is missing.
"""

from __future__ import annotations

import sys
from pathlib import Path


def missing_figures(docs: Path) -> list[str]:
    bad = []
    for example in sorted((docs / "gallery").glob("plot_*.py")):
        name = example.stem
        images = list((docs / "auto_examples" / "images").glob(f"sphx_glr_{name}_0*.png"))
        page = docs / "_build" / "html" / "auto_examples" / f"{name}.html"
        if not images or not page.is_file() or f"sphx_glr_{name}_0" not in page.read_text("utf-8"):
            bad.append(name)
    return bad


def main() -> int:
    docs = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent)
    examples = sorted((docs / "gallery").glob("plot_*.py"))
    bad = missing_figures(docs)
    if bad:
        print(f"gallery: no figure from {', '.join(bad)}", file=sys.stderr)
        return 1
    print(f"gallery: {len(examples)} examples, each with its figure")
    return 0


if __name__ == "__main__":
    sys.exit(main())
