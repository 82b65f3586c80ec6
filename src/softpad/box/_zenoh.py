"""The zenoh back-end (``zenoh://HOST:PORT[/KEY-PREFIX]``): a box served by ``softpad box serve``.

:class:`ZenohBox` subscribes to the daemon's frames (pushed as they are sampled) and returns
them in order from :meth:`~softpad.box.Box.read`; it is a read-only monitor until its first
valve command, when it takes control of the box (declaring its liveliness token and sending
heartbeats). Another client controlling the box makes valve commands fail with
:class:`ControlRefused`, naming it. See :mod:`softpad.box._link` for the keys.
"""

from __future__ import annotations

import math
import queue
import threading
from typing import Any

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._daemon import new_client_id
from softpad.box._link import (
    DEFAULT_PREFIX,
    StampedFrame,
    decode_frame,
    decode_request,
    encode_json,
    session_config,
)
from softpad.errors import HardwareFault, InputError

#: Seconds to wait for a frame or a reply before the link counts as lost.
DEFAULT_TIMEOUT_S = 5.0


class ControlRefused(HardwareFault):
    """The daemon refused control or a command (another controller, a safety limit)."""


class ZenohBox(Box):
    """A box served over zenoh by :class:`~softpad.box.BoxDaemon`.

    Parameters
    ----------
    host, port
        The daemon's endpoint (``tcp/HOST:PORT``); only this one is connected, no scouting.
    key_prefix
        The daemon's key prefix (``softpad/box``).
    timeout_s
        Longest wait for a frame or a reply, seconds.
    queue_frames
        Frames kept while nobody reads; older ones are dropped (counted in :attr:`dropped`).
    auth
        Keyword arguments of :func:`softpad.box._link.session_config` (user/password, TLS).

    Raises
    ------
    ConnectionLost
        Nobody answers at the endpoint within ``timeout_s``.
    """

    def __init__(
        self,
        host: str,
        port: int,
        key_prefix: str = DEFAULT_PREFIX,
        timeout_s: float = DEFAULT_TIMEOUT_S,
        queue_frames: int = 100_000,
        auth: dict[str, Any] | None = None,
    ) -> None:
        super().__init__()
        if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
            raise InputError(f"zenoh port must be an integer from 1 to 65535, got {port!r}")
        if not (math.isfinite(timeout_s) and timeout_s > 0):
            raise InputError(f"timeout_s must be > 0 s, got {timeout_s!r}")
        host_part = f"[{host}]" if ":" in host else host
        self.endpoint = f"tcp/{host_part}:{port}"
        self.address = f"zenoh://{host_part}:{port}/{key_prefix}"
        self.prefix = key_prefix.strip("/")
        self.timeout_s = float(timeout_s)
        self.client_id = new_client_id()
        self.dropped = 0
        self._queue: queue.Queue[StampedFrame] = queue.Queue(maxsize=queue_frames)
        self._token: Any = None
        self._ack: Any = None
        self._beat: threading.Thread | None = None
        self._beat_stop = threading.Event()
        self.last: StampedFrame | None = None
        config = session_config("client", connect=(self.endpoint,), **(auth or {}))
        import zenoh

        try:
            self._session = zenoh.open(config)
        except zenoh.ZError as exc:
            why = str(exc).split(" at /")[0]  # without zenoh's Rust source location
            raise ConnectionLost(f"cannot connect to the box at {self.endpoint}: {why}") from None
        try:
            self.info = self._get("info", {})
            self._sub = self._session.declare_subscriber(f"{self.prefix}/frames", self._on_frame)
        except BaseException:
            self._session.close()
            raise
        self._channels = int(self.info["channels"])
        self._rate = float(self.info["sample_rate_hz"])

    # --- frames -----------------------------------------------------------------------
    def _on_frame(self, sample: Any) -> None:
        try:
            f = decode_frame(sample.payload.to_bytes())
        except InputError:
            return
        try:
            self._queue.put_nowait(f)
        except queue.Full:
            self.dropped += 1

    def read_stamped(self) -> StampedFrame:
        """The next published frame with its sequence number and the daemon's time stamp."""
        self._check_open()
        try:
            f = self._queue.get(timeout=self.timeout_s)
        except queue.Empty:
            raise ConnectionLost(
                f"no frame from the box at {self.endpoint} for {self.timeout_s:g} s"
            ) from None
        self.last = f
        if self._ack is not None:  # a lock-stepped simulator waits for the controller
            self._ack.put(encode_json({"client": self.client_id, "seq": f.seq}))
        return f

    @property
    def channels(self) -> int:
        return self._channels

    @property
    def sample_rate_hz(self) -> float:
        return self._rate

    def _read(self) -> PressureFrame:
        return self.read_stamped().frame

    # --- requests ---------------------------------------------------------------------
    def _get(self, key: str, msg: dict[str, Any]) -> dict[str, Any]:
        try:
            payload = encode_json(msg)
        except (TypeError, ValueError) as exc:
            raise InputError(f"request {key} cannot be sent: {exc}") from None
        replies = self._session.get(f"{self.prefix}/{key}", payload=payload, timeout=self.timeout_s)
        for r in replies:
            if r.ok is None:
                continue
            try:
                return decode_request(r.ok.payload.to_bytes())
            except InputError as exc:
                raise HardwareFault(f"box at {self.endpoint} answered garbage: {exc}") from None
        raise ConnectionLost(f"no box answers {self.prefix}/{key} at {self.endpoint}")

    def request(self, key: str, **fields: Any) -> dict[str, Any]:
        """Send one query carrying this client's id; raise on a refusal.

        Raises
        ------
        InputError
            The daemon found the request malformed.
        ControlRefused
            Control is held by another client, or a safety limit refused the command.
        """
        reply = self._get(key, {"client": self.client_id, **fields})
        if reply.get("ok") is True:
            return reply
        kind, text = reply.get("kind"), str(reply.get("error", "refused"))
        if kind == "input":
            raise InputError(f"box: {text}")
        if kind in ("control", "safety"):
            raise ControlRefused(f"box refused: {text}")
        raise HardwareFault(f"box: {text}")

    @property
    def controlling(self) -> bool:
        """True while this client holds control of the box."""
        return self._token is not None

    def take_control(self) -> None:
        """Declare the liveliness token, ask for control, start heartbeats (idempotent)."""
        if self._token is not None:
            return
        self._token = self._session.liveliness().declare_token(
            f"{self.prefix}/control/holder/{self.client_id}"
        )
        try:
            reply = self.request("control/take")
        except BaseException:
            self._token.undeclare()
            self._token = None
            if self._ack is not None:
                self._ack.undeclare()
                self._ack = None
            raise
        self._ack = self._session.declare_publisher(f"{self.prefix}/control/ack", express=True)
        period = float(reply.get("watchdog_s", 0.5)) / 5
        self._beat_stop.clear()
        self._beat = threading.Thread(target=self._heartbeats, args=(period,), daemon=True)
        self._beat.start()

    def _heartbeats(self, period: float) -> None:
        pub = self._session.declare_publisher(f"{self.prefix}/control/heartbeat", express=True)
        msg = encode_json({"client": self.client_id})
        while not self._beat_stop.wait(period):
            pub.put(msg)
        pub.undeclare()

    def release_control(self) -> None:
        """Give control back (the daemon closes every valve); no-op when not controlling."""
        if self._token is None:
            return
        self._beat_stop.set()
        try:
            self.request("control/release")
        finally:
            if self._beat is not None:
                self._beat.join(timeout=2.0)
            self._token.undeclare()
            self._token = None
            if self._ack is not None:
                self._ack.undeclare()
                self._ack = None

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        self.take_control()
        self.request("valves", channel=channel, command=command.value)

    def _vent(self, channel: int) -> None:
        """The client-side guard vents only when this client controls the box; a monitor
        leaves venting to the daemon's own guard (it never takes control to vent)."""
        if self._token is None:
            return
        try:
            super()._vent(channel)
        except ControlRefused:
            pass  # control lost: the daemon's watchdog and guard have the valves

    def close_valves(self) -> None:
        """Close every valve (only a controlling client can; a monitor changes nothing)."""
        if self._token is not None and not self.closed:
            try:
                super().close_valves()
            except (ControlRefused, ConnectionLost):
                pass  # control or link lost: the daemon's watchdog has closed the valves

    def _close(self) -> None:
        try:
            self.release_control()
        except HardwareFault:
            pass
        finally:
            self._session.close()


def open_zenoh_url(location: str, options: dict[str, str]) -> ZenohBox:
    """Factory for ``zenoh://HOST:PORT[/KEY-PREFIX]?timeout_s=5``."""
    from urllib.parse import urlsplit

    unknown = set(options) - {"timeout_s"}
    if unknown:
        raise InputError(f"unknown zenoh:// option {sorted(unknown)[0]!r}; known: timeout_s")
    hostport, _, prefix = location.partition("/")
    parts = urlsplit(f"//{hostport}")
    try:
        port = parts.port
    except ValueError:
        port = None
    if not parts.hostname or port is None:
        raise InputError(
            f"zenoh box URL must look like zenoh://HOST:PORT[/PREFIX], got {location!r}"
        )
    timeout = DEFAULT_TIMEOUT_S
    if "timeout_s" in options:
        try:
            timeout = float(options["timeout_s"])
        except ValueError:
            raise InputError(
                f"zenoh:// timeout_s must be a number, got {options['timeout_s']!r}"
            ) from None
    return ZenohBox(parts.hostname, port, prefix.strip("/") or DEFAULT_PREFIX, timeout)
