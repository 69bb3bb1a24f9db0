"""The simulated touch probe started from given machine positions (issue 43: a probing cycle
run through a controller, measured by the twin from the joints it reached)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.touch_probe import SimulatedTouchProbe
from axiscal.machines.five_axis import FiveAxisMachine
from axiscal.physics.rotary_location import Geometry

MACHINE = FiveAxisMachine(Geometry("A", (0.0, -0.06), (0.0, 0.0)),
                          {"E_Y0A": 12e-6, "E_B0A": 25e-6, "E_X0C": 20e-6})


def test_touches_from_start_points_lie_on_the_sphere_where_probe_sphere_has_them():
    """Without noise, starting 2 mm out along each normal gives the points probe_sphere gives
    (the stylus-ball centres at the effective radius along the normals), within 1e-12 m; from
    start points off the normals the touches still lie at the effective radius."""
    probe = SimulatedTouchProbe(offset=(1e-6, -2e-6, 3e-6))
    place, a, c = np.array([0.15, 0.02, 0.06]), -0.8, 2.0
    centre = MACHINE.to_machine(np.array([a]), np.array([c]), place)[0]
    d = probe.directions / np.linalg.norm(probe.directions, axis=1, keepdims=True)
    starts = centre + (probe.effective_radius + 2e-3) * d
    want = probe.probe_sphere(MACHINE, a, c, place)
    np.testing.assert_allclose(probe.touch_from(MACHINE, a, c, place, starts), want, atol=1e-12)
    shifted = starts + np.array([0.3e-3, -0.2e-3, 0.1e-3])
    got = probe.touch_from(MACHINE, a, c, place, shifted) + np.array(probe.offset)
    np.testing.assert_allclose(np.linalg.norm(got - centre, axis=1), probe.effective_radius,
                               atol=1e-12)


def test_a_start_inside_the_sphere_is_refused():
    probe = SimulatedTouchProbe()
    place = np.array([0.15, 0.02, 0.06])
    centre = MACHINE.to_machine(np.array([0.0]), np.array([0.0]), place)[0]
    with pytest.raises(InputError, match="inside the sphere"):
        probe.touch_from(MACHINE, 0.0, 0.0, place, np.tile(centre, (5, 1)))
