"""A configuration given as a dict, checked by the same schema as its TOML file.

:func:`axiscal.simulate` takes a configuration as a mapping as well as a file: the mapping is
written as TOML text (:func:`toml_text`) and read by the reader of the file, so a dict and a
file are refused for the same keys, units and bounds with the same messages (the source named
``<dict>``).
"""

from __future__ import annotations

import math
from typing import Any, Mapping

__all__ = ["toml_text", "SOURCE"]

#: The name a dict configuration goes by in messages.
SOURCE = "<dict>"


def toml_text(config: Mapping[str, Any]) -> str:
    """A mapping of tables as TOML text (TOML v1.0.0: tables, arrays of tables, inline values).

    Examples
    --------
    >>> cfg = {"test": {"step_deg": 45}, "axis": {"positioning": {"harmonics": [[1, 10.0, 0.0]]}}}
    >>> print(toml_text(cfg))
    [test]
    step_deg = 45
    <BLANKLINE>
    [axis.positioning]
    harmonics = [[1, 10.0, 0.0]]
    <BLANKLINE>
    """
    from axiscal.errors import ConfigError

    if not isinstance(config, Mapping):
        raise ConfigError(f"{SOURCE}: a configuration is a mapping of tables, not "
                          f"{type(config).__name__}")
    lines: list[str] = []
    _table(config, (), lines)
    return "\n".join(lines).strip("\n") + "\n" if lines else ""


def _table(d: Mapping[str, Any], path: tuple, lines: list[str]) -> None:
    """Append ``d``'s values, then its sub-tables and arrays of tables, under ``path``."""
    simple = {k: v for k, v in d.items() if not _is_table(v) and not _is_table_array(v)}
    header = bool(path) and (bool(simple) or not any(_is_table(v) or _is_table_array(v)
                                                     for v in d.values()))
    if header:
        lines.append(f"[{'.'.join(_key(p) for p in path)}]")
    lines.extend(f"{_key(k)} = {_value(v, (*path, k))}" for k, v in simple.items())
    if simple or header:
        lines.append("")
    for k, v in d.items():
        if _is_table(v):
            _table(v, (*path, k), lines)
        elif _is_table_array(v):
            for item in v:
                lines.append(f"[[{'.'.join(_key(p) for p in (*path, k))}]]")
                lines.extend(f"{_key(ik)} = {_value(iv, (*path, k, ik))}"
                             for ik, iv in item.items())
                lines.append("")


def _is_table(v: Any) -> bool:
    return isinstance(v, Mapping)


def _is_table_array(v: Any) -> bool:
    return isinstance(v, (list, tuple)) and bool(v) and all(isinstance(x, Mapping) for x in v)


def _key(k: Any) -> str:
    import re

    k = str(k)
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else _string(k)


def _string(s: str) -> str:
    import json

    return json.dumps(s, ensure_ascii=False)   # a TOML basic string has JSON's escapes


def _value(v: Any, where: tuple) -> str:
    """One inline value; anything TOML cannot hold is refused naming the key."""
    from axiscal.errors import ConfigError

    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, str):
        return _string(v)
    if hasattr(v, "tolist") and not isinstance(v, Mapping):   # a NumPy number or array
        return _value(v.tolist(), where)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x, where) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{" + ", ".join(f"{_key(k)} = {_value(x, (*where, k))}" for k, x in v.items()) + "}"
    raise ConfigError(f"{SOURCE}: {'.'.join(map(str, where))} = {v!r}: a "
                      f"{type(v).__name__} has no TOML form (numbers, text, true/false, lists "
                      "and tables)")
