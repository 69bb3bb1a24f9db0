"""Loss of the laser's signal along every move of a rotary calibration (issue 21, item 1).

Seed 000 ("Rotary axis calibration"): the angular interferometer alone is "only suitable for
checking angular movements over a range of about ±10°", beyond which the reflector's rotation
misaligns the returned beams. A real laser loses the beams, and the whole run, the moment the
reflector passes that angle, whether the axis is at a target or overrunning it.
"""

import tomllib
from pathlib import Path

import pytest

from axiscal.errors import SignalLossError
from axiscal.procedures.rotary_config import run_rotary_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _config(test, setup):
    cfg = tomllib.loads((EXAMPLES / "rotary_turntable.toml").read_text())
    cfg["test"].update(test)
    cfg["setup"].update(setup)
    return cfg


def test_overrun_beyond_the_limit_without_counter_rotation_loses_the_signal():
    """Targets −9°..+9° are inside ±10°, but a 5° overrun takes the reflector to −14° before the
    first approach (9° + 5°, first principles: without counter-rotation the reflector turns
    with the axis). The run must fail naming that overrun move, not pass at its targets."""
    cfg = _config({"start_deg": -9.0, "travel_deg": 18.0, "step_deg": 3.0, "runs": 2,
                   "overrun": 5.0}, {"counter_rotation": False})
    with pytest.raises(SignalLossError) as err:
        run_rotary_config(cfg)
    msg = str(err.value)
    assert "move 1 of the plan (overrun move of run 1, 0° to -14°)" in msg
    assert "-14.1°" in msg or "-14.0°" in msg or "-13.9°" in msg
    assert "counter-rotate" in msg


def test_overrun_inside_the_limit_runs():
    """The same plan with a 0.5° overrun keeps the reflector within 9.5° (+ the 0.1° datum
    misalignment) of the beams along every move: no error, the limit is not over-reported."""
    cfg = _config({"start_deg": -9.0, "travel_deg": 18.0, "step_deg": 3.0, "runs": 2,
                   "overrun": 0.5}, {"counter_rotation": False})
    r = run_rotary_config(cfg)
    assert r.plan.overrun == 0.5


def test_counter_rotation_keeps_the_reflector_facing_the_laser_through_the_overrun():
    """With counter-rotation the calibrator is driven opposite to the axis during every move
    (seed 000), so the same plan with a 5° overrun runs."""
    cfg = _config({"start_deg": -9.0, "travel_deg": 18.0, "step_deg": 3.0, "runs": 2,
                   "overrun": 5.0}, {"counter_rotation": True})
    assert run_rotary_config(cfg).plan.overrun == 5.0
