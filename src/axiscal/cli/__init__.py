"""The ``axiscal`` command line: a thin layer over the library.

Each command group lives in its own module with a ``register(app)`` function. A command parses its
options, calls one library function and renders; heavy imports (matplotlib, scipy, rich tables)
happen inside the command body so ``axiscal ... --json`` starts fast.

Every :class:`axiscal.errors.AxiscalError` becomes one line on stderr, ``axiscal: error: ...``,
and exit code 2; no traceback for a user's mistake. A mistake on the command line itself (an
unknown command or option, a missing argument, ``--length abc``) is reported the same way, with
the command's ``--help`` to look at, instead of click's usage panel. Every number option must be
finite: ``nan`` and ``inf`` are refused where the command line is parsed.
"""

from __future__ import annotations

import gc
import sys

import typer

from axiscal import __version__
from typer._click.exceptions import NoArgsIsHelpError, UsageError  # typer 0.28 vendors click
from typer._click.types import FloatParamType, FloatRange

from axiscal.errors import AxiscalError, one_line

__all__ = ["app", "main"]

EXIT_USER_ERROR = 2


#: Command name -> module that registers it. Modules are imported only when their command runs
#: (or when help lists them), so start-up cost does not grow with the number of commands.
COMMANDS: dict[str, str] = {
    "iso230-2": "axiscal.cli.iso230_2",
    "evaluate": "axiscal.cli.evaluate",
    "plan": "axiscal.cli.plan",
    "simulate": "axiscal.cli.simulate",
    "demo": "axiscal.cli.demo",
    "motion": "axiscal.cli.motion",
    "straightness": "axiscal.cli.squareness",
    "squareness": "axiscal.cli.squareness",
    "compensate": "axiscal.cli.compensate",
    "rotary": "axiscal.cli.rotary",
    "air": "axiscal.cli.air",
    "scale": "axiscal.cli.scale",
    "compensate-environment": "axiscal.cli.measured",
    "capture": "axiscal.cli.measured",
    "formats": "axiscal.cli.measured",
    "serve": "axiscal.cli.serve",
    "history": "axiscal.cli.history",
    "certificate": "axiscal.cli.certificate",
    "volumetric": "axiscal.cli.volumetric",
    "config": "axiscal.cli.config",
    "ballbar": "axiscal.cli.ballbar",
    "calibrate": "axiscal.cli.calibrate",
    "thermal": "axiscal.cli.thermal",
    "fiveaxis": "axiscal.cli.fiveaxis",
}

#: Command name -> the first paragraph of its help, as ``axiscal --help`` lists it: the list is
#: drawn from here, without importing the command modules (tests/cli/test_cli_startup.py
#: checks each entry against its command's own help).
SUMMARIES: dict[str, str] = {
    "iso230-2":
        "Evaluate a positioning test by ISO 230-2:2014: A, E, M, R, B, their U and verdicts.",
    "evaluate": "Evaluate a positioning test by a named standard, or by all of them side by side.",
    "plan": "Make test plans (ISO 230-2, 230-4 circular, squareness lines) and their part programs.",
    "simulate": "Simulate an ISO 230-2 positioning test of a configured axis and evaluate it.",
    "demo":
        "Run the demonstration: linear and rotary positioning tests and a full rotary "
        "calibration, simulated, evaluated and reported.",
    "motion":
        "Five motion errors of a rotary axis at once (Optics Express 2018, Five-DOF motion "
        "errors of a rotary axis) and ISO 230-7 error motion evaluation.",
    "straightness":
        "Straightness deviation and slope of one trajectory (ISO 230-1 reference lines).",
    "squareness":
        "Squareness between two linear axes by ISO 230-1, -4 and -6; every result gives the "
        "sign of Chapman, Calibration of machine squareness (positive when the angle exceeds "
        "90°) and the ISO 230-1 datum/referred-axis sign.",
    "compensate":
        "Write compensation tables for CNC controllers, read them back, or verify them by "
        "re-measuring.",
    "rotary":
        "Rotary-axis calibration with an angular interferometer and a counter-rotating "
        "reference calibrator (Renishaw, Interferometric calibration of rotary axes).",
    "air": "Refractive index of air, wavelength in air and compensation factor (Ciddor, Edlén).",
    "scale":
        "Laser scale with an environmental compensator: referencing, gantry homing, "
        "compensation factor (Renishaw, Laser scale axis referencing).",
    "compensate-environment":
        "Compensate raw laser readings for the air (Ciddor) and refer the axis to 20 °C "
        "(ISO 1).",
    "capture":
        "Take a positioning test from a continuous record with no trigger: stops found, "
        "matched.",
    "formats": "Every file format axiscal reads and writes, with an example file each.",
    "serve": "Serve the web workbench: machines, history, upload, compare, trend, tables, plans.",
    "history":
        "Calibration history: every machine, axis, test, result and table kept, compared and "
        "trended (SQLite by default, PostgreSQL with --db).",
    "certificate":
        "The certificate register: numbers, issued documents and amendments "
        "(ISO/IEC 17025:2017 §7.8.8) kept in the calibration history.",
    "volumetric":
        "Volumetric accuracy of a three-axis machine: the 21 geometric errors (ISO 230-1) "
        "mapped by the rigid-body model (ISO/TR 16907), compensated by tables, verified on the "
        "body diagonals (ISO 230-6). Format: README, 'Volumetric configuration'.",
    "calibrate": "Calibrate an axis on LinuxCNC in one run: test, compensate, test again, store both.",
    "config": "Show the user configuration (company, operator, instruments, uncertainty inputs).",
    "ballbar":
        "Ballbar (circular test) diagnosis after ISO 230-4:2005 and Renishaw, Calibration of "
        "machine squareness, Method 4: every separable machine error, ranked, with advice.",
    "thermal":
        "Thermal effects by ISO 230-3:2020: ETVE, spindle, linear-axis and rotary-table tests "
        "planned, simulated on a thermal twin and evaluated; a thermal model; SINUMERIK and "
        "LinuxCNC temperature compensation.",
    "fiveaxis":
        "Five-axis machines: the location errors of both rotary axes (ISO 230-1, ISO 230-7) "
        "identified from probed spheres and R-tests, with their uncertainty.",
}

#: ``ctx.meta`` key set while the root's help is drawn (commands listed, not loaded).
_LISTING = "axiscal.listing"


class AxiscalGroup(typer.core.TyperGroup):
    """Top-level group: lazy command modules, and library errors as one line with exit code 2."""

    def list_commands(self, ctx):  # noqa: D401 - click API
        return sorted(set(super().list_commands(ctx)) | set(COMMANDS))

    def get_command(self, ctx, name):  # noqa: D401 - click API
        if name in COMMANDS:
            if ctx is not None and ctx.meta.get(_LISTING) and name in SUMMARIES:
                return typer.core.TyperCommand(name, help=SUMMARIES[name])   # listed only
            return _load_command(name)
        return super().get_command(ctx, name)

    def format_help(self, ctx, formatter):  # noqa: D401 - click API
        """The root's help lists every command from :data:`SUMMARIES`, importing none."""
        ctx.meta[_LISTING] = True
        try:
            return super().format_help(ctx, formatter)
        finally:
            del ctx.meta[_LISTING]

    def parse_args(self, ctx, args):  # noqa: D401 - click API
        for arg in args:
            _text_argument(arg)
        try:
            return super().parse_args(ctx, args)
        except UsageError as exc:
            _usage_error(exc)

    def invoke(self, ctx):  # noqa: D401 - click API
        import warnings

        schema = sys.modules.get("axiscal._schema")   # imported only by commands that read TOML
        if schema is not None:
            schema.forget_documents()   # a document an earlier command of this process read
        try:
            with warnings.catch_warnings():
                # a numpy overflow or invalid value means an absurd input got past a check:
                # stop with one line instead of printing warning text and a nonsense result
                warnings.simplefilter("error", RuntimeWarning)
                return super().invoke(ctx)
        except RuntimeWarning as exc:
            typer.echo(one_line(f"axiscal: error: a value is too large to compute with ({exc}); "
                                "check the input for a number of absurd magnitude"), err=True)
            raise typer.Exit(EXIT_USER_ERROR) from None
        except MemoryError:
            typer.echo("axiscal: error: out of memory; a count, duration or size in the input is "
                       "far larger than a calibration needs", err=True)
            raise typer.Exit(EXIT_USER_ERROR) from None
        except AxiscalError as exc:
            typer.echo(one_line(f"axiscal: error: {_with_source(exc)}"), err=True)
            raise typer.Exit(EXIT_USER_ERROR) from None
        except UsageError as exc:
            _usage_error(exc)
        except KeyboardInterrupt as exc:
            from axiscal.io._files import WRITTEN

            done = (f"wrote before it: {', '.join(WRITTEN[:5])}"
                    + (f" and {len(WRITTEN) - 5} more" if len(WRITTEN) > 5 else "")
                    if WRITTEN else "no file was written")
            typer.echo(one_line(f"axiscal: {getattr(exc, 'what', 'interrupted')}; {done}; "
                                "temporary files removed"), err=True)
            raise typer.Exit(getattr(exc, "code", 130)) from None
        except BrokenPipeError:   # `axiscal ... | head -1`: quiet, as Unix tools are
            _quiet_stdout()
            raise typer.Exit(EXIT_BROKEN_PIPE) from None
        except OSError as exc:
            if getattr(sys.stdout, "failed", None) is not exc:
                raise
            _stdout_error(exc)


#: Exit codes of the output stream itself: standard output closed, full or failing
#: (sysexits.h EX_IOERR), and a reader that went away (128 + SIGPIPE, what a shell reports for a
#: tool SIGPIPE ended: ``axiscal ... | head -1``). Exit 1 means "tolerance not met".
EXIT_STREAM = 74
EXIT_BROKEN_PIPE = 141


def _quiet_stdout() -> None:
    """Point standard output at /dev/null so the interpreter's last flush finds no broken pipe
    (Python documentation, "signal": Note on SIGPIPE)."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, AttributeError, ValueError):
        pass


def _watch_stdout() -> None:
    """Replace ``sys.stdout`` by a :class:`_WatchedStdout` on the same buffer, so that an error
    of standard output itself (``> /dev/full``) is told from any other OSError."""
    import io

    old = sys.stdout
    if type(old) is not io.TextIOWrapper:
        return
    try:
        kw = dict(encoding=old.encoding, errors=old.errors, line_buffering=old.line_buffering)
        old.flush()
        buffer = old.detach()
    except (OSError, ValueError):
        return
    sys.stdout = _watched()(buffer, **kw)


def _watched():
    import io

    class _WatchedStdout(io.TextIOWrapper):
        """Standard output that keeps the OSError its last write or flush raised."""

        failed = None

        def write(self, text):
            try:
                return super().write(text)
            except OSError as exc:
                self.failed = exc
                raise

        def flush(self):
            try:
                return super().flush()
            except OSError as exc:
                self.failed = exc
                raise

    return _WatchedStdout


def _stdout_error(exc: OSError):
    """One line on stderr for an output stream that cannot be written, and its exit code."""
    from axiscal.io._files import os_reason

    _quiet_stdout()
    typer.echo(f"axiscal: error: cannot write to standard output: {os_reason(exc)}", err=True)
    raise typer.Exit(EXIT_STREAM)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the process is so that ``finally`` blocks remove temporary files
    (a partial archive, a ``.creating`` database) as they do on Ctrl-C."""

    code = 143
    what = "terminated (SIGTERM)"


def _on_sigterm(signum, frame):   # noqa: ARG001 - signal API
    raise Terminated()


def _prepare_process() -> None:
    """What the console-script entry sets up before a command runs (issue 39).

    * SIGTERM raises :class:`Terminated` (temporary files removed, what was written said);
      SIGXFSZ is ignored, so a write beyond ``ulimit -f`` fails with EFBIG and is named
      instead of killing the process;
    * a closed standard output is refused at once (exit 74, one line on stderr);
    * a console that cannot encode µ, ° or ″ gets ASCII spellings (``u``, ``deg``, ``"``);
    * an absurd ``COLUMNS`` (0, negative, not a number, 10,000,000) is clamped;
    * matplotlib's cache goes to a private temporary folder when HOME cannot be written.
    """
    import os
    import signal

    signal.signal(signal.SIGTERM, _on_sigterm)
    if hasattr(signal, "SIGXFSZ"):
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    if sys.stdout is None or not _fd_open(1):
        if sys.stderr is not None:
            sys.stderr.write("axiscal: error: standard output is closed; redirect it to a "
                             "file or to /dev/null\n")
        raise SystemExit(EXIT_STREAM)
    _watch_stdout()
    for stream in (sys.stdout, sys.stderr):
        _ascii_fallback(stream)
    clamp_columns(os.environ)
    _writable_caches(os.environ)


def _fd_open(fd: int) -> bool:
    import os

    try:
        os.fstat(fd)
    except OSError:
        return False
    return True


#: ASCII spellings of the characters axiscal prints, for a console that cannot show them.
ASCII_SPELLINGS = {"µ": "u", "°": "deg", "″": '"', "′": "'", "±": "+/-", "−": "-", "…": "...",
                   "≤": "<=", "≥": ">=", "×": "x", "→": "->", "←": "<-", "²": "^2", "³": "^3",
                   "√": "sqrt", "—": "-", "–": "-", "·": ".", "Δ": "D", "σ": "s", "θ": "theta",
                   "’": "'", "“": '"', "”": '"', "✓": "ok", "✗": "x"}


def _ascii_errors(exc):
    """Codec error handler: the ASCII spelling of each character the console cannot encode."""
    text = exc.object[exc.start:exc.end]
    return "".join(ASCII_SPELLINGS.get(c, "?") for c in text), exc.end


def _ascii_fallback(stream) -> None:
    """Let ``stream`` print every character, spelled in ASCII where its encoding has none.

    An ASCII stream is re-wrapped in the codec ``axiscal_ascii`` (ASCII with the spellings):
    click takes a stream that says ``ascii`` for a misconfigured locale and writes UTF-8 to it
    regardless, which an ASCII console shows as garbage.
    """
    import codecs

    if stream is None:
        return
    try:
        "µ°″—…".encode(stream.encoding or "ascii")
        return
    except (UnicodeEncodeError, LookupError):
        pass
    codecs.register_error("axiscal-ascii", _ascii_errors)
    codecs.register(_ascii_codec)
    try:
        if codecs.lookup(stream.encoding or "ascii").name == "ascii":
            stream.reconfigure(encoding="axiscal_ascii", errors="axiscal-ascii")
        else:
            stream.reconfigure(errors="axiscal-ascii")
    except (AttributeError, ValueError, OSError, LookupError):
        pass


def _ascii_codec(name: str):
    """The codec ``axiscal_ascii``: ASCII, unencodable characters spelled (ASCII_SPELLINGS)."""
    import codecs

    if name != "axiscal_ascii":
        return None

    def encode(text, errors="axiscal-ascii"):
        return codecs.ascii_encode(text, "axiscal-ascii")

    class Encoder(codecs.IncrementalEncoder):
        def encode(self, text, final=False):
            return codecs.ascii_encode(text, "axiscal-ascii")[0]

    class Decoder(codecs.IncrementalDecoder):
        def decode(self, data, final=False):
            return codecs.ascii_decode(data, self.errors)[0]

    return codecs.CodecInfo(encode, codecs.ascii_decode, name="axiscal_ascii",
                            incrementalencoder=Encoder, incrementaldecoder=Decoder)


#: The widest and narrowest console a table or help text is drawn for, characters.
WIDEST, NARROWEST = 1000, 20


def clamp_columns(env) -> None:
    """``COLUMNS`` within :data:`NARROWEST` … :data:`WIDEST`; removed when it is not a
    positive number (0 printed nothing; 10,000,000 made ``--help`` take 68 s)."""
    text = env.get("COLUMNS")
    if text is None:
        return
    try:
        n = int(text.strip())
    except ValueError:
        n = 0
    if n <= 0:
        del env["COLUMNS"]
    else:
        env["COLUMNS"] = str(min(max(n, NARROWEST), WIDEST))


def _writable_caches(env) -> None:
    """MPLCONFIGDIR in a private temporary folder when HOME cannot be written (matplotlib
    warned on every --plot, and wrote under /nonexistent)."""
    import os
    import tempfile

    if env.get("MPLCONFIGDIR"):
        return
    home = env.get("HOME") or os.path.expanduser("~")
    if home and os.path.isdir(home) and os.access(home, os.W_OK):
        return
    try:
        path = os.path.join(tempfile.gettempdir(), f"axiscal-mpl-{os.getuid()}")
        os.makedirs(path, mode=0o700, exist_ok=True)
        if os.stat(path).st_uid != os.getuid():
            path = tempfile.mkdtemp(prefix="axiscal-mpl-")
    except OSError:
        return
    env["MPLCONFIGDIR"] = path


def _with_source(exc: AxiscalError) -> str:
    """The message, with the configuration file named when a reader raised it from the table
    alone (``[compensation] needs spacing``) and the command read exactly one such file.

    The caller shows it through :func:`axiscal.errors.one_line`, the one place a message is cut
    to an excerpt of the input it quotes."""
    from axiscal._schema import document_sources
    from axiscal.errors import ConfigError

    message = str(exc)
    if isinstance(exc, ConfigError):
        sources = document_sources()
        if len(sources) == 1 and not any(message.startswith(s) for s in sources):
            return f"{sources[0]}: {message}"
    return message


def _text_argument(arg: str) -> None:
    """Refuse an argument that is not text: bytes that are not UTF-8 (Python keeps them as lone
    surrogates, which no file, database or report can hold) or a NUL (no path or name has one)."""
    try:
        arg.encode("utf-8")
    except UnicodeEncodeError as exc:
        bad = arg[:exc.start].encode("utf-8", "replace")[-30:].decode()
        _refuse(f"an argument is not UTF-8 text (after {bad!r}); give names and paths in UTF-8")
    if "\x00" in arg:
        _refuse(f"an argument holds a NUL character ({one_line(repr(arg), 60)})")


def _refuse(message: str) -> None:
    typer.echo(f"axiscal: error: {message}", err=True)
    raise typer.Exit(EXIT_USER_ERROR)


def _usage_error(exc) -> None:
    """Report a command-line mistake as one line with exit code 2 (help on no arguments stays)."""
    if isinstance(exc, NoArgsIsHelpError):
        raise exc
    message = " ".join(exc.format_message().split())
    message = (message[:1].lower() + message[1:]).rstrip(".")
    path = exc.ctx.command_path if exc.ctx is not None else "axiscal"
    where = path.partition(" ")[2]
    typer.echo(one_line(f"axiscal: error: {where + ': ' if where else ''}{message}", 440)
               + f" (see '{path} --help')", err=True)
    raise typer.Exit(EXIT_USER_ERROR) from None


class _Finite:
    """Mixin: a float option that refuses ``nan`` and ``inf`` (no length, angle or time is)."""

    def convert(self, value, param, ctx):  # noqa: D401 - click API
        import math

        v = super().convert(value, param, ctx)
        if not math.isfinite(v):
            self.fail(f"{value!r} is not a finite number", param, ctx)
        return v


class FiniteFloat(_Finite, FloatParamType):
    """``float`` without NaN and infinity."""

    name = "float"


class FiniteFloatRange(_Finite, FloatRange):
    """A bounded ``float`` (``typer.Option(min=, max=)``) without NaN."""


def _finite_floats(command) -> None:
    """Give every float option of ``command`` (and of its sub-commands) a finite type."""
    for param in command.params:
        t = param.type
        if isinstance(t, _Finite):
            continue
        if isinstance(t, FloatRange):
            param.type = FiniteFloatRange(t.min, t.max, t.min_open, t.max_open, t.clamp)
        elif isinstance(t, FloatParamType):
            param.type = FiniteFloat()
    for sub in getattr(command, "commands", {}).values():
        _finite_floats(sub)


def _load_command(name: str):
    """Import the module of command ``name``, let it register on a scratch app, return the command."""
    import importlib

    module = importlib.import_module(COMMANDS[name])
    scratch = typer.Typer(add_completion=False)   # completion belongs to the root only
    module.register(scratch)
    # A scratch app with a single group or command collapses to it; otherwise look the name up.
    group = typer.main.get_group(scratch) if scratch.registered_groups or len(scratch.registered_commands) > 1 else None
    command = typer.main.get_command(scratch) if group is None else group.get_command(None, name)
    _finite_floats(command)
    _resume_gc()
    return command


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


#: True while :func:`main` holds the cycle collector paused for start-up.
_gc_paused = False


def main(*, gc_paused: bool = False) -> None:
    """Console-script entry point.

    Start-up makes some 27,000 objects that live as long as the process (the modules, classes
    and functions of typer, the command and what it imports), and CPython's cycle collector,
    started by allocation counts, would walk them again and again while they are made (about
    4 % of the instructions of ``axiscal iso230-2 FILE --json``). So the collector is paused
    from here (under ``python -m axiscal`` from before this module is imported: ``gc_paused``)
    until the command is loaded; then what exists is moved out of its reach and it runs again
    for the command's own work (Python documentation, "gc — Garbage Collector interface",
    ``gc.freeze``). A program that paused the collector itself finds it paused after the call.
    """
    global _gc_paused
    _gc_paused = gc_paused or gc.isenabled()
    gc.disable()
    _prepare_process()
    try:
        app(prog_name="axiscal")
    except SystemExit as exc:   # help drawn at parse time, or rich's own exit on a broken pipe
        failed = getattr(sys.stdout, "failed", None)
        if failed is not None and exc.code not in (EXIT_STREAM, EXIT_BROKEN_PIPE):
            _stream_exit(failed)
        _flush_stdout()
        raise
    except OSError as exc:
        if getattr(sys.stdout, "failed", None) is exc:
            _stream_exit(exc)
        raise
    finally:
        _resume_gc()


def _flush_stdout() -> None:
    """Flush standard output before the interpreter does, so a full or broken stream ends with
    its own exit code (and one line, but none for a broken pipe) instead of a traceback."""
    try:
        sys.stdout.flush()
    except OSError as exc:
        _stream_exit(exc)


def _stream_exit(exc: OSError) -> None:
    """End the process for a failing standard output: quietly with 141 for a broken pipe, else
    one line and 74."""
    if isinstance(exc, BrokenPipeError):
        _quiet_stdout()
        raise SystemExit(EXIT_BROKEN_PIPE) from None
    try:
        _stdout_error(exc)
    except typer.Exit as stop:
        raise SystemExit(stop.exit_code) from None


def _resume_gc() -> None:
    """End the start-up pause of :func:`main`: the objects made so far frozen, the collector on."""
    global _gc_paused
    if _gc_paused:
        _gc_paused = False
        gc.freeze()
        gc.enable()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
