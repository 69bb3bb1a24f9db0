"""A thermal machine twin: heat sources, lumped temperatures and the displacement they cause.

The twin is what the ISO 230-3:2020 tests measure against (``standards/iso230_3.py``). It holds

* the **room**: a mean temperature, a daily cycle and a slow ramp (the environment of the ETVE
  test, ISO 230-3:2020 Clause 5);
* **nodes**: lumped first-order temperatures (spindle bearings and motor, ball-screw nut and
  bearings, a rotary table's drive and bearings, the machine's bulk structure). Each relaxes to the temperature it ``follows`` (the room
  or an earlier node) with its time constant τ, raised by ``rise`` times its load u(t) in [0, 1]
  (the spindle's or the rotary table's speed as a fraction of its maximum, an axis's share of
  time in motion);
* a **structure**: each node's temperature above 20 °C times a sensitivity gives the relative
  displacement of tool and table in three translations (X, Y, Z) and two tilts (A about X, B about
  Y), at the tool's reference point;
* **axes**: each linear axis's screw grows with its screw node's temperature, so its positioning
  error at position P grows as α·ΔT·(P − P_fixed) (the screw's fixed bearing at P_fixed), on top of
  the structure's translation along the axis.

Everything is SI inside: seconds, metres, radians, °C (kelvin for differences).

Notes
-----
Node equation (a first-order lumped model, e.g. Mayr et al., "Thermal issues in machine tools",
CIRP Annals 61/2, 2012, section 3)::

    τ dT/dt = T_follow(t) + rise · u(t) − T

integrated exactly for inputs held constant over each step (zero-order hold):
``T[k+1] = T_drive[k] + (T[k] − T_drive[k]) · exp(−Δt/τ)``. The room is

    T_room(t) = T_mean + A · cos(2π (t − t_peak) / P) + r · t

Structure (a linear map of node temperatures, the same form the thermal model of
``compensation/thermal_model.py`` fits)::

    d(t) = Σ_nodes S_node · (T_node(t) − 20 °C)            d = (X, Y, Z, A, B)
    e_axis(P, t) = d_axis(t) + (c + α_axis (P − P_fixed)) · (T_screw(t) − 20 °C)

The positioning error ``e_axis`` is linear in P, the form SINUMERIK's temperature compensation
ΔK = K0 + tanβ·(P − P0) represents exactly (see ``compensation/thermal_model.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import InputError, one_line

__all__ = ["Room", "ThermalNode", "ThermalAxis", "TemperatureSensor", "ThermalTwin",
           "ThermalHistory", "DIRECTIONS", "REFERENCE_C"]

#: The five components of the tool–table displacement: three translations (m), two tilts (rad).
DIRECTIONS = ("X", "Y", "Z", "A", "B")
#: Standard reference temperature of ISO 1:2022, °C: a node at 20 °C causes no displacement.
REFERENCE_C = 20.0


@dataclass(frozen=True)
class Room:
    """The shop's air temperature over time.

    Attributes
    ----------
    mean : float, °C
    amplitude : float, K
        Half the peak-to-peak of the daily cycle.
    period : float, s
        Period of the cycle (86 400 s for a day).
    peak_time : float, s
        Time of the warmest moment after the start of the simulation.
    ramp : float, K/s
        Slow drift of the mean.
    """

    mean: float = 20.0
    amplitude: float = 0.0
    period: float = 86_400.0
    peak_time: float = 0.0
    ramp: float = 0.0

    def temperature(self, t):
        """Room temperature, °C, at times ``t`` (s)."""
        t = np.asarray(t, dtype=float)
        return (self.mean + self.amplitude * np.cos(2 * math.pi * (t - self.peak_time) / self.period)
                + self.ramp * t)


@dataclass(frozen=True)
class ThermalNode:
    """A lumped temperature (see the module Notes).

    Attributes
    ----------
    name : str
    time_constant : float, s
    follows : str
        ``"room"`` or the name of an earlier node.
    heat : str
        What loads it: ``"none"``, ``"spindle"``, ``"rotary"`` (a rotary table turning) or
        ``"axis:X"`` (the axis named X moving).
    rise : float, K
        Steady rise above what it follows at full load (u = 1).
    sensitivity : tuple of 5 floats
        d(X, Y, Z) in m/K and d(A, B) in rad/K per kelvin of this node above 20 °C.
    """

    name: str
    time_constant: float
    follows: str = "room"
    heat: str = "none"
    rise: float = 0.0
    sensitivity: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        if not self.time_constant > 0:
            raise InputError(f"node {self.name}: time constant {self.time_constant} s must be > 0")
        if len(self.sensitivity) != 5:
            raise InputError(f"node {self.name}: 5 sensitivities (X, Y, Z, A, B) needed")


@dataclass(frozen=True)
class ThermalAxis:
    """A linear axis whose screw grows with a node's temperature.

    Attributes
    ----------
    name : str
    travel : tuple of float, m
    screw_node : str
        The node whose temperature is the screw's.
    alpha : float, 1/K
        Expansion coefficient of the screw (steel about 11.5e-6).
    fixed_end : float, m
        Position of the screw's fixed bearing, where its growth is zero.
    offset : float, m/K
        Position-independent shift of the axis per kelvin of the screw node above 20 °C (the
        nut's bearing block and the motor flange growing), added to the structure's.
    """

    name: str
    travel: tuple[float, float]
    screw_node: str
    alpha: float = 11.5e-6
    fixed_end: float = 0.0
    offset: float = 0.0


@dataclass(frozen=True)
class TemperatureSensor:
    """A temperature sensor on a node (or the room) with white noise and a fixed offset.

    Attributes
    ----------
    name : str
        Column name in the log (``T_spindle``).
    node : str
        ``"room"`` or a node name.
    noise : float, K
        Standard deviation of one reading.
    offset : float, K
        Calibration error of the sensor (constant).
    lag : float, s
        Time constant through which the sensor sees its node (a sensor on a housing's surface
        sees the bearings late); 0 reads the node itself.
    """

    name: str
    node: str
    noise: float = 0.0
    offset: float = 0.0
    lag: float = 0.0


@dataclass(frozen=True)
class ThermalHistory:
    """The twin's truth over a time grid (never written into a log: simulation reports only).

    Attributes
    ----------
    time : ndarray, s
    room : ndarray, °C
    nodes : dict of str to ndarray, °C
    displacement : ndarray, shape (n, 5)
        X, Y, Z in m and A, B in rad at the tool's reference point.
    """

    time: np.ndarray
    room: np.ndarray
    nodes: dict[str, np.ndarray]
    displacement: np.ndarray

    def temperature(self, node: str) -> np.ndarray:
        """A node's (or ``"room"``'s) temperature, °C."""
        return self.room if node == "room" else self.nodes[node]


@dataclass(frozen=True)
class ThermalTwin:
    """A machine's thermal behaviour (see the module docstring).

    Examples
    --------
    >>> twin = ThermalTwin(nodes=(ThermalNode("spindle", 1800.0, heat="spindle", rise=10.0,
    ...                                       sensitivity=(0, 0, -1e-6, 0, 0)),))
    >>> h = twin.run(np.arange(0, 36_001, 60.0), spindle=np.ones(601))
    >>> round(float(h.nodes["spindle"][-1]), 3)          # 20 °C + 10 K (1 - e^-20)
    30.0
    >>> round(float(h.displacement[-1, 2]) * 1e6, 3)      # -1 µm/K × 10 K, in µm
    -10.0
    """

    room: Room = Room()
    nodes: tuple[ThermalNode, ...] = ()
    axes: tuple[ThermalAxis, ...] = ()
    sensors: tuple[TemperatureSensor, ...] = ()
    displacement_noise: float = 0.0
    start_at_equilibrium: bool = True
    meta: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        known = {"room"}
        for n in self.nodes:
            if n.name in known:
                raise InputError(f"node {one_line(repr(n.name), 60)} is named twice (or is called 'room')")
            if n.follows not in known:
                raise InputError(f"node {n.name}: follows {one_line(repr(n.follows), 60)}, which is not the room or "
                                 "an earlier node")
            if n.heat not in ("none", "spindle", "rotary") and not n.heat.startswith("axis:"):
                raise InputError(f"node {n.name}: heat {one_line(repr(n.heat), 60)}; use none, "
                                 "spindle, rotary or axis:NAME")
            known.add(n.name)
        for a in self.axes:
            if a.screw_node not in known:
                raise InputError(f"axis {a.name}: screw node {one_line(repr(a.screw_node), 60)} is not a node")
        for s in self.sensors:
            if s.node not in known:
                raise InputError(f"sensor {s.name}: node {one_line(repr(s.node), 60)} is not a node or the room")

    def axis(self, name: str) -> ThermalAxis:
        """The axis named ``name``."""
        for a in self.axes:
            if a.name.upper() == name.upper():
                return a
        raise InputError(f"axis {one_line(repr(name), 60)}: the twin has {', '.join(a.name for a in self.axes) or 'no axes'}")

    def heats(self, source: str) -> bool:
        """Whether a node is heated by ``source`` (``"spindle"``, ``"rotary"``)."""
        return any(n.heat == source for n in self.nodes)

    def run(self, time, spindle=None, axes=None, rotary=None) -> ThermalHistory:
        """Temperatures and displacement over ``time`` for the given loads.

        Parameters
        ----------
        time : array_like, s
            Increasing sample times; loads are held from one sample to the next.
        spindle : array_like, optional
            Spindle speed as a fraction of its maximum, one per sample (0 if omitted).
        axes : dict of str to array_like, optional
            Each axis's share of time in motion (0 to 1), one per sample.
        rotary : array_like, optional
            A rotary table's speed as a fraction of its maximum, one per sample (0 if omitted).

        Returns
        -------
        ThermalHistory
        """
        t = np.asarray(time, dtype=float)
        if t.ndim != 1 or t.size < 1 or np.any(np.diff(t) <= 0):
            raise InputError("twin: time must be a 1-D increasing array")
        load = {"none": np.zeros_like(t), "spindle": _load(spindle, t, "spindle"),
                "rotary": _load(rotary, t, "rotary table")}
        for name, u in (axes or {}).items():
            load[f"axis:{name.upper()}"] = _load(u, t, f"axis {name}")
        room = self.room.temperature(t)
        temps: dict[str, np.ndarray] = {"room": room}
        for n in self.nodes:
            u = load.get("axis:" + n.heat[5:].upper() if n.heat.startswith("axis:") else n.heat)
            if u is None:
                u = np.zeros_like(t)
            drive = temps[n.follows] + n.rise * u
            start = temps[n.follows][0] if self.start_at_equilibrium else REFERENCE_C
            temps[n.name] = _first_order(drive, t, n.time_constant, start)
        d = np.zeros((t.size, 5))
        for n in self.nodes:
            d += np.outer(temps[n.name] - REFERENCE_C, n.sensitivity)
        return ThermalHistory(t, room, {n.name: temps[n.name] for n in self.nodes}, d)

    def positioning_error(self, history: ThermalHistory, axis: str, position) -> np.ndarray:
        """The axis's thermal positioning error at ``position`` (m) over the history, m.

        ``e(P, t) = d_axis(t) + (c + α (P − P_fixed)) (T_screw(t) − 20 °C)`` (module Notes); an axis
        named other than X, Y or Z has no structural translation.
        """
        a = self.axis(axis)
        p = np.asarray(position, dtype=float)
        k = DIRECTIONS.index(a.name.upper()) if a.name.upper() in "XYZ" else None
        base = history.displacement[:, k] if k is not None else np.zeros(history.time.size)
        growth = a.alpha * (history.temperature(a.screw_node) - REFERENCE_C)
        dt = history.temperature(a.screw_node) - REFERENCE_C
        base = base + a.offset * dt
        out = base[:, None] + growth[:, None] * (np.atleast_1d(p) - a.fixed_end)[None, :]
        return out if p.ndim else out[:, 0]

    def read_temperatures(self, history: ThermalHistory, rng: np.random.Generator | None):
        """Each sensor's readings over the history, °C (noise drawn from ``rng``)."""
        out = {}
        for s in self.sensors:
            v = history.temperature(s.node)
            if s.lag > 0:
                v = _first_order(v, history.time, s.lag, float(v[0]))
            v = v + s.offset
            if rng is not None and s.noise > 0:
                v = v + rng.normal(0.0, s.noise, v.shape)
            out[s.name] = v
        return out


def _load(u, t: np.ndarray, what: str) -> np.ndarray:
    if u is None:
        return np.zeros_like(t)
    a = np.broadcast_to(np.asarray(u, dtype=float), t.shape).copy()
    if not np.all(np.isfinite(a)) or np.any(a < 0) or np.any(a > 1):
        raise InputError(f"twin: the {what} load must be between 0 and 1")
    return a


def _first_order(drive: np.ndarray, t: np.ndarray, tau: float, start: float) -> np.ndarray:
    """Exact zero-order-hold response of τ dT/dt = drive − T on the grid ``t`` from ``start``."""
    out = np.empty_like(drive)
    out[0] = start
    decay = np.exp(-np.diff(t) / tau)
    x = out[0]
    for k in range(t.size - 1):
        x = drive[k] + (x - drive[k]) * decay[k]
        out[k + 1] = x
    return out
