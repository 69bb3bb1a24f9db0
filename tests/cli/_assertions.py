"""Assertions shared by the command-line tests."""

from __future__ import annotations


def one_error_line(r, *words) -> str:
    """``r`` (a CliRunner result) is a user error: exit 2, exactly one ``axiscal: error:`` line on
    stderr holding every one of ``words``, nothing on stdout, no traceback. Returns the line."""
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    assert r.stdout == "" and "Traceback" not in r.output
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]
