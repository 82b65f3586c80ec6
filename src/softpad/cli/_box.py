"""``softpad box read|monitor|stats|serve|inflate``: frames, live views, the box daemon,
inflation."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad.cli._args import (
    add_box_option,
    add_command,
    add_group,
    add_number,
    add_p0_option,
    bounded_int,
    finite_float,
)
from softpad.cli._output import emit, say
from softpad.errors import InputError

_EPILOG = """examples:
  softpad box read --count 5
  softpad box read --box 'sim://?inflated_kpa=1.1&object=banana' --count 3 --json
  softpad box read --box zenoh://127.0.0.1:7447 --count 100 --json     a served box (monitor)
"""

_GROUP_EPILOG = """examples:
  softpad box read --count 5                             frames of a simulated box (kPa)
  softpad box serve --sim                                the box daemon: the simulator on zenoh
  softpad box monitor                                    watch the served box (127.0.0.1:7447)
  softpad box stats                                      its achieved rate, jitter, drops
  softpad box inflate --box zenoh://127.0.0.1:7447       inflate and adjust every module to p0
"""

_SERVE_EPILOG = """examples:
  softpad box serve --sim                                   the simulator on tcp/127.0.0.1:7447
  softpad box serve --sim --port 7450 --rate-hz 500         (--port N: tcp/127.0.0.1:N)
  softpad box serve --box hw:///etc/softpad/site.toml       the real box (GPIO + IIO)
  then: softpad box monitor --box zenoh://127.0.0.1:7447
        softpad run --box zenoh://127.0.0.1:7447 --objects object-5   (with --sim)

Zenoh with multicast scouting off, listening only on the endpoints given (127.0.0.1 by
default). Any number of monitors; one controlling client at a time. When the controller's
liveliness token vanishes or its heartbeats stop for the watchdog time, every inflation valve
closes. Listening beyond loopback needs link.allow_remote = true and authentication in the
installation file; otherwise the daemon refuses to start. Ctrl-C or SIGTERM stops it.
"""


_MONITOR_EPILOG = """examples:
  softpad box monitor                                    the served box (box serve), plain lines
  softpad box monitor --box sim:// --count 500           a simulated box of its own, real time
  softpad box monitor --foxglove                         the served box, ws://127.0.0.1:8765
  softpad box monitor --foxglove --port 0 --box 'sim://?object=banana&inflated_kpa=1.1'
  then in Foxglove: Open connection -> Foxglove WebSocket -> ws://127.0.0.1:8765
  (docs/foxglove-layout.json: a pressure plot per module and the pad picture)

Serves /softpad/module_K/pressure for the pad's modules (--layout; FluidPressure: absolute, Pa),
/softpad/pressures (gauge, Pa), /softpad/supply/pressure, /tf_static and /softpad/pad (3D
picture) to any number of viewers, on 127.0.0.1 only, at the box's pace (never faster than real
time). Clients of either subprotocol connect: foxglove.websocket.v1 (Foxglove Studio before the
SDK, Lichtblick) and foxglove.sdk.v1 (today's Foxglove app).
Ctrl-C stops. 'softpad run --foxglove PORT' serves a whole run (plans, contact, robot) live.
"""

_INFLATE_EPILOG = """examples:
  softpad box inflate                                 the simulated box, to p0
  softpad box inflate --box zenoh://127.0.0.1:7447 --json
"""


_MONITOR_DESCRIPTION = """\
Live figures of a box, one line per period (--period-s): sequence number, box time, the pad's
module pressures and the supply (gauge, kPa), frames per second, latency p50/p99 (ms, from the
daemon's sample to this monitor; a served box on this machine) and frames lost on the way. On a
terminal the line refreshes in place under a header; into a pipe or a file each period is a
plain line; --json prints one JSON object per period. With --foxglove the frames are served to
Foxglove viewers. A monitor never commands valves. Without --box it watches the installation's
link (zenoh://127.0.0.1:7447, or the link of --config FILE) and fails within seconds, naming
the link, when nothing serves there; a simulated box (--box sim://) runs paced at real time
unless its URL says realtime=0."""

#: The box a monitor watches without --box or --config: the box daemon's default link
#: (:data:`softpad.box.LINK_DEFAULT`, not imported so that building the parser loads no box).
LINK_DEFAULT = "zenoh://127.0.0.1:7447"

_MONITOR_BOX_HELP = (
    f"box URL (default: the installation's link, {LINK_DEFAULT}; --config FILE for another; "
    "sim:// for a simulated box of its own, paced at real time)"
)

#: Fields of ``box read --json`` (one object per frame) and ``box monitor --json`` (per period).
READ_FIELDS = ("seq", "t_s", "pressures_kpa", "supply_kpa")
MONITOR_FIELDS = (
    "seq", "t_s", "pressures_kpa", "supply_kpa", "rate_hz", "latency_p50_ms",
    "latency_p99_ms", "lost",
)  # fmt: skip

_INFLATE_DESCRIPTION = """\
Bring every module to p0 within t_adj and print the reference (mean of 10 reads); works on
any box URL, e.g. a zenoh:// box served by 'softpad box serve'."""


def register(sub: Any) -> None:
    bsub = add_group(
        sub,
        "box",
        "talk to a pneumatic box: read, monitor, stats, serve (zenoh daemon), inflate",
        "Pneumatic box utilities. Every action says on its first line which box it talks to.",
        _GROUP_EPILOG,
    )
    r = _action(
        bsub,
        read,
        "print frames (gauge pressure of every channel and the supply, kPa)",
        "Read frames from a box and print one line per frame (kPa).",
        _EPILOG,
        json=f"JSON lines, one per frame: {', '.join(READ_FIELDS)} (gauge, kPa)",
    )
    r.add_argument("--count", type=int, default=10, help="frames, 0 for endless (default 10)")
    r.add_argument("--every", type=int, default=1, help="print every k-th frame (default 1)")
    m = _action(
        bsub,
        monitor,
        "watch a box live: a line per period, or Foxglove (--foxglove; read-only)",
        _MONITOR_DESCRIPTION,
        _MONITOR_EPILOG,
        json=f"JSON lines, one per period: {', '.join(MONITOR_FIELDS)} (kPa, ms); with "
        "--foxglove: the viewer URL",
        box=LINK_DEFAULT,
        box_help=_MONITOR_BOX_HELP,
    )
    m.add_argument("--foxglove", action="store_true", help="serve to Foxglove (WebSocket)")
    m.add_argument(
        "--port",
        type=bounded_int("--port", 0, 65535),
        default=8765,
        help="port on 127.0.0.1 (0: a free one)",
    )
    m.add_argument("--count", type=int, default=0, help="frames, 0 for endless (default 0)")
    add_number(
        m, "--period-s", "box time between two lines, s, up to 60 (default 0.5)", 0.5, lo=0.001,
        hi=60.0, unit="s",
    )  # fmt: skip
    m.add_argument("--layout", default="2x3", help="the pad: its modules are shown (default 2x3)")
    _action(
        bsub,
        stats,
        "sampling figures of a served box: achieved rate, jitter, dropped samples",
        "Ask a box daemon for its sampling statistics.",
        json="print one JSON object",
        box=LINK_DEFAULT,
    )
    _register_serve(bsub)
    i = _action(
        bsub,
        inflate,
        "inflate every module to p0 and save the reference (Section 6.2.1.1)",
        _INFLATE_DESCRIPTION,
        json="print the result as one JSON object",
    )
    i.add_argument("--modules", type=int, default=6, help="modules on the pad (default 6)")
    add_p0_option(i)


def _action(
    bsub: Any, handler: Any, *texts: str, json: str, box: str = "sim://", box_help: str = ""
) -> argparse.ArgumentParser:
    """The parser of the box action ``handler`` (named like it: ``read`` is ``box read``),
    with ``--box`` (default ``box``); ``texts`` as for :func:`add_command`."""
    p = add_command(bsub, handler.__name__, *texts, json=json)
    add_box_option(p, box, box_help or None)
    p.set_defaults(handler=handler)
    return p


def _register_serve(bsub: Any) -> None:
    s = _action(
        bsub,
        serve,
        "run the box daemon: serve the simulator or the hardware over zenoh",
        "Serve a box over zenoh (frames pushed, valve commands acknowledged).",
        _SERVE_EPILOG,
        json="print the endpoints as one JSON object",
        box_help="the box to serve: any back-end's URL (sim://, hw://FILE.toml: the real box "
        "wired in FILE; default sim://)",
    )
    what = s.add_mutually_exclusive_group()
    what.add_argument("--sim", action="store_true", help="serve the simulated box (--box URL)")
    what.add_argument("--hardware", metavar="FILE.toml", help="the same as --box hw://FILE.toml")
    s.add_argument("--config", metavar="FILE.toml", help="installation file (link, thresholds)")
    s.add_argument(
        "--listen",
        action="append",
        metavar="ENDPOINT",
        help="zenoh endpoint (default tcp/127.0.0.1:7447 or the installation file's)",
    )
    s.add_argument(
        "--port", type=int, help="listen on tcp/127.0.0.1:PORT (loopback), beside any --listen"
    )
    add_number(
        s,
        "--rate-hz",
        "with --sim: frames per second of the simulated box (default 1000, or the --box URL's "
        "rate_hz); 'softpad box stats' tells what the machine achieves",
        lo=1.0,
        hi=10000.0,
        unit="Hz",
    )
    add_number(
        s,
        "--watchdog-s",
        "controller silence that closes the inflation valves, s (default 0.5)",
        lo=0.01,
        hi=60.0,
        unit="s",
    )
    s.add_argument(
        "--realtime",
        action="store_true",
        help="with --sim: run the simulator on the wall clock even when its controller lags "
        "(default: at most 2 frames ahead of the frames the controller has read)",
    )
    s.add_argument(
        "--duration-s",
        type=finite_float("--duration-s", lo=0.001, unit="s"),
        help="stop after this long (default: run forever)",
    )
    s.add_argument(
        "--rt-priority",
        type=int,
        metavar="N",
        help="run the daemon under the real-time SCHED_FIFO policy at priority N (1..99; "
        "Linux, root or CAP_SYS_NICE): the 1 kHz schedule holds on a loaded machine",
    )


def _first_line(
    command: str, url: str, json_mode: bool, tail: str = "", paced: bool | None = None
) -> None:
    """The first line of a command that talks to a box: which box (stderr under --json)."""
    from softpad.box import describe_box

    say(f"softpad box {command}: {describe_box(url, paced)}{tail}", json_mode)


def read(args: argparse.Namespace) -> int:
    from softpad.box import Pacer, open_box, stamped_frames

    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    if args.every < 1:
        raise InputError(f"--every must be >= 1, got {args.every}")
    pacer = Pacer(args.box)
    with open_box(args.box) as box:
        _first_line("read", args.box, args.json, paced=pacer.on)
        args.partial = {"frames": 0}
        if not args.json:
            head = "    t_s  " + " ".join(f"{'ch' + str(k + 1):>8s}" for k in range(box.channels))
            print(head + "  supply   (kPa)")
        frames = stamped_frames(box, pacer)
        i = 0
        while args.count == 0 or i < args.count:
            seq, f, _ = next(frames)
            if i % args.every == 0:
                if args.json:
                    emit({"seq": seq, **f.to_dict()})
                else:
                    vals = " ".join(f"{v / 1e3:8.4f}" for v in f.pressures_pa)
                    print(f"{f.t_s:8.3f}  {vals}  {f.supply_pa / 1e3:6.2f}", flush=True)
            i += 1
            args.partial["frames"] = i
    return 0


def monitor(args: argparse.Namespace) -> int:
    from softpad.box import Pacer, monitor_header, monitor_periods, open_watched
    from softpad.layout import parse_layout

    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    layout = parse_layout(args.layout)
    if args.foxglove:
        return _monitor_foxglove(args, layout)
    pacer = Pacer(args.box)
    with open_watched(args.box) as box:
        tail = " (read-only); Ctrl-C stops"
        _first_line("monitor", args.box, args.json, tail, paced=pacer.on)
        n = min(layout.n_modules, box.channels)
        terminal = sys.stdout.isatty() and not args.json
        if not args.json:
            print(monitor_header(n), flush=True)
        try:
            for period in monitor_periods(box, pacer, n, args.period_s, args.count):
                if args.json:
                    emit(period.to_dict())
                else:
                    line = period.line()
                    print(
                        "\r" + line if terminal else line, end="" if terminal else "\n", flush=True
                    )
        finally:  # Ctrl-C too (exit 130): end the line refreshed in place
            if terminal:
                print()
    return 0


def stats(args: argparse.Namespace) -> int:
    from softpad.box import ZenohBox, open_box, stats_lines

    with open_box(args.box) as box:
        if not isinstance(box, ZenohBox):
            raise InputError(f"--box must be a served box (zenoh://HOST:PORT), got {args.box!r}")
        _first_line("stats", args.box, args.json)
        d = box.request("stats")
    d.pop("ok", None)
    if args.json:
        emit(d)
    else:
        print("\n".join(stats_lines(d)))
    return 0


def _serve_options(args: argparse.Namespace) -> Any:
    from softpad.box import ServeOptions

    return ServeOptions(
        args.box, args.hardware, args.config, args.listen or (), args.port, args.rate_hz,
        args.watchdog_s, args.realtime, args.rt_priority,
    )  # fmt: skip


def _daemon_for(args: argparse.Namespace) -> Any:
    return _serve_options(args).daemon(_daemon_log)


def _daemon_log(text: str) -> None:
    """The daemon's messages on stderr, but its start line: the command's first line says
    what is served, in words (the daemon names the outermost layer of the box's classes)."""
    if not text.startswith("serving "):
        print(f"softpad box serve: {text}", file=sys.stderr, flush=True)


def serve(args: argparse.Namespace) -> int:
    options = _serve_options(args)
    daemon = options.daemon(_daemon_log)
    what = options.served
    try:
        with daemon:
            if args.json:
                emit({"serving": what, "listen": list(daemon.listen), "key_prefix": daemon.prefix})
            else:
                print(
                    f"softpad box serve: serving {what} on {', '.join(daemon.listen)} "
                    f"(key {daemon.prefix}); Ctrl-C stops",
                    flush=True,
                )
            daemon.wait(args.duration_s)
    finally:  # Ctrl-C (exit 130) and SIGTERM (143) too: the daemon closed the valves
        print("softpad box serve: stopped; valves closed", file=sys.stderr)
    return 0


def inflate(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.control import InflationParams, inflate_and_adjust

    with open_box(args.box) as box:
        _first_line("inflate", args.box, args.json)
        if not 1 <= args.modules <= box.channels:
            raise InputError(
                f"--modules must be within 1..{box.channels} (channels of the box), got {args.modules}"
            )
        take = getattr(box, "take_control", None)
        if take is not None:  # a served box: control first, then only frames under its key
            take()
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


def _monitor_foxglove(args: argparse.Namespace, layout: Any) -> int:
    """Read frames from the box and publish them to Foxglove, paced to real time."""
    from softpad.box import describe_box, open_watched
    from softpad.cli._installation import installed_pad_pose
    from softpad.record import FoxgloveLive, relay_frames

    if not 0 <= args.port <= 65535:
        raise InputError(f"--port must be within 0..65535, got {args.port}")
    pad = installed_pad_pose(getattr(args, "config", None))  # the installation's [pad.pose]
    with open_watched(args.box) as box, FoxgloveLive(args.port, layout, pad=pad) as live:
        if args.json:
            emit({"foxglove": live.url, "port": live.port, "serving": args.box})
        else:
            print(
                f"softpad box monitor: {describe_box(args.box)} to Foxglove at {live.url} "
                f"(port {live.port}); Ctrl-C stops",
                flush=True,
            )
        try:
            relay_frames(box, live, args.count)
        finally:  # Ctrl-C too (exit 130)
            print("softpad box monitor: stopped", file=sys.stderr)
    return 0
