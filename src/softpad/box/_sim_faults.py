"""Faults of the simulated box: what they are, how they are written, when they start.

Physical faults (``stuck``, ``leak``, ``supply_loss``) change the gas physics of the plain
:class:`~softpad.box.SimBox`; sensor faults (``nan``, ``dropout``) and the lost link
(``disconnect``) are layers around it (:mod:`softpad.box._sim_layers`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from softpad.box._base import ValveCommand
from softpad.errors import InputError

#: Fault kinds the simulated box can inject.
FAULT_KINDS = ("nan", "dropout", "stuck", "leak", "supply_loss", "disconnect")

#: Faults of the physics (the plain box), of the sensors' readings, of the link.
PHYSICAL_FAULTS = ("stuck", "leak", "supply_loss")
SENSOR_FAULTS = ("nan", "dropout")
LINK_FAULTS = ("disconnect",)

#: Default leak effective area (Cd A) when a leak is given without size, m^2.
DEFAULT_LEAK_M2 = 1.0e-8


@dataclass(frozen=True)
class Fault:
    """A fault injected into the simulated box.

    Parameters
    ----------
    kind
        ``"nan"`` (sensor reads NaN), ``"dropout"`` (sensor wire broken: reads its lower rail),
        ``"stuck"`` (valves stuck in state ``arg``: closed/inflate/deflate), ``"leak"`` (an
        orifice to atmosphere of ``Cd A = arg`` m^2), ``"supply_loss"`` (supply drops to 0),
        ``"disconnect"`` (the box stops answering: reads and valve commands raise
        :class:`ConnectionLost`; its physics and its own safety guard go on with every read
        tried, and the valves stay as they were).
    channel
        1-based channel for channel faults, None for box-wide ones.
    at_s
        Virtual time at which the fault starts, seconds.
    arg
        Stuck state (str) or leak area (float, m^2).
    """

    kind: str
    channel: int | None = None
    at_s: float = 0.0
    arg: str | float | None = None

    def __post_init__(self) -> None:
        if self.kind not in FAULT_KINDS:
            raise InputError(f"unknown fault {self.kind!r}; known faults: {', '.join(FAULT_KINDS)}")
        if self.kind in ("nan", "dropout", "stuck", "leak") and self.channel is None:
            raise InputError(f"fault {self.kind!r} needs a channel")
        if not math.isfinite(self.at_s) or self.at_s < 0:
            raise InputError(f"fault time must be >= 0 s, got {self.at_s!r}")
        if self.kind == "stuck":
            ValveCommand.parse(str(self.arg))
        if self.kind == "leak" and self.arg is not None:
            a = float(self.arg)  # type: ignore[arg-type]
            if not (math.isfinite(a) and 0 < a <= 1e-5):
                raise InputError(f"leak area must be > 0 and at most 10 mm^2, got {a * 1e6:g} mm^2")

    @classmethod
    def parse(cls, text: str) -> Fault:
        """Parse ``KIND[:CHANNEL[:ARG]][@T_S]``, e.g. ``stuck:3:inflate@2``, ``leak:2:0.02``
        (leak area in mm^2), ``supply_loss@5``."""
        spec, _, at = text.partition("@")
        fields = spec.split(":")
        kind = fields[0].strip()
        try:
            at_s = float(at) if at else 0.0
            if kind in ("supply_loss", "disconnect"):
                if len(fields) > 1:
                    raise ValueError
                return cls(kind, None, at_s)
            channel = int(fields[1]) if len(fields) > 1 else None
            arg: str | float | None = None
            if kind == "stuck":
                arg = fields[2] if len(fields) > 2 else "inflate"
            elif kind == "leak":
                arg = float(fields[2]) * 1e-6 if len(fields) > 2 else DEFAULT_LEAK_M2
            elif len(fields) > 2:
                raise ValueError
        except ValueError:
            raise InputError(
                f"malformed fault {text!r}; use KIND[:CHANNEL[:ARG]][@T_S], e.g. stuck:3:inflate@2"
            ) from None
        return cls(kind, channel, at_s, arg)


class FaultSchedule:
    """Faults waiting for their time, started by the frame whose time reaches theirs.

    A frame at ``t`` starts every fault with ``at_s <= t + 1e-12`` once ``t`` has reached the
    earliest waiting ``at_s`` (:attr:`next_s`); a fault injected at or before the last frame's
    time starts at once.
    """

    def __init__(self) -> None:
        self.waiting: list[Fault] = []
        #: Time of the earliest waiting fault, seconds (inf: none).
        self.next_s = math.inf

    def add(self, fault: Fault) -> None:
        """Schedule ``fault``."""
        self.waiting.append(fault)
        self.next_s = min(self.next_s, fault.at_s)

    def due(self, t_s: float) -> list[Fault]:
        """Remove and return the faults that start by ``t_s``, in the order they were added."""
        now = [f for f in self.waiting if f.at_s <= t_s + 1e-12]
        self.waiting = [f for f in self.waiting if f.at_s > t_s + 1e-12]
        self.next_s = min((f.at_s for f in self.waiting), default=math.inf)
        return now
