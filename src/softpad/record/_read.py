"""Read a SoftPad MCAP recording back: frames, events, valve commands, robot poses, metadata.

:func:`load_recording` returns a :class:`RecordedRun`; a file cut short by a crash (no summary
or index, a torn last chunk) is read up to its last complete chunk, and :func:`recover`
rewrites such a file as a complete, indexed MCAP.
"""

from __future__ import annotations

import bisect
import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad.errors import InputError
from softpad.record import _schemas as S

_MODULE_PREFIX = "/softpad/module_"


@dataclass
class RecordedRun:
    """A recording loaded into memory (SI units; box time in seconds).

    Attributes
    ----------
    path
        File it came from.
    metadata
        The ``softpad`` metadata record, JSON-decoded (parameters, seed, objects, version...).
    t_s
        Box time of every frame, seconds, shape (n,).
    pressures_pa
        Gauge pressure of every channel, pascals, shape (n, channels); NaN where missing.
    supply_pa
        Supply pressure, pascals, shape (n,).
    wall_ns
        Recorded clock of each frame (UNIX ns: the box time mapped onto the wall clock at the
        run's start; format 1 recordings: the wall clock when the frame was written), shape (n,).
    events
        ``(t_s, kind, data)`` in time order.
    valves
        ``(t_s, commands)`` of every recorded valve command set.
    robot_poses
        Measured robot poses ``(t_s, x_m, y_m, z_m, yaw_rad)``, shape (m, 5).
    complete
        False when the file was cut short (no summary section: a crash).
    """

    path: Path
    metadata: dict[str, Any]
    t_s: NDArray[np.float64]
    pressures_pa: NDArray[np.float64]
    supply_pa: NDArray[np.float64]
    wall_ns: NDArray[np.int64]
    events: list[tuple[float, str, dict[str, Any]]] = field(default_factory=list)
    valves: list[tuple[float, list[str]]] = field(default_factory=list)
    robot_poses: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 5)))
    complete: bool = True

    def __len__(self) -> int:
        return int(self.t_s.shape[0])

    @property
    def channels(self) -> int:
        """Number of recorded channels."""
        return int(self.pressures_pa.shape[1]) if self.pressures_pa.ndim == 2 else 0

    @property
    def duration_s(self) -> float:
        """Box time from the first to the last frame, seconds."""
        return float(self.t_s[-1] - self.t_s[0]) if len(self) else 0.0

    def events_of(self, kind: str) -> list[tuple[float, dict[str, Any]]]:
        """Events of one kind, as (t_s, data)."""
        return [(t, d) for t, k, d in self.events if k == kind]

    @property
    def phases(self) -> list[str]:
        """Phase of each frame, from the phase events (a frame stamped at a phase change
        belongs to the phase before it, as the execution reported it)."""
        changes = self.events_of("phase")
        times = [t for t, _ in changes]
        out = []
        for t in self.t_s:
            i = bisect.bisect_left(times, float(t)) - 1
            out.append(changes[i][1]["phase"] if i >= 0 else "idle")
        return out

    def phase_spans(self) -> list[tuple[str, float, float]]:
        """(phase, start s, end s) of every phase in order."""
        changes = [(t, d["phase"]) for t, d in self.events_of("phase")]
        end = float(self.t_s[-1]) if len(self) else 0.0
        spans = []
        for i, (t, ph) in enumerate(changes):
            t1 = changes[i + 1][0] if i + 1 < len(changes) else end
            spans.append((ph, t, max(t, t1)))
        return spans

    @property
    def outcome(self) -> str:
        """Outcome of the last grasp, ``fault``, or ``unfinished`` when none was recorded."""
        for _, kind, d in reversed(self.events):
            if kind == "outcome":
                return str(d.get("outcome"))
            if kind in ("fault", "no_contact"):
                return "fault" if kind == "fault" else "contact_not_detected"
        return "unfinished"

    def plans(self) -> list[dict[str, Any]]:
        """Recorded plan dicts (modules, pcom, cog, theta, rule, cog_m) of every object."""
        return [o for _, d in self.events_of("plan") for o in d.get("objects", [])]

    def summary(self) -> dict[str, Any]:
        """JSON-ready summary: topics, duration, frames, objects, plans, contact, outcome."""
        contact = self.events_of("contact")
        return {
            "path": str(self.path),
            "complete": self.complete,
            "format": self.metadata.get("format"),
            "software_version": self.metadata.get("software_version"),
            "wall_clock_start": self.metadata.get("wall_clock_start"),
            "objects": self.metadata.get("objects"),
            "frames": len(self),
            "channels": self.channels,
            "duration_s": round(self.duration_s, 6),
            "sample_rate_hz": round(self.sample_rate_hz, 3),
            "events": len(self.events),
            "valve_commands": len(self.valves),
            "robot_poses": int(self.robot_poses.shape[0]),
            "plans": self.plans(),
            "contact": [{"t_s": t, **d} for t, d in contact],
            "outcome": self.outcome,
        }

    @property
    def sample_rate_hz(self) -> float:
        """Frame rate, hertz (median spacing of the frames)."""
        if len(self) < 2:
            return 0.0
        return float(1.0 / np.median(np.diff(self.t_s)))

    # --- tables -----------------------------------------------------------------------
    def table(self) -> dict[str, list[Any]]:
        """Frames and events as one table, time-ordered: columns ``t_s, wall_ns, phase,
        p1_pa .. pN_pa, supply_pa, event, event_json`` (events are rows without pressures)."""
        from softpad.record._export import table

        return table(self)

    def to_csv(self, path: str | Path) -> Path:
        """Write :meth:`table` as CSV (pressures in Pa, events included)."""
        from softpad.record._export import to_csv

        return to_csv(self, path)

    def to_parquet(self, path: str | Path) -> Path:
        """Write :meth:`table` as Parquet (needs ``pyarrow``)."""
        from softpad.record._export import to_parquet

        return to_parquet(self, path)

    # --- pictures -----------------------------------------------------------------------
    def plot(self, path: str | Path | None = None, title: str | None = None) -> Any:
        """Pressure traces of every module with the phases as shaded bands (cf. Fig. 6.8);
        see :func:`softpad.record.plot_traces`."""
        from softpad.record._plots import plot_traces

        return plot_traces(self, path, title)

    def plot_pad(self, path: str | Path | None = None) -> Any:
        """The pad seen from above with the recorded objects and grasps; see
        :func:`softpad.record.plot_pad`."""
        from softpad.record._plots import plot_pad

        return plot_pad(self, path)


def _decode_metadata(records: dict[str, str]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in records.items():
        try:
            out[k] = json.loads(v)
        except json.JSONDecodeError:
            out[k] = v
    return out


def _iter_records(path: Path) -> tuple[list[Any], bool]:
    """Every complete record of the file (chunks expanded), and whether the file ended cleanly."""
    from mcap.exceptions import McapError
    from mcap.stream_reader import StreamReader

    records: list[Any] = []
    complete = False
    with open(path, "rb") as f:
        try:
            for rec in StreamReader(f, skip_magic=False, emit_chunks=False).records:
                records.append(rec)
            complete = True
        except (McapError, EOFError, ValueError, KeyError, IndexError, OSError) as exc:
            if not records:
                raise InputError(f"{str(path)!r} is not a readable MCAP file: {exc}") from None
        except Exception as exc:  # torn chunk: decompression or struct errors of any kind
            if not records:
                raise InputError(f"{str(path)!r} is not a readable MCAP file: {exc}") from None
    from mcap.records import Footer

    complete = complete and any(isinstance(r, Footer) for r in records)
    return records, complete


def load_recording(path: str | Path) -> RecordedRun:
    """Load a SoftPad recording; a crash-truncated file is read up to its last whole chunk.

    Raises
    ------
    InputError
        Missing file, not an MCAP file, or not a SoftPad recording.
    """
    from mcap.records import Channel, Message, Metadata, Schema
    from mcap_ros2.decoder import DecoderFactory

    p = Path(path)
    if not p.is_file():
        raise InputError(f"recording {str(p)!r} does not exist")
    records, complete = _iter_records(p)
    schemas: dict[int, Schema] = {}
    channels: dict[int, Channel] = {}
    meta: dict[str, Any] = {}
    by_topic: dict[str, list[tuple[int, Any]]] = {}
    factory = DecoderFactory()
    decoders: dict[int, Callable[[bytes], Any]] = {}
    for rec in records:
        if isinstance(rec, Schema):
            schemas[rec.id] = rec
        elif isinstance(rec, Channel):
            channels[rec.id] = rec
        elif isinstance(rec, Metadata) and rec.name == "softpad":
            meta.update(_decode_metadata(dict(rec.metadata)))
        elif isinstance(rec, Metadata) and rec.name == S.CLOCK_RECORD:
            meta["clock_offset_ns"] = int(rec.metadata["offset_ns"])
        elif isinstance(rec, Message) and rec.channel_id in channels:
            ch = channels[rec.channel_id]
            dec = decoders.get(ch.schema_id)
            if dec is None:
                found = factory.decoder_for("cdr", schemas[ch.schema_id])
                if found is None:
                    raise InputError(f"{str(p)!r}: no CDR decoder for {schemas[ch.schema_id].name}")
                dec = decoders[ch.schema_id] = found
            by_topic.setdefault(ch.topic, []).append((rec.log_time, dec(rec.data)))
    if meta.get("format") not in S.READABLE_FORMATS:
        raise InputError(f"{str(p)!r} is not a SoftPad recording ({S.RECORDING_FORMAT})")
    return _assemble(p, meta, by_topic, complete)


def _assemble(
    path: Path, meta: dict[str, Any], by_topic: dict[str, list[tuple[int, Any]]], complete: bool
) -> RecordedRun:
    offset = int(meta.get("clock_offset_ns", 0))  # format 1: stamps are box time

    def _t(msg: Any) -> float:
        return (msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec - offset) * 1e-9

    # format 2 publishes absolute pressures (gauge + ambient); the run holds gauge readings
    ambient = (
        float(meta.get("ambient_pressure_pa", 0.0)) if meta["format"] != "softpad-mcap/1" else 0.0
    )
    n_ch = 0
    while S.module_topic(n_ch + 1) in by_topic:
        n_ch += 1
    supply = by_topic.get(S.SUPPLY_TOPIC, [])
    n = min([len(supply)] + [len(by_topic[S.module_topic(k)]) for k in range(1, n_ch + 1)])
    t = np.array([_t(m) for _, m in supply[:n]], dtype=float)
    p = np.full((n, n_ch), np.nan)
    for k in range(n_ch):
        p[:, k] = [m.fluid_pressure - ambient for _, m in by_topic[S.module_topic(k + 1)][:n]]
    events = [
        (_t(m), str(m.kind), dict(json.loads(m.data_json)))
        for _, m in by_topic.get(S.EVENT_TOPIC, [])
    ]
    events.sort(key=lambda e: e[0])  # stable: same-time events keep their order
    valves = [(_t(m), list(m.commands)) for _, m in by_topic.get(S.VALVE_TOPIC, [])]
    poses = np.array(
        [
            (
                _t(m),
                m.pose.position.x,
                m.pose.position.y,
                m.pose.position.z,
                2 * math.atan2(m.pose.orientation.z, m.pose.orientation.w),
            )
            for _, m in by_topic.get(S.ROBOT_POSE_TOPIC, [])
        ],
        dtype=float,
    ).reshape(-1, 5)
    return RecordedRun(
        path,
        meta,
        t,
        p,
        np.array([m.fluid_pressure - ambient for _, m in supply[:n]], dtype=float),
        np.array([w for w, _ in supply[:n]], dtype=np.int64),
        events,
        valves,
        poses,
        complete,
    )


def recover(path: str | Path, out: str | Path | None = None, force: bool = False) -> Path:
    """Rewrite a crash-truncated recording as a complete, indexed MCAP file.

    Parameters
    ----------
    path
        The recording (read up to its last complete chunk).
    out
        Output file; default ``<stem>.recovered.mcap`` beside it.
    force
        Overwrite ``out`` if it exists.

    Returns
    -------
    Path
        The written file (every complete record of the input, same schemas and channels).
    """
    from mcap.records import Channel, Message, Metadata, Schema
    from mcap.writer import Writer

    from softpad.record._mcap import check_output

    src = Path(path)
    if not src.is_file():
        raise InputError(f"recording {str(src)!r} does not exist")
    if out is not None and not str(out).strip():
        raise InputError("the recovered file's name is empty: give FILE.mcap, or leave --out out")
    dst = check_output(out or src.with_name(src.stem + ".recovered.mcap"), force)
    records, _ = _iter_records(src)
    schema_ids: dict[int, int] = {}
    channel_ids: dict[int, int] = {}
    with open(dst, "wb") as f:
        w = Writer(f)
        w.start(profile=S.PROFILE, library="softpad recover")
        for rec in records:
            # a complete file repeats its schemas and channels in the summary: register once
            if isinstance(rec, Schema) and rec.id not in schema_ids:
                schema_ids[rec.id] = w.register_schema(rec.name, rec.encoding, rec.data)
            elif isinstance(rec, Channel) and rec.id not in channel_ids:
                channel_ids[rec.id] = w.register_channel(
                    rec.topic, rec.message_encoding, schema_ids.get(rec.schema_id, 0), rec.metadata
                )
            elif isinstance(rec, Metadata):
                w.add_metadata(rec.name, dict(rec.metadata))
            elif isinstance(rec, Message) and rec.channel_id in channel_ids:
                w.add_message(
                    channel_ids[rec.channel_id],
                    rec.log_time,
                    rec.data,
                    rec.publish_time,
                    rec.sequence,
                )
        w.finish()
    return dst
