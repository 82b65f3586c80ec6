"""``softpad box read|monitor|stats|serve|inflate``: frames, live views, the box daemon,
inflation."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad.cli._args import finite_float
from softpad.cli._output import emit

_EPILOG = """examples:
  softpad box read --count 5
  softpad box read --box 'sim://?inflated_kpa=1.1&object=banana' --count 3 --json
  softpad box read --box zenoh://127.0.0.1:7447 --count 100 --json     a served box (monitor)
"""

_SERVE_EPILOG = """examples:
  softpad box serve --sim                                   the simulator on tcp/127.0.0.1:7447
  softpad box serve --sim --box 'sim://?rate_hz=1000' --listen tcp/127.0.0.1:7450
  softpad box serve --hardware /etc/softpad/site.toml       the real box (GPIO + IIO)
  then: softpad box monitor --box zenoh://127.0.0.1:7447
        softpad run --box zenoh://127.0.0.1:7447 --objects object-5   (with --sim)

Zenoh with multicast scouting off, listening only on the endpoints given (127.0.0.1 by
default). Any number of monitors; one controlling client at a time. When the controller's
liveliness token vanishes or its heartbeats stop for the watchdog time, every inflation valve
closes. Listening beyond loopback needs link.allow_remote = true and authentication in the
installation file; otherwise the daemon refuses to start. Ctrl-C or SIGTERM stops it.
"""


def _box_arg(p: argparse.ArgumentParser, default: str = "sim://") -> None:
    p.add_argument("--box", default=default, metavar="URL", help=f"box URL (default {default})")


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
  softpad box inflate --box zenoh://127.0.0.1:7447 --json
"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "box",
        help="talk to a pneumatic box: read, monitor, serve (zenoh daemon), inflate",
        description="Pneumatic box utilities.",
    )
    bsub = p.add_subparsers(dest="box_command", metavar="ACTION")
    fmt = argparse.RawDescriptionHelpFormatter
    r = bsub.add_parser(
        "read",
        help="print frames (gauge pressure of every channel and the supply, kPa)",
        description="Read frames from a box and print one line per frame (kPa).",
        epilog=_EPILOG,
        formatter_class=fmt,
    )
    _box_arg(r)
    r.add_argument("--count", type=int, default=10, help="frames, 0 for endless (default 10)")
    r.add_argument("--every", type=int, default=1, help="print every k-th frame (default 1)")
    r.add_argument(
        "--json",
        action="store_true",
        help="JSON lines: seq, t_s, pressures_pa, supply_pa (the last the error if any)",
    )
    r.set_defaults(handler=read)
    m = bsub.add_parser(
        "monitor",
        help="watch a box live: one refreshing line, or Foxglove (--foxglove; read-only)",
        description=(
            "Live pressures (kPa), frame rate and lost frames on one line; with --foxglove the "
            "frames are served to Foxglove viewers. A monitor never commands valves."
        ),
        epilog=_MONITOR_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    m.add_argument("--box", default="sim://", metavar="URL", help="box URL (default sim://)")
    m.add_argument("--foxglove", action="store_true", help="serve to Foxglove (WebSocket)")
    m.add_argument("--port", type=int, default=8765, help="port on 127.0.0.1 (0: a free one)")
    m.add_argument("--count", type=int, default=0, help="frames, 0 for endless (default 0)")
    m.add_argument("--json", action="store_true", help="with --foxglove: the viewer URL as JSON")
    m.set_defaults(handler=monitor)
    st = bsub.add_parser(
        "stats",
        help="sampling figures of a served box: achieved rate, jitter, dropped samples",
        description="Ask a box daemon for its sampling statistics.",
    )
    _box_arg(st, "zenoh://127.0.0.1:7447")
    st.add_argument("--json", action="store_true", help="print one JSON object")
    st.set_defaults(handler=stats)
    _register_serve(bsub)
    _register_inflate(bsub)
    p.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(handler=_usage, _parser=p)


def _register_serve(bsub: Any) -> None:
    s = bsub.add_parser(
        "serve",
        help="run the box daemon: serve the simulator or the hardware over zenoh",
        description="Serve a box over zenoh (frames pushed, valve commands acknowledged).",
        epilog=_SERVE_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    what = s.add_mutually_exclusive_group(required=True)
    what.add_argument("--sim", action="store_true", help="serve the simulated box (--box URL)")
    what.add_argument("--hardware", metavar="FILE.toml", help="serve the real box wired in FILE")
    s.add_argument("--box", default="sim://", metavar="URL", help="with --sim: the sim:// URL")
    s.add_argument("--config", metavar="FILE.toml", help="installation file (link, thresholds)")
    s.add_argument(
        "--listen",
        action="append",
        metavar="ENDPOINT",
        help="zenoh endpoint (default tcp/127.0.0.1:7447 or the installation file's)",
    )
    s.add_argument(
        "--watchdog-s",
        type=finite_float("watchdog time", lo=0.01, hi=60.0, unit="s"),
        help="controller silence that closes the inflation valves, s (default 0.5)",
    )
    s.add_argument(
        "--realtime",
        action="store_true",
        help="with --sim: run the simulator on the wall clock even when its controller lags "
        "(default: at most 2 frames ahead of the frames the controller has read)",
    )
    s.add_argument("--duration-s", type=float, help="stop after this long (default: run forever)")
    s.add_argument("--json", action="store_true", help="print the endpoints as one JSON object")
    s.set_defaults(handler=serve)


def _register_inflate(bsub: Any) -> None:
    i = bsub.add_parser(
        "inflate",
        help="inflate every module to p0 and save the reference (Section 6.2.1.1)",
        description=(
            "Bring every module to p0 within t_adj and print the reference (mean of 10 reads); "
            "works on any box URL, e.g. a zenoh:// box served by 'softpad box serve'."
        ),
    )
    _box_arg(i)
    i.add_argument("--modules", type=int, default=6, help="modules on the pad (default 6)")
    i.add_argument(
        "--p0-kpa",
        type=finite_float("--p0-kpa", lo=0.5, hi=2.8, unit="kPa"),
        default=1.1,
        help="target pressure p0, kPa, 0.5..2.8 (default 1.1)",
    )
    i.add_argument("--json", action="store_true", help="print the result as one JSON object")
    i.set_defaults(handler=inflate)


def _usage(args: argparse.Namespace) -> int:
    from softpad.cli.main import UsageError

    args._parser.print_help(sys.stderr)
    raise UsageError(
        "an ACTION is required: read, monitor, stats, serve or inflate (see softpad box --help)"
    )


def _stamped(box: Any, i: int) -> tuple[int, Any]:
    """(seq, frame): the daemon's sequence number for a served box, else the frame index."""
    from softpad.box import ZenohBox

    if isinstance(box, ZenohBox):
        s = box.read_stamped()
        return s.seq, s.frame
    return i + 1, box.read()


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
            seq, f = _stamped(box, i)
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

    from softpad.box import open_box
    from softpad.errors import InputError

    if args.foxglove:
        return _monitor_foxglove(args)
    if args.count < 0:
        raise InputError(f"--count must be >= 0 (0: endless), got {args.count}")

    with open_box(args.box) as box:
        i, t0, gaps, last = 0, time.monotonic(), 0, None
        while args.count == 0 or i < args.count:
            seq, f = _stamped(box, i)
            gaps += 0 if last is None else max(0, seq - last - 1)
            last, i = seq, i + 1
            if i % max(1, int(box.sample_rate_hz) // 10) == 0 or i == args.count:
                rate = i / max(time.monotonic() - t0, 1e-9)
                vals = " ".join(f"{v / 1e3:7.3f}" for v in f.pressures_pa)
                print(
                    f"\rseq {seq:9d}  t {f.t_s:9.3f} s  {vals} kPa  {rate:7.1f} frames/s  "
                    f"lost {gaps}",
                    end="",
                    flush=True,
                )
        print()
    return 0


def stats(args: argparse.Namespace) -> int:
    from softpad.box import ZenohBox, open_box
    from softpad.errors import InputError

    with open_box(args.box) as box:
        if not isinstance(box, ZenohBox):
            raise InputError(f"--box must be a served box (zenoh://HOST:PORT), got {args.box!r}")
        d = box.request("stats")
    d.pop("ok", None)
    if args.json:
        emit(d)
        return 0

    def ms(v: float | None) -> str:
        return "-" if v is None else f"{v * 1e3:.3f} ms"

    print(f"rate      {d['achieved_rate_hz']:.1f} Hz achieved of {d['target_rate_hz']:g} Hz")
    print(
        f"period    mean {ms(d['period_mean_s'])}, jitter (std) {ms(d['jitter_std_s'])}, p99 {ms(d['period_p99_s'])}"
    )
    print(f"dropped   {d['dropped_samples']} samples; malformed payloads {d['malformed_payloads']}")
    print(
        f"safety    {d['safety_vents']} vents, {d['watchdog_trips']} watchdog trips, {d['refused_commands']} refused"
    )
    print(f"control   {d['controller'] or 'nobody'}; frames {d['frames']}, seq {d['seq']}")
    return 0


def _daemon_for(args: argparse.Namespace) -> Any:
    from softpad.box import BoxDaemon, HardwareBox, SimBox, open_box
    from softpad.config import Installation, check_endpoint, check_remote_policy, load_installation

    path = args.hardware or args.config
    inst = load_installation(path) if path else Installation()
    link = inst.link
    if args.listen:
        import dataclasses

        link = dataclasses.replace(
            link, listen=tuple(check_endpoint(e, "--listen") for e in args.listen)
        )
        check_remote_policy(link)
    box = HardwareBox(inst.box) if args.hardware else open_box(args.box)
    try:
        services = {}
        if isinstance(box, SimBox):  # the world and robot too, so 'softpad run' works over zenoh
            from softpad.harness import simulation_extensions

            services = simulation_extensions(box)
        return BoxDaemon(
            box,
            link.listen,
            link.key_prefix,
            max_pressure_pa=inst.thresholds.max_pressure_pa,
            watchdog_s=args.watchdog_s or link.watchdog_s,
            watchdog_action=link.watchdog_action,
            services=services,
            lockstep_frames=2 if services and not args.realtime else None,
            auth=_auth(link),
            log=lambda text: print(f"softpad box serve: {text}", file=sys.stderr, flush=True),
        )
    except BaseException:
        box.close()
        raise


def _auth(link: Any) -> dict[str, Any]:
    """session_config keyword arguments for the link's authentication."""
    out: dict[str, Any] = {}
    if link.user is not None:
        out.update(user=link.user, dictionary_file=link.password_file)
    if link.tls_certificate is not None:
        tls = {
            "listen_certificate": link.tls_certificate,
            "listen_private_key": link.tls_private_key,
        }
        if link.tls_root_ca:
            tls["root_ca_certificate"] = link.tls_root_ca
        out["tls"] = tls
    return out


def serve(args: argparse.Namespace) -> int:
    import signal
    import threading

    daemon = _daemon_for(args)

    def _terminate(signum: int, frame: object) -> None:
        raise KeyboardInterrupt  # SIGTERM (systemd) stops like Ctrl-C

    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _terminate) if main_thread else None
    try:
        with daemon:
            if args.json:
                emit(
                    {
                        "serving": type(daemon.box).__name__,
                        "listen": list(daemon.listen),
                        "key_prefix": daemon.prefix,
                    }
                )
            else:
                print(
                    f"serving {type(daemon.box).__name__} on {', '.join(daemon.listen)} "
                    f"(key {daemon.prefix}); Ctrl-C stops",
                    flush=True,
                )
            try:
                daemon.wait(args.duration_s)
            except KeyboardInterrupt:
                pass
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


def _monitor_foxglove(args: argparse.Namespace) -> int:
    """Read frames from the box and publish them to Foxglove, paced to real time."""
    import sys
    import time

    from softpad.box import open_box
    from softpad.errors import InputError
    from softpad.record import FoxgloveLive

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
