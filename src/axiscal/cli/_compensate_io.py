"""What ``axiscal compensate``'s uses share: typed ``--option`` values, the files written and
the table rendered (terminal and ``--json``)."""

from __future__ import annotations

from pathlib import Path

import typer

from axiscal.cli._common import note, print_json

__all__ = ["_typed", "_value", "_table_json", "_render_table", "_write_files"]


def _check_out(cf, out) -> None:
    """The controller file's name must suit the format (and what its companion files name)."""
    from axiscal.errors import InputError

    p, own = Path(out), Path(cf.filename)
    if any(cf.filename in text for text in cf.extra_files.values()):
        if p.name.upper() != own.name.upper():
            raise InputError(f"{cf.controller}: {', '.join(sorted(cf.extra_files))} names the "
                             f"table {cf.filename}; write it as --out {p.parent / own.name}")
        return
    allowed = {own.suffix.lower()} | ({".txt"} if cf.controller != "csv" else set())
    if p.suffix.lower() not in allowed:
        raise InputError(f"{cf.controller} table {p.name}: use a {' or '.join(sorted(allowed))} "
                         "extension")


def _typed(function, raw: dict[str, str], what: str, exclude: tuple[str, ...] = ()) -> dict:
    """Options ``function`` takes, converted to the type of its default (named on error).

    ``detection_unit=abc`` or ``zero_ends=maybe`` would otherwise reach the writer as text and fail
    there with a traceback; ``machine_axis=01`` stays the text ``01``.
    """
    import inspect

    from axiscal.compensation.controllers import check_options
    from axiscal.errors import InputError

    check_options(function, raw, what)
    fixed = sorted(set(raw) & set(exclude))
    if fixed:
        raise InputError(f"{what}: {', '.join(fixed)} is set by the command, not by --option")
    params = inspect.signature(function).parameters
    return {k: _convert(k, v, _like(params[k]), what) for k, v in raw.items()}


def _like(param):
    """A value of the type ``param`` takes: its default, or for a default of None the type its
    annotation names (``machine_axis: str | None = None``: text, so ``01`` stays ``01``)."""
    if param.default is not None:
        return param.default
    note = str(param.annotation)
    for name, example in (("bool", False), ("int", 0), ("float", 0.0), ("str", "")):
        if name in note.replace("None", ""):
            return example
    return None


def _convert(key: str, text: str, default, what: str):
    import math

    from axiscal.errors import InputError

    if isinstance(default, bool):
        if text.lower() not in ("true", "false"):
            raise InputError(f"{what}: {key}={text!r} must be true or false")
        return text.lower() == "true"
    if isinstance(default, (int, float)):
        try:
            value = int(text) if isinstance(default, int) else float(text)
        except ValueError:
            kind = "a whole number" if isinstance(default, int) else "a number"
            raise InputError(f"{what}: {key}={text!r} must be {kind}") from None
        if not math.isfinite(value):
            raise InputError(f"{what}: {key}={text!r} must be a finite number")
        return value
    if isinstance(default, str):
        return text
    return _value(text)


def _value(v: str):
    low = v.lower()
    if low in ("true", "false"):
        return low == "true"
    for cast in (int, float):
        try:
            return cast(v)
        except ValueError:
            pass
    return v


def _write_files(cf, out):
    """Write ``cf`` to ``out`` (and its companions beside it); the file as written, its enabling
    steps naming ``out``'s name (``COMP_FILE = …``)."""
    if out is None:
        return cf
    from axiscal.io._files import write_text_atomic

    _check_out(cf, out)
    write_text_atomic(out, cf.text)
    note(f"wrote {cf.controller} table {out}")
    for name, text in cf.extra_files.items():
        p = Path(out).parent / name
        write_text_atomic(p, text)
        note(f"wrote {p}")
    return cf.written_as(Path(out).name)


def _table_json(t) -> dict:
    return dict(n_points=t.n_points, spacing=t.spacing, start=t.start, end=t.end,
                position_unit=t.position_unit, correction_unit=t.correction_unit,
                reference_index=t.reference_index, reference_position=t.reference_position,
                largest_correction=t.largest, backlash=t.backlash, bidirectional=t.bidirectional,
                modulo=t.modulo, equidistant=t.equidistant, table=t.to_dict())


def _render_table(cf, out, json_out) -> None:
    t = cf.table
    if json_out:
        d = dict(controller=cf.controller, file=None if out is None else str(out),
                 extra_files=sorted(cf.extra_files), enable=list(cf.enable), notes=list(cf.notes))
        d.update(_table_json(t))
        print_json(d)
        return
    for line in cf.summary():          # the lines the workbench shows too
        typer.echo(line)
    if out is None:
        typer.echo("")
        typer.echo(cf.text.rstrip("\n"))
