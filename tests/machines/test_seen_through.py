"""A machine seen through a controller keeps the machine's name, travel, repeatability and chain
(axiscal.machines.seen_through), and the volumetric figures are written once for both loops."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.compensation.apply import CompensatedAxis
from axiscal.compensation.tables import table_from_deviations
from axiscal.compensation.volumetric import (CompensatedMachine, fall, fall_text, figure_row,
                                             figure_rows)
from axiscal.errors import AxiscalError
from axiscal.machines.linear import LinearAxis
from axiscal.machines.rotary import RotaryAxis
from axiscal.machines.three_axis import simulated_machine


def test_a_compensated_linear_axis_is_the_axis_behind_but_for_its_deviation():
    ax = LinearAxis(name="Y", travel=(0.1, 0.9), repeatability_sigma=0.4e-6)
    comp = CompensatedAxis(ax, table_from_deviations([100, 900], [0.0, 8.0], spacing=100))
    assert (comp.name, comp.travel, comp.repeatability_sigma) == ("Y", (0.1, 0.9), 0.4e-6)
    comp.check_in_travel(0.5)
    with pytest.raises(AxiscalError):
        comp.check_in_travel(0.95)            # beyond the axis's travel, as the axis says


def test_a_continuous_rotary_axis_seen_through_has_no_travel():
    ax = RotaryAxis(name="C")
    comp = CompensatedAxis(ax, table_from_deviations([0, 180, 360], [0.0, 1.0, 0.0],
                                                     spacing=180, position_unit="deg",
                                                     correction_unit="arcsec"))
    assert comp.name == "C" and comp.travel is None is ax.travel


def test_a_compensated_machine_keeps_the_chain_and_travel():
    m = simulated_machine(np.random.default_rng(1))
    cm = CompensatedMachine(m, tables=None)
    assert cm.chain is m.chain and cm.travel == m.travel


def test_the_volumetric_figures_one_column_per_measurement():
    """Rows: the map's largest error, its ranges X, Y, Z, then each body diagonal (ISO 230-6);
    the fall is 1 − after/before, 0 (and a dash) where nothing was there."""
    class Map:
        def __init__(self, largest, r):
            self.largest, self.ranges = largest, dict(zip("XYZ", r))

    class Diagonal:
        def __init__(self, name, rng):
            self.name, self.range = name, rng

    maps = [Map(10.0, (4.0, 5.0, 6.0)), Map(2.0, (1.0, 1.0, 0.0))]
    diags = [[Diagonal("PPP", 8.0), Diagonal("NPP", 0.0)],
             [Diagonal("PPP", 2.0), Diagonal("NPP", 0.0)]]
    rows = figure_rows(maps, diags)
    assert [r[0] for r in rows] == ["largest volumetric error", "range X", "range Y", "range Z",
                                    "body diagonal PPP", "body diagonal NPP"]
    assert figure_row(rows, "range Y") == (5.0, 1.0)
    assert fall(*figure_row(rows, "largest volumetric error")) == pytest.approx(0.8)
    assert fall(0.0, 0.0) == 0.0 and fall_text(0.0, 0.0) == "—"
    assert fall_text(8.0, 2.0) == "75.0 %"
    with pytest.raises(KeyError):
        figure_row(rows, "range W")
