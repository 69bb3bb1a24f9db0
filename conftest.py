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
#: (``--dist loadgroup`` in the Makefile): two LinuxCNC instances at once on the 2-core machine
#: lost an MDI line (a 30 s timeout of the volumetric test in 2 of 3 ``make test`` runs).
LINUXCNC_FILES = {"test_programs_on_linuxcnc.py", "test_linuxcnc_live.py", "test_on_linuxcnc.py",
                  "test_calibrate_on_linuxcnc.py", "test_on_linuxcnc_volumetric.py",
                  "test_five_axis_linuxcnc.py", "test_thermal_on_linuxcnc.py"}


def pytest_collection_modifyitems(config, items):
    import pytest

    for item in items:
        if item.path.name in LINUXCNC_FILES:
            item.add_marker(pytest.mark.xdist_group("linuxcnc"))
