"""The ``axiscal`` command line: a thin layer over the library.

Each command group lives in its own module with a ``register(app)`` function. A command parses its
options, calls one library function and renders; heavy imports (matplotlib, scipy, rich tables)
happen inside the command body so ``axiscal ... --json`` starts fast.

Every :class:`axiscal.errors.AxiscalError` becomes one line on stderr, ``axiscal: error: ...``,
and exit code 2; no traceback for a user's mistake.
"""

from __future__ import annotations

import sys

import typer

from axiscal import __version__
from axiscal.errors import AxiscalError

__all__ = ["app", "main"]

EXIT_USER_ERROR = 2


class AxiscalGroup(typer.core.TyperGroup):
    """Top-level group that turns library errors into one clean line and exit code 2."""

    def invoke(self, ctx):  # noqa: D401 - click API
        try:
            return super().invoke(ctx)
        except AxiscalError as exc:
            typer.echo(f"axiscal: error: {exc}", err=True)
            raise typer.Exit(EXIT_USER_ERROR) from None
        except KeyboardInterrupt:  # pragma: no cover - interactive only
            typer.echo("axiscal: interrupted; nothing was written", err=True)
            raise typer.Exit(130) from None


app = typer.Typer(
    cls=AxiscalGroup,
    name="axiscal",
    help="Calibrate machine-tool and turntable axes: evaluate by ISO 230, simulate instruments, "
    "write reports and compensation tables.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"axiscal {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Calibrate machine-tool and turntable axes."""


def _register_all() -> None:
    # One line per command module; each module imports only typer at import time.
    from axiscal.cli import air, iso230_2, scale

    for module in (iso230_2, air, scale):
        module.register(app)


_register_all()


def main() -> None:
    """Console-script entry point."""
    app(prog_name="axiscal")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
