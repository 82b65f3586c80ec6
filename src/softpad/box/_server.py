"""Serve any :class:`~softpad.box.Box` over TCP with the ``softpad-box`` protocol.

``BoxServer(box, host="127.0.0.1", port=0)`` binds exactly the address it is given
(loopback by default; port 0 lets the system pick a free port, see :attr:`BoxServer.port`)
and serves one client at a time: a second client is answered "busy" and disconnected. When
a client leaves — ``close`` request, closed or reset socket, garbage that ends the session,
or silence longer than ``idle_timeout_s`` — the server closes every valve of its box (the
safe state: no inflation) before it accepts the next client.
"""

from __future__ import annotations

import math
import selectors
import socket
import time
from collections.abc import Callable, Mapping
from typing import Any

from softpad import __version__
from softpad.box._base import Box, ConnectionLost, ValveCommand
from softpad.box._protocol import (
    MAX_LINE_BYTES,
    OPS,
    PROTOCOL_VERSION,
    ProtocolError,
    decode,
    encode,
)
from softpad.errors import HardwareFault, InputError, SoftPadError

#: Seconds of client silence after which the server drops the client and closes the valves.
DEFAULT_IDLE_TIMEOUT_S = 10.0


class _EndSession(Exception):
    """The current client session is over (the reason is in the message)."""


class BoxServer:
    """Expose ``box`` on ``tcp://host:port``.

    Parameters
    ----------
    box
        The box to serve (any back-end); it stays open between clients and is closed by
        :meth:`close`.
    host
        Address to bind; only this one (127.0.0.1 by default: this computer only).
    port
        TCP port; 0 picks a free one (read it from :attr:`port`).
    idle_timeout_s
        A client silent for longer than this, seconds, is dropped and the valves are closed
        (a controller that hangs must not leave a module inflating).
    log
        Called with one line of text per session event (connections, errors); None: silent.
    extensions
        Extra requests by ``op`` name (each containing a dot, e.g. ``"robot.stop"``): a
        handler takes the request and returns the reply's fields, or raises a
        :class:`~softpad.errors.SoftPadError`. Listed to the client in the ``hello`` reply.
        :func:`softpad.control.simulation_extensions` gives those that run the grasp loop
        against a served simulator.
    """

    def __init__(
        self,
        box: Box,
        host: str = "127.0.0.1",
        port: int = 0,
        idle_timeout_s: float = DEFAULT_IDLE_TIMEOUT_S,
        log: Callable[[str], None] | None = None,
        extensions: Mapping[str, Callable[[dict[str, Any]], dict[str, Any]]] | None = None,
    ) -> None:
        if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
            raise InputError(f"port must be an integer from 0 to 65535, got {port!r}")
        if not (math.isfinite(idle_timeout_s) and idle_timeout_s > 0):
            raise InputError(f"idle timeout must be > 0 s, got {idle_timeout_s!r}")
        self.extensions = dict(extensions or {})
        for name in self.extensions:
            if "." not in name:
                raise InputError(f"extension op names must contain a dot, got {name!r}")
        self.box = box
        self.idle_timeout_s = float(idle_timeout_s)
        self._log = log
        try:
            infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
        except OSError as exc:
            raise InputError(f"cannot resolve host {host!r}: {exc}") from None
        family, _, _, _, addr = infos[0]
        self._listener = socket.socket(family, socket.SOCK_STREAM)
        try:
            self._listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            self._listener.bind(addr)
            self._listener.listen(2)
        except OSError as exc:
            self._listener.close()
            raise InputError(f"cannot listen on {host}:{port}: {exc}") from None
        self._listener.setblocking(False)
        self.host = host
        self.port = int(self._listener.getsockname()[1])
        self._stop = False
        self._client: socket.socket | None = None
        self._buf = b""
        self._hello = False
        #: Number of client sessions served so far.
        self.sessions = 0

    @property
    def url(self) -> str:
        """URL a client opens: ``tcp://host:port``."""
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"tcp://{host}:{self.port}"

    def _say(self, text: str) -> None:
        if self._log is not None:
            self._log(text)

    # --- main loop ------------------------------------------------------------------
    def serve(self, max_sessions: int | None = None, poll_s: float = 0.2) -> None:
        """Serve clients until :meth:`stop` (from another thread), ``max_sessions`` ended
        sessions, or KeyboardInterrupt (which propagates after the valves are closed).

        Parameters
        ----------
        max_sessions
            Stop after this many client sessions (None: serve forever).
        poll_s
            How often the loop checks for :meth:`stop`, seconds.
        """
        sel = selectors.DefaultSelector()
        sel.register(self._listener, selectors.EVENT_READ, "listen")
        last_heard = 0.0
        try:
            while not self._stop:
                if max_sessions is not None and self.sessions >= max_sessions:
                    break
                for key, _ in sel.select(timeout=poll_s):
                    if key.data == "listen":
                        if self._accept(sel):  # a new controller: its own watchdog starts
                            last_heard = time.monotonic()
                    elif self._client is not None:
                        try:
                            # only the controller's own valid, complete requests feed the
                            # watchdog: refused connections and partial lines do not
                            if self._receive():
                                last_heard = time.monotonic()
                        except _EndSession as why:
                            self._end_session(sel, str(why))
                if self._client is not None and time.monotonic() - last_heard > self.idle_timeout_s:
                    self._end_session(sel, f"client silent for more than {self.idle_timeout_s:g} s")
        finally:
            if self._client is not None:
                self._end_session(sel, "server stopping")
            sel.close()

    def stop(self) -> None:
        """Ask :meth:`serve` to return (thread-safe; takes effect within ``poll_s``)."""
        self._stop = True

    def close(self) -> None:
        """Stop listening and close the served box (its valves close). Idempotent."""
        self._stop = True
        try:
            self._listener.close()
        finally:
            self.box.close()

    def __enter__(self) -> BoxServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- sessions -------------------------------------------------------------------
    def _accept(self, sel: selectors.BaseSelector) -> bool:
        """Accept a connection; True when it became the controlling client."""
        try:
            conn, peer = self._listener.accept()
        except OSError:
            return False
        if self._client is not None:
            try:
                conn.settimeout(1.0)
                conn.sendall(
                    encode(
                        {
                            "ok": False,
                            "kind": "hardware",
                            "error": "box busy: another client is connected",
                        }
                    )
                )
            except OSError:
                pass
            conn.close()
            self._say(f"refused {peer}: busy")
            return False
        conn.setblocking(True)
        conn.settimeout(self.idle_timeout_s)
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self._client, self._buf, self._hello = conn, b"", False
        sel.register(conn, selectors.EVENT_READ, "client")
        self._say(f"client {peer} connected")
        return True

    def _end_session(self, sel: selectors.BaseSelector, why: str) -> None:
        conn, self._client = self._client, None
        if conn is not None:
            try:
                sel.unregister(conn)
            except (KeyError, ValueError):
                pass
            try:
                conn.close()
            except OSError:
                pass
        self.sessions += 1
        self._safe_state()
        self._say(f"session ended ({why}); valves closed")

    def _safe_state(self) -> None:
        """Close every valve of the served box (no-op for a box that cannot be reached)."""
        try:
            if not self.box.closed:
                self.box.close_valves()
        except SoftPadError as exc:
            self._say(f"could not close the valves: {exc}")

    def _receive(self) -> bool:
        """Handle the complete lines received; True when one was a valid request."""
        conn = self._client
        assert conn is not None
        try:
            chunk = conn.recv(65536)
        except OSError as exc:
            raise _EndSession(f"connection error: {exc}") from None
        if not chunk:
            raise _EndSession("client disconnected")
        self._buf += chunk
        valid = False
        while True:
            i = self._buf.find(b"\n")
            if i < 0:
                if len(self._buf) > MAX_LINE_BYTES:
                    self._reply({"ok": False, "kind": "input", "error": "message too long"})
                    raise _EndSession("message too long")
                return valid
            line, self._buf = self._buf[:i], self._buf[i + 1 :]
            if line.strip():
                reply = self._handle(line)
                valid = valid or bool(reply.get("ok"))
                self._reply(reply)

    def _reply(self, message: dict[str, Any]) -> None:
        conn = self._client
        if conn is None:
            return
        end = message.pop("_end", False)
        try:
            conn.sendall(encode(message))
        except OSError as exc:
            raise _EndSession(f"cannot reply: {exc}") from None
        if end:
            raise _EndSession(str(message.get("error", "closed by the client")))

    # --- requests -------------------------------------------------------------------
    def _handle(self, line: bytes) -> dict[str, Any]:
        try:
            msg = decode(line)
            op = msg.get("op")
            if not isinstance(op, str) or (op not in OPS and op not in self.extensions):
                known = ", ".join([*OPS, *self.extensions])
                raise InputError(f"unknown request op={op!r}; known: {known}")
            if op == "hello":
                return self._op_hello(msg)
            if not self._hello:
                raise InputError(f"send hello before {op!r}")
            if op == "read":
                return self._op_read()
            if op == "valve":
                return self._op_valve(msg)
            if op in self.extensions:
                return {"ok": True, **self.extensions[op](msg)}
            self._safe_state()
            return {"ok": True, "_end": True}
        except _Fatal as exc:
            return {"ok": False, "kind": "input", "error": str(exc), "_end": True}
        except ConnectionLost as exc:
            return {"ok": False, "kind": "connection", "error": f"served box: {exc}"}
        except HardwareFault as exc:
            return {"ok": False, "kind": "hardware", "error": str(exc)}
        except (InputError, ProtocolError) as exc:
            return {"ok": False, "kind": "input", "error": str(exc)}
        except Exception as exc:  # a bug in a back-end or extension: report it, keep serving
            self._say(f"error handling {line[:80]!r}: {type(exc).__name__}: {exc}")
            return {
                "ok": False,
                "kind": "hardware",
                "error": f"server error: {type(exc).__name__}: {exc}",
            }

    def _op_hello(self, msg: dict[str, Any]) -> dict[str, Any]:
        version = msg.get("protocol")
        if version != PROTOCOL_VERSION:
            raise _Fatal(
                f"protocol version mismatch: client speaks {version!r}, "
                f"server speaks {PROTOCOL_VERSION}"
            )
        self._hello = True
        box = self.box
        return {
            "ok": True,
            "protocol": PROTOCOL_VERSION,
            "channels": box.channels,
            "sample_rate_hz": float(box.sample_rate_hz),
            "box": type(box).__name__,
            "server": f"softpad {__version__}",
            "extensions": sorted(self.extensions),
        }

    def _op_read(self) -> dict[str, Any]:
        f = self.box.read()
        pressures = [float(v) if math.isfinite(v) else None for v in f.pressures_pa.tolist()]
        supply = float(f.supply_pa)
        if not math.isfinite(supply):
            raise HardwareFault(f"supply sensor gives no valid reading ({supply!r})")
        return {"ok": True, "t_s": float(f.t_s), "pressures_pa": pressures, "supply_pa": supply}

    def _op_valve(self, msg: dict[str, Any]) -> dict[str, Any]:
        ch = msg.get("channel")
        if isinstance(ch, float) and ch.is_integer():
            ch = int(ch)
        self.box.set_valve(ch, ValveCommand.parse(msg.get("command")))  # type: ignore[arg-type]
        return {"ok": True}


class _Fatal(InputError):
    """A request error that ends the session (protocol version mismatch)."""
