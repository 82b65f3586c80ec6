"""Run log: every frame and event of a run kept in memory, plotted like Fig. 6.8.

A :class:`RunLog` is the in-memory recorder of :class:`softpad.control.GraspExecution`: it
appends each frame and event the moment it arrives, so when a run stops on a fault nothing
already logged is lost. Files are written by :class:`softpad.record.McapRecorder`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from softpad.box import PressureFrame

if TYPE_CHECKING:
    from softpad.record._read import RecordedRun


class RunLog:
    """Frames and events of one run (implements the ``softpad.control.Recorder`` hook).

    Attributes
    ----------
    events
        ``(t_s, kind, data)`` in arrival order; kinds include ``phase``, ``adjusted``,
        ``reference``, ``object_seen``, ``plan``, ``contact``, ``no_contact``,
        ``retry``, ``outcome``, ``carried``, ``fault``.
    meta
        Free JSON-ready facts about the run (box URL, objects...).
    """

    def __init__(self, meta: dict[str, Any] | None = None) -> None:
        self._t: list[float] = []
        self._p: list[NDArray[np.float64]] = []
        self._s: list[float] = []
        self._ph: list[str] = []
        self.events: list[tuple[float, str, dict[str, Any]]] = []
        self.meta: dict[str, Any] = dict(meta or {})

    # --- Recorder hook --------------------------------------------------------------
    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Append one frame read during ``phase``."""
        self._t.append(frame.t_s)
        self._p.append(np.array(frame.pressures_pa, dtype=float))
        self._s.append(frame.supply_pa)
        self._ph.append(phase)

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Append an event."""
        self.events.append((float(t_s), kind, _jsonable(data)))

    # --- access ---------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self._t)

    @property
    def t_s(self) -> NDArray[np.float64]:
        """Frame times, seconds, shape (n,)."""
        return np.asarray(self._t, dtype=float)

    @property
    def pressures_pa(self) -> NDArray[np.float64]:
        """Channel pressures, pascals, shape (n, channels)."""
        if not self._p:
            return np.zeros((0, 0))
        return np.vstack(self._p)

    @property
    def supply_pa(self) -> NDArray[np.float64]:
        """Supply pressure, pascals, shape (n,)."""
        return np.asarray(self._s, dtype=float)

    @property
    def phases(self) -> list[str]:
        """Phase of each frame."""
        return list(self._ph)

    def phase_spans(self) -> list[tuple[str, float, float]]:
        """(phase, start s, end s) of consecutive runs of frames in the same phase."""
        spans: list[tuple[str, float, float]] = []
        for t, ph in zip(self._t, self._ph, strict=True):
            if spans and spans[-1][0] == ph:
                spans[-1] = (ph, spans[-1][1], t)
            else:
                spans.append((ph, t, t))
        return spans

    def events_of(self, kind: str) -> list[tuple[float, dict[str, Any]]]:
        """Events of one kind, as (t_s, data)."""
        return [(t, d) for t, k, d in self.events if k == kind]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (events and meta; frames summarised by count and span)."""
        return {
            "meta": self.meta,
            "frames": len(self),
            "t_span_s": [self._t[0], self._t[-1]] if self._t else None,
            "events": [{"t_s": round(t, 6), "kind": k, **d} for t, k, d in self.events],
        }

    def to_recorded(self) -> RecordedRun:
        """The log as a :class:`softpad.record.RecordedRun` (as if read back from a recording)."""
        from softpad.record._read import RecordedRun

        n = len(self)
        return RecordedRun(
            Path("<memory>"),
            dict(self.meta),
            self.t_s,
            self.pressures_pa if n else np.zeros((0, 0)),
            self.supply_pa,
            np.zeros(n, dtype=np.int64),
            sorted(self.events, key=lambda e: e[0]),
        )

    # --- plotting -------------------------------------------------------------------
    def plot(self, path: str | Path | None = None, title: str | None = None) -> Any:
        """Pressure traces of every module with the phases shaded, like the thesis's Fig. 6.8
        (:func:`softpad.record.plot_traces`; never switches the matplotlib backend).

        Returns
        -------
        matplotlib.figure.Figure
        """
        from softpad.record._plots import plot_traces

        return plot_traces(self.to_recorded(), path, title)


def _jsonable(d: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, np.ndarray):
            v = v.tolist()
        elif isinstance(v, np.generic):
            v = v.item()
        elif isinstance(v, tuple):
            v = list(v)
        out[k] = v
    return out
