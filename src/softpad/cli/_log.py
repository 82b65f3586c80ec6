"""``softpad log info|plot|export|recover FILE.mcap``: look into a recording."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from softpad.cli._args import add_command, add_group
from softpad.errors import InputError

_EPILOG = """examples:
  softpad log info run.mcap                 topics, duration, objects, plan, contact, outcome
  softpad log info run.mcap --json
  softpad log plot run.mcap --png traces.png --pad-png pad.png
  softpad log export run.mcap --out run.csv (or run.parquet, needs pyarrow)
  softpad log export run.mcap --rosbag2 run_bag   a rosbag2 directory (ros2 bag info|play)
  softpad log export run.mcap --rosbag1 run.bag   a ROS 1 bag (rosbag play)
  softpad log recover crashed.mcap --out fixed.mcap

A recording cut short by a crash (kill -9, power loss) is read up to its last flushed chunk;
'recover' rewrites it as a complete, indexed MCAP for other tools.
"""


def register(sub: Any) -> None:
    actions = add_group(
        sub,
        "log",
        "summarise, plot, export or recover a recording (.mcap)",
        "Look into a recording written by --record.",
        _EPILOG,
    )
    info = add_command(
        actions,
        "info",
        "topics, duration, objects, plans, contact, outcome",
        json="print the summary as JSON",
    )
    info.add_argument("file", metavar="FILE.mcap")
    written = "print the written files as JSON"
    plot = add_command(
        actions, "plot", "pressure traces with phases; the pad with the grasp", json=written
    )
    plot.add_argument("file", metavar="FILE.mcap")
    plot.add_argument("--png", metavar="FILE", required=True, help="pressure traces picture")
    plot.add_argument("--pad-png", metavar="FILE", help="pad picture with objects and grasps")
    plot.add_argument("--force", action="store_true", help="overwrite existing pictures")
    export = add_command(
        actions, "export", "as a table (CSV, Parquet), a rosbag2 directory or a ROS 1 bag",
        json=written,
    )  # fmt: skip
    export.add_argument("file", metavar="FILE.mcap")
    to = export.add_mutually_exclusive_group(required=True)
    to.add_argument("--out", metavar="FILE", help="FILE.csv or FILE.parquet: frames and events")
    to.add_argument("--csv", metavar="FILE.csv", help="frames and events as CSV")
    to.add_argument("--parquet", metavar="FILE.parquet", help="the same as Parquet (pyarrow)")
    to.add_argument(
        "--rosbag2", metavar="DIR", help="every message as a rosbag2 directory (SQLite 3)"
    )
    to.add_argument("--rosbag1", metavar="FILE.bag", help="every message as a ROS 1 bag")
    export.add_argument("--force", action="store_true", help="overwrite an existing output")
    recover = add_command(actions, "recover", "rewrite a crash-truncated recording", json=written)
    recover.add_argument("file", metavar="FILE.mcap")
    recover.add_argument("--out", metavar="FILE.mcap", help="default: FILE.recovered.mcap")
    recover.add_argument("--force", action="store_true", help="overwrite --out")
    for q in (info, plot, export, recover):
        q.set_defaults(handler=run)


def _info(run: Any, as_json: bool) -> None:
    from softpad.cli._output import emit
    from softpad.record import info_lines, recording_info

    s = recording_info(run)
    if as_json:
        emit(s)
        return
    print("\n".join(info_lines(s)))


def run(args: argparse.Namespace) -> int:
    from softpad.record import load_recording, recover

    if args.log_command == "recover":
        out = recover(args.file, args.out, args.force)
        n = len(load_recording(out))
        _done(args, f"recovered {n} frames into {out}", files=[str(out)], frames=n)
        return 0
    _check_outputs(args)  # before reading: nothing is computed for a file that cannot be written
    rec = load_recording(args.file)
    if not rec.complete:
        print(
            f"note: {args.file} was cut short; read up to its last flushed chunk", file=sys.stderr
        )
    if args.log_command == "info":
        _info(rec, args.json)
    elif args.log_command == "plot":
        rec.plot(args.png)
        if args.pad_png:
            rec.plot_pad(args.pad_png)
        _done(
            args,
            f"pressure traces: {args.png}" + (f"; pad: {args.pad_png}" if args.pad_png else ""),
            files=[f for f in (args.png, args.pad_png) if f],
        )
    else:
        _export(args, rec)
    return 0


def _check_outputs(args: argparse.Namespace) -> None:
    """The output files of ``plot`` and ``export``: right suffix, writable, not clobbered."""
    from softpad.cli._paths import check_output

    if args.log_command == "plot":
        check_output(args.png, "--png", force=args.force, suffix=".png")
        check_output(args.pad_png, "--pad-png", force=args.force, suffix=".png")
        if args.pad_png is not None and Path(args.pad_png).resolve() == Path(args.png).resolve():
            raise InputError("--png and --pad-png name the same file")
    elif args.log_command == "export":
        # --rosbag2 DIR: checked by softpad.record.to_rosbag2 itself
        for flag, value, suffix in (
            ("--out", args.out, (".csv", ".parquet")),
            ("--csv", args.csv, ".csv"),
            ("--parquet", args.parquet, ".parquet"),
            ("--rosbag1", args.rosbag1, ".bag"),
        ):
            check_output(value, flag, force=args.force, suffix=suffix)


def _export(args: argparse.Namespace, rec: Any) -> None:
    from softpad.record import export_recording

    table, bag = (args.out, args.csv, args.parquet), (args.rosbag2, args.rosbag1)
    text, out = export_recording(rec, args.file, table, bag, force=args.force)
    _done(args, text, files=[out])


def _done(args: argparse.Namespace, text: str, **result: Any) -> None:
    """The human line, or (with --json) the result as one JSON object and the line on stderr."""
    from softpad.cli._output import emit, say

    say(text, args.json)
    if args.json:
        emit(result)
