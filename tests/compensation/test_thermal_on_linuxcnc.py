"""The temperature compensation proven on LinuxCNC (issue 44, "Must show": through LinuxCNC,
the drift of the moving-axis test falls by ≥ 80 % with the compensation).

The model is fitted on three simulated ISO 230-3:2020 linear-axis runs of the thermal twin
(``src/axiscal/data/thermal_vmc.toml``; fit at 8 h with 80 % duty, choice at 13 h with 50 %,
judged at 2 h with 100 %), and a fourth run (10 h, 70 % duty, seed 9) is measured through a
headless LinuxCNC twice on one simulated thermal history: axiscal's HAL component
``axiscal_thermcomp.py`` active, then inactive. The simulated sensors feed LinuxCNC through HAL
pins on a time-compressed clock; every 5 min the X axis moves to P1 and P2 by MDI.

Skipped, with the concrete reason, only where LinuxCNC cannot run (not Debian, not root).
"""

import dataclasses

import numpy as np
import pytest

from axiscal.compensation.on_controller_thermal import verify_thermal_on_linuxcnc
from axiscal.compensation.thermal_model import fit_thermal_model, sinumerik_compensation
from axiscal.instruments.linuxcnc_controller import platform_reason
from axiscal.machines.thermal_config import parse_thermal_config
from axiscal.procedures.thermal import plan_thermal, simulate_thermal

WHY = platform_reason()
CONFIG = "src/axiscal/data/thermal_vmc.toml"


def _run(twin, seed, start_h, duty):
    plan = plan_thermal(twin, "linear", start=start_h * 3600.0, duty=duty)
    return dataclasses.replace(simulate_thermal(twin, plan, np.random.default_rng(seed)).log,
                               source=f"seed {seed}")


@pytest.mark.skipif(WHY is not None, reason=f"LinuxCNC cannot run here: {WHY}")
def test_thermal_drift_falls_by_80_percent_through_linuxcnc():
    """4 h of cycling (the minimum of axiscal's Clause 7 test), 49 readings at each target per
    run, 196 LinuxCNC moves in all. Measured (seed 9): P1 5.41 µm → 0.51 µm (90 %), P2 56.9 µm →
    1.60 µm (97 %); the twin alone (``verify_on_twin``, 5 h) gave 92 % and 96 %. LinuxCNC's
    offset equals −ΔK of axiscal's model at every reading within 0.1 µm (the offset planner
    stops ≤ 20 nm short; the count is 1 nm)."""
    twin = parse_thermal_config(open(CONFIG).read(), CONFIG)
    model = fit_thermal_model(_run(twin, 1, 8, 0.8), _run(twin, 2, 13, 0.5),
                              _run(twin, 3, 2, 1.0))
    comp = sinumerik_compensation(model)
    plan = plan_thermal(twin, "linear", start=10 * 3600.0, duty=0.7, duration=4 * 3600.0)
    r = verify_thermal_on_linuxcnc(twin, plan, comp, 9)
    c = r.check
    assert abs(c.before["P1"]) > 3e-6 and abs(c.before["P2"]) > 30e-6   # a drift to remove
    for k in ("P1", "P2"):
        assert c.reduction[k] >= 0.80, (k, c.before[k], c.after[k])
    assert r.moves == 2 * 49
    assert r.applied < 0.1e-6
    assert r.compression > 10          # hours of the sensors' clock in LinuxCNC's seconds
