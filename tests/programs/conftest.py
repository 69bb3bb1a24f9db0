"""LinuxCNC's own RS274/NGC interpreter (``rs274``, Debian linuxcnc-uspace 2.9) for the program
tests. It needs no root and no running LinuxCNC, so it runs wherever it is installed (as any
user: its tool table goes to a HOME of its own). Skipped only where it is not installed and
``make test`` cannot install it (not Debian, or not root to run apt); on Debian as root a
missing ``rs274`` fails, since ``make test`` installs it (``make linuxcnc``)."""

import os
import shutil
import subprocess

import pytest

from axiscal.instruments.linuxcnc_controller import platform_reason


@pytest.fixture
def rs274(tmp_path_factory):
    """``run(path, timeout=120)`` -> the interpreter's canonical output for the program at
    ``path`` (it must end with status 0). A run ended by a signal gets one more try: rs274 ended
    by SIGBUS once in a make test while a LinuxCNC ran beside it (cause not found); the
    interpreter's own answers are never retried."""
    exe = shutil.which("rs274")
    if exe is None:
        why = platform_reason()
        if why is not None:
            pytest.skip("rs274 (LinuxCNC's interpreter, Debian's linuxcnc-uspace) is not "
                        f"installed, and make test installs it only on Debian as root: {why}")
        pytest.fail("rs274 (linuxcnc-uspace) is missing: make test installs it (make linuxcnc)")
    # rs274 keeps its tool table in $HOME/.tool.mmap: a HOME of its own, writable by any user
    env = {**os.environ, "HOME": str(tmp_path_factory.mktemp("rs274-home"))}

    def run(path, timeout: float = 120.0) -> str:
        for _ in range(2):
            r = subprocess.run([exe, "-g", str(path)], capture_output=True, text=True,
                               timeout=timeout, env=env)
            if r.returncode >= 0:
                break
        assert r.returncode == 0, r.stdout[-500:] + r.stderr[-500:]
        return r.stdout

    return run
