"""What ``softpad log info`` tells of a recording: its summary with the MCAP topics, and that
summary as lines of text."""

from __future__ import annotations

from typing import Any


def _topics(path: str) -> list[tuple[str, str, int]]:
    """(topic, schema, messages) of every channel of the MCAP file ``path``."""
    from mcap.reader import make_reader

    with open(path, "rb") as f:
        summary = make_reader(f).get_summary()
    if summary is None or summary.statistics is None:
        return []
    counts = summary.statistics.channel_message_counts
    return sorted(
        (ch.topic, summary.schemas[ch.schema_id].name, counts.get(cid, 0))
        for cid, ch in summary.channels.items()
    )


def recording_info(run: Any) -> dict[str, Any]:
    """A recording's summary (:meth:`RecordedRun.summary`) with its ``topics`` (topic, type,
    messages; none for a recording cut short).

    Parameters
    ----------
    run
        The :class:`~softpad.record.RecordedRun`.
    """
    s: dict[str, Any] = run.summary()
    s["topics"] = [
        {"topic": t, "type": ty, "messages": n}
        for t, ty, n in (_topics(s["path"]) if run.complete else [])
    ]
    return s


def info_lines(s: dict[str, Any]) -> list[str]:
    """The summary of :func:`recording_info` as text.

    Parameters
    ----------
    s
        The summary (s, Hz, counts).
    """
    lines = [
        f"{s['path']}: {s['frames']} frames of {s['channels']} channels over {s['duration_s']:.2f} s",
        f"  recorded {s['wall_clock_start']} by softpad {s['software_version']}, "
        f"{s['sample_rate_hz']:g} Hz",
    ]
    if not s["complete"]:
        lines.append(
            "  cut short (crash?): read up to the last flushed chunk; 'softpad log recover' fixes it"
        )
    lines.append(f"  objects: {', '.join(s['objects'] or []) or '-'}")
    for o in s["plans"]:
        lines.append(
            f"  plan: modules {','.join(map(str, o['modules']))}  COG ({o['cog'][0]:.2f}, "
            f"{o['cog'][1]:.2f})  theta {o['theta']:+.3f} rad  [{o['rule']}]"
        )
    for c in s["contact"]:
        lines.append(
            f"  contact: t = {c['t_s']:.3f} s on module(s) {', '.join(map(str, c['modules']))}"
        )
    lines.append(
        f"  events {s['events']}, valve commands {s['valve_commands']}, "
        f"robot poses {s['robot_poses']}"
    )
    lines.append(f"  outcome: {s['outcome']}")
    for t in s["topics"]:
        lines.append(f"  {t['topic']:32s} {t['type']:36s} {t['messages']}")
    return lines


__all__ = ["info_lines", "recording_info"]
