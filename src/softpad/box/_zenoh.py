"""The zenoh back-end (``zenoh://HOST:PORT[/KEY-PREFIX]``): a box served by ``softpad box serve``.

:class:`ZenohBox` subscribes to the daemon's frames (pushed as they are sampled) and returns
them in order from :meth:`~softpad.box.Box.read`; it is a read-only monitor until its first
valve command, when it takes control of the box (declaring its liveliness token and sending
heartbeats). Another client controlling the box makes valve commands fail with
:class:`ControlRefused`, naming it. See :mod:`softpad.box._link` for the keys.
"""

from __future__ import annotations

import atexit
import logging
import math
import queue
import threading
import time
import weakref
from typing import Any

from softpad.box._auth import Sealer, split_frame, tag_ok
from softpad.box._base import WORLD_SERVICES, Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._daemon import new_client_id
from softpad.box._link import (
    DEFAULT_CONNECT_TIMEOUT_S,
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
#: At connection, seconds to wait after the first box's answer for a second one (two boxes
#: on one key prefix are refused); later queries wait only for the pinned box.
PIN_GRACE_S = 0.5
#: Sequence numbers ahead of what the box can have sampled are refused; seconds of frames
#: allowed beyond that (a daemon's late ticks only make it slower than its rate).
SEQ_SLACK_S = 2.0

_log = logging.getLogger("softpad.box")

#: Boxes still open; closed at interpreter exit. zenoh-python runs callbacks on a non-daemon
#: thread that lives as long as the session: a script that never closed its box would wait
#: for it forever, so the boxes are closed before the interpreter joins its threads.
_OPEN: weakref.WeakSet[ZenohBox] = weakref.WeakSet()


def _close_open_boxes() -> None:
    for box in list(_OPEN):
        try:
            box.close()
        except Exception:  # exiting: nothing more to do about it
            pass


# threading's exit hooks run before non-daemon threads are joined (atexit's run after)
getattr(threading, "_register_atexit", atexit.register)(_close_open_boxes)


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
        Longest wait for a frame or a reply, seconds; the wait for the endpoint to accept the
        connection is the shorter of this and
        :data:`~softpad.box._link.DEFAULT_CONNECT_TIMEOUT_S` (3 s).
    queue_frames
        Frames kept while nobody reads; older ones are dropped (counted in :attr:`dropped`).
    auth
        Keyword arguments of :func:`softpad.box._link.session_config` (user/password, TLS;
        :func:`softpad.box._credentials.client_auth` makes them from the installation file).
    protocol
        ``tcp`` or ``tls`` (the daemon's endpoint's protocol).

    Raises
    ------
    ConnectionLost
        Nobody accepts the connection at the endpoint within ``min(timeout_s, 3 s)`` or the
        box does not answer within ``timeout_s``.
    """

    def __init__(
        self,
        host: str,
        port: int,
        key_prefix: str = DEFAULT_PREFIX,
        timeout_s: float = DEFAULT_TIMEOUT_S,
        queue_frames: int = 100_000,
        auth: dict[str, Any] | None = None,
        protocol: str = "tcp",
    ) -> None:
        super().__init__()
        if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
            raise InputError(f"zenoh port must be an integer from 1 to 65535, got {port!r}")
        if not (math.isfinite(timeout_s) and timeout_s > 0):
            raise InputError(f"timeout_s must be > 0 s, got {timeout_s!r}")
        host_part = f"[{host}]" if ":" in host else host
        if protocol not in ("tcp", "tls"):
            raise InputError(f"zenoh protocol must be tcp or tls, got {protocol!r}")
        self.endpoint = f"{protocol}/{host_part}:{port}"
        self.address = f"zenoh://{host_part}:{port}/{key_prefix}"
        self.prefix = key_prefix.strip("/")
        self.timeout_s = float(timeout_s)
        self.client_id = new_client_id()
        self.dropped = 0
        #: Frames refused: a wrong tag (forged) or a sequence number not above the last.
        self.forged_frames = 0
        self._last_seq = -1
        #: (sequence number, monotonic time) of the first frame taken: bounds later ones.
        self._anchor: tuple[int, float] | None = None
        self._command_seen_after_s: float | None = None
        self._read_key: bytes | None = None
        self._sealer: Sealer | None = None
        self._take_seq = 0
        self._request_lock = threading.Lock()
        #: The daemon's zenoh id, pinned by the ``info`` query at connection (one box only).
        self._box_zid: str | None = None
        #: Answers to this client's queries from others than the pinned box (impostors).
        self.impostor_replies = 0
        #: Frames with their body and control tag: checked again when read (a frame queued
        #: before this client took control must carry the control key's tag to be read after).
        self._queue: queue.Queue[tuple[StampedFrame, bytes, bytes]] = queue.Queue(
            maxsize=queue_frames
        )
        #: Sequence number of the last frame returned by :meth:`read_stamped`.
        self._read_seq = -1
        self._token: Any = None
        self._ack: Any = None
        self._beat: threading.Thread | None = None
        self._beat_stop = threading.Event()
        self.last: StampedFrame | None = None
        self._connect(auth)

    def _connect(self, auth: dict[str, Any] | None) -> None:
        """Open the session, pin the box by its ``info`` answer, subscribe to its frames."""
        config = session_config(
            "client",
            connect=(self.endpoint,),
            connect_timeout_s=min(self.timeout_s, DEFAULT_CONNECT_TIMEOUT_S),
            **(auth or {}),
        )
        import zenoh

        try:
            self._session = zenoh.open(config)
        except zenoh.ZError as exc:
            why = str(exc).split(" at /")[0]  # without zenoh's Rust source location
            raise ConnectionLost(f"cannot connect to the box at {self.endpoint}: {why}") from None
        try:
            self.info = self._get("info", {})
            seq = self.info.get("seq")
            if type(seq) is int:
                self._anchor = (seq, time.monotonic())
            self._read_key = _hex_key(self.info.get("read_key"))
            self._sub = self._session.declare_subscriber(f"{self.prefix}/frames", self._on_frame)
        except BaseException:
            self._session.close()
            raise
        _OPEN.add(self)

    # --- frames -----------------------------------------------------------------------
    def _on_frame(self, sample: Any) -> None:
        data = sample.payload.to_bytes()
        body, read_tag, control_tag = split_frame(data)
        try:
            f = decode_frame(body)
        except InputError:
            self._forged("a payload that is not a frame")
            return
        sealer = self._sealer
        if sealer is not None:  # the controller believes only frames under its own key
            if not tag_ok(sealer.secret, body, control_tag):
                if not (f.seq <= self._take_seq + 2 and tag_ok(self._read_key, body, read_tag)):
                    self._forged(f"frame {f.seq} without the control key's tag")
                return  # else sampled before control was granted: stale, not forged
        elif not tag_ok(self._read_key, body, read_tag):
            self._forged(f"frame {f.seq} without the box's read tag")
            return
        elif not self._plausible(f.seq):
            self._forged(f"frame {f.seq}, further ahead than the box can have sampled")
            return
        if f.seq <= self._last_seq:
            self._forged(f"frame {f.seq} after frame {self._last_seq} (replayed)")
            return
        self._last_seq = f.seq
        try:
            self._queue.put_nowait((f, body, control_tag))
        except queue.Full:
            self.dropped += 1

    def _plausible(self, seq: int) -> bool:
        """True when ``seq`` is no further ahead than the box can have sampled since the first
        frame this client took (its advertised rate, 0.1 % clock drift, 2 s of slack): one
        forged frame far ahead (2**64 - 1) would otherwise make every real frame after it
        look replayed, for good (issue 49)."""
        now = time.monotonic()
        if self._anchor is None:
            self._anchor = (seq, now)
            return True
        seq0, t0 = self._anchor
        rate = float(self.info.get("sample_rate_hz", 0.0)) or 1e4
        return seq - seq0 <= rate * (1.001 * (now - t0) + SEQ_SLACK_S)

    def _forged(self, what: str) -> None:
        self.forged_frames += 1
        n = self.forged_frames
        if n & (n - 1) == 0:  # the 1st, 2nd, 4th, 8th ...: said, never a flood
            _log.warning(
                "%s: ignored %s (%d forged or replayed frames so far)", self.address, what, n
            )

    def read_stamped(self) -> StampedFrame:
        """The next published frame with its sequence number and the daemon's time stamp."""
        self._check_open()
        deadline = time.monotonic() + self.timeout_s
        while True:
            try:
                f, body, control_tag = self._queue.get(
                    timeout=max(deadline - time.monotonic(), 0.0)
                )
            except queue.Empty:
                raise ConnectionLost(
                    f"no frame from the box at {self.endpoint} for {self.timeout_s:g} s"
                ) from None
            sealer = self._sealer
            if f.seq <= self._read_seq:
                continue  # the same frame again (queued before and after a take)
            if sealer is None or tag_ok(sealer.secret, body, control_tag):
                break
            if f.seq > self._take_seq + 2:  # queued before the take, not the box's
                self._forged(f"frame {f.seq} queued before the take without the control tag")
        self._read_seq = f.seq
        self.last = f
        if self._ack is not None and sealer is not None:  # a lock-stepped simulator waits
            msg = sealer.seal("ack", "control/ack", {"client": self.client_id, "seq": f.seq})
            self._ack.put(encode_json(msg))
        return f

    @property
    def channels(self) -> int:
        """Channels of the served box, from its ``info``."""
        return int(self.info["channels"])

    @property
    def sample_rate_hz(self) -> float:
        """Frame rate of the served box, from its ``info``, hertz."""
        return float(self.info["sample_rate_hz"])

    @property
    def supply_sensor(self) -> bool:
        """Whether the served box measures its supply, from its ``info``."""
        return self.info.get("supply_sensor") is not False

    @property
    def simulated(self) -> bool:
        """Whether the served box offers the simulated world's requests
        (:data:`~softpad.box._base.WORLD_SERVICES`), from its ``info``."""
        return set(WORLD_SERVICES) <= set(self.info.get("services", []))

    def _read(self) -> PressureFrame:
        return self.read_stamped().frame

    # --- requests ---------------------------------------------------------------------
    def _get(self, key: str, msg: dict[str, Any]) -> dict[str, Any]:
        try:
            payload = encode_json(msg)
        except (TypeError, ValueError) as exc:
            raise InputError(f"request {key} cannot be sent: {exc}") from None
        import zenoh

        # every queryable on the key gets the query (zenoh's default picks one: an impostor's
        # queryable would take the daemon's commands), but only the pinned box's answer is
        # waited for: a queryable that never answers delays nothing (issue 49)
        answers: queue.Queue[tuple[str, bytes] | None] = queue.Queue()
        pinned = self._box_zid

        def on_reply(r: Any) -> None:
            if r.ok is None:
                return
            rid = r.replier_id
            zid = str(rid.zid) if rid is not None else "?"
            if pinned is not None and zid != pinned:  # counted even after the answer came
                self.impostor_replies += 1
                _log.warning("%s: ignored an answer to %s not from the box", self.address, key)
                return
            answers.put((zid, r.ok.payload.to_bytes()))

        self._session.get(
            f"{self.prefix}/{key}",
            payload=payload,
            timeout=self.timeout_s,
            target=zenoh.QueryTarget.ALL,
            consolidation=zenoh.ConsolidationMode.NONE,
            handler=zenoh.handlers.Callback(on_reply, lambda: answers.put(None)),
        )
        data = self._answer_of(key, answers)
        try:
            return decode_request(data)
        except InputError as exc:
            raise HardwareFault(f"box at {self.endpoint} answered garbage: {exc}") from None

    def _answer_of(self, key: str, answers: queue.Queue[tuple[str, bytes] | None]) -> bytes:
        """The pinned box's answer from ``answers`` (None: the query ended), waiting at most
        the timeout. Unpinned (the first query, ``info``): the first answer pins the box;
        a second box answering within :data:`PIN_GRACE_S` after it is refused."""
        deadline = time.monotonic() + self.timeout_s
        found: dict[str, bytes] = {}
        while True:
            left = deadline - time.monotonic()
            if found:
                left = min(left, PIN_GRACE_S)
            try:
                item = answers.get(timeout=max(left, 0.0))
            except queue.Empty:
                item = None
            if item is not None and self._box_zid is not None:
                return item[1]  # only the pinned box's answers are queued
            if item is not None:
                found.setdefault(*item)
                if len(found) > 1:
                    raise HardwareFault(
                        f"{len(found)} boxes answer {self.prefix}/{key} at {self.endpoint}: one "
                        "is an impostor or a second daemon on the same key prefix; refusing "
                        "to connect"
                    )
                continue
            if not found:
                raise ConnectionLost(f"no box answers {self.prefix}/{key} at {self.endpoint}")
            self._box_zid, data = next(iter(found.items()))
            return data

    def request(self, key: str, **fields: Any) -> dict[str, Any]:
        """Send one query carrying this client's id; raise on a refusal.

        Raises
        ------
        InputError
            The daemon found the request malformed.
        ControlRefused
            Control is held by another client, or a safety limit refused the command.
        """
        with self._request_lock:  # one at a time: the counters arrive in order
            msg = {"client": self.client_id, **fields}
            if self._sealer is not None:
                try:
                    msg = self._sealer.seal("query", key, msg)
                except (TypeError, ValueError) as exc:  # NaN, a non-JSON value
                    raise InputError(f"request {key} cannot be sent: {exc}") from None
            reply = self._get(key, msg)
        if reply.get("ok") is True:
            return reply
        kind, text = reply.get("kind"), str(reply.get("error", "refused"))
        if kind == "input":
            raise InputError(f"box: {text}")
        if kind in ("control", "safety"):
            if "does not control the box" in text:  # lost it (watchdog): frames by read tag
                self._sealer = None
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
            secret = _hex_key(reply.get("key"))
            if secret is None:
                raise HardwareFault(f"box at {self.endpoint} granted control without a key")
        except BaseException:
            self._token.undeclare()
            self._token = None
            raise
        seq = reply.get("seq")
        self._take_seq = seq if type(seq) is int else 0
        self._sealer = Sealer(secret)
        # frames are now believed by the control tag only: a frame forged with the read key
        # before the take may have pushed the last sequence number ahead of the box's
        self._last_seq = min(self._last_seq, self._take_seq)
        self._ack = self._session.declare_publisher(f"{self.prefix}/control/ack", express=True)
        period = float(reply.get("watchdog_s", 0.5)) / 5
        self._beat_stop.clear()
        self._beat = threading.Thread(target=self._heartbeats, args=(period,), daemon=True)
        self._beat.start()

    def _heartbeats(self, period: float) -> None:
        pub = self._session.declare_publisher(f"{self.prefix}/control/heartbeat", express=True)
        sealer = self._sealer
        while sealer is not None:  # the first at once: the watchdog runs from the grant
            msg = sealer.seal("heartbeat", "control/heartbeat", {"client": self.client_id})
            pub.put(encode_json(msg))
            if self._beat_stop.wait(period):
                break
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
            self._sealer = None
            if self._ack is not None:
                self._ack.undeclare()
                self._ack = None

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        self.take_control()
        reply = self.request("valves", channel=channel, command=command.value)
        t = reply.get("t_s")
        if isinstance(t, int | float) and not isinstance(t, bool) and math.isfinite(t):
            self._command_seen_after_s = float(t)

    @property
    def command_seen_after_s(self) -> float | None:
        """The daemon's last sampled frame time when it applied the last valve command."""
        return self._command_seen_after_s

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

    def close_inflation(self) -> None:
        """Close every inflation valve (only a controlling client can; a monitor changes
        nothing); vented channels keep venting."""
        if self._token is not None and not self.closed:
            try:
                super().close_inflation()
            except (ControlRefused, ConnectionLost):
                pass  # control or link lost: the daemon's watchdog has closed inflation

    def _close(self) -> None:
        _OPEN.discard(self)
        try:
            self.release_control()
        except HardwareFault:
            pass
        finally:
            self._session.close()


def _hex_key(value: object) -> bytes | None:
    """A key sent as hex text, or None when absent or malformed."""
    if not isinstance(value, str):
        return None
    try:
        return bytes.fromhex(value)
    except ValueError:
        return None


def open_zenoh_url(location: str, options: dict[str, str]) -> ZenohBox:
    """Factory for ``zenoh://HOST:PORT[/KEY-PREFIX]?timeout_s=5&config=FILE.toml`` (the
    installation file with the link's credentials; :mod:`softpad.box._credentials`)."""
    from urllib.parse import urlsplit

    from softpad.box._credentials import ENV_PASSWORD, ENV_USER, client_auth, client_link

    unknown = set(options) - {"timeout_s", "config"}
    if unknown:
        raise InputError(
            f"unknown zenoh:// option {sorted(unknown)[0]!r}; known: timeout_s, config"
        )
    hostport, _, prefix = location.partition("/")
    if "@" in hostport:
        raise InputError(
            "a zenoh:// URL never carries credentials (it is logged and recorded): give them "
            f"in the installation file (config=FILE) or in {ENV_USER} and {ENV_PASSWORD}"
        )
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
        if not 0.0 < timeout <= 3600.0:  # NaN fails too
            raise InputError(f"zenoh:// timeout_s must be from 0 to 3600 s, got {timeout:g}")
    protocol, auth = client_auth(client_link(options))
    if protocol == "tcp" and not _loopback(parts.hostname):
        raise InputError(
            f"zenoh://{hostport} is beyond loopback over plain tcp: refused; give the link's "
            "TLS settings (link.tls_root_ca, and a client certificate) with config=FILE"
        )
    return ZenohBox(
        parts.hostname,
        port,
        prefix.strip("/") or DEFAULT_PREFIX,
        timeout,
        auth=auth,
        protocol=protocol,
    )


def _loopback(host: str) -> bool:
    import ipaddress

    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
