"""The layers of the simulated box: what acts on its readings, its link and its pace.

``sim://`` composes them around the plain physical :class:`~softpad.box.SimBox`, innermost
first (:func:`compose_sim_box`):

1. :class:`SensorZeroShift` (with the slow disturbances only): the sensors' thermal zero shift,
   driven by the room temperature the gas feels too;
2. :class:`SensorFaults`: ``nan`` and ``dropout`` faults of single sensors;
3. :class:`Unreachable`: the ``disconnect`` fault, the link lost (the box's physics and its own
   guard go on, nothing reaches the client);
4. :class:`WallClock` (``realtime=1`` only): each read waits for its virtual time.

The order is that of the box before the layers were split out of it (zero shift, then the
sensor faults on the shifted readings, then the guard of a lost box on those, then pacing for
what reached the client), so frames, messages and exceptions are the same, bit for bit.

The layers are one box: the plain box's safety guard checks what the outermost layer passes
on, once per frame (a layer reads the next one in without a guard of its own), and valve
states are tracked by the plain box. What a layer does not define (``world``,
``true_pressures_pa``, ``time_s``, ``inject_fault``...) is the next layer's, so the outermost
layer reads like the plain box; :func:`simulator_of` finds the plain box behind any wrappers.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand, unchecked_frame
from softpad.box._safety import SafetyGuard, SafetyLimits
from softpad.box._sim import SimBox
from softpad.box._sim_faults import LINK_FAULTS, SENSOR_FAULTS, Fault, FaultSchedule
from softpad.box._wrapper import BoxWrapper

if TYPE_CHECKING:
    from softpad.sim import Disturbances


class SimLayer(BoxWrapper):
    """A layer around the simulated box (module docstring): one guard, one set of valve
    states (the plain box's), everything else read through from the next layer in."""

    inner: SimBox | SimLayer

    def __init__(self, inner: SimBox | SimLayer) -> None:
        super().__init__(inner)
        self._plain: SimBox = inner if isinstance(inner, SimBox) else inner._plain
        self._blocked = False

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__") or name == "inner":
            raise AttributeError(name)
        return getattr(self.inner, name)

    @property
    def safety(self) -> SafetyGuard:
        """The plain box's guard: it checks the frames the outermost layer passes on."""
        return self._plain.safety

    @property
    def safety_limits(self) -> SafetyLimits:
        return self._plain.safety_limits

    @safety_limits.setter
    def safety_limits(self, limits: SafetyLimits) -> None:
        self._plain.safety_limits = limits

    def _read(self) -> PressureFrame:
        return self.inner._read()  # the guard checks the outermost layer's frame only

    def read(self) -> PressureFrame:
        """Read one frame. While every layer passes the frames on unchanged (no fault of
        theirs waiting or acting: :meth:`_passes_through`), the plain box reads the frame and
        checks it with its guard, the layers' guard, itself: the same frame, trips and vents
        without a call through every layer.

        Whether they do is kept on the plain box (``_passed_by``: the outermost layer found
        passing) until a fault is injected into a layer; a layer that stops passing frames on
        (its faults waiting or started) never passes them on again, so ``_blocked`` stays.
        Meanwhile this layer's ``read`` is the plain box's own (an attribute of this layer,
        removed with ``_passed_by``: no call through this method on every frame), unless
        ``read`` was set on this layer by someone else (a wrapper's): that one is kept."""
        plain = self._plain
        if plain._passed_by is self:
            return plain.read()
        if self._blocked or not self._passes_through():
            self._blocked = True
            return super().read()
        plain._passed_by = self
        self.__dict__.setdefault("read", plain.read)
        return plain.read()

    def _stop_passing(self) -> None:
        """A fault was injected into a layer: the layers read the frames again."""
        plain = self._plain
        passed_by = plain._passed_by
        if isinstance(passed_by, SimLayer) and passed_by.__dict__.get("read") == plain.read:
            del passed_by.__dict__["read"]
        plain._passed_by = None

    def _passes_through(self) -> bool:
        """Whether this layer and those within pass every frame on as it is, and will until
        a fault is injected into one of them."""
        return False

    def close_valves(self) -> None:
        if not self.closed:
            self.inner.close_valves()

    def close_inflation(self) -> None:
        if not self.closed:
            self.inner.close_inflation()

    def _close(self) -> None:
        # the valve step ran through every layer from the outermost (close_inflation):
        # the layers within are released without one of their own
        inner = self.inner
        inner._closed = True
        inner._close()

    def inject_fault(self, fault: Fault) -> None:
        """Schedule ``fault`` in the layer that takes its kind (the plain box: physical)."""
        self.inner.inject_fault(fault)


class _FaultLayer(SimLayer):
    """A layer that starts its own kinds of fault when the frames' time reaches theirs."""

    kinds: tuple[str, ...] = ()

    def __init__(self, inner: SimBox | SimLayer) -> None:
        super().__init__(inner)
        self._faults = FaultSchedule()

    def inject_fault(self, fault: Fault) -> None:
        if fault.kind not in self.kinds:
            self.inner.inject_fault(fault)
            return
        self._stop_passing()  # this layer no longer passes every frame on
        if fault.channel is not None:
            self.check_channel(fault.channel)
        self._faults.add(fault)
        now = self.time_s
        if fault.at_s <= now:
            self._start(self._faults.due(now))

    def _start(self, faults: list[Fault]) -> None:
        raise NotImplementedError

    def _acting(self) -> bool:
        """Whether one of this layer's faults has started."""
        raise NotImplementedError

    def _passes_through(self) -> bool:
        inner = self.inner
        return (
            not self._acting()
            and self._faults.next_s == math.inf
            and (isinstance(inner, SimBox) or inner._passes_through())
        )


class SensorZeroShift(SimLayer):
    """The sensors' thermal zero shift: ``tempco x (T - T_room)`` added to every reading, the
    room temperature ``T`` being the one the plain box's slow disturbances give the gas."""

    def __init__(self, inner: SimBox | SimLayer, room: Disturbances) -> None:
        super().__init__(inner)
        self.room = room
        self._at: float | None = None
        self._shift_pa: NDArray[np.float64] = np.zeros(inner.channels)

    def _read(self) -> PressureFrame:
        frame = self.inner._read()
        room = self.room
        if room.last_s != self._at:  # the temperature moves at the disturbances' updates
            self._shift_pa, self._at = room.sensor_shift_pa(), room.last_s
        return unchecked_frame(frame.t_s, frame.pressures_pa + self._shift_pa, frame.supply_pa)


class SensorFaults(_FaultLayer):
    """``nan`` (the sensor gives no valid value) and ``dropout`` (its wire broken: it reads
    its lower rail ``lower_rail_pa``) faults of single sensors."""

    kinds = SENSOR_FAULTS

    def __init__(self, inner: SimBox | SimLayer, lower_rail_pa: float) -> None:
        super().__init__(inner)
        self.lower_rail_pa = lower_rail_pa
        self._nan = np.zeros(inner.channels, dtype=bool)
        self._dropout = np.zeros(inner.channels, dtype=bool)
        self._bad = False

    def _start(self, faults: list[Fault]) -> None:
        for f in faults:
            assert f.channel is not None
            (self._nan if f.kind == "nan" else self._dropout)[f.channel - 1] = True
            self._bad = True

    def _acting(self) -> bool:
        return self._bad

    def _read(self) -> PressureFrame:
        frame = self.inner._read()
        if frame.t_s >= self._faults.next_s:
            self._start(self._faults.due(frame.t_s))
        if not self._bad:
            return frame
        values = frame.pressures_pa.copy()
        values[self._dropout] = self.lower_rail_pa
        values[self._nan] = np.nan
        return unchecked_frame(frame.t_s, values, frame.supply_pa)


class Unreachable(_FaultLayer):
    """The ``disconnect`` fault: the box stops answering. Reads and valve commands raise
    :class:`~softpad.box.ConnectionLost`; the box's physics and its own guard go on with every
    read tried (its firmware vents an over-pressure whatever the link does), and the valves
    stay as they were (closing them cannot reach the box)."""

    kinds = LINK_FAULTS

    def __init__(self, inner: SimBox | SimLayer) -> None:
        super().__init__(inner)
        self.disconnected = False

    def _start(self, faults: list[Fault]) -> None:
        self.disconnected = self.disconnected or bool(faults)

    def _acting(self) -> bool:
        return self.disconnected

    def _read(self) -> PressureFrame:
        frame = self.inner._read()
        if frame.t_s >= self._faults.next_s:
            self._start(self._faults.due(frame.t_s))
        if self.disconnected:
            for ch in self.safety.check(frame.t_s, frame.pressures_pa):
                self._plain.firmware_vent(ch)
            raise ConnectionLost(f"the simulated box stopped answering at t = {frame.t_s:.3f} s")
        return frame

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        if self.disconnected:
            raise ConnectionLost(
                f"the simulated box stopped answering at t = {self.time_s:.3f} s: "
                f"channel {channel} not commanded"
            )
        super()._apply_valve(channel, command)

    def close_valves(self) -> None:
        """Close every valve; a disconnected box cannot be reached (its valves stay as they are)."""
        if not self.disconnected:
            super().close_valves()

    def close_inflation(self) -> None:
        """Close inflation; a disconnected box cannot be reached (its valves stay as they are)."""
        if not self.disconnected:
            super().close_inflation()


class WallClock(SimLayer):
    """Real-time pacing: each read returns when its virtual time has come on the wall clock
    (``time.perf_counter``, from the first frame on)."""

    def __init__(self, inner: SimBox | SimLayer) -> None:
        super().__init__(inner)
        self._wall0: float | None = None

    def _read(self) -> PressureFrame:
        frame = self.inner._read()
        t, now = frame.t_s, time.perf_counter()
        if self._wall0 is None:
            self._wall0 = now - t
        wait = self._wall0 + t - now
        if wait > 0:
            time.sleep(wait)
        return frame


def compose_sim_box(box: SimBox, realtime: bool = False) -> SimLayer:
    """The layers of ``sim://`` around the plain ``box``, in their order (module docstring):
    the zero shift when ``box`` has slow disturbances, the sensor faults, the lost link, and
    the wall clock when ``realtime``. Faults of every kind can then be injected.

    Parameters
    ----------
    box
        The plain simulated box.
    realtime
        Pace the frames on the wall clock.
    """
    layer: SimBox | SimLayer = box
    if box.disturbances is not None:
        layer = SensorZeroShift(layer, box.disturbances)
    layer = Unreachable(SensorFaults(layer, box.sensor_params.range_min_pa))
    return WallClock(layer) if realtime else layer


def simulator_of(box: Box) -> SimBox | None:
    """The plain simulated box behind ``box`` and any :class:`~softpad.box.BoxWrapper` views
    or layers around it, in this process.

    Parameters
    ----------
    box
        Any box.

    Returns
    -------
    SimBox or None
        None for a box with no simulator in this process (:attr:`Box.simulated` answers
        whether a simulated world stands behind a box at all, served ones included).
    """
    while isinstance(box, BoxWrapper):
        box = box.inner
    return box if isinstance(box, SimBox) else None


__all__ = [
    "SensorFaults",
    "SensorZeroShift",
    "SimLayer",
    "Unreachable",
    "WallClock",
    "compose_sim_box",
    "simulator_of",
]
