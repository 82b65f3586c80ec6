"""``softpad box read|serve|inflate|monitor``: stream frames, serve a box over TCP, inflate and
adjust, watch a box live in Foxglove."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad.cli._args import finite_float
from softpad.cli._output import emit

_EPILOG = """examples:
  softpad box read --count 5
  softpad box read --box 'sim://?inflated_kpa=1.1&object=banana' --count 3 --json
  softpad box read --box 'sim://?realtime=1' --count 0          stream until Ctrl-C
  softpad box read --box tcp://127.0.0.1:5757 --count 3        a box served over the network
"""

_SERVE_EPILOG = """examples:
  softpad box serve --port 5757                                 the simulated box on loopback
  softpad box serve --box 'sim://?realtime=1&object=banana' --port 5757 --once
  then: softpad box read --box tcp://127.0.0.1:5757

Binds only --host (127.0.0.1 by default: this computer only). One client at a time; when a
client leaves or goes silent for --idle-timeout-s, every valve of the served box is closed.
Ctrl-C stops the server (valves closed, box closed). A served sim:// box also offers its world
and robot, so 'softpad run --box tcp://HOST:PORT' runs the whole loop through the network.
"""

_MONITOR_EPILOG = """examples:
  softpad box monitor --foxglove                         the simulated box, ws://127.0.0.1:8765
  softpad box monitor --foxglove --port 0 --box 'sim://?object=banana&inflated_kpa=1.1'
  then in Foxglove: Open connection -> Foxglove WebSocket -> ws://127.0.0.1:8765
  (docs/foxglove-layout.json: a pressure plot per module and the pad picture)

Serves /softpad/module_K/pressure (Pa), /softpad/supply/pressure and /softpad/pad (3D picture)
to any number of viewers, on 127.0.0.1 only, at the box's pace (never faster than real time).
Ctrl-C stops. 'softpad run --foxglove PORT' serves a whole run (plans, contact, robot) live.
"""

_INFLATE_EPILOG = """examples:
  softpad box inflate                                 the simulated box, to p0
  softpad box inflate --box tcp://127.0.0.1:5757 --json
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
    r.add_argument(
        "--json", action="store_true", help="one JSON object per line (the last the error if any)"
    )
    r.set_defaults(handler=read)
    m = bsub.add_parser(
        "monitor",
        help="watch a box live (Foxglove WebSocket server on 127.0.0.1)",
        description="Serve a box's frames live to Foxglove viewers.",
        epilog=_MONITOR_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    m.add_argument("--box", default="sim://", metavar="URL", help="box URL (default sim://)")
    m.add_argument("--foxglove", action="store_true", help="serve to Foxglove (WebSocket)")
    m.add_argument("--port", type=int, default=8765, help="port on 127.0.0.1 (0: a free one)")
    m.add_argument("--count", type=int, default=0, help="frames to serve, 0 for endless")
    m.add_argument("--json", action="store_true", help="print the viewer URL as one JSON object")
    m.set_defaults(handler=monitor)
    s = bsub.add_parser(
        "serve",
        help="serve a box over TCP (softpad-box protocol; loopback by default)",
        description="Expose a box (any URL, the simulator by default) on tcp://HOST:PORT.",
        epilog=_SERVE_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    s.add_argument("--box", default="sim://", metavar="URL", help="box to serve (default sim://)")
    s.add_argument(
        "--host", default="127.0.0.1", help="address to bind, and only it (default 127.0.0.1)"
    )
    s.add_argument("--port", type=int, default=0, help="TCP port (default 0: a free one, printed)")
    s.add_argument(
        "--idle-timeout-s",
        type=finite_float("--idle-timeout-s", lo=0.01, hi=3600.0, unit="s"),
        default=10.0,
        help="drop a silent client and close the valves after this long, s (default 10)",
    )
    s.add_argument("--once", action="store_true", help="stop when the first client leaves")
    s.add_argument("--json", action="store_true", help="print the served URL as one JSON object")
    s.set_defaults(handler=serve)
    i = bsub.add_parser(
        "inflate",
        help="inflate every module to p0 and save the reference (Section 6.2.1.1)",
        description=(
            "Bring every module to p0 within t_adj and print the reference (mean of 10 reads); "
            "works on any box URL, e.g. a tcp:// box served by 'softpad box serve'."
        ),
        epilog=_INFLATE_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    i.add_argument("--box", default="sim://", metavar="URL", help="box URL (default sim://)")
    i.add_argument("--modules", type=int, default=6, help="modules on the pad (default 6)")
    i.add_argument(
        "--p0-kpa",
        type=finite_float("--p0-kpa", lo=0.5, hi=2.8, unit="kPa"),
        default=1.1,
        help="target pressure p0, kPa, 0.5..2.8 (default 1.1)",
    )
    i.add_argument("--json", action="store_true", help="print the result as one JSON object")
    i.set_defaults(handler=inflate)
    p.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(handler=_usage, _parser=p)


def _usage(args: argparse.Namespace) -> int:
    from softpad.cli.main import UsageError

    args._parser.print_help(sys.stderr)
    raise UsageError("an ACTION is required: read, serve or inflate (see softpad box --help)")


def read(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.errors import InputError

    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    if args.every < 1:
        raise InputError(f"--every must be >= 1, got {args.every}")
    with open_box(args.box) as box:
        args.partial = {"frames": 0}
        if not args.json:
            head = "    t_s  " + " ".join(f"{'ch' + str(k + 1):>8s}" for k in range(box.channels))
            print(head + "  supply   (kPa)")
        i = 0
        while args.count == 0 or i < args.count:
            f = box.read()
            if i % args.every == 0:
                if args.json:
                    emit(f.to_dict())
                else:
                    vals = " ".join(f"{v / 1e3:8.4f}" for v in f.pressures_pa)
                    print(f"{f.t_s:8.3f}  {vals}  {f.supply_pa / 1e3:6.2f}", flush=True)
            i += 1
            args.partial["frames"] = i
    return 0


def serve(args: argparse.Namespace) -> int:
    from softpad.box import BoxServer, SimBox, open_box
    from softpad.errors import InputError

    if not 0 <= args.port <= 65535:
        raise InputError(f"--port must be within 0..65535, got {args.port}")
    box = open_box(args.box)
    try:
        extensions = {}
        if isinstance(box, SimBox):  # the world and robot too, so 'softpad run' works over tcp
            from softpad.harness import simulation_extensions

            extensions = simulation_extensions(box)
        server = BoxServer(
            box,
            args.host,
            args.port,
            idle_timeout_s=args.idle_timeout_s,
            log=lambda text: print(f"softpad box serve: {text}", file=sys.stderr, flush=True),
            extensions=extensions,
        )
    except BaseException:
        box.close()
        raise

    def _terminate(signum: int, frame: object) -> None:
        raise KeyboardInterrupt  # SIGTERM (e.g. a service manager) stops like Ctrl-C

    import signal
    import threading

    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _terminate) if main_thread else None
    try:
        with server:
            if args.json:
                emit({"serving": args.box, "url": server.url, "port": server.port})
            else:
                print(
                    f"serving {args.box} on {server.url} (port {server.port}); Ctrl-C stops",
                    flush=True,
                )
            try:
                server.serve(max_sessions=1 if args.once else None)
            except KeyboardInterrupt:
                print("softpad box serve: stopped; valves closed", file=sys.stderr)
    finally:
        if main_thread:
            signal.signal(signal.SIGTERM, previous)
    return 0


def inflate(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.control import InflationParams, inflate_and_adjust
    from softpad.errors import InputError

    with open_box(args.box) as box:
        if not 1 <= args.modules <= box.channels:
            raise InputError(
                f"--modules must be within 1..{box.channels} (channels of the box), got {args.modules}"
            )
        res = inflate_and_adjust(box, args.modules, InflationParams(target_pa=args.p0_kpa * 1e3))
    if args.json:
        emit(res.to_dict())
    else:
        ref = " ".join(f"{v / 1e3:.3f}" for v in res.reference_pa)
        print(
            f"adjusted at t = {res.adjusted_at_s:.2f} s; reference (kPa) saved at "
            f"t = {res.reference_at_s:.2f} s: {ref}"
        )
    return 0


def monitor(args: argparse.Namespace) -> int:
    """Read frames from the box and publish them to Foxglove, paced to real time."""
    import sys
    import time

    from softpad.box import open_box
    from softpad.errors import InputError
    from softpad.record import FoxgloveLive

    if not args.foxglove:
        raise InputError("box monitor needs a viewer: add --foxglove")
    if not 0 <= args.port <= 65535:
        raise InputError(f"--port must be within 0..65535, got {args.port}")
    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    with open_box(args.box) as box, FoxgloveLive(args.port) as live:
        if args.json:
            emit({"foxglove": live.url, "port": live.port, "serving": args.box})
        else:
            print(
                f"foxglove: {live.url} (port {live.port}); serving {args.box}; Ctrl-C stops",
                flush=True,
            )
        wall0 = t0 = None
        i = 0
        try:
            while args.count == 0 or i < args.count:
                f = box.read()
                if wall0 is None or t0 is None:
                    wall0, t0 = time.monotonic(), f.t_s
                delay = wall0 + (f.t_s - t0) - time.monotonic()
                if delay > 0:  # a simulated box runs faster than real time: keep pace
                    time.sleep(delay)
                live.frame(f, "monitor")
                i += 1
        except KeyboardInterrupt:
            print("softpad box monitor: stopped", file=sys.stderr)
    return 0
