"""``--encoding``: the code page of a Renishaw ``.rtl``/``.rta`` export, shared by ``iso230-2``,
``evaluate`` and ``compensate`` (the reader: :func:`axiscal.io.renishaw.decode`), and by
``simulate --data x.rtl`` (the writer: :func:`axiscal.io.renishaw.encode`)."""

from __future__ import annotations

from typing import Optional

import typer

__all__ = ["ENCODING", "WRITE_ENCODING"]

ENCODING: Optional[str] = typer.Option(
    None, "--encoding", help="Code page of a Renishaw .rtl/.rta export written by Windows "
    "software: cp1252 (read when the file is neither UTF-8 nor UTF-16 with a BOM), cp1250, "
    "cp1251, cp1253, cp1254, cp1257, cp932, cp936, utf-8 or utf-16; refused for other files "
    "and for an unknown name.")
WRITE_ENCODING: Optional[str] = typer.Option(
    None, "--encoding", help="With --data x.rtl/.rta: write the export in this code page, as "
    "Renishaw's Windows software does (cp1252, cp1250 ... or utf-8, the default); refused for "
    "other files and for an unknown name.")
