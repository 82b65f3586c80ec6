"""``softpad replay FILE.mcap``: today's sensing and planning on a recording, next to what it holds."""

from __future__ import annotations

import argparse
import math
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


def _plan_text(o: dict[str, Any]) -> str:
    mods = ",".join(map(str, o["modules"]))
    return (
        f"modules {mods}  COG ({o['cog'][0]:.3f}, {o['cog'][1]:.3f})  theta {o['theta']:+.4f} rad "
        f"({math.degrees(o['theta']):+.0f} deg)  [{o['rule']}]"
    )


def _contact_text(c: dict[str, Any] | None) -> str:
    if c is None:
        return "none"
    return f"t = {c['t_s']:.3f} s on module(s) {', '.join(map(str, c['modules']))}"


def run(args: argparse.Namespace) -> int:
    from softpad.record import compare_replay

    d = compare_replay(args.file)
    if args.json:
        from softpad.cli._output import emit

        emit(d)
        return 0 if d["same"] else 1
    print(f"softpad replay: {d['path']} (recorded outcome: {d['outcome']})")
    plan = d["plan"]
    for label, plans in (("recorded", plan["recorded"]), ("now", plan["now"] or [])):
        for o in plans or [{}]:
            print(f"  plan {label:8s} {_plan_text(o) if o else 'none'}")
    print(f"  plan: {'same' if plan['same'] else 'DIFFERENT'}")
    for i, c in enumerate(d["contacts"], 1):
        print(f"  descent {i}: recorded contact {_contact_text(c['recorded'])}")
        print(f"  descent {i}: now      contact {_contact_text(c['now'])}")
        print(f"  descent {i}: {'same contact sample' if c['same'] else 'DIFFERENT'}")
    print("verdict: " + ("today's code decides what was recorded" if d["same"] else "DIFFERENT"))
    return 0 if d["same"] else 1
