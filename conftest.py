"""Collection settings for the whole repository (tests and doctests of src/axiscal)."""

import importlib.util
import os
import tempfile

# Evaluations and reports kept by axiscal.store.cache go to a folder of this test run, not the
# user's cache folder (subprocesses inherit it).
os.environ.setdefault("AXISCAL_CACHE", tempfile.mkdtemp(prefix="axiscal-test-cache-"))

# The numba kernels (the optional ``fast`` extra) hold no doctests and import numba at module
# level; without numba the NumPy path is tested instead (tests/physics/test_quadrature_*).
collect_ignore = ([] if importlib.util.find_spec("numba") is not None
                  else ["src/axiscal/physics/_sincos_numba.py"])

#: The test files that start a real LinuxCNC. They run one after the other on one xdist worker
#: (``--dist loadgroup`` in the Makefile): one LinuxCNC runs per computer (a session waits for
#: the session lock), so spread over the workers they would only wait for each other, and the
#: sessions are timed by LinuxCNC's servo thread, which wants a core the others leave free.
LINUXCNC_FILES = {"test_programs_on_linuxcnc.py", "test_linuxcnc_live.py", "test_on_linuxcnc.py",
                  "test_calibrate_on_linuxcnc.py", "test_on_linuxcnc_volumetric.py",
                  "test_five_axis_linuxcnc.py", "test_thermal_on_linuxcnc.py",
                  "test_five_axis_ballbar_linuxcnc.py"}


def pytest_xdist_make_scheduler(config, log):
    """``--dist loadgroup`` (the Makefile's): every test on any free worker, except the tests of
    :data:`LINUXCNC_FILES`, which all go to one worker, one after another.

    pytest-xdist's own loadgroup reads ``xdist_group`` marks by renaming each item's node id
    (``nodeid@group``), which pytest 9 no longer lets a plugin do: the groups were silently
    ignored, and the LinuxCNC tests spread over every worker, each waiting for the one LinuxCNC
    session lock instead of computing (seen with pytest 9.2 and pytest-xdist 3.8). The scope
    scheduler keeps a scope on one worker; here a test's scope is itself, a LinuxCNC file's test's
    the word ``linuxcnc``."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class LinuxCNCOnOneWorker(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            file = nodeid.split("::", 1)[0].rsplit("/", 1)[-1]
            return "linuxcnc" if file in LINUXCNC_FILES else nodeid

    return LinuxCNCOnOneWorker(config, log)
