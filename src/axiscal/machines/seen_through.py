"""A machine or an axis seen through something that changes its commands.

A controller's compensation table (:class:`~axiscal.compensation.apply.CompensatedAxis`), a live
drive (:class:`~axiscal.instruments.linuxcnc_controller.LinuxCNCAxis`) or a controller applying
volumetric tables (:class:`~axiscal.compensation.volumetric.CompensatedMachine`,
:class:`~axiscal.compensation.on_controller_volumetric.ThroughLinuxCNC`) change where the machine
goes for a command, not what the machine is: its name, travel, repeatability and kinematic chain
stay those of the machine behind. These mixins give a wrapper those properties from the wrapped
machine, so that the procedures' axis and machine interfaces hold for it; the wrapper writes only
what it changes (``move``, ``systematic_deviation``, ``pose``).

A class using :class:`AxisSeenThrough` has an attribute ``axis`` (a
:class:`~axiscal.machines.linear.LinearAxis` or :class:`~axiscal.machines.rotary.RotaryAxis`);
one using :class:`MachineSeenThrough` an attribute ``machine`` (a
:class:`~axiscal.machines.three_axis.ThreeAxisMachine`). All quantities SI.
"""

from __future__ import annotations

__all__ = ["AxisSeenThrough", "MachineSeenThrough"]


class AxisSeenThrough:
    """The name, repeatability and travel of the axis behind (attribute ``axis``)."""

    @property
    def name(self) -> str:
        """The axis name."""
        return self.axis.name

    @property
    def repeatability_sigma(self) -> float:
        """The axis's repeatability, SI (what is seen through does not change it)."""
        return self.axis.repeatability_sigma

    @property
    def travel(self):
        """The axis's travel, SI (None for a continuous rotary axis)."""
        return self.axis.travel

    def check_in_travel(self, position) -> None:
        """Commanded positions (SI) must lie in the axis's travel."""
        self.axis.check_in_travel(position)


class MachineSeenThrough:
    """The kinematic chain and travel of the three-axis machine behind (attribute ``machine``)."""

    @property
    def chain(self):
        """The machine's kinematic chain."""
        return self.machine.chain

    @property
    def travel(self):
        """The machine's travel per axis, SI."""
        return self.machine.travel
