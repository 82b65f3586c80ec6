"""What the box daemon and its clients share over zenoh: key names, payloads, session config.

Keys under the daemon's prefix (``softpad/box`` by default):

==========================  ===========  ================================================
key                         kind         payload
==========================  ===========  ================================================
``PREFIX/frames``           publication  binary frame (:func:`encode_frame`), every sample
``PREFIX/info``             queryable    JSON: channels, sample_rate_hz, limits, services
``PREFIX/stats``            queryable    JSON: achieved rate, jitter, dropped, malformed
``PREFIX/control/take``     queryable    JSON ``{"client": ID}``: take control (ack/refusal)
``PREFIX/control/release``  queryable    JSON ``{"client": ID}``
``PREFIX/control/holder/ID`` liveliness  the controlling client's token (vanishes with it)
``PREFIX/control/heartbeat`` publication JSON ``{"client": ID}`` from the controller
``PREFIX/valves``           queryable    JSON ``{"client": ID, "channel": k, "command": c}``
``PREFIX/ext/OP``           queryable    JSON: a served simulator's world and robot
==========================  ===========  ================================================

The controller's messages also carry ``n`` (a counter) and ``mac`` (HMAC-SHA256 under the key
that ``control/take`` answered with), and every frame carries a read tag and a control tag:
see :mod:`softpad.box._auth`. A client's credentials for the link itself (mutual TLS,
user/password) come from :mod:`softpad.box._credentials`.

Every query is answered with a JSON object ``{"ok": true, ...}`` or ``{"ok": false, "kind":
K, "error": MESSAGE}`` (``K``: ``input``, ``control``, ``safety``, ``hardware``). Payloads
larger than :data:`MAX_PAYLOAD_BYTES`, nested deeper than :data:`MAX_PAYLOAD_DEPTH` or not a
JSON object are counted and answered with an ``input`` error.

Network rule: multicast scouting and gossip are off, and only the endpoints given are used.
"""

from __future__ import annotations

import json
import math
import struct
from dataclasses import dataclass
from typing import Any

import numpy as np

from softpad.box._base import PressureFrame
from softpad.errors import InputError

#: Largest accepted request payload, bytes.
MAX_PAYLOAD_BYTES = 4096

#: Deepest accepted nesting of arrays and objects in a request (checked before parsing).
MAX_PAYLOAD_DEPTH = 8

#: Default key prefix of a box.
DEFAULT_PREFIX = "softpad/box"

#: A client's longest wait for its endpoint to accept the connection, seconds (zenoh's
#: ``connect/timeout_ms``) when the caller gives none.
DEFAULT_CONNECT_TIMEOUT_S = 3.0

#: Longest connect timeout accepted, seconds (as a ``zenoh://`` URL's ``timeout_s``).
MAX_CONNECT_TIMEOUT_S = 3600.0

_HEAD = struct.Struct("<QddHH")  # seq, mono_s, t_s, channels, reserved; then supply + channels
_MAGIC = 0x5350  # "SP"


@dataclass(frozen=True, slots=True)
class StampedFrame:
    """A frame as the daemon published it.

    Attributes
    ----------
    seq
        Sequence number, +1 per published frame (a gap is a frame lost on the way).
    mono_s
        The daemon's monotonic clock when the frame was sampled, seconds.
    frame
        The pressures (box time ``frame.t_s``).
    """

    seq: int
    mono_s: float
    frame: PressureFrame

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: ``seq``, ``mono_s``, ``t_s``, ``pressures_kpa``, ``supply_kpa``."""
        return {"seq": self.seq, "mono_s": round(self.mono_s, 6), **self.frame.to_dict()}


def encode_frame(seq: int, mono_s: float, frame: PressureFrame) -> bytes:
    """Binary frame: little-endian header (seq u64, mono_s f64, t_s f64, channels u16, magic
    u16) then supply_pa and each channel's pressure as f64 (NaN: no valid reading)."""
    n = frame.channels
    head = _HEAD.pack(seq, mono_s, frame.t_s, n, _MAGIC)
    body = np.empty(n + 1)
    body[0] = frame.supply_pa
    body[1:] = frame.pressures_pa
    return head + body.astype("<f8").tobytes()


def decode_frame(data: bytes) -> StampedFrame:
    """Inverse of :func:`encode_frame`; InputError on a payload that is not a frame."""
    if len(data) < _HEAD.size:
        raise InputError(f"frame payload of {len(data)} bytes is too short")
    seq, mono, t, n, magic = _HEAD.unpack_from(data)
    if magic != _MAGIC or len(data) != _HEAD.size + 8 * (n + 1):
        raise InputError(f"not a softpad frame ({len(data)} bytes, {n} channels)")
    body = np.frombuffer(data, dtype="<f8", offset=_HEAD.size).astype(np.float64)
    return StampedFrame(seq, mono, PressureFrame(t, body[1:].copy(), float(body[0])))


def decode_request(data: bytes | None) -> dict[str, Any]:
    """A request payload as a JSON object; InputError naming what is wrong (size, syntax)."""
    if data is None:
        return {}
    if len(data) > MAX_PAYLOAD_BYTES:
        raise InputError(f"payload of {len(data)} bytes exceeds the limit of {MAX_PAYLOAD_BYTES}")
    depth = nesting_depth(data)
    if depth > MAX_PAYLOAD_DEPTH:
        raise InputError(
            f"payload nests arrays and objects {depth} deep; the limit is {MAX_PAYLOAD_DEPTH}"
        )
    try:
        msg = json.loads(data.decode("utf-8"), parse_constant=_no_constant)
    except (UnicodeDecodeError, json.JSONDecodeError, ValueError, RecursionError) as exc:
        raise InputError(f"malformed JSON payload: {exc}") from None
    if not isinstance(msg, dict):
        raise InputError(f"payload must be a JSON object, got {type(msg).__name__}")
    return msg


def nesting_depth(data: bytes) -> int:
    """Deepest nesting of ``[`` and ``{`` in JSON text, outside strings (no parsing: a deep
    payload is refused before :func:`json.loads` could recurse on it)."""
    depth = deepest = 0
    in_string = escaped = False
    for c in data:
        if in_string:
            if escaped:
                escaped = False
            elif c == 0x5C:  # backslash
                escaped = True
            elif c == 0x22:  # quote
                in_string = False
        elif c == 0x22:
            in_string = True
        elif c in (0x5B, 0x7B):
            depth += 1
            deepest = max(deepest, depth)
        elif c in (0x5D, 0x7D):
            depth -= 1
    return deepest


def _no_constant(token: str) -> Any:
    raise ValueError(f"{token} is not valid JSON")


def encode_json(msg: dict[str, Any]) -> bytes:
    """Compact JSON bytes (NaN refused)."""
    return json.dumps(msg, allow_nan=False, separators=(",", ":")).encode()


def session_config(
    mode: str,
    listen: tuple[str, ...] = (),
    connect: tuple[str, ...] = (),
    *,
    user: str | None = None,
    password: str | None = None,
    dictionary_file: str | None = None,
    tls: dict[str, str] | None = None,
    connect_timeout_s: float = DEFAULT_CONNECT_TIMEOUT_S,
) -> Any:
    """A :class:`zenoh.Config` with multicast scouting and gossip off and explicit endpoints.

    Parameters
    ----------
    mode
        ``"peer"`` (the daemon) or ``"client"`` (everyone else).
    listen, connect
        Zenoh endpoints (``tcp/127.0.0.1:7447``); nothing else is listened on or scouted.
    user, password, dictionary_file
        Zenoh user/password authentication: a connecting side logs in with ``user`` and
        ``password`` (both or neither); a listener checks them against ``dictionary_file``
        (``user:password`` lines). See :mod:`softpad.box._credentials`.
    tls
        ``transport/link/tls`` settings (certificate, private key, root CA, ``enable_mtls``).
    connect_timeout_s
        A client's longest wait for its endpoints to accept the connection, seconds (zenoh's
        ``connect/timeout_ms``); more than 0 and at most :data:`MAX_CONNECT_TIMEOUT_S`.
        Unused by a peer.

    Raises
    ------
    InputError
        ``connect_timeout_s`` not a number in (0, 3600] s, a user without a password or the
        reverse, or zenoh not installed.
    """
    connect_ms = _connect_timeout_ms(connect_timeout_s)
    try:
        import zenoh
    except ImportError:
        raise InputError("the zenoh link needs eclipse-zenoh: pip install 'softpad[box]'") from None

    c = zenoh.Config()
    c.insert_json5("mode", json.dumps(mode))
    c.insert_json5("scouting/multicast/enabled", "false")
    c.insert_json5("scouting/gossip/enabled", "false")
    c.insert_json5("listen/endpoints", json.dumps(list(listen)))
    c.insert_json5("connect/endpoints", json.dumps(list(connect)))
    if mode == "client":
        c.insert_json5("connect/timeout_ms", str(connect_ms))
    auth = _usrpwd(user, password, dictionary_file)
    if auth:
        c.insert_json5("transport/auth/usrpwd", json.dumps(auth))
    if tls:
        c.insert_json5("transport/link/tls", json.dumps(tls))
    return c


def _usrpwd(user: str | None, password: str | None, dictionary_file: str | None) -> dict[str, str]:
    """``transport/auth/usrpwd`` settings (empty: none); InputError on a user without a
    password or the reverse (zenoh rejects one without the other)."""
    if (user is None) != (password is None):
        raise InputError("zenoh user/password authentication needs both a user and a password")
    auth: dict[str, str] = {}
    if user is not None and password is not None:
        auth.update(user=user, password=password)
    if dictionary_file is not None:
        auth["dictionary_file"] = dictionary_file
    return auth


def _connect_timeout_ms(timeout_s: float) -> int:
    """``timeout_s`` in whole milliseconds (at least 1); InputError naming it and the limit."""
    if (
        isinstance(timeout_s, bool)
        or not isinstance(timeout_s, int | float)
        or not 0.0 < timeout_s <= MAX_CONNECT_TIMEOUT_S  # NaN fails too
    ):
        raise InputError(
            f"zenoh connect timeout must be more than 0 s and at most "
            f"{MAX_CONNECT_TIMEOUT_S:g} s, got {timeout_s!r}"
        )
    return max(1, math.ceil(timeout_s * 1000.0))


def check_number(msg: dict[str, Any], key: str) -> float:
    """``msg[key]`` as a finite float, else InputError naming the key and value."""
    v = msg.get(key)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"{key} must be a finite number, got {v!r}")
    return float(v)
