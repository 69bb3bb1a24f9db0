"""Pages generated from the code itself when the site is built (called by conf.py):

* ``generated/cli.rst``: the command-line reference, walking the click tree of ``axiscal.cli.app``
  (every command and sub-command, its help, its arguments and options with their defaults);
* ``generated/formats.rst``: the file-format page, from :data:`axiscal.io.formats.FORMATS`;
* ``generated/json.rst``: the ``--json`` objects: the results-as-data block (schema version,
  ``quantities``) from :mod:`axiscal.standards.quantities` and each command's keys from its
  module's docstring, the text ``tests/cli/test_cli_json.py`` checks every key against;
* ``generated/uncertainty_inputs.rst``: every input of the ISO 230-2 Annex A and squareness
  budgets, from :func:`axiscal.standards.iso230_9_inputs.input_table` and
  :func:`axiscal.standards.iso230_9_geometry.squareness_input_table`.

So the site cannot say something the program does not do. Run alone:
``python docs/_generate.py`` writes the same files.
"""

from __future__ import annotations

from pathlib import Path

HERE = Path(__file__).resolve().parent
OUT = HERE / "generated"


def _title(text: str, mark: str) -> str:
    return f"{text}\n{mark * len(text)}\n\n"


def _indent(text: str, pad: str = "   ") -> str:
    return "\n".join(pad + line if line.strip() else "" for line in text.splitlines())


def _param_rows(command, ctx) -> list[tuple[str, str]]:
    rows = []
    for p in command.params:
        if getattr(p, "hidden", False):
            continue
        option = p.param_type_name == "option"     # typer vendors click: no isinstance
        name = ", ".join(p.opts + p.secondary_opts) if option else p.human_readable_name
        # a help text escapes a literal "[table]" from Rich's markup with a backslash
        help_ = (getattr(p, "help", None) or "").replace("\n", " ").replace("\\[", "[")
        default = p.default
        if option and not p.is_flag and default not in (None, (), []):
            help_ += f" [default: {default}]"
        rows.append((name, help_ or "—"))
    return rows


def _command_rst(path: str, command, ctx, level: str) -> str:
    out = _title(f"axiscal {path}", level)
    usage = command.collect_usage_pieces(ctx)
    out += f".. code-block:: text\n\n   axiscal {path} {' '.join(usage)}\n\n"
    out += _escape((command.help or "").strip()) + "\n\n"
    rows = _param_rows(command, ctx)
    if rows:
        out += ".. list-table::\n   :header-rows: 1\n   :widths: 25 75\n\n"
        out += "   * - argument or option\n     - meaning\n"
        for name, help_ in rows:
            out += f"   * - ``{name}``\n     - {_escape(help_)}\n"
        out += "\n"
    if hasattr(command, "list_commands"):        # a group: its sub-commands
        sub = command.context_class(command, parent=ctx, info_name=command.name)
        for name in command.list_commands(sub):
            out += _command_rst(f"{path} {name}", command.get_command(sub, name), sub, "~")
    return out


def _escape(text: str) -> str:
    """Text safe in reStructuredText (no role or emphasis from a stray * or `)."""
    return (text.replace("\\", "\\\\").replace("*", r"\*").replace("`", r"\`")
            .replace("|", r"\|").replace("_", r"\_"))


def cli_page() -> str:
    import typer

    from axiscal.cli import app

    root = typer.main.get_command(app)
    ctx = root.context_class(root, info_name="axiscal")
    out = _title("Command-line reference", "=")
    out += ("Generated from the program itself when the site is built (``docs/_generate.py`` "
            "walks the commands of ``axiscal.cli.app``). ``axiscal COMMAND --help`` prints the "
            "same text.\n\n")
    for name in root.list_commands(ctx):
        out += _command_rst(name, root.get_command(ctx, name), ctx, "-")
    return out


def formats_page() -> str:
    from axiscal.io.formats import FORMATS

    out = _title("File formats", "=")
    out += ("Every format axiscal reads or writes, generated from the format registry "
            "(:data:`axiscal.io.formats.FORMATS`, also printed by ``axiscal formats``). "
            ":func:`axiscal.read` tells a file's format by its content.\n\n")
    out += ".. list-table::\n   :header-rows: 1\n   :widths: 28 8 8 12 22 22\n\n"
    out += ("   * - format\n     - read\n     - write\n     - extensions\n     - example\n"
            "     - described in\n")
    for f in FORMATS:
        cells = (f.name, "yes" if f.read else "no", "yes" if f.write else "no",
                 ", ".join(f.extensions), f.example, f.described_in)
        out += "   * - " + "\n     - ".join(_escape(c) for c in cells) + "\n"
    return out + "\n" + _samples()


def _samples() -> str:
    """Each format with columns or a sample: the columns and the sample written by axiscal's
    own writer (:mod:`axiscal.io.format_samples`), first lines only."""
    from axiscal.io.format_samples import COLUMNS, sample
    from axiscal.io.formats import FORMATS

    out = _title("Columns and samples", "-")
    out += ("The samples are written by axiscal's own writer of each format, from a made-up "
            "three-target test (``axiscal.io.format_samples``).\n\n")
    for f in FORMATS:
        text, columns = sample(f.name), COLUMNS.get(f.name)
        if text is None and columns is None:
            continue
        out += _title(f.name, "~")
        if columns:
            out += columns + "\n\n"
        if text:
            lines = text.splitlines()
            shown = lines[:24] + (["..."] if len(lines) > 24 else [])
            out += ".. code-block:: text\n\n" + _indent("\n".join(shown)) + "\n\n"
    return out


def json_page() -> str:
    import importlib
    import inspect

    from axiscal.cli import COMMANDS
    from axiscal.standards import quantities

    out = _title("JSON output", "=")
    out += ("Generated from the program itself when the site is built: every command's "
            "``--json`` keys are the ones its module documents, and ``tests/cli/test_cli_json.py``"
            " fails on a key printed but not documented here.\n\n")
    out += _title(f"Results as data (schema {quantities.SCHEMA_VERSION})", "-")
    out += inspect.cleandoc(quantities.__doc__).split("\nExamples")[0] + "\n\n"
    out += ("The same block is in ``axiscal history show --json``, the workbench's "
            "``/tests/ID/result.json``, each record of a history archive and "
            ":meth:`axiscal.Evaluation.to_dict`.\n\n")
    out += _title("Each command's keys", "-")
    seen = set()
    for name, module in COMMANDS.items():
        if module in seen:
            continue
        seen.add(module)
        doc = inspect.cleandoc(importlib.import_module(module).__doc__ or "")
        if "json" not in doc.lower():
            continue
        out += _title(f"axiscal {name}", "~") + _bars(doc) + "\n\n"
    return out


def _bars(text: str) -> str:
    """A docstring's ``|`` outside literals escaped (``|b|`` is an absolute value, not a
    reStructuredText substitution)."""
    import re

    parts = re.split(r"(``.*?``)", text, flags=re.S)
    return "".join(p if p.startswith("``") else p.replace("|", r"\|") for p in parts)


def uncertainty_inputs_page() -> str:
    from axiscal.standards.iso230_9_inputs import input_table

    out = _title("Uncertainty inputs", "=")
    out += ("Every input of the uncertainty budgets (ISO 230-2:2014 Annex A; the squareness "
            "budgets of ISO/TR 230-9), generated from the "
            "code (:func:`axiscal.standards.iso230_9_inputs.input_table`, "
            ":func:`axiscal.standards.iso230_9_geometry.squareness_input_table`). Give one in the "
            "``[uncertainty]`` table of the user configuration or a job file (squareness: "
            "``[squareness_uncertainty]``; straightness: ``[straightness_uncertainty]``, "
            ":mod:`axiscal.standards.iso230_9_straightness`), with "
            "``--uncertainty NAME=VALUE``, or in the ``uncertainty=`` mapping of "
            ":func:`axiscal.evaluate`. A number is in the unit of the table, the unit the "
            "output shows beside U (α as 11.5 for 11.5 µm/(m·K)); text carries its own unit, "
            "read by pint (``\"11.5 um/(m K)\"``, ``\"20.5 degC\"``, ``\"293.15 K\"``; a "
            "temperature difference in K also takes ``\"0.1 degC\"``). A value outside the "
            "plausible range is refused with the range: it is most often a value in another "
            "unit. An input not given takes its default, shown as assumed beside U with its "
            "rule.\n\n")
    from axiscal.standards.iso230_9_geometry import squareness_input_table
    from axiscal.standards.iso230_9_straightness import straightness_input_table

    rows = input_table() + squareness_input_table() + straightness_input_table()
    titles = {"linear": "Linear axis (ISO 230-2:2014 Annex A)",
              "rotary": "Rotary axis (ISO 230-2:2014 Annex A)",
              "squareness": "Squareness (ISO/TR 230-9; the [squareness_uncertainty] table)",
              "straightness": "Straightness (ISO 230-1:2012 §8.2, ISO/TR 230-9; the "
                              "[straightness_uncertainty] table; the reading noise and the "
                              "slope fit are measured from the file)"}
    for budget, title in titles.items():
        out += _title(title, "-")
        out += ".. list-table::\n   :header-rows: 1\n   :widths: 18 20 9 9 16 28\n\n"
        out += ("   * - name\n     - what it is\n     - unit\n     - default\n"
                "     - plausible range\n     - rule of the default\n")
        for r in rows:
            if r["budget"] == budget:
                cells = (r["name"], r["label"], r["unit"] or "—", r["default"],
                         f"{r['range']} ({r['why']})" if r["why"] else r["range"],
                         r["rule"])
                out += "   * - " + "\n     - ".join(_escape(c) for c in cells) + "\n"
        out += "\n"
    return out + _motion_inputs()


def _motion_inputs() -> str:
    """The ``[motion_uncertainty]`` table of a five-motion-error test (ISO 230-7), from
    :data:`axiscal.standards.iso230_7_uncertainty.MOTION_INPUTS`."""
    from axiscal.standards.iso230_7_uncertainty import MOTION_INPUTS

    out = _title("Five-motion-error test (ISO 230-7; the [motion_uncertainty] table)", "-")
    out += ("The budget of :mod:`axiscal.standards.iso230_7_uncertainty` (read by ``motion "
            "analyze``, the history, the workbench and the certificate). Channel keys: ``dx``, "
            "``dy`` (radial), ``dz`` (axial), ``ex``, ``ey`` (tilt). With two runs or more the "
            "run-to-run scatter of each channel is measured from the file.\n\n")
    out += ".. list-table::\n   :header-rows: 1\n   :widths: 18 26 9 9 10 28\n\n"
    out += ("   * - name\n     - what it is\n     - unit\n     - default\n"
            "     - plausible range\n     - rule of the default\n")
    for name, (label, unit, default, rule) in MOTION_INPUTS.items():
        cells = (name, label, unit or "—", f"{default:g}", "> 0" if name == "k" else "≥ 0",
                 rule)
        out += "   * - " + "\n     - ".join(_escape(c) for c in cells) + "\n"
    return out + "\n"


def generate() -> None:
    OUT.mkdir(exist_ok=True)
    for name, text in (("cli.rst", cli_page()), ("formats.rst", formats_page()),
                       ("json.rst", json_page()),
                       ("uncertainty_inputs.rst", uncertainty_inputs_page())):
        p = OUT / name
        if not p.exists() or p.read_text("utf-8") != text:   # unchanged: no rebuild
            p.write_text(text, "utf-8")


if __name__ == "__main__":
    generate()
