"""A recording exported as ``softpad log export`` does: a table (CSV, Parquet) of its frames
and events, or every message as a rosbag2 directory or a ROS 1 bag."""

from __future__ import annotations

from typing import Any

from softpad.errors import InputError


def export_recording(
    rec: Any,
    source: str,
    table: tuple[str | None, str | None, str | None] = (None, None, None),
    bag: tuple[str | None, str | None] = (None, None),
    force: bool = False,
) -> tuple[str, str]:
    """Export the recording ``rec`` read from ``source``; return what was written, in words,
    and the file written.

    Parameters
    ----------
    rec
        The :class:`~softpad.record.RecordedRun`.
    source
        Its file (.mcap), which the bags are converted from.
    table
        (out, csv, parquet): a table file by suffix (``.csv``, ``.parquet``), or one of the
        two formats by name; the first given is written.
    bag
        (rosbag2 directory, ROS 1 bag file); the first given is written instead of a table.
    force
        Overwrite an existing bag.
    """
    rosbag2, rosbag1 = bag
    if rosbag2 or rosbag1:
        from softpad.record._bags import to_rosbag1, to_rosbag2

        out = rosbag2 or rosbag1
        assert out is not None
        write = to_rosbag2 if rosbag2 else to_rosbag1
        write(source, out, force=force)
        kind = "rosbag2 directory" if rosbag2 else "ROS 1 bag"
        return f"{len(rec)} frames and every message written to the {kind} {out}", out
    any_out, csv, parquet = table
    path = any_out or csv or parquet
    if path is None:
        raise InputError(
            "give the file to export to (--out, --csv, --parquet, --rosbag2, --rosbag1)"
        )
    if (csv and not path.endswith(".csv")) or (parquet and not path.endswith(".parquet")):
        raise InputError(f"the file's name must end in its format's suffix, got {path!r}")
    if path.endswith(".csv"):
        rec.to_csv(path)
    elif path.endswith(".parquet"):
        rec.to_parquet(path)
    else:
        raise InputError(f"--out must end in .csv or .parquet, got {path!r}")
    return f"{len(rec)} frames and {len(rec.events)} events written to {path}", path


__all__ = ["export_recording"]
