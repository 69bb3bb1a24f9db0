"""Child process of the CLI fuzz harness (tests/cli/test_cli_fuzz.py).

Reads one JSON request per line on stdin, ``{"args": [...], "cwd": FOLDER}``, runs
``axiscal ARGS`` in-process (typer's CliRunner) in that folder and writes one JSON line with the
exit code, stdout, stderr and any traceback. The parent set a memory limit (RLIMIT_AS) on this
process and times each answer, so a runaway allocation or a hang fails the case instead of the
machine.
"""

from __future__ import annotations

import json
import os
import sys
import traceback


def main() -> None:
    from typer.testing import CliRunner

    from axiscal.cli import app

    out = sys.stdout
    out.write('"ready"\n')
    out.flush()
    for line in sys.stdin:
        request = json.loads(line)
        if isinstance(request, list):
            request = {"args": request}
        if request.get("cwd"):
            os.chdir(request["cwd"])
        r = CliRunner().invoke(app, request["args"])
        tb = None
        if r.exception is not None and not isinstance(r.exception, SystemExit):
            tb = "".join(traceback.format_exception(*r.exc_info))
        out.write(json.dumps({"exit": r.exit_code, "stdout": r.stdout[-2000:],
                              "stderr": r.stderr[-4000:], "stderr_chars": len(r.stderr),
                              "traceback": tb}) + "\n")
        out.flush()


if __name__ == "__main__":
    main()
