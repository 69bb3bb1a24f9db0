"""The motion-error data file and configuration (axiscal.io.motion)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError, ConfigError, DataFormatError
from axiscal.io.motion import format_motion_errors, parse_motion_config, parse_motion_errors
from axiscal.standards.iso230_7 import MotionErrorData
from axiscal.units import ARCSEC, UM


def test_round_trip_with_dx():
    th = np.radians(np.arange(0, 361, 45.0))
    rng = np.random.default_rng(1)
    ch = {c: rng.normal(0, 5 * (ARCSEC if c[0] == "e" else UM), (2, th.size))
          for c in ("ez", "ey", "ex", "dy", "dz", "dx")}
    d = MotionErrorData(th, title="round trip", **ch)
    back = parse_motion_errors(format_motion_errors(d))
    assert back.title == "round trip" and back.n_runs == 2
    for c in ch:
        assert np.allclose(getattr(back, c), getattr(d, c), atol=1e-6 * (ARCSEC if c[0] == "e" else UM))


def test_columns_in_any_order_and_comments():
    text = ("# comment\ndz_um,run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um\n"
            + "\n".join(f"{a / 90},1,{a},1,2,3,4" for a in range(0, 360, 90)))
    d = parse_motion_errors(text)
    assert d.dz[0, 3] == pytest.approx(3 * UM) and d.ey[0, 0] == pytest.approx(2 * ARCSEC)


def test_config_defaults_and_overrides():
    cfg = parse_motion_config("[mounting]\nrealistic = true\nbeam_yaw_arcsec = 0.0\n"
                              "[instrument]\nh_mm = 40\n")
    assert cfg.system.h == pytest.approx(0.04)
    assert cfg.system.mounting.beam_yaw == 0.0 and cfg.system.mounting.beam_pitch > 0
    assert cfg.runs == 3 and cfg.system.qd1.noise == pytest.approx(0.08 * UM / 6)
    with pytest.raises(ConfigError, match="unknown key"):
        parse_motion_config("[drift]\nspeed = 1\n")
    with pytest.raises(ConfigError, match="runs"):
        parse_motion_config("[test]\nruns = 1\n")


def test_run_angles_must_agree():
    text = ("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n"
            + "\n".join(f"1,{a},0,0,0,0,0" for a in range(0, 360, 90)) + "\n"
            + "\n".join(f"2,{a},0,0,0,0,0" for a in range(0, 360, 60)))
    with pytest.raises(DataFormatError, match="run 2"):
        parse_motion_errors(text)


@settings(max_examples=60, deadline=None)
@given(st.text(max_size=300))
def test_parser_raises_only_axiscal_errors(text):
    """Arbitrary text never raises anything but an AxiscalError."""
    try:
        parse_motion_errors("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n" + text)
    except AxiscalError:
        pass
    try:
        parse_motion_config(text)
    except AxiscalError:
        pass
