"""The exceptions of axiscal.

Every error axiscal raises on purpose derives from :class:`AxiscalError` and from the builtin that
matches its meaning (``ValueError``, ``FileNotFoundError`` ...), the pattern of pint's
``DefinitionError(ValueError, PintError)``. The command line turns an :class:`AxiscalError` into one
line on stderr and exit code 2; anything else is a bug and keeps its traceback.

Messages name the parameter, the value and the rule, for example::

    InsufficientRunsError: 1 run at target 45 deg; ISO 230-2 needs at least 2 to estimate
    repeatability (5 recommended)
"""

from __future__ import annotations

__all__ = [
    "AxiscalError",
    "InputError",
    "UnitError",
    "DataFormatError",
    "MissingFileError",
    "ConfigError",
    "InsufficientRunsError",
    "MeasurementError",
    "SignalLossError",
    "ControllerLimitError",
    "SignConventionError",
    "NotAvailableError",
    "StoreError",
    "NotFoundError",
    "ProgramError",
    "NotAuthorisedError",
    "MissingExtraError",
    "ERRORS",
    "one_line",
    "MAX_MESSAGE",
]

#: Longest message shown, characters: a message quotes at most an excerpt of the input (a
#: 200 MB one-line file once gave a 200 MB "one-line" error). Room for a long path and the list
#: of a configuration table's known keys, which a message should not cut.
MAX_MESSAGE = 800


def one_line(message: str, limit: int = MAX_MESSAGE) -> str:
    """``message`` on one line (line breaks become spaces) and at most ``limit`` characters:
    beyond that its beginning and end with ``…`` between, so the reason (at the start) and the
    rule (often at the end) both stay.

    Examples
    --------
    >>> one_line("header: " + "x" * 10_000 + " is not a number", 60)
    'header: xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx … is not a number'
    """
    text = " ".join(message.splitlines())
    if len(text) <= limit:
        return text
    tail = min(limit // 4, 120)
    return f"{text[:limit - tail - 3].rstrip()} … {text[-tail:].lstrip()}"



class AxiscalError(Exception):
    """Base class of every error axiscal raises on purpose."""


class InputError(AxiscalError, ValueError):
    """A parameter has a value the function cannot accept (the message says which rule)."""


class UnitError(InputError):
    """A unit name is unknown, or not of the expected dimension (length or angle)."""


class ConfigError(InputError):
    """A configuration (TOML) file or value is missing a key or holds an impossible value."""


class InsufficientRunsError(InputError):
    """Too few runs (or readings) to estimate what a standard asks for."""


class ControllerLimitError(InputError):
    """A compensation table breaks a limit of the target controller's format."""


class SignConventionError(InputError):
    """Two inputs combine only with a sign convention that they contradict."""


class DataFormatError(AxiscalError, ValueError):
    """A file's content is not in the expected format.

    Parameters
    ----------
    message : str
        What is wrong.
    source : str, optional
        The file name (or ``"<text>"``) the content came from.
    line : int, optional
        The 1-based line number of the offending line, where there is one.
    """

    def __init__(self, message: str, source: str | None = None, line: int | None = None):
        self.message = message
        self.source = source
        self.line = line
        where = ""
        if source is not None:
            where = f"{source}:{line}: " if line is not None else f"{source}: "
        elif line is not None:
            where = f"line {line}: "
        super().__init__(where + message)


class MissingFileError(AxiscalError, FileNotFoundError):
    """A file that should be read does not exist or cannot be opened."""

    def __init__(self, path: object, reason: str = "no such file"):
        self.path = str(path)
        self.reason = reason
        super().__init__(f"{self.path}: {reason}")

    def __str__(self) -> str:  # FileNotFoundError's own __str__ wants errno fields
        return f"{self.path}: {self.reason}"


class MeasurementError(AxiscalError, RuntimeError):
    """A (real or simulated) measurement could not be taken as asked."""


class SignalLossError(MeasurementError):
    """An instrument lost its signal (beam obstructed, reflector turned too far, ...)."""


class NotAvailableError(InputError):
    """The standard is known, but no public definition of its parameters was available."""


class StoreError(AxiscalError, RuntimeError):
    """The history database cannot be used as asked (not a database, full, unreachable)."""


class NotFoundError(AxiscalError, LookupError):
    """No such test, machine or axis in the history."""


class NotAuthorisedError(AxiscalError, PermissionError):
    """The account may not make this change (ISO/IEC 17025:2017 §6.2.6: only authorised
    personnel); the workbench answers 403."""

    status = 403


class ProgramError(InputError):
    """A part program cannot be made as asked (``option`` names the option to change)."""

    def __init__(self, option: str, message: str):
        super().__init__(message)
        self.option = option


class MissingExtraError(AxiscalError, ImportError):
    """A feature needs an optional extra that is not installed (``pip install 'axiscal[web]'``)."""


#: Every exception class of the library, each importable from the package's top
#: (``axiscal.DataFormatError``).
ERRORS = ("AxiscalError", "InputError", "UnitError", "ConfigError", "InsufficientRunsError",
          "ControllerLimitError", "SignConventionError", "NotAvailableError", "DataFormatError",
          "MissingFileError", "MeasurementError", "SignalLossError", "StoreError",
          "NotFoundError", "MissingExtraError", "ProgramError", "NotAuthorisedError")
