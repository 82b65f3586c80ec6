"""Attacks on a served simulated box (``softpad bench --only safety``): the issue-35 red team's
attacks replayed on loopback, the simulator's true chamber pressure watched throughout.

Each attack runs against a fresh daemon (``sim://``, 100 Hz, watchdog 0.5 s, hold) with a
controller that took control and inflated modules 1-6 to about 1.1 kPa; an attacker is a
second zenoh session on the same endpoint. Reported per attack: the peak true pressure
(target at most 3.1 kPa: the 3 kPa maximum plus the stated 100 Pa margin of the fault
campaign) and what the attack achieved (commands accepted, frames believed, time to safe).
"""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from softpad.benchmarks._common import BenchResult

#: Watchdog of the attacked daemon, seconds.
WATCHDOG_S = 0.5
#: Peak true pressure target, pascals (3 kPa maximum + 100 Pa margin).
PEAK_LIMIT_PA = 3100.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class _Scene:
    """A served box, its controller with modules inflated, an attacker session, a watcher of
    the true pressure (under the daemon's lock, every 5 ms)."""

    def __init__(self) -> None:
        import zenoh

        from softpad.box import BoxDaemon, ZenohBox, open_box
        from softpad.box.wire import session_config
        from softpad.harness import simulation_extensions

        port = _free_port()
        box = open_box("sim://?seed=4&rate_hz=100")
        self.daemon = BoxDaemon(
            box,
            (f"tcp/127.0.0.1:{port}",),
            services=simulation_extensions(box),  # type: ignore[arg-type]
            watchdog_s=WATCHDOG_S,
        ).start()
        self.url = f"zenoh://127.0.0.1:{port}"
        c = open_box(self.url)
        assert isinstance(c, ZenohBox)
        self.ctl = c
        self.bad = zenoh.open(session_config("client", connect=(f"tcp/127.0.0.1:{port}",)))
        self.peak = 0.0
        self._stop = threading.Event()
        self._watch = threading.Thread(target=self._watcher, daemon=True)
        self._watch.start()
        self._inflate()

    def _watcher(self) -> None:
        d = self.daemon
        while not self._stop.wait(0.005):
            with d._lock:
                self.peak = max(self.peak, float(np.max(d.box.true_pressures_pa)))  # type: ignore[attr-defined]

    def _inflate(self) -> None:
        from softpad.control import InflationParams, inflate_and_adjust

        inflate_and_adjust(self.ctl, 6, InflationParams(target_pa=1100.0))

    def ask(self, key: str, payload: bytes) -> dict[str, Any]:
        from softpad.box.wire import decode_request

        for r in self.bad.get(f"softpad/box/{key}", payload=payload, timeout=5.0):
            if r.ok is not None:
                return decode_request(r.ok.payload.to_bytes())
        return {"ok": None}

    def close(self) -> None:
        self._stop.set()
        self._watch.join(timeout=2)
        self.bad.close()
        try:
            self.ctl.close()
        finally:
            self.daemon.close()


def _forged_commands(s: _Scene) -> tuple[float, str]:
    from softpad.box.wire import encode_json

    cid = s.ctl.client_id
    ok = 0
    for _ in range(50):
        for ch in range(1, 7):
            r = s.ask("valves", encode_json({"client": cid, "channel": ch, "command": "inflate"}))
            ok += r.get("ok") is True
    for _ in range(100):
        s.ctl.read()
    return ok, "inflate commands accepted of 300 sent with the controller's public id"


def _forged_release_take(s: _Scene) -> tuple[float, str]:
    from softpad.box.wire import encode_json

    cid = s.ctl.client_id
    ok = sum(
        s.ask(k, encode_json({"client": cid})).get("ok") is True
        for k in ("control/release", "control/take")
        for _ in range(20)
    )
    s.ctl.close_valves()  # the real controller's safe-state commands still work
    return ok, f"releases/takes accepted of 40; controller kept: {s.daemon.controller == cid}"


def _frozen_controller(s: _Scene) -> tuple[float, str]:
    """Controller inflating then frozen; attacker holds a token in its name and sends
    forged heartbeats. Figure: seconds from its last authentic heartbeat to the trip."""
    from softpad.box.wire import encode_json

    for ch in range(1, 7):
        s.ctl.set_valve(ch, "inflate")
    token = s.bad.liveliness().declare_token(f"softpad/box/control/holder/{s.ctl.client_id}")
    s.ctl._beat_stop.set()
    end = time.monotonic() + 10 * WATCHDOG_S
    n = 0
    while s.daemon.controller is not None and time.monotonic() < end:
        n += 1
        s.bad.put("softpad/box/control/heartbeat", encode_json({"client": s.ctl.client_id}))
        time.sleep(0.01)
    time.sleep(2.0)  # the box alone after the trip: does anything rise?
    token.undeclare()
    trip = s.daemon.last_trip or {}
    silent = float(trip.get("silent_s", float("inf")))
    return silent, f"s from the last authentic heartbeat to the trip ({n} forged heartbeats)"


def _forged_frames(s: _Scene) -> tuple[float, str]:
    from softpad.box import PressureFrame
    from softpad.box.wire import encode_frame, seal_frame

    s.ctl.take_control()
    bad = PressureFrame(0.0, np.full(8, np.nan), 1e4)
    over = PressureFrame(0.0, np.full(8, 9e3), 1e4)
    sent = 0
    believed = 0
    for k in range(200):
        for f in (bad, over):
            data = encode_frame(10**9 + k, time.monotonic(), f)
            s.bad.put("softpad/box/frames", seal_frame(data, b"x" * 32, b"x" * 32))
            sent += 1
        got = s.ctl.read_stamped()
        believed += got.seq >= 10**9 or not np.isfinite(got.frame.pressures_pa).all()
    return believed, f"forged frames believed by the controller of {sent} sent"


def _replayed_commands(s: _Scene) -> tuple[float, str]:
    from softpad.box.wire import encode_json

    sealer = s.ctl._sealer
    if sealer is None:
        s.ctl.take_control()
        sealer = s.ctl._sealer
    assert sealer is not None
    msg = sealer.seal(
        "query", "valves", {"client": s.ctl.client_id, "channel": 1, "command": "inflate"}
    )
    s.ask("valves", encode_json(msg))  # the original (as if captured in flight)
    s.ctl.set_valve(1, "closed")
    ok = sum(s.ask("valves", encode_json(msg)).get("ok") is True for _ in range(100))
    return ok, "replays of a captured inflate command accepted of 100"


def _service_flood(s: _Scene) -> tuple[float, str]:
    from softpad.errors import InputError

    s.ctl.take_control()
    refused = 0
    for _ in range(20):
        try:
            s.ctl.request("ext/sim.place", objects=["object-5"] * 300)
        except InputError:
            refused += 1
    return (
        s.daemon.stats.service_max_s,
        f"s longest service under the lock; {refused}/20 300-object places refused",
    )


def _impostor(s: _Scene) -> tuple[float, str]:
    """An impostor queryable on ``valves`` acknowledges everything: the controller's
    commands must still reach the box. Figure: commands that did not reach it."""
    from softpad.box import ValveCommand
    from softpad.box.wire import encode_json

    fake = encode_json({"ok": True, "valves": ["closed"] * 8})
    q = s.bad.declare_queryable("softpad/box/valves", lambda q: q.reply(q.key_expr, fake))
    try:
        missed = 0
        for k in range(30):
            ch, cmd = 1 + k % 6, ("deflate", "closed")[k % 2]
            s.ctl.set_valve(ch, cmd)
            missed += s.daemon.box.valves[ch - 1] is not ValveCommand.parse(cmd)
    finally:
        q.undeclare()
    return (
        missed,
        f"of 30 controller commands missed the box ({s.ctl.impostor_replies} impostor answers ignored)",
    )


ATTACKS: tuple[tuple[str, Callable[[_Scene], tuple[float, str]]], ...] = (
    ("forged commands (controller's id)", _forged_commands),
    ("forged release and take", _forged_release_take),
    ("frozen controller + forged token and heartbeats", _frozen_controller),
    ("forged frames (NaN, 9 kPa, seq 1e9)", _forged_frames),
    ("replayed commands", _replayed_commands),
    ("sim.place with 300 objects", _service_flood),
    ("impostor queryable acknowledging commands", _impostor),
)


def run(quick: bool) -> list[BenchResult]:
    """One row per attack: the peak true pressure, and what the attack achieved."""
    out = []
    for name, attack in ATTACKS:
        scene = _Scene()
        try:
            value, what = attack(scene)
        finally:
            scene.close()
        met = scene.peak <= PEAK_LIMIT_PA and (
            value <= WATCHDOG_S + 0.05 if "heartbeat" in name else "service" in what or value == 0
        )
        out.append(
            BenchResult(
                f"attack: {name}",
                scene.peak / 1e3,
                "kPa peak true pressure",
                target=f"<= {PEAK_LIMIT_PA / 1e3:g} kPa, attack refused",
                met=met,
                detail=f"{value:.4g} {what}; sim 100 Hz, watchdog {WATCHDOG_S:g} s",
            )
        )
    return out
