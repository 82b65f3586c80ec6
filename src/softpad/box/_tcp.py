"""The network back-end (``tcp://host:port``): a box reached over the ``softpad-box`` protocol.

:class:`TcpBox` is a client :class:`~softpad.box.Box`: every :meth:`~softpad.box.Box.read`
and valve command is one request/reply exchange (see :mod:`softpad.box._protocol`). Any box
can be served with :class:`softpad.box.BoxServer` (``softpad box serve``); a real pneumatic
box's firmware would speak the same protocol.

A lost link (refused or reset connection, the server gone, no reply within ``timeout_s``)
raises :class:`~softpad.box.ConnectionLost`. The client then does what it still can for the
safe state: it sends "close" commands for every channel without waiting (they arrive if the
link still carries data) and drops the connection; the server closes the inflation valves of
its box as soon as its client disappears.
"""

from __future__ import annotations

import math
import socket
from typing import Any

import numpy as np

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._protocol import (
    MAX_LINE_BYTES,
    PROTOCOL_VERSION,
    ProtocolError,
    decode,
    encode,
    finite_number,
)
from softpad.errors import HardwareFault, InputError

#: Seconds to wait for a reply before the link counts as lost.
DEFAULT_TIMEOUT_S = 5.0

_TCP_OPTIONS = {"timeout_s": "seconds to wait for each reply before the link counts as lost (5)"}


class TcpBox(Box):
    """A box served over TCP by :class:`~softpad.box.BoxServer` (or a real box's firmware).

    Parameters
    ----------
    host
        Host name or address of the server.
    port
        TCP port of the server (1..65535).
    timeout_s
        Longest wait for a connection or a reply, seconds; longer counts as a lost link.

    Raises
    ------
    ConnectionLost
        Nobody answers at ``host:port``.
    HardwareFault
        The server answers but not with a valid ``hello`` (wrong protocol version, garbage).
    """

    def __init__(self, host: str, port: int, timeout_s: float = DEFAULT_TIMEOUT_S) -> None:
        super().__init__()
        if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
            raise InputError(f"TCP port must be an integer from 1 to 65535, got {port!r}")
        if not (isinstance(timeout_s, int | float) and math.isfinite(timeout_s) and timeout_s > 0):
            raise InputError(f"timeout_s must be a positive number of seconds, got {timeout_s!r}")
        self.address = f"tcp://{host}:{port}"
        self.timeout_s = float(timeout_s)
        self._buf = b""
        try:
            self._sock: socket.socket | None = socket.create_connection(
                (host, port), timeout=self.timeout_s
            )
        except OSError as exc:
            raise ConnectionLost(f"cannot connect to the box at {self.address}: {exc}") from None
        self._sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        try:
            info = self._request({"op": "hello", "protocol": PROTOCOL_VERSION})
            version = info.get("protocol")
            if version != PROTOCOL_VERSION:
                raise HardwareFault(
                    f"box at {self.address} speaks protocol {version!r}, this client "
                    f"speaks {PROTOCOL_VERSION}"
                )
            ch = info.get("channels")
            if isinstance(ch, bool) or not isinstance(ch, int) or not 1 <= ch <= 1024:
                raise HardwareFault(f"box at {self.address} reports a bad channel count {ch!r}")
            rate = finite_number(info, "sample_rate_hz", f"hello from {self.address}")
            if rate <= 0:
                raise HardwareFault(f"box at {self.address} reports a sample rate of {rate} Hz")
        except BaseException:
            self._drop()
            raise
        self._channels = ch
        self._rate = rate
        #: The ``hello`` reply: protocol, channels, sample rate, served box, server version.
        self.info: dict[str, Any] = info

    # --- Box API --------------------------------------------------------------------
    @property
    def channels(self) -> int:
        return self._channels

    @property
    def sample_rate_hz(self) -> float:
        return self._rate

    @property
    def extensions(self) -> tuple[str, ...]:
        """Extra requests the server offers (``hello``'s ``extensions``), e.g. ``robot.stop``."""
        ext = self.info.get("extensions", [])
        return tuple(e for e in ext if isinstance(e, str)) if isinstance(ext, list) else ()

    def request(self, op: str, **fields: Any) -> dict[str, Any]:
        """Send an extension request ``op`` with ``fields``; return the reply's fields.

        Raises
        ------
        InputError
            The server does not offer ``op``, or refuses the request (message from it).
        ConnectionLost
            The link is lost.
        """
        self._check_open()
        if op not in self.extensions:
            offered = ", ".join(self.extensions) or "none"
            raise InputError(f"box at {self.address} does not offer {op!r} (extensions: {offered})")
        reply = self._request({**fields, "op": op})
        reply.pop("ok", None)
        return reply

    @property
    def connected(self) -> bool:
        """False once the link is lost or closed."""
        return self._sock is not None

    def _read(self) -> PressureFrame:
        msg = self._request({"op": "read"})
        where = f"frame from {self.address}"
        try:
            t = finite_number(msg, "t_s", where)
            supply = finite_number(msg, "supply_pa", where)
        except HardwareFault as exc:
            raise self._fault(exc) from None
        raw = msg.get("pressures_pa")
        if not isinstance(raw, list) or len(raw) != self._channels:
            n = len(raw) if isinstance(raw, list) else raw
            raise self._fault(
                HardwareFault(
                    f"{where}: pressures_pa must be a list of {self._channels} values, got {n!r}"
                )
            )
        values = np.empty(self._channels)
        for i, v in enumerate(raw):
            if v is None:
                values[i] = np.nan
            elif isinstance(v, bool) or not isinstance(v, int | float):
                raise self._fault(
                    HardwareFault(f"{where}: pressure of channel {i + 1} is not a number: {v!r}")
                )
            else:
                values[i] = v
        return PressureFrame(t, values, supply)

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        self._request({"op": "valve", "channel": channel, "command": command.value})

    def close_valves(self) -> None:
        """Close every valve; after a lost link nothing can be commanded (the server does it)."""
        if self._sock is None:
            return
        super().close_valves()

    def close(self) -> None:
        """Close every valve, end the session and the connection. Idempotent, and quiet when
        the link is lost on the way (the server closes its box's valves when we vanish)."""
        try:
            super().close()
        except ConnectionLost:
            pass

    def _close(self) -> None:
        if self._sock is None:
            return
        try:
            self._request({"op": "close"})
        except (ConnectionLost, HardwareFault, InputError):
            pass
        finally:
            self._drop()

    # --- link -----------------------------------------------------------------------
    def _check_open(self) -> None:
        super()._check_open()
        if self._sock is None:
            raise ConnectionLost(f"the link to the box at {self.address} was lost")

    def _drop(self) -> None:
        sock, self._sock = self._sock, None
        if sock is not None:
            try:
                sock.close()
            except OSError:
                pass

    def _lose(self, why: str) -> ConnectionLost:
        """Mark the link lost, try to leave the valves closed, and return the error to raise."""
        sock = self._sock
        if sock is not None:
            try:  # best effort, no waiting: the server also closes them when we vanish
                sock.settimeout(0.2)
                sock.sendall(
                    b"".join(
                        encode({"op": "valve", "channel": k, "command": "closed"})
                        for k in range(1, self._channels_or_zero() + 1)
                    )
                )
            except OSError:
                pass
        self._drop()
        if self._valves is not None:
            self._valves = [ValveCommand.CLOSED] * len(self._valves)
        return ConnectionLost(f"lost the link to the box at {self.address}: {why}")

    def _channels_or_zero(self) -> int:
        return int(getattr(self, "_channels", 0))

    def _fault(self, exc: HardwareFault) -> HardwareFault:
        """A garbled reply: the stream can no longer be trusted; drop it and return ``exc``."""
        self._lose(str(exc))
        return exc

    def _request(self, message: dict[str, Any]) -> dict[str, Any]:
        sock = self._sock
        if sock is None:
            raise ConnectionLost(f"the link to the box at {self.address} was lost")
        try:
            data = encode(message)
        except (TypeError, ValueError) as exc:  # NaN/inf or objects: not JSON
            raise InputError(
                f"request {message.get('op')!r} cannot be sent: {exc} (in {message!r})"
            ) from None
        try:
            sock.sendall(data)
            line = self._readline(sock)
        except TimeoutError:
            raise self._lose(f"no reply within {self.timeout_s:g} s") from None
        except OSError as exc:
            raise self._lose(str(exc) or type(exc).__name__) from None
        except BaseException:  # interrupted mid-exchange (Ctrl-C): the stream is out of step
            self._lose("interrupted")
            raise
        try:
            reply = decode(line)
        except ProtocolError as exc:
            raise self._fault(HardwareFault(f"box at {self.address} sent {exc}")) from None
        ok = reply.get("ok")
        if ok is True:
            return reply
        error = reply.get("error")
        kind = reply.get("kind")
        if ok is not False or not isinstance(error, str):
            raise self._fault(
                HardwareFault(f"box at {self.address} sent a reply without ok/error: {reply!r}")
            )
        text = f"box at {self.address}: {error}"
        if kind == "input":
            raise InputError(text)
        if kind == "connection":
            raise self._lose(error)
        raise HardwareFault(text)

    def _readline(self, sock: socket.socket) -> bytes:
        buf = self._buf
        while True:
            i = buf.find(b"\n")
            if i >= 0:
                self._buf = buf[i + 1 :]
                return buf[:i]
            if len(buf) > MAX_LINE_BYTES:
                raise self._fault(
                    HardwareFault(
                        f"box at {self.address} sent a line longer than {MAX_LINE_BYTES} bytes"
                    )
                )
            chunk = sock.recv(65536)
            if not chunk:
                raise ConnectionResetError("the server closed the connection")
            buf += chunk


def open_tcp_url(location: str, options: dict[str, str]) -> TcpBox:
    """Build a :class:`TcpBox` from ``tcp://host:port[?timeout_s=5]``."""
    unknown = sorted(set(options) - set(_TCP_OPTIONS))
    if unknown:
        raise InputError(
            f"unknown tcp:// option {unknown[0]!r}; known options: {', '.join(_TCP_OPTIONS)}"
        )
    host, sep, port_text = location.rstrip("/").rpartition(":")
    if not sep or not host or "/" in location.rstrip("/"):
        raise InputError(f"tcp:// needs host:port (e.g. tcp://127.0.0.1:5757), got {location!r}")
    host = host.strip("[]")  # IPv6 literal
    try:
        port = int(port_text)
    except ValueError:
        raise InputError(f"tcp:// port must be an integer, got {port_text!r}") from None
    timeout = DEFAULT_TIMEOUT_S
    if "timeout_s" in options:
        try:
            timeout = float(options["timeout_s"])
        except ValueError:
            raise InputError(
                f"tcp:// option timeout_s={options['timeout_s']!r} must be a number"
            ) from None
    return TcpBox(host, port, timeout)
