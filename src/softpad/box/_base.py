"""The pneumatic box interface (seed, Section 6.1.1: the "Pneumaticbox").

A box has ``channels`` pneumatic channels, each with an inflation valve, a deflation valve
and a differential (gauge) pressure sensor, plus one supply-pressure sensor shared by all
channels. Software reads timestamped frames and commands each channel's valves.
"""

from __future__ import annotations

import enum
import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass
from types import TracebackType

import numpy as np
from numpy.typing import NDArray

from softpad.box._safety import SafetyGuard, SafetyLimits
from softpad.errors import HardwareFault, InputError

#: Requests a box with a simulated world behind it answers (``ext/OP`` of a served box):
#: set up the gripper mounting (reply: the pad's layout) and place catalogue objects.
WORLD_SERVICES = ("sim.setup", "sim.place")


class ConnectionLost(HardwareFault):
    """The box stopped answering (network down, box powered off)."""


class ValveCommand(enum.Enum):
    """State commanded to one channel's pair of valves."""

    CLOSED = "closed"
    """Both valves closed: the module is sealed."""
    INFLATE = "inflate"
    """Inflation valve open (to the supply), deflation valve closed."""
    DEFLATE = "deflate"
    """Deflation valve open (to the atmosphere), inflation valve closed."""

    @classmethod
    def parse(cls, value: ValveCommand | str) -> ValveCommand:
        """Accept a member or its name/value (``"inflate"``), else raise InputError."""
        if isinstance(value, cls):
            return value
        try:
            return cls(str(value).lower())
        except ValueError:
            raise InputError(
                f"valve command must be one of {', '.join(c.value for c in cls)}, got {value!r}"
            ) from None


@dataclass(frozen=True, slots=True)
class PressureFrame:
    """One reading of the box.

    Attributes
    ----------
    t_s
        Time stamp, seconds since the box was opened (virtual time in simulation).
    pressures_pa
        Gauge pressure of every channel, pascals, shape (channels,); channel k is index k-1.
        NaN marks a channel whose sensor gave no valid value.
    supply_pa
        Gauge pressure of the shared supply, pascals.
    """

    t_s: float
    pressures_pa: NDArray[np.float64]
    supply_pa: float

    def __post_init__(self) -> None:
        if not math.isfinite(self.t_s):
            raise InputError(
                f"frame time stamp t_s must be a finite number of seconds, got {self.t_s!r}"
            )
        if getattr(self.pressures_pa, "ndim", None) != 1:
            raise InputError("frame pressures_pa must be a 1-D array, one value per channel")

    @property
    def channels(self) -> int:
        """Number of channels in the frame."""
        return int(self.pressures_pa.shape[0])

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict with pressures in kPa (the CLI's edge unit)."""
        return {
            "t_s": round(self.t_s, 6),
            "pressures_kpa": [
                None if not np.isfinite(p) else round(float(p) / 1e3, 5) for p in self.pressures_pa
            ],
            "supply_kpa": round(self.supply_pa / 1e3, 4) if np.isfinite(self.supply_pa) else None,
        }


# PressureFrame's slots, set directly: a frame without the constructor's checks
_SET_T, _SET_P, _SET_S = (
    getattr(PressureFrame, n).__set__ for n in ("t_s", "pressures_pa", "supply_pa")
)


def unchecked_frame(
    t_s: float, pressures_pa: NDArray[np.float64], supply_pa: float
) -> PressureFrame:
    """A :class:`PressureFrame` from a producer that guarantees what the constructor checks (a
    finite ``t_s``, a 1-D array): the simulated box's hot path, about half the constructor's
    cost."""
    frame = object.__new__(PressureFrame)
    _SET_T(frame, t_s)
    _SET_P(frame, pressures_pa)
    _SET_S(frame, supply_pa)
    return frame


class Box(ABC):
    """Abstract pneumatic box. Back-ends subclass it; :func:`softpad.box.open_box` picks one.

    Subclasses implement :attr:`channels`, :attr:`sample_rate_hz`, :meth:`_read`,
    :meth:`_apply_valve` and :meth:`_close`; the base class validates arguments, tracks the
    commanded valve states, enforces the safety limits (:class:`~softpad.box.SafetyGuard`:
    every frame read is checked, an over-pressure or invalid channel is vented and refuses
    inflate commands until it is below the release level) and gives the context-manager
    protocol. Every back-end must pass
    :func:`softpad.box.check_conformance`.
    """

    def __init__(self) -> None:
        self._closed = False
        self._valves: list[ValveCommand] | None = None
        self._guard: SafetyGuard | None = None
        self._limits = SafetyLimits()

    # --- to implement ---------------------------------------------------------------
    @property
    @abstractmethod
    def channels(self) -> int:
        """Number of pneumatic channels."""

    @property
    @abstractmethod
    def sample_rate_hz(self) -> float:
        """Frames per second delivered by :meth:`read`, hertz."""

    @abstractmethod
    def _read(self) -> PressureFrame:
        """Return the next frame (blocking until it is due)."""

    @abstractmethod
    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        """Drive the valves of ``channel`` (1-based)."""

    @abstractmethod
    def _close(self) -> None:
        """Release the back-end's resources (valves are already closed)."""

    # --- public API -----------------------------------------------------------------
    @property
    def command_seen_after_s(self) -> float | None:
        """Box time after which frames show the last valve command, seconds; None: from the
        next frame read. A remote box answers a command with the time of the last frame its
        daemon had sampled, so that frames already on their way (a busy link) are not taken
        as the command's effect."""
        return None

    @property
    def supply_sensor(self) -> bool:
        """True when the box measures its supply pressure (a box without one reports 0 Pa,
        and supply-loss checks must not judge it)."""
        return True

    @property
    def simulated(self) -> bool:
        """True when a simulated world stands behind this box: a simulator in this process
        (``sim://``, any view of it) or one served with the world's requests
        (:data:`WORLD_SERVICES`). The one answer to "is this box simulated?"; a real box
        answers False."""
        return False

    @property
    def closed(self) -> bool:
        """True after :meth:`close`."""
        return self._closed

    @property
    def valves(self) -> tuple[ValveCommand, ...]:
        """Last commanded state of every channel's valves."""
        if self._valves is None:
            self._valves = [ValveCommand.CLOSED] * self.channels
        return tuple(self._valves)

    @property
    def safety(self) -> SafetyGuard:
        """The box-side safety guard (limits, tripped channels, trip history)."""
        if self._guard is None:
            self._guard = SafetyGuard(self.channels, self._limits)
        return self._guard

    @property
    def safety_limits(self) -> SafetyLimits:
        """Limits enforced on every channel (settable; a new guard starts untripped)."""
        return self._limits

    @safety_limits.setter
    def safety_limits(self, limits: SafetyLimits) -> None:
        if not isinstance(limits, SafetyLimits):
            raise InputError(f"safety limits must be a SafetyLimits, got {limits!r}")
        self._limits = limits
        self._guard = None

    def _check_open(self) -> None:
        if self._closed:
            raise InputError("the box is closed")

    def check_channel(self, channel: int) -> int:
        """Return ``channel`` if it is a valid 1-based channel number, else raise InputError."""
        if (
            isinstance(channel, bool)
            or not isinstance(channel, int | np.integer)
            or not 1 <= channel <= self.channels
        ):
            raise InputError(
                f"channel must be an integer from 1 to {self.channels}, got {channel!r}"
            )
        return int(channel)

    def read(self) -> PressureFrame:
        """Read one frame: every channel's gauge pressure and the supply pressure."""
        self._check_open()
        frame = self._read()
        for ch in self.safety.check(frame.t_s, frame.pressures_pa):
            self._vent(ch)
        return frame

    def _vent(self, channel: int) -> None:
        """Open the deflation valve of a tripped channel (inflation closed)."""
        if self._valves is None:
            self._valves = [ValveCommand.CLOSED] * self.channels
        self._apply_valve(channel, ValveCommand.DEFLATE)
        self._valves[channel - 1] = ValveCommand.DEFLATE

    def read_many(self, n: int) -> list[PressureFrame]:
        """Read ``n`` consecutive frames."""
        if not isinstance(n, int) or n < 0:
            raise InputError(f"number of frames must be an integer >= 0, got {n!r}")
        return [self.read() for _ in range(n)]

    def set_valve(self, channel: int, command: ValveCommand | str) -> None:
        """Command the valves of one channel (1-based).

        Raises
        ------
        SafetyTrip
            ``inflate`` on a tripped channel (over the trip level or invalid reading, not yet
            below the release level). Other commands on a tripped channel leave it venting.
        """
        self._check_open()
        ch = self.check_channel(channel)
        cmd = ValveCommand.parse(command)
        if self._valves is None:
            self._valves = [ValveCommand.CLOSED] * self.channels
        guard = self.safety
        if guard.tripped[ch - 1]:
            if cmd is ValveCommand.INFLATE:
                raise guard.refuse_inflate(ch)
            cmd = ValveCommand.DEFLATE
        self._apply_valve(ch, cmd)
        self._valves[ch - 1] = cmd

    def set_valves(self, commands: Sequence[ValveCommand | str]) -> None:
        """Command every channel at once (one command per channel, channel order)."""
        if len(commands) != self.channels:
            raise InputError(
                f"need {self.channels} valve commands (one per channel), got {len(commands)}"
            )
        parsed = [ValveCommand.parse(c) for c in commands]
        for ch, cmd in enumerate(parsed, start=1):
            self.set_valve(ch, cmd)

    def close_valves(self) -> None:
        """Close every valve (the safe state: no air in or out)."""
        if not self._closed:
            for ch in range(1, self.channels + 1):
                self.set_valve(ch, ValveCommand.CLOSED)

    def close_inflation(self) -> None:
        """The safe state nothing undoes: close every inflation valve and leave every channel
        being vented venting (a channel the safe state or the guard vented may have a stuck
        inflation valve: sealing it again would let the supply fill it, issue 35)."""
        if not self._closed:
            for ch, cmd in enumerate(self.valves, start=1):
                if cmd is ValveCommand.INFLATE:
                    self.set_valve(ch, ValveCommand.CLOSED)

    def close(self) -> None:
        """Close every inflation valve (vented channels keep venting: :meth:`close_inflation`)
        and release the box; further reads raise. Idempotent."""
        if self._closed:
            return
        try:
            self.close_inflation()
        finally:
            self._closed = True
            self._close()

    def __enter__(self) -> Box:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()
