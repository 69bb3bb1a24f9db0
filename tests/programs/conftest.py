"""LinuxCNC's own RS274/NGC interpreter (``rs274``, Debian linuxcnc-uspace 2.9) for the program
tests: skipped only where no install can help (not Debian, not root: ``platform_reason``); on
Debian as root a missing ``rs274`` fails, since ``make test`` installs it (``make linuxcnc``)."""

import shutil
import subprocess

import pytest

from axiscal.instruments.linuxcnc_controller import platform_reason


@pytest.fixture
def rs274():
    """``run(path, timeout=120)`` -> the interpreter's canonical output for the program at
    ``path`` (it must end with status 0). A run ended by a signal gets one more try: rs274 ended
    by SIGBUS once in a make test while a LinuxCNC ran beside it (cause not found); the
    interpreter's own answers are never retried."""
    why = platform_reason()
    if why is not None:
        pytest.skip(f"LinuxCNC cannot run here: {why}")
    exe = shutil.which("rs274")
    assert exe, "rs274 (linuxcnc-uspace) is missing: make test installs it (make linuxcnc)"

    def run(path, timeout: float = 120.0) -> str:
        for _ in range(2):
            r = subprocess.run([exe, "-g", str(path)], capture_output=True, text=True,
                               timeout=timeout)
            if r.returncode >= 0:
                break
        assert r.returncode == 0, r.stdout[-500:] + r.stderr[-500:]
        return r.stdout

    return run
