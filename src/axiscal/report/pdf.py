"""PDF from the same HTML pages as the browser reports, through WeasyPrint.

The page size (A4 or US Letter), the margins and the running "page n of N" come from the
``@page`` rules of ``templates/base.html``; this module only turns HTML into bytes and writes them
atomically. WeasyPrint (the ``report`` extra) needs Pango from the operating system; on Debian
``make setup`` installs it.
"""

from __future__ import annotations

from pathlib import Path

from axiscal.errors import InputError

__all__ = ["html_to_pdf", "write_pdf"]


def html_to_pdf(html: str) -> bytes:
    """Render an HTML page (inline SVG figures, no network) to PDF bytes.

    Raises
    ------
    InputError
        WeasyPrint or the system libraries it needs are missing (the message says what to install).
    """
    try:
        import logging

        from weasyprint import HTML
    except ImportError as exc:  # not installed
        raise InputError(
            "a PDF report needs WeasyPrint: pip install 'axiscal[report]' " f"({exc})"
        ) from None
    except OSError as exc:  # installed, but Pango/HarfBuzz missing
        raise InputError(
            "WeasyPrint cannot load the system libraries it needs (Pango): on "
            f"Debian apt-get install libpango-1.0-0 libpangoft2-1.0-0 ({exc})"
        ) from None
    logging.getLogger("weasyprint").setLevel(logging.ERROR)
    logging.getLogger("fontTools").setLevel(logging.ERROR)
    return HTML(string=html, base_url=".").write_pdf()


def write_pdf(html: str, path) -> Path:
    """Write ``html`` as a PDF file atomically; returns the path."""
    from axiscal.io._files import write_bytes_atomic

    return write_bytes_atomic(Path(path), html_to_pdf(html))
