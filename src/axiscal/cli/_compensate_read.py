"""``axiscal compensate --read FILE``: a controller file read back, compared or converted.

Thin: the library reads (``controllers.<name>.parse``, :func:`~axiscal.compensation.
controllers.siemens_840d.read_tables`, :func:`~axiscal.compensation.controllers.siemens_cec.
read_cross_axis`), converts (:func:`~axiscal.compensation.controllers.convert.convert`) and
compares (:func:`~axiscal.compensation.readback.compare`); this module chooses and renders.
"""

from __future__ import annotations

from pathlib import Path

import typer

from axiscal.cli._common import print_json

__all__ = ["read_back"]

#: Prefix of an option meant for the writer of ``--to`` (``-o to.machine_axis=AX2``).
TO = "to."


def read_back(path: Path, controller, source, opts, json_out, ini=None, to=None, out=None,
              encoding=None) -> None:
    """Read ``path`` (a table, a file of several, or a CEC file) and render, compare or convert."""
    from axiscal.cli._compensate_io import _typed
    from axiscal.io._files import read_controller_text

    text, used = read_controller_text(path)
    mod = _module(path, text, controller)
    if to is None and out is not None:
        from axiscal.errors import InputError

        raise InputError("--read writes --out only with --to NAME (the controller format to "
                         "convert the table to); give --to or drop --out")
    reader, writer = _split(mod, opts, to)
    if mod.NAME == "siemens-840d" and _cec_only(text):
        return _read_cec(path, text, used, reader, json_out, to, source, ini)
    reader = _typed(mod.parse, reader, f"--option for reading {mod.NAME}")
    reader, ini_inputs, md_text = _beside(mod, path, text, ini, reader)
    notes: list[str] = []
    stated: dict = {}
    if mod.NAME == "siemens-840d":
        table, notes, md = _siemens_table(mod, path, text, used, reader, md_text, json_out, to)
        if table is None:
            return
        if md_text and md.metric is not None:       # MD10240 of the --ini states the unit
            stated = dict(metric=md.metric, metric_source="--ini")
    else:
        table = mod.parse(text, source=str(path), **reader)
    if to is not None:
        return _convert_table(table, to, writer, out, source, json_out)
    _render_read(mod, path, text, used, table, reader, ini_inputs, notes, source, json_out,
                 stated, encoding)


def _module(path, text, controller):
    from axiscal.compensation.controllers import controller as get_controller
    from axiscal.compensation.controllers import detect
    from axiscal.errors import InputError

    found = detect(text)
    if controller is None:
        if found is None:
            raise InputError(f"{path}: the controller format cannot be told from the content; "
                             "give --controller")
        controller = found
    elif found is not None and found != get_controller(controller).NAME:
        raise InputError(f"{path} looks like a {found} file, not {controller}: drop "
                         f"--controller or give --controller {found}")
    return get_controller(controller)


def _split(mod, opts: dict, to) -> tuple[dict, dict]:
    """Options for the reader and, with ``--to``, for the writer: ``to.KEY=…`` goes to the
    writer; another option goes to the reader if it takes it, else to the writer."""
    import inspect

    from axiscal.compensation.controllers import controller as get_controller
    from axiscal.errors import InputError

    reader, writer = {}, {}
    takes = inspect.signature(mod.parse).parameters
    for k, v in opts.items():
        if k.startswith(TO):
            if to is None:
                raise InputError(f"--option {k}=…: options for the writer need --to NAME")
            writer[k[len(TO):]] = v
        elif k in takes or to is None:
            reader[k] = v
        else:
            writer[k] = v
    if to is not None:
        from axiscal.cli._compensate_io import _typed

        w = get_controller(to)
        writer = _typed(w.write, writer, f"--option for writing {w.NAME} (to.KEY=… for the "
                                         "writer)")
    return reader, writer


def _cec_only(text: str) -> bool:
    import re

    # a builder's loader writes `$AN_CEC [0,0] = …` with a blank before the bracket
    return re.search(r"\$AN_CEC\s*\[", text, re.IGNORECASE) is not None and \
        re.search(r"\$AA_ENC_COMP\s*\[", text, re.IGNORECASE) is None


def _beside(mod, path, text, ini, opts) -> tuple[dict, tuple, str]:
    """LinuxCNC: unit, type and joint kind from the INI naming the file. 840D: the machine data
    (``INITIAL.INI``) given with ``--ini``, as text."""
    from axiscal.errors import InputError

    if mod.NAME == "siemens-840d":
        if ini is None:
            return opts, (), ""
        from axiscal.io._files import read_controller_text

        return opts, (), read_controller_text(ini)[0]
    if mod.NAME != "linuxcnc":
        if ini is not None:
            raise InputError(f"--ini is read with a LinuxCNC compensation file (its INI) or a "
                             f"SINUMERIK table (its INITIAL.INI); {path} is a {mod.NAME} file: "
                             "drop --ini")
        return opts, (), ""
    from axiscal.compensation.controllers.linuxcnc_ini import read_options
    from axiscal.io.linuxcnc_ini import find_comp_settings

    o, inputs = read_options(find_comp_settings(path, ini), opts, text, str(path))
    return o, inputs, ""


def _siemens_table(mod, path, text, encoding, opts, md_text, json_out, to):
    """The one table asked for (or the only one) with its notes; several without a choice are
    listed, each read or refused on its own (returns None then)."""
    from axiscal.errors import InputError

    choose = {k: opts.pop(k) for k in ("machine_axis", "measuring_system") if k in opts}
    r = mod.read_tables(text, str(path), machine_data=md_text, machine_data_source="--ini",
                        **{k: v for k, v in opts.items() if k in ("axis_kind", "correction_unit",
                                                                   "unit")})
    keys = list(r.tables) + list(r.refused)
    if not choose and len(keys) > 1:
        if to is not None:
            raise InputError(f"{path} holds {len(keys)} tables ({', '.join(map(r.key, keys))}): "
                             "convert one, chosen with -o machine_axis=… (-o measuring_system=2)")
        _render_tables(mod, path, encoding, r, json_out)
        return None, [], r.md
    table = mod.parse(text, str(path), machine_data=md_text, **opts, **choose)
    name = r.key((table.origin.machine_axis, table.origin.measuring_system))
    mine = (f"{name}:", f"assumed: {name} ", "line ", "unit ")
    notes = [n for n in r.notes if n.startswith(mine)]
    return table, notes, r.md


def _render_tables(mod, path, encoding, r, json_out) -> None:
    """Every table of a multi-table file, a refused one with its reason (exit 2 if any)."""
    from axiscal.cli._compensate_io import _table_json
    from axiscal.errors import DataFormatError

    if json_out:
        print_json(dict(controller=mod.NAME, encoding=encoding,
                        tables=[dict(key=r.key(k), machine_axis=k[0], measuring_system=k[1],
                                     **_table_json(t)) for k, t in r.tables.items()],
                        refused=[dict(key=r.key(k), reason=v) for k, v in r.refused.items()],
                        notes=list(r.notes)))
    else:
        typer.echo(f"{mod.NAME} file ({encoding}): {len(r.tables) + len(r.refused)} tables "
                   "(choose one with -o machine_axis=…, -o measuring_system=2)")
        for k, t in r.tables.items():
            typer.echo(f"  {r.key(k):<7} {t}")
        for v in r.refused.values():
            typer.echo(f"  refused: {v}")
        for n in r.notes:
            typer.echo(f"  note: {n}")
    if r.refused:
        rest = "; the others were read" if r.tables else ""
        raise DataFormatError(f"{len(r.refused)} of {len(r.tables) + len(r.refused)} tables "
                              f"refused (listed above){rest}", str(path))


def _read_cec(path, text, encoding, opts, json_out, to, source, ini=None) -> None:
    """The cross-axis tables of an NC_CEC.INI, each with its input and output axis (a rotary
    axis in degrees with the INITIAL.INI given as ``--ini``)."""
    from axiscal.compensation.controllers.siemens_cec import in_error, loader_notes, read_cross_axis
    from axiscal.errors import DataFormatError, InputError
    from axiscal.io._files import read_controller_text

    if to is not None or source is not None or opts:
        raise InputError(f"{path} holds cross-axis (CEC) tables: they are listed; --to, a data "
                         "file to compare with and --option are for EEC tables")
    md = read_controller_text(ini)[0] if ini is not None else ""
    tables, refused = read_cross_axis(text, str(path), machine_data=md)
    notes = loader_notes(text, str(path))
    if json_out:
        print_json(dict(controller="siemens-840d", encoding=encoding, kind="cross-axis (CEC)",
                        tables=[c.to_dict() for c in tables],
                        refused=[dict(index=i, reason=v) for i, v in in_error(refused).items()],
                        not_in_use=[dict(index=i, reason=v) for i, v in refused.items()
                                    if i not in in_error(refused)], notes=list(notes)))
    else:
        typer.echo(f"siemens-840d cross-axis (CEC) file ({encoding}): "
                   f"{len(tables) + len(refused)} tables")
        for c in tables:
            typer.echo(f"  {c}")
            for n in c.notes:
                typer.echo(f"    note: {n}")
        for i, v in refused.items():
            typer.echo(f"  {'refused' if i in in_error(refused) else 'reserved'}: {v}")
        for n in notes:
            typer.echo(f"  note: {n}")
    if in_error(refused):
        raise DataFormatError(f"{len(in_error(refused))} CEC table(s) refused (listed above); "
                              "the others were read", str(path))


def _convert_table(table, to, writer, out, source, json_out) -> None:
    """--read FILE --to NAME: the table read, written for the same axis in another format."""
    from axiscal.cli._compensate_io import _render_table, _write_files
    from axiscal.compensation.controllers.convert import convert
    from axiscal.errors import InputError

    if source is not None:
        raise InputError("--read converts with --to NAME [--out FILE] or compares with SOURCE; "
                         "give one of them")
    cf = convert(table, to, **writer)
    cf = _write_files(cf, out)
    _render_table(cf, out, json_out)


def _render_read(mod, path, text, encoding, table, opts, ini_inputs, notes, source,
                 json_out, stated=None, source_encoding=None) -> None:
    import numpy as np

    from axiscal.cli._compensate_io import _table_json
    from axiscal.compensation.readback import compare
    from axiscal.io.results import load_mean_deviations

    inputs = ini_inputs + _file_inputs(mod, text, path, source, {**opts, **(stated or {})})
    jumps = mod.trim_jumps(table) if hasattr(mod, "trim_jumps") else ()
    d = dict(controller=mod.NAME, encoding=encoding, **_table_json(table),
             inputs=[i.to_dict() for i in inputs], trim_jumps=[j.to_dict() for j in jumps],
             notes=list(notes))
    rb = None
    if source is not None:
        res, _ = load_mean_deviations(source, encoding=source_encoding)
        _same_units(res, table, source)
        dev = 0.5 * (res.mean_up + np.where(np.isfinite(res.mean_down), res.mean_down, res.mean_up))
        rb = compare(table, res.targets, dev, mod.NAME)
        d.update(residual=list(rb.rows), largest_residual=rb.largest_residual,
                 shift_undone=rb.shift, comparison_note=rb.note)
    if json_out:
        print_json(d)
        return
    typer.echo(f"{mod.NAME} file ({encoding}): {table}")
    for i in inputs:
        typer.echo(f"  {i}")
    for n in notes:
        typer.echo(f"  note: {n}")
    for j in jumps:
        typer.echo(f"  warning: {j.describe(table, opts.get('unit'))}")
    if rb is not None:
        u = table.correction_unit
        typer.echo(f"compared with {source} (mean bidirectional deviation + correction):")
        if rb.note:
            typer.echo(f"  {rb.note}")
        for r in rb.rows:
            typer.echo(f"  {r['target']:>10.4g} {table.position_unit}: deviation {r['deviation']:+8.3f}, "
                       f"correction {r['correction']:+8.3f}, residual {r['residual']:+8.3f} {u}")
        typer.echo(f"largest residual {rb.largest_residual:.3f} {u}")


def _file_inputs(mod, text, path, source, opts) -> tuple:
    """What the parser took from the file, was given, or assumed (``mod.inputs``, where the
    format leaves numbers out); a comparison resting on an assumed position is refused."""
    from axiscal.errors import InputError

    keep = {k: v for k, v in opts.items() if k not in ("machine_data",)}
    inputs = mod.inputs(text, source=str(path), **keep) if hasattr(mod, "inputs") else ()
    for i in inputs:
        if source is not None and i.assumed and i.needed_to_compare:
            raise InputError(f"{path}: {i.why}: give -o {i.name}=… ({i.unit}) to compare it "
                             f"with {source}")
    return tuple(inputs)


def _same_units(res, table, source) -> None:
    """A table is compared only with data in its own units (mm/µm against deg/arcsec is nonsense)."""
    from axiscal import units
    from axiscal.errors import InputError

    data = (units.canonical(res.target_unit), units.canonical(res.deviation_unit))
    own = (units.canonical(table.position_unit), units.canonical(table.correction_unit))
    if data != own:
        raise InputError(f"{source} is in {data[0]} and {data[1]}, the table in {own[0]} and "
                         f"{own[1]}; compare a table with data of the same axis (a rotary table "
                         "is read with -o axis_kind=rotary)")
