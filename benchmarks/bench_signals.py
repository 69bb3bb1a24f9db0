"""Speed of quadrature decoding and sine/cosine interpolation on 10^7 samples (issue 3).

Reported as samples per second and as the ratio of the operation's time to ``numpy.copy`` of the
same input array in the same run (aim: within 10x on one core). The interpolation is measured
both ways in the same run: with the numba kernels (the ``fast`` extra, when installed) and with
the NumPy fallback. Best of three
runs for every timing. Run alone with ``python benchmarks/run.py bench_signals``.
"""

from __future__ import annotations

import time

import numpy as np

from _timing import best_of

N = 10**7




def run() -> list[dict]:
    from axiscal.physics import quadrature
    from axiscal.physics.quadrature import decode_quadrature, encode_quadrature, interpolate_sincos

    rng = np.random.default_rng(0)
    counts = np.concatenate(([0], np.cumsum(rng.choice(np.array([-1, 1]), N - 1))))
    a, b = encode_quadrature(counts)
    x = np.cumsum(rng.uniform(-0.1, 0.1, N))
    s, c = np.sin(2 * np.pi * x), np.cos(2 * np.pi * x)

    rows = []
    t_dec = best_of(lambda: decode_quadrature(a, b))
    t_copy_counts = best_of(lambda: np.copy(counts))
    t_copy_ab = best_of(lambda: (np.copy(a), np.copy(b)))
    rows.append(dict(name="quadrature decode x4, 10^7 samples", value=N / t_dec, unit="samples/s",
                     reference=f"numpy.copy of the int64 count array ({t_copy_counts * 1e3:.1f} ms)",
                     ratio=t_dec / t_copy_counts, aim="ratio (time / copy) <= 10"))
    rows.append(dict(name="quadrature decode vs copy of the A/B bool inputs", value=t_dec * 1e3,
                     unit="ms", reference=f"numpy.copy of A and B ({t_copy_ab * 1e3:.2f} ms)",
                     ratio=t_dec / t_copy_ab, aim="informative (bool inputs are 8x smaller)"))
    t_copy_s = best_of(lambda: np.copy(s))
    ref = f"numpy.copy of the float64 sine array ({t_copy_s * 1e3:.1f} ms)"
    t0 = time.perf_counter()
    fast = quadrature._kernels(N, None)          # numba import + compile or cache load
    t_load = time.perf_counter() - t0
    if fast is not None:
        interpolate_sincos(s[:10], c[:10], accelerate=True)
        t_load = time.perf_counter() - t0
        t_int = best_of(lambda: interpolate_sincos(s, c))
        rows.append(dict(name="sin/cos interpolation + period count, 10^7 (numba kernels)",
                         value=N / t_int, unit="samples/s", reference=ref,
                         ratio=t_int / t_copy_s, aim="ratio (time / copy) <= 10"))
        rows.append(dict(name="numba import + kernel load (first large record)", value=t_load,
                         unit="s", reference="once per process; compiled kernels cached on disk",
                         ratio=None, aim="informative"))
    t_np = best_of(lambda: interpolate_sincos(s, c, accelerate=False))
    rows.append(dict(name="sin/cos interpolation + period count, 10^7 (NumPy fallback)",
                     value=N / t_np, unit="samples/s", reference=ref, ratio=t_np / t_copy_s,
                     aim="ratio (time / copy) <= 10" if fast is None else "informative (fallback)"))
    t_atan = best_of(lambda: np.arctan2(s, c))
    rows.append(dict(name="numpy.arctan2 alone (floor of the interpolation)", value=N / t_atan,
                     unit="samples/s", reference="numpy.copy of the sine array",
                     ratio=t_atan / t_copy_s, aim="informative"))
    return rows
