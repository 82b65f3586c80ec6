"""The network back-end: tcp:// client, BoxServer, protocol errors, lost links, safe state.

Everything runs on 127.0.0.1 with port 0 (a free port); every socket has a timeout, so a
broken test fails instead of hanging.
"""

from __future__ import annotations

import contextlib
import json
import socket
import threading
from collections.abc import Callable, Iterator

import numpy as np
import pytest

from softpad.box import (
    PROTOCOL_VERSION,
    BoxServer,
    ConnectionLost,
    SimBox,
    TcpBox,
    ValveCommand,
    open_box,
)
from softpad.errors import HardwareFault, InputError


@contextlib.contextmanager
def served(url: str = "sim://?seed=1", **kw: float) -> Iterator[BoxServer]:
    """A BoxServer for ``url`` on loopback, serving in a thread; stopped and closed after."""
    server = BoxServer(open_box(url), "127.0.0.1", 0, **kw)
    thread = threading.Thread(target=server.serve, daemon=True)
    thread.start()
    try:
        yield server
    finally:
        server.stop()
        thread.join(timeout=5)
        server.close()
        assert not thread.is_alive()


class RawClient:
    """A hand-written client sending exact lines (for malformed requests)."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=5)
        self.buf = b""

    def send(self, line: bytes) -> dict:
        self.sock.sendall(line + b"\n")
        while b"\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("closed")
            self.buf += chunk
        line, _, self.buf = self.buf.partition(b"\n")
        return json.loads(line)

    def closed_by_peer(self) -> bool:
        try:
            return self.sock.recv(1) == b""
        except OSError:
            return True


def test_frames_over_tcp_equal_the_served_box_frames() -> None:
    """The link is transparent: same frames as the same sim box read directly (NaN as NaN)."""
    url = "sim://?seed=4&faults=nan:2@0.05"
    with open_box(url) as direct:
        expected = direct.read_many(20)
    with served(url) as server, open_box(server.url) as box:
        assert isinstance(box, TcpBox)
        assert box.channels == 8 and box.sample_rate_hz == 100.0
        assert box.info["box"] == "SimBox" and box.info["protocol"] == PROTOCOL_VERSION
        got = box.read_many(20)
    for a, b in zip(expected, got, strict=True):
        assert a.t_s == b.t_s and a.supply_pa == b.supply_pa
        np.testing.assert_array_equal(a.pressures_pa, b.pressures_pa)  # NaN == NaN here
    assert np.isnan(got[-1].pressures_pa[1])


def test_valve_commands_reach_the_served_box() -> None:
    with served() as server, open_box(server.url) as box:
        box.set_valve(2, "inflate")
        box.set_valve(5, ValveCommand.DEFLATE)
        box.read()
        served_box = server.box
        assert served_box.valves[1] is ValveCommand.INFLATE
        assert served_box.valves[4] is ValveCommand.DEFLATE
    assert set(served_box.valves) == {ValveCommand.CLOSED}  # closed by the client's close()


def _inflate_then(server: BoxServer, vanish: Callable[[TcpBox], None]) -> SimBox:
    box = open_box(server.url)
    assert isinstance(box, TcpBox)
    box.set_valves(["inflate"] * 6 + ["closed"] * 2)
    box.read_many(250)  # 2.5 s of inflation from flat: about 0.5 kPa, rising
    vanish(box)
    served_box = server.box
    assert isinstance(served_box, SimBox)
    return served_box


@pytest.mark.parametrize(
    "vanish",
    [
        lambda b: b._sock.close(),  # socket closed without a goodbye
        lambda b: b._sock.shutdown(socket.SHUT_RDWR),  # link cut
    ],
    ids=["socket-closed", "shutdown"],
)
def test_client_vanishing_mid_inflation_leaves_the_served_box_closed(vanish) -> None:
    with served("sim://?seed=2") as server:
        served_box = _inflate_then(server, vanish)
        p_then = served_box.true_pressures_pa[:6].copy()
        assert (p_then > 200).all() and (p_then < 1500).all()
        for _ in range(500):  # the server notices within its poll interval
            if server.sessions == 1:
                break
            threading.Event().wait(0.01)
        assert server.sessions == 1
        assert set(served_box.valves) == {ValveCommand.CLOSED}
        # nobody inflates any more: 30 s of box time later the pressure has not risen
        peak = max(f.pressures_pa[:6].max() for f in served_box.read_many(3000))
        assert peak < 3000.0  # the configured maximum (InflationParams default)
        np.testing.assert_allclose(served_box.true_pressures_pa[:6], p_then, atol=1.0)


def test_silent_client_is_dropped_and_valves_closed() -> None:
    with served("sim://?seed=2", idle_timeout_s=0.2) as server:
        served_box = _inflate_then(server, lambda b: threading.Event().wait(0.6))
        assert set(served_box.valves) == {ValveCommand.CLOSED}
        assert server.sessions == 1


def test_server_killed_raises_connection_lost_and_keeps_logged_frames() -> None:
    """inflate_and_adjust over tcp; the server stops mid-inflation: ConnectionLost, frames kept."""
    from softpad.control import inflate_and_adjust

    logged = []
    with served("sim://?seed=3") as server:
        box = open_box(server.url + "?timeout_s=2")

        def hook(frame) -> None:
            logged.append(frame)
            if len(logged) == 50:
                server.stop()

        with pytest.raises(ConnectionLost, match=r"lost the link to the box at tcp://127\.0\.0\.1"):
            inflate_and_adjust(box, 6, on_frame=hook)
        assert len(logged) >= 50
        assert [f.t_s for f in logged] == sorted(f.t_s for f in logged)
        with pytest.raises(ConnectionLost):
            box.read()
        box.close()  # no error: nothing left to close on this side
        assert box.closed


def test_served_box_fault_is_relayed_as_connection_lost() -> None:
    """The served sim box itself stops answering (disconnect fault at 0.1 s)."""
    with served("sim://?faults=disconnect@0.1") as server, open_box(server.url) as box:
        box.read_many(9)
        with pytest.raises(ConnectionLost, match=r"served box: .*stopped answering at t = 0.1"):
            box.read_many(3)
        assert not box.connected


def test_inflate_and_adjust_over_tcp_matches_the_direct_box() -> None:
    from softpad.control import inflate_and_adjust

    url = "sim://?seed=6"
    with open_box(url) as direct:
        a = inflate_and_adjust(direct, 6)
    with served(url) as server, open_box(server.url) as box:
        b = inflate_and_adjust(box, 6)
    np.testing.assert_array_equal(a.reference_pa, b.reference_pa)
    assert a.reference_at_s == b.reference_at_s
    np.testing.assert_allclose(b.reference_pa, 1100.0, atol=40.0)


def test_no_answer_within_timeout_is_connection_lost() -> None:
    listener = socket.create_server(("127.0.0.1", 0))
    try:
        port = listener.getsockname()[1]
        with pytest.raises(ConnectionLost, match=r"no reply within 0.3 s"):
            open_box(f"tcp://127.0.0.1:{port}?timeout_s=0.3")
    finally:
        listener.close()


def test_nobody_listening_is_connection_lost() -> None:
    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]
    listener.close()
    with pytest.raises(
        ConnectionLost, match=f"cannot connect to the box at tcp://127.0.0.1:{port}"
    ):
        open_box(f"tcp://127.0.0.1:{port}")


HELLO = b'{"ok":true,"protocol":1,"channels":2,"sample_rate_hz":100.0}'


@pytest.mark.parametrize(
    ("replies", "exc", "match"),
    [
        ([b"hello there"], HardwareFault, "malformed JSON message 'hello there'"),
        (
            [b'{"ok":true,"protocol":2,"channels":2,"sample_rate_hz":100}'],
            HardwareFault,
            "speaks protocol 2, this client speaks 1",
        ),
        (
            [b'{"ok":true,"protocol":1,"channels":0,"sample_rate_hz":100}'],
            HardwareFault,
            "bad channel count 0",
        ),
        (
            [b'{"ok":true,"protocol":1,"channels":2,"sample_rate_hz":NaN}'],
            HardwareFault,
            "NaN is not a valid JSON number",
        ),
        (
            [HELLO, b'{"ok":true,"t_s":0.01,"pressures_pa":[1.0],"supply_pa":1e4}'],
            HardwareFault,
            "pressures_pa must be a list of 2 values, got 1",
        ),
        (
            [HELLO, b'{"ok":true,"t_s":0.01,"pressures_pa":[1.0,"x"],"supply_pa":1e4}'],
            HardwareFault,
            "pressure of channel 2 is not a number: 'x'",
        ),
        (
            [HELLO, b'{"ok":true,"t_s":null,"pressures_pa":[1.0,2.0],"supply_pa":1e4}'],
            HardwareFault,
            "t_s must be a finite number, got None",
        ),
        (
            [HELLO, b'{"ok":true,"t_s":0.01,"pressures_pa":[1.0,Infinity],"supply_pa":1e4}'],
            HardwareFault,
            "Infinity is not a valid JSON number",
        ),
        (
            [HELLO, b'{"ok":false,"kind":"hardware","error":"valve 2 driver overheated"}'],
            HardwareFault,
            "valve 2 driver overheated",
        ),
        (
            [HELLO, b'{"ok":false,"kind":"input","error":"channel 9 out of range"}'],
            InputError,
            "channel 9 out of range",
        ),
        ([HELLO, b'{"result":1}'], HardwareFault, "reply without ok/error"),
        ([HELLO], ConnectionLost, "server closed the connection"),
    ],
    ids=[
        "garbage",
        "version",
        "channels",
        "nan-rate",
        "count",
        "string",
        "null-t",
        "inf",
        "hw-error",
        "input-error",
        "no-ok",
        "eof",
    ],
)
def test_bad_replies_from_a_box_raise_clear_errors(replies, exc, match) -> None:
    """A scripted 'box' answers each request with the next line, then hangs up."""
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(5)
    port = listener.getsockname()[1]

    def script() -> None:
        conn, _ = listener.accept()
        with conn:
            conn.settimeout(5)
            f = conn.makefile("rb")
            for r in replies:
                if not f.readline():
                    return
                conn.sendall(r + b"\n")
            f.readline()

    t = threading.Thread(target=script, daemon=True)
    t.start()
    opened = []
    try:
        with pytest.raises(exc, match=match):
            opened.append(open_box(f"tcp://127.0.0.1:{port}?timeout_s=2"))
            opened[0].read()
        for box in opened:
            box.close()
    finally:
        t.join(timeout=5)
        listener.close()


@pytest.mark.parametrize(
    ("line", "match"),
    [
        (b"{not json", "malformed JSON message"),
        (b"[1, 2]", "must be a JSON object"),
        (b'{"op": "explode"}', "unknown request op='explode'"),
        (
            b'{"op": "valve", "channel": 9, "command": "inflate"}',
            "channel must be an integer from 1 to 8, got 9",
        ),
        (b'{"op": "valve", "channel": 1.5, "command": "inflate"}', "got 1.5"),
        (
            b'{"op": "valve", "channel": NaN, "command": "inflate"}',
            "NaN is not a valid JSON number",
        ),
        (b'{"op": "valve", "channel": 2, "command": "open-ish"}', "got 'open-ish'"),
        (b'{"op": "valve", "channel": 2}', "got None"),
        (b"\xff\xfe", "not UTF-8"),
        (b'{"op": ["read"]}', "unknown request op=['read']"),
    ],
    ids=[
        "json",
        "array",
        "op",
        "channel",
        "fraction",
        "nan",
        "command",
        "missing",
        "utf8",
        "op-list",
    ],
)
def test_server_answers_bad_requests_with_input_errors_and_keeps_serving(line, match) -> None:
    with served() as server:
        c = RawClient(server.port)
        assert c.send(b'{"op":"hello","protocol":1}')["ok"] is True
        reply = c.send(line)
        assert reply["ok"] is False and reply["kind"] == "input"
        assert match in reply["error"]
        assert c.send(b'{"op":"read"}')["ok"] is True  # the session goes on
        assert set(server.box.valves) == {ValveCommand.CLOSED}
        c.sock.close()


def test_server_requires_hello_and_refuses_other_protocol_versions() -> None:
    with served() as server:
        c = RawClient(server.port)
        r = c.send(b'{"op":"read"}')
        assert r["kind"] == "input" and "send hello before 'read'" in r["error"]
        r = c.send(b'{"op":"hello","protocol":99}')
        assert r["ok"] is False and "protocol version mismatch: client speaks 99" in r["error"]
        assert c.closed_by_peer()


def test_second_client_is_told_the_box_is_busy() -> None:
    with served() as server, open_box(server.url):
        with pytest.raises(HardwareFault, match="box busy"):
            open_box(server.url + "?timeout_s=2")


@pytest.mark.parametrize(
    ("url", "match"),
    [
        ("tcp://127.0.0.1", "needs host:port"),
        ("tcp://127.0.0.1:http", "port must be an integer, got 'http'"),
        ("tcp://127.0.0.1:70000", "port must be an integer from 1 to 65535, got 70000"),
        ("tcp://127.0.0.1:5000?timeout_s=nan", "timeout_s must be a positive number"),
        ("tcp://127.0.0.1:5000?retries=3", "unknown tcp:// option 'retries'"),
    ],
    ids=["no-port", "port-name", "port-range", "timeout-nan", "option"],
)
def test_bad_tcp_urls(url: str, match: str) -> None:
    with pytest.raises(InputError, match=match):
        open_box(url)


def test_server_binds_only_the_requested_address() -> None:
    with BoxServer(open_box("sim://"), "127.0.0.1", 0) as server:
        host, port = server._listener.getsockname()[:2]
        assert host == "127.0.0.1" and port == server.port > 0
        assert server.url == f"tcp://127.0.0.1:{server.port}"
    with pytest.raises(InputError, match="port must be an integer from 0 to 65535"):
        BoxServer(open_box("sim://"), "127.0.0.1", -1)


def test_a_failing_extension_is_reported_and_the_server_keeps_serving() -> None:
    def broken(msg: dict) -> dict:
        return {"x": 1 / 0}

    server = BoxServer(open_box("sim://"), "127.0.0.1", 0, extensions={"test.broken": broken})
    thread = threading.Thread(target=server.serve, daemon=True)
    thread.start()
    try:
        with open_box(server.url) as box:
            assert isinstance(box, TcpBox) and box.extensions == ("test.broken",)
            with pytest.raises(HardwareFault, match="server error: ZeroDivisionError"):
                box.request("test.broken")
            box.read()
    finally:
        server.stop()
        thread.join(timeout=5)
        server.close()
    with pytest.raises(InputError, match="must contain a dot"):
        BoxServer(open_box("sim://"), "127.0.0.1", 0, extensions={"broken": broken})


def _controller_inflating(server: BoxServer) -> RawClient:
    ctl = RawClient(server.port)
    assert ctl.send(b'{"op": "hello", "protocol": %d}' % PROTOCOL_VERSION)["ok"]
    assert ctl.send(b'{"op": "valve", "channel": 1, "command": "inflate"}')["ok"]
    return ctl


def _wait_for(cond: Callable[[], bool], poke: Callable[[], None], limit_s: float = 5.0) -> bool:
    """Poke the server until ``cond`` holds (True) or ``limit_s`` passes (False)."""
    stop = threading.Event()
    t = 0.0
    while t < limit_s:
        if cond():
            return True
        poke()
        stop.wait(0.05)
        t += 0.05
    return cond()


@pytest.mark.parametrize("intruder", ["refused-connections", "partial-line", "garbage-lines"])
def test_only_the_controllers_valid_messages_feed_the_watchdog(intruder: str) -> None:
    """A silent controller with inflation open is dropped (valves closed) although someone
    keeps the link busy: refused connection attempts, a trickle of one byte of an unfinished
    line, or lines that are not valid requests."""
    with served("sim://?seed=2", idle_timeout_s=0.3) as server:
        ctl = _controller_inflating(server)
        assert server.box.valves[0] is ValveCommand.INFLATE

        def poke() -> None:
            try:
                if intruder == "refused-connections":
                    with socket.create_connection(("127.0.0.1", server.port), timeout=1):
                        pass
                elif intruder == "partial-line":
                    ctl.sock.sendall(b" ")
                else:
                    ctl.sock.sendall(b"not json\n")
            except OSError:
                pass

        assert _wait_for(lambda: server.sessions >= 1, poke)
        assert set(server.box.valves) == {ValveCommand.CLOSED}
        ctl.sock.close()
