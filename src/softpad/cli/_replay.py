"""``softpad replay FILE.mcap``: today's sensing and planning on a recording, next to what it holds."""

from __future__ import annotations

import argparse
from typing import Any

from softpad.cli._args import add_command

_EPILOG = """examples:
  softpad replay run.mcap
  softpad replay tests/data/banana.mcap --json

exit status: 0 when today's code decides what was recorded (same plan, same contact sample),
1 when it differs, 2 on bad input.
"""


_DESCRIPTION = """\
Play a recording's frames through today's reference capture, object detection and grasp
planning, and contact detection, and print what the code decides now next to what was
recorded: the same plan? the same contact sample?"""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "replay",
        "re-run today's sensing, planning and contact detection on a recording",
        _DESCRIPTION,
        _EPILOG,
        json="print the comparison as one JSON object",
    )
    p.add_argument("file", metavar="FILE.mcap", help="a recording (softpad run --record)")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.cli._output import emit
    from softpad.record import compare_replay, replay_lines

    d = compare_replay(args.file)
    if args.json:
        emit(d)
    else:
        print("\n".join(replay_lines(d)))
    return 0 if d["same"] else 1
