"""Send a run's frames and events to several recorders at once."""

from __future__ import annotations

from typing import Any

from softpad.box import PressureFrame


class Tee:
    """A ``softpad.control.Recorder`` that forwards every frame and event to ``recorders``.

    ``None`` entries are skipped, so optional recorders can be passed as they are.
    """

    def __init__(self, *recorders: Any) -> None:
        self.recorders = [r for r in recorders if r is not None]

    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Forward one frame."""
        for r in self.recorders:
            r.frame(frame, phase)

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Forward one event."""
        for r in self.recorders:
            r.event(t_s, kind, **data)
