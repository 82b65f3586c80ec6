"""``softpad box read``: stream frames of a box to the terminal."""

from __future__ import annotations

import argparse
import json
from typing import Any

_EPILOG = """examples:
  softpad box read --count 5
  softpad box read --box 'sim://?inflated_kpa=1.1&object=banana' --count 3 --json
  softpad box read --box 'sim://?realtime=1' --count 0          stream until Ctrl-C
"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "box",
        help="talk to a pneumatic box (read frames)",
        description="Pneumatic box utilities.",
    )
    bsub = p.add_subparsers(dest="box_command", metavar="ACTION")
    r = bsub.add_parser(
        "read",
        help="stream frames (gauge pressure of every channel and the supply, kPa)",
        description="Read frames from a box and print one line per frame (kPa).",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    r.add_argument("--box", default="sim://", metavar="URL", help="box URL (default sim://)")
    r.add_argument(
        "--count", type=int, default=10, help="frames to read, 0 for endless (default 10)"
    )
    r.add_argument("--every", type=int, default=1, help="print every k-th frame (default 1)")
    r.add_argument("--json", action="store_true", help="one JSON object per line")
    r.set_defaults(handler=read)
    p.set_defaults(handler=_usage, _parser=p)


def _usage(args: argparse.Namespace) -> int:
    args._parser.print_help()
    return 2


def read(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.errors import InputError

    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    if args.every < 1:
        raise InputError(f"--every must be >= 1, got {args.every}")
    with open_box(args.box) as box:
        if not args.json:
            head = "    t_s  " + " ".join(f"{'ch' + str(k + 1):>8s}" for k in range(box.channels))
            print(head + "  supply   (kPa)")
        i = 0
        while args.count == 0 or i < args.count:
            f = box.read()
            if i % args.every == 0:
                if args.json:
                    print(json.dumps(f.to_dict()), flush=True)
                else:
                    vals = " ".join(f"{v / 1e3:8.4f}" for v in f.pressures_pa)
                    print(f"{f.t_s:8.3f}  {vals}  {f.supply_pa / 1e3:6.2f}", flush=True)
            i += 1
    return 0
