"""Run log: every frame, event and plan of a run, saved and loaded, plotted like Fig. 6.8.

A :class:`RunLog` is the recorder hook of :class:`softpad.control.GraspExecution`: it appends
each frame and event the moment it arrives, so when a run stops on a fault nothing already
logged is lost (the caller still holds the log and can save it).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad.box import PressureFrame
from softpad.errors import InputError

#: Format tag of saved logs.
LOG_FORMAT = "softpad-runlog/1"

#: Events drawn as vertical lines in plots.
_MARKED_EVENTS = ("reference", "object_seen", "contact", "no_contact", "fault")

#: Colours of the phases in plots.
_PHASE_COLOURS = {
    "adjust": "#dddddd",
    "reference": "#bbbbbb",
    "wait_object": "#e8f0ff",
    "plan": "#cfe0ff",
    "approach": "#fff3d6",
    "descend": "#ffe0b3",
    "close": "#ffc9c9",
    "lift": "#e2f5e2",
    "hold": "#d0f0d0",
    "release": "#f0e6ff",
    "safe": "#ffb3b3",
}


class RunLog:
    """Frames and events of one run (implements the ``softpad.control.Recorder`` hook).

    Attributes
    ----------
    events
        ``(t_s, kind, data)`` in arrival order; kinds include ``phase``, ``adjusted``,
        ``reference``, ``object_seen``, ``plan``, ``contact``, ``no_contact``, ``outcome``,
        ``fault``.
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

    # --- saving ---------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (events and meta; frames summarised by count and span)."""
        return {
            "format": LOG_FORMAT,
            "meta": self.meta,
            "frames": len(self),
            "t_span_s": [self._t[0], self._t[-1]] if self._t else None,
            "events": [{"t_s": round(t, 6), "kind": k, **d} for t, k, d in self.events],
        }

    def to_csv(self, path: str | Path | None = None) -> str:
        """Frames as CSV (``t_s, phase, p1_kpa .. pN_kpa, supply_kpa``); written to ``path`` if given."""
        p = self.pressures_pa
        n = p.shape[1] if p.size else 0
        lines = ["t_s,phase," + ",".join(f"p{k + 1}_kpa" for k in range(n)) + ",supply_kpa"]
        for i, t in enumerate(self._t):
            vals = ",".join("" if not np.isfinite(v) else f"{v / 1e3:.5f}" for v in p[i])
            lines.append(f"{t:.6f},{self._ph[i]},{vals},{self._s[i] / 1e3:.4f}")
        text = "\n".join(lines) + "\n"
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text

    def save(self, path: str | Path) -> Path:
        """Save frames, phases, events and meta to a compressed ``.npz`` file."""
        path = Path(path)
        if path.suffix != ".npz":
            raise InputError(f"run logs are saved as .npz files, got {str(path)!r}")
        phase_names = sorted(set(self._ph))
        codes = np.array([phase_names.index(ph) for ph in self._ph], dtype=np.int16)
        np.savez_compressed(
            path,
            t_s=self.t_s,
            pressures_pa=self.pressures_pa,
            supply_pa=self.supply_pa,
            phase_code=codes,
            info=np.array(
                json.dumps(
                    {
                        "format": LOG_FORMAT,
                        "phase_names": phase_names,
                        "events": [[t, k, d] for t, k, d in self.events],
                        "meta": self.meta,
                    }
                )
            ),
        )
        return path

    @classmethod
    def load(cls, path: str | Path) -> RunLog:
        """Load a log written by :meth:`save`; InputError on a missing or corrupt file."""
        p = Path(path)
        try:
            with np.load(p, allow_pickle=False) as z:
                info = json.loads(str(z["info"][()]))
                if info.get("format") != LOG_FORMAT:
                    raise InputError(f"{str(p)!r} is not a SoftPad run log ({LOG_FORMAT})")
                log = cls(info.get("meta"))
                names = info["phase_names"]
                t, pr, s, codes = z["t_s"], z["pressures_pa"], z["supply_pa"], z["phase_code"]
                log._t = [float(v) for v in t]
                log._p = [row.astype(float) for row in pr]
                log._s = [float(v) for v in s]
                log._ph = [names[int(c)] for c in codes]
                log.events = [(float(e[0]), str(e[1]), dict(e[2])) for e in info["events"]]
                return log
        except InputError:
            raise
        except FileNotFoundError:
            raise InputError(f"run log {str(p)!r} does not exist") from None
        except (OSError, ValueError, KeyError, IndexError, TypeError, EOFError) as exc:
            raise InputError(f"run log {str(p)!r} is unreadable or corrupt: {exc}") from None

    # --- plotting -------------------------------------------------------------------
    def plot(
        self, path: str | Path | None = None, channels: int | None = None, title: str | None = None
    ) -> Any:
        """Pressure traces of every channel with the phases shaded, like the seed's Fig. 6.8.

        Parameters
        ----------
        path
            Write the figure there (PNG, SVG, PDF by suffix) when given.
        channels
            Plot channels 1..channels (default: those that were ever above 0.2 kPa, i.e. the
            modules; all when none was).
        title
            Figure title.

        Returns
        -------
        matplotlib.figure.Figure
        """
        import matplotlib

        if path is not None:
            matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        t = self.t_s
        p = self.pressures_pa
        if channels is None:
            used = (
                np.flatnonzero(np.nanmax(p, axis=0) > 200.0) if p.size else np.array([], dtype=int)
            )
            channels = int(used.max()) + 1 if used.size else (p.shape[1] if p.size else 0)
        fig, ax = plt.subplots(figsize=(10, 4.5), constrained_layout=True)
        seen: set[str] = set()
        for ph, t0, t1 in self.phase_spans():
            colour = _PHASE_COLOURS.get(ph, "#f5f5f5")
            ax.axvspan(t0, t1, color=colour, alpha=0.6, lw=0, label=None if ph in seen else ph)
            seen.add(ph)
        for k in range(channels):
            ax.plot(t, p[:, k] / 1e3, lw=0.8, label=f"module {k + 1}")
        marked = [(t_ev, kind) for t_ev, kind, _ in self.events if kind in _MARKED_EVENTS]
        for i, (t_ev, kind) in enumerate(marked):
            ax.axvline(t_ev, color="k", ls="--", lw=0.7)
            ax.annotate(
                kind.replace("_", " "),
                (t_ev, 0.98 - 0.14 * (i % 3)),  # staggered: close events do not overlap
                xycoords=("data", "axes fraction"),
                rotation=90,
                va="top",
                ha="right",
                fontsize=7,
            )
        ax.set_xlabel("time (s)")
        ax.set_ylabel("pressure (kPa)")
        ax.set_title(title or "SoftPad pressures during the grasp (cf. seed Fig. 6.8)")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=7)
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


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
