"""A box that forwards to another: the base of views that add something around a box."""

from __future__ import annotations

from softpad.box._base import Box, PressureFrame, ValveCommand


class BoxWrapper(Box):
    """A :class:`Box` that forwards everything to ``inner``: channels, rate, frames, valve
    commands and valve states.

    Subclasses override what they add (a hook around each read, an event per valve command).
    The wrapper's own safety guard checks the frames it passes on, as on any box.

    Parameters
    ----------
    inner
        The wrapped box.
    owns_inner
        Closing the wrapper closes ``inner`` (default); False for a view of a box that its
        caller closes.
    """

    def __init__(self, inner: Box, owns_inner: bool = True) -> None:
        super().__init__()
        self.inner = inner
        self.owns_inner = owns_inner

    @property
    def channels(self) -> int:
        return self.inner.channels

    @property
    def sample_rate_hz(self) -> float:
        return self.inner.sample_rate_hz

    @property
    def supply_sensor(self) -> bool:
        return self.inner.supply_sensor

    @property
    def simulated(self) -> bool:
        return self.inner.simulated

    @property
    def command_seen_after_s(self) -> float | None:
        return self.inner.command_seen_after_s

    @property
    def valves(self) -> tuple[ValveCommand, ...]:
        """The wrapped box's valve states (its safety guard may vent a channel)."""
        return self.inner.valves

    def _read(self) -> PressureFrame:
        return self.inner.read()

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        self.inner.set_valve(channel, command)

    def _close(self) -> None:
        if self.owns_inner:
            self.inner.close()
