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
