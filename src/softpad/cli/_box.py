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

#: The box a monitor watches without --box or --config: the box daemon's default link.
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


class Pacer:
    """Keeps a simulated box opened by this command at real time: each frame waits until the
    wall clock reaches its box time. A served box is paced by its daemon; ``sim://?realtime=0``
    asks for no pacing (as fast as the simulator computes).

    Parameters
    ----------
    url
        The box's URL.
    """

    def __init__(self, url: str) -> None:
        from softpad.box import parse_url

        self.on = url.startswith("sim://") and parse_url(url)[2].get("realtime") != "0"
        self._start: tuple[float, float] | None = None  # (wall s, box s) of the first frame

    def wait(self, t_s: float) -> None:
        """Wait until the wall clock reaches box time ``t_s`` (s) after the first frame."""
        import time

        if not self.on:
            return
        if self._start is None:
            self._start = (time.monotonic(), t_s)
        delay = self._start[0] + (t_s - self._start[1]) - time.monotonic()
        if delay > 0:
            time.sleep(delay)


def describe_box(url: str, paced: bool | None = None) -> str:
    """Which box a command talks to, for its first line (``paced``: whether the command keeps
    a simulated box at real time; None says nothing of it)."""
    if url.startswith("sim://"):
        pace = {True: " (paced at real time; sim://?realtime=0: unpaced)", False: " (unpaced)"}
        return f"the simulated box {url}{'' if paced is None else pace[paced]}"
    if url.startswith("zenoh://"):
        return f"the served box at {url}"
    return f"the box {url}"


def _first_line(
    command: str, url: str, json_mode: bool, tail: str = "", paced: bool | None = None
) -> None:
    """The first line of a command that talks to a box: which box (stderr under --json)."""
    say(f"softpad box {command}: {describe_box(url, paced)}{tail}", json_mode)


def _stamped(box: Any, i: int, pacer: Pacer) -> tuple[int, Any]:
    """(seq, frame): the daemon's sequence number for a served box, else the frame index."""
    from softpad.box import ZenohBox

    if isinstance(box, ZenohBox):
        s = box.read_stamped()
        return s.seq, s.frame
    f = box.read()
    pacer.wait(f.t_s)
    return i + 1, f


def read(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.errors import InputError

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
        i = 0
        while args.count == 0 or i < args.count:
            seq, f = _stamped(box, i, pacer)
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
    import time

    from softpad.errors import InputError
    from softpad.layout import parse_layout

    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")
    layout = parse_layout(args.layout)
    if args.foxglove:
        return _monitor_foxglove(args, layout)
    pacer = Pacer(args.box)
    with _open_watched(args.box) as box:
        tail = " (read-only); Ctrl-C stops"
        _first_line("monitor", args.box, args.json, tail, paced=pacer.on)
        n = min(layout.n_modules, box.channels)
        terminal = sys.stdout.isatty() and not args.json
        if not args.json:
            print(_monitor_header(n), flush=True)
        every = max(1, round(box.sample_rate_hz * args.period_s))
        i, lost, last, lat, t0, i0 = 0, 0, None, [], time.monotonic(), 0
        try:
            while args.count == 0 or i < args.count:
                seq, f, latency_s = _timed(box, i, pacer)
                lost += 0 if last is None else max(0, seq - last - 1)
                last, i = seq, i + 1
                if latency_s is not None:
                    lat.append(latency_s)
                if i % every == 0 or i == args.count:  # frames per wall second in the period
                    now = time.monotonic()
                    rate = (i - i0) / max(now - t0, 1e-9)
                    _monitor_line(args.json, terminal, seq, f, n, rate, lat, lost)
                    lat, t0, i0 = [], now, i
        finally:  # Ctrl-C too (exit 130): end the line refreshed in place
            if terminal:
                print()
    return 0


def _open_watched(url: str) -> Any:
    """The box a monitor watches; when nothing serves at a zenoh:// link, the error says how
    to serve one or to watch a simulated box instead."""
    from softpad.box import ConnectionLost, open_box

    try:
        return open_box(url)
    except ConnectionLost as exc:
        raise ConnectionLost(
            f"{exc} (is a box served there? 'softpad box serve --sim' serves the simulator; "
            "--box sim:// watches a simulated box of this command's own)"
        ) from None


def _timed(box: Any, i: int, pacer: Pacer) -> tuple[int, Any, float | None]:
    """(seq, frame, latency s): the latency from the daemon's sample to now for a served box
    (its monotonic clock is this machine's on loopback), None for a box opened here."""
    import time

    from softpad.box import ZenohBox

    if isinstance(box, ZenohBox):
        s = box.read_stamped()
        return s.seq, s.frame, time.monotonic() - s.mono_s
    f = box.read()
    pacer.wait(f.t_s)
    return i + 1, f, None


def _monitor_header(n: int) -> str:
    modules = " ".join(f"{f'm{k + 1}_kpa':>8s}" for k in range(n))
    return (
        f"{'seq':>9s} {'t_s':>9s} {modules} {'supply_kpa':>10s} {'frames/s':>9s} "
        f"{'p50_ms':>8s} {'p99_ms':>8s} {'lost':>6s}"
    )


def _monitor_line(
    as_json: bool, terminal: bool, seq: int, f: Any, n: int, rate: float, lat: list[float],
    lost: int,
) -> None:  # fmt: skip
    import numpy as np

    p50 = p99 = None
    if lat:
        p50, p99 = (round(float(v) * 1e3, 3) for v in np.percentile(lat, [50, 99]))
    if as_json:
        d = f.to_dict()
        d["pressures_kpa"] = d["pressures_kpa"][:n]
        emit({"seq": seq, **d, "rate_hz": round(rate, 1), "latency_p50_ms": p50,
              "latency_p99_ms": p99, "lost": lost})  # fmt: skip
        return
    vals = " ".join(f"{v / 1e3:8.3f}" for v in f.pressures_pa[:n])
    ms = " ".join(f"{'-':>8s}" if v is None else f"{v:8.2f}" for v in (p50, p99))
    line = f"{seq:9d} {f.t_s:9.3f} {vals} {f.supply_pa / 1e3:10.2f} {rate:9.1f} {ms} {lost:6d}"
    print("\r" + line if terminal else line, end="" if terminal else "\n", flush=True)


def stats(args: argparse.Namespace) -> int:
    from softpad.box import ZenohBox, open_box
    from softpad.errors import InputError

    with open_box(args.box) as box:
        if not isinstance(box, ZenohBox):
            raise InputError(f"--box must be a served box (zenoh://HOST:PORT), got {args.box!r}")
        _first_line("stats", args.box, args.json)
        d = box.request("stats")
    d.pop("ok", None)
    if args.json:
        emit(d)
        return 0

    def ms(v: float | None) -> str:
        return "-" if v is None else f"{v * 1e3:.3f} ms"

    print(f"rate      {d['achieved_rate_hz']:.1f} Hz achieved of {d['target_rate_hz']:g} Hz")
    print(
        f"period    p50 {ms(d.get('period_p50_s'))}, p99 {ms(d['period_p99_s'])}, "
        f"max {ms(d.get('period_max_s'))}, jitter (std) {ms(d['jitter_std_s'])}; "
        f"error p99 {ms(d.get('period_error_p99_s'))}"
    )
    print(f"dropped   {d['dropped_samples']} ticks; malformed payloads {d['malformed_payloads']}")
    if "cpu_percent" in d:
        print(
            f"cpu       daemon {d['cpu_percent']:.1f} % of a core, sampling thread "
            f"{d['sampler_cpu_percent']:.1f} %; gc {d['gc_collections']} collections, "
            f"longest {ms(d['gc_pause_max_s'])}; load average {d['load_average_1min']:g}"
        )
    print(
        f"safety    {d['safety_vents']} vents, {d['watchdog_trips']} watchdog trips, {d['refused_commands']} refused, {d.get('auth_failures', 0)} forged or replayed"
    )
    print(f"control   {d['controller'] or 'nobody'}; frames {d['frames']}, seq {d['seq']}")
    return 0


def _daemon_for(args: argparse.Namespace) -> Any:
    from softpad.box import BoxDaemon, daemon_auth, open_box, parse_url, served_services
    from softpad.config import Installation, check_endpoint, check_remote_policy, load_installation
    from softpad.errors import InputError

    if args.rt_priority is not None and not 1 <= args.rt_priority <= 99:
        raise InputError(f"--rt-priority must be from 1 to 99, got {args.rt_priority}")
    url = f"hw://{args.hardware}" if args.hardware else _sim_url(args)
    scheme, location, _options = parse_url(url)
    path = args.hardware or args.config or (location if scheme == "hw" else None)
    inst = load_installation(path) if path else Installation()
    link = inst.link
    listen = [check_endpoint(e, "--listen") for e in args.listen or ()]
    if args.port is not None:
        if not 1 <= args.port <= 65535:
            raise InputError(f"--port must be within 1..65535, got {args.port}")
        listen.append(f"tcp/127.0.0.1:{args.port}")
    if listen:
        import dataclasses

        link = dataclasses.replace(link, listen=tuple(listen))
        check_remote_policy(link)
    if link.tls_certificate is not None and not any(e.startswith("tls/") for e in link.listen):
        raise InputError(
            "link.tls_certificate is set but no listen endpoint is tls/: TLS would protect "
            f"nothing on {', '.join(link.listen)}; listen on tls/HOST:PORT or drop the TLS keys"
        )
    box = open_box(url)
    try:
        services = served_services(url, box)  # the simulator's world and robot for sim://
        return BoxDaemon(
            box,
            link.listen,
            link.key_prefix,
            max_pressure_pa=inst.thresholds.max_pressure_pa,
            watchdog_s=args.watchdog_s or link.watchdog_s,
            watchdog_action=link.watchdog_action,
            services=services,
            lockstep_frames=2 if services and not args.realtime else None,
            rt_priority=args.rt_priority,
            auth=daemon_auth(link),
            log=_daemon_log,
        )
    except BaseException:
        box.close()
        raise


def _daemon_log(text: str) -> None:
    """The daemon's messages on stderr, but its start line: the command's first line says
    what is served, in words (the daemon names the outermost layer of the box's classes)."""
    if not text.startswith("serving "):
        print(f"softpad box serve: {text}", file=sys.stderr, flush=True)


#: Frame rate of ``box serve --sim`` unless the URL or --rate-hz says otherwise, Hz (the
#: hardware box's default sample rate).
SERVE_SIM_RATE_HZ = 1000.0


def _sim_url(args: argparse.Namespace) -> str:
    """The --box URL with the served simulator's rate: --rate-hz, else the URL's rate_hz, else
    :data:`SERVE_SIM_RATE_HZ`."""
    from softpad.box import parse_url

    url = str(args.box)
    if not url.startswith("sim://"):
        return url
    if args.rate_hz is None and "rate_hz" in parse_url(url)[2]:
        return url
    rate = args.rate_hz or SERVE_SIM_RATE_HZ
    if "rate_hz" in parse_url(url)[2]:
        raise InputError("give the rate once: --rate-hz or the URL's rate_hz")
    return url + ("&" if "?" in url else "?") + f"rate_hz={rate:g}"


def serve(args: argparse.Namespace) -> int:
    daemon = _daemon_for(args)
    what = _served(args)
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


def _served(args: argparse.Namespace) -> str:
    """What ``box serve`` serves, in words: the simulated box and its URL, or the hardware."""
    if args.hardware:
        return f"the hardware box wired in {args.hardware}"
    return f"the simulated box {_sim_url(args)}"


def inflate(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.control import InflationParams, inflate_and_adjust
    from softpad.errors import InputError

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
    import sys
    import time

    from softpad.cli._installation import installed_pad_pose
    from softpad.errors import InputError
    from softpad.record import FoxgloveLive

    if not 0 <= args.port <= 65535:
        raise InputError(f"--port must be within 0..65535, got {args.port}")
    pad = installed_pad_pose(getattr(args, "config", None))  # the installation's [pad.pose]
    with _open_watched(args.box) as box, FoxgloveLive(args.port, layout, pad=pad) as live:
        if args.json:
            emit({"foxglove": live.url, "port": live.port, "serving": args.box})
        else:
            print(
                f"softpad box monitor: {describe_box(args.box)} to Foxglove at {live.url} "
                f"(port {live.port}); Ctrl-C stops",
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
        finally:  # Ctrl-C too (exit 130)
            print("softpad box monitor: stopped", file=sys.stderr)
    return 0
