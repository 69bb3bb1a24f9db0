"""``axiscal config``: where the user configuration is, what it holds, and a template to start.

The user configuration is the one place for the company letterhead, the operator, the
instruments with their calibration certificates and the uncertainty inputs that every
certificate uses (:mod:`axiscal.io.user_config`).

JSON output (``--json``): ``path`` (text), ``exists`` (bool), ``config`` (the file's tables).
"""

from __future__ import annotations

import typer

from axiscal.cli._common import note, print_json


def config(
    init: bool = typer.Option(False, "--init", help="Write a commented template at the configuration path (refused if a file is there)."),
    json_out: bool = typer.Option(False, "--json", help="Print the path and the configuration as JSON."),
) -> None:
    """Show the user configuration (company, operator, instruments, uncertainty inputs).

    Example: axiscal config --init   (then edit the file it names; AXISCAL_CONFIG overrides the path)
    """
    from axiscal.errors import InputError
    from axiscal.io._files import write_text_atomic
    from axiscal.io.user_config import TEMPLATE, config_path, load_user_config

    path = config_path()
    if init:
        if path.exists():
            raise InputError(f"{path} exists; edit it, or move it away to start from the template")
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot create {path.parent}: {exc.strerror or exc}") from None
        write_text_atomic(path, TEMPLATE)
        note(f"wrote {path}")
    cfg = load_user_config() if path.exists() else {}
    if json_out:
        print_json({"path": str(path), "exists": path.exists(), "config": cfg})
        return
    typer.echo(f"user configuration: {path}" + ("" if path.exists() else " (absent; axiscal config --init writes a template)"))
    for line in _config_lines(cfg):
        typer.echo(line)


def _config_lines(cfg: dict) -> list[str]:
    """The configuration as its file writes it: ``[table]`` then ``key = value`` lines, each
    ``[[instrument]]`` on its own (the tables printed as Python dicts were hard to read)."""
    import json

    def value(v) -> str:
        return json.dumps(v, ensure_ascii=False, default=str)

    lines: list[str] = []
    for table, body in cfg.items():
        items = body if isinstance(body, list) else [body]
        for item in items:
            lines.append(f"[[{table}]]" if isinstance(body, list) else f"[{table}]")
            if not isinstance(item, dict):
                lines.append(f"  {value(item)}")
            elif not item:
                lines.append(f"  ({_EMPTY.get(table, 'empty')})")
            else:
                lines.extend(f"  {k} = {value(v)}" for k, v in item.items())
    return lines


#: What an empty table means, said where it is shown.
_EMPTY = {"uncertainty": "none declared: the uncertainty budget assumes each input by its "
                         "documented rule, except E_VE, which U then leaves out"}


def register(app: typer.Typer) -> None:
    """Add the ``config`` command."""
    app.command("config")(config)
