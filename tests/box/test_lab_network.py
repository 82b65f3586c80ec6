"""The box on a lab network (issue 49): a silent queryable, frames forged before a take or
with a sequence number far ahead, a command racing the watchdog, client ids that forge log
lines. Served on loopback with scouting off; every wait is bounded by a count or a deadline.
"""

from __future__ import annotations

import threading
from typing import Any
from urllib.parse import urlsplit

import numpy as np
import pytest

from softpad.box import ValveCommand, ZenohBox, open_box
from softpad.box._auth import Sealer, seal_frame
from softpad.box._base import PressureFrame
from softpad.box._link import encode_frame, session_config
from softpad.errors import InputError


def _session(url: str) -> Any:
    import zenoh

    port = urlsplit(url).port
    return zenoh.open(session_config("client", connect=(f"tcp/127.0.0.1:{port}",)))


def _forge(box: ZenohBox, seq: int, marker_pa: float) -> bytes:
    """A frame any reader of ``info`` can make: the read tag right, the control tag zero."""
    frame = PressureFrame(0.0, np.full(box.channels, marker_pa), 0.0)
    assert box._read_key is not None
    return seal_frame(encode_frame(seq, 0.0, frame), box._read_key, None)


def test_a_silent_queryable_neither_delays_commands_nor_trips_the_watchdog(served) -> None:
    """Before: every query waited for every queryable on the key (QueryTarget.ALL), so the
    take's reply came after the client's timeout and the watchdog (0.5 s) withdrew control
    before the first heartbeat; the second command was refused."""
    with served(watchdog_s=0.5) as (daemon, url):
        s = _session(url)
        held: list[Any] = []  # never answered, never dropped: the query stays open
        q = s.declare_queryable("softpad/box/**", held.append)
        try:
            with open_box(url.replace("timeout_s=60", "timeout_s=3")) as a:
                a.set_valve(1, "deflate")  # takes control
                a.set_valve(2, "deflate")
                assert daemon.controller == a.client_id  # type: ignore[attr-defined]
                assert daemon.box.valves[:2] == (ValveCommand.DEFLATE,) * 2
                assert daemon.stats.watchdog_trips == 0
        finally:
            q.undeclare()
            held.clear()
            s.close()


def test_frames_forged_before_the_take_are_not_read_after_it(served, until) -> None:
    """Before: 20 frames forged with the read key (from ``info``) sat in the client's queue and
    were read as the box's after it took control."""
    with served() as (_daemon, url):
        s = _session(url)
        try:
            with open_box(url) as a:
                assert isinstance(a, ZenohBox)
                seq = a.read_stamped().seq
                for k in range(20):
                    s.put("softpad/box/frames", _forge(a, seq + 2 + k, 12345.0))
                until(lambda: a._last_seq >= seq + 21 or a.forged_frames >= 20, "the forgeries")
                a.take_control()
                read = [a.read().pressures_pa[0] for _ in range(40)]
                assert 12345.0 not in read
        finally:
            s.close()


def test_one_frame_far_ahead_does_not_blind_a_monitor(served, until) -> None:
    """Before: a frame with sequence number 2**64 - 1 made every later real frame look
    replayed: the monitor read nothing more (ConnectionLost after its timeout)."""
    with served() as (_daemon, url):
        s = _session(url)
        try:
            with open_box(url.replace("timeout_s=60", "timeout_s=10")) as m:
                assert isinstance(m, ZenohBox)
                m.read_stamped()
                s.put("softpad/box/frames", _forge(m, 2**64 - 1, 777.0))
                until(lambda: m.forged_frames >= 1 or m._last_seq == 2**64 - 1, "the forgery")
                seqs = [m.read_stamped().seq for _ in range(50)]
                assert max(seqs) < 2**32 and np.all(np.diff(seqs) > 0)
        finally:
            s.close()


def test_box_inflate_over_zenoh_works_while_frames_far_ahead_are_forged(served, cli) -> None:
    """The issue saw ``box inflate`` read as a monitor first and end with exit 3 ("no frame for
    5 s"): a frame numbered 2**64 - 1 accepted before the take makes every real frame look
    replayed. It now takes control first and refuses such forgeries (read key from ``info``,
    sent every 10 ms). A regression check: on the code before, this run also passed (the take
    came before any forgery was accepted); the blinding itself is
    test_one_frame_far_ahead_does_not_blind_a_monitor."""
    with served("sim://?seed=4&rate_hz=200") as (_daemon, url):
        s = _session(url)
        stop = threading.Event()
        try:
            with open_box(url) as spy:
                assert isinstance(spy, ZenohBox)
                forged = _forge(spy, 2**64 - 1, 777.0)

            def flood() -> None:
                while not stop.wait(0.01):
                    s.put("softpad/box/frames", forged)

            t = threading.Thread(target=flood, daemon=True)
            t.start()
            code, out, err = cli(
                "box", "inflate", "--box", url.replace("timeout_s=60", "timeout_s=5"),
                "--modules", "2",
            )  # fmt: skip
        finally:
            stop.set()
            s.close()
    assert code == 0, err
    assert "reference (kPa)" in out


def _controlled(daemon: Any) -> tuple[str, Sealer]:
    reply = daemon._on_take({"client": "ctl"})
    return "ctl", Sealer(bytes.fromhex(reply["key"]))


def test_a_command_racing_the_watchdog_lands_before_its_safe_state() -> None:
    """Before: ``_on_valves`` checked control outside the daemon's lock; with the window
    widened (a delay after the check) the watchdog's safe state came first and the inflate
    landed after it, with nobody in control."""
    from softpad.box import BoxDaemon

    daemon = BoxDaemon(open_box("sim://?seed=4"))
    try:
        client, sealer = _controlled(daemon)
        checked = threading.Event()
        original = daemon._require_control

        def slow_check(msg: dict[str, Any]) -> str:
            who = original(msg)
            checked.set()
            threading.Event().wait(0.3)  # the window the issue widened
            return who

        daemon._require_control = slow_check  # type: ignore[method-assign]
        msg = sealer.seal("query", "valves", {"client": client, "channel": 1, "command": "inflate"})
        cmd = threading.Thread(
            target=daemon._on_valves, args=({**msg, "_key": "softpad/box/valves"},)
        )
        cmd.start()
        assert checked.wait(10.0)
        daemon._trip("test: heartbeats stopped")
        cmd.join(10.0)
        assert daemon.controller is None
        assert daemon.box.valves[0] is not ValveCommand.INFLATE
    finally:
        daemon.close()


@pytest.mark.parametrize(
    "client",
    ["evil\nwatchdog: controller x lost", "\x1b[2Jcleared", "a\ud800b", "tab\there", ""],
    ids=["newline", "escape", "lone-surrogate", "tab", "empty"],
)
def test_client_ids_that_would_forge_log_lines_are_refused(client: str) -> None:
    from softpad.box import BoxDaemon

    daemon = BoxDaemon(open_box("sim://?seed=4"))
    try:
        with pytest.raises(InputError, match="client must be"):
            daemon._on_take({"client": client})
        assert daemon.controller is None
    finally:
        daemon.close()


def test_a_plain_client_id_is_still_granted() -> None:
    from softpad.box import BoxDaemon
    from softpad.box._daemon import new_client_id

    daemon = BoxDaemon(open_box("sim://?seed=4"))
    try:
        for c in (new_client_id(), "robot-1.arm_A"):
            daemon._on_take({"client": c})
            assert daemon.controller == c
            daemon.controller = None
        with pytest.raises(InputError):
            daemon._on_take({"client": "x" * 65})
    finally:
        daemon.close()
