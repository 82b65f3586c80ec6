"""Who may command the box, and which frames a client may believe: keys, tags, counters.

Control is proven on every message, not claimed by a name:

* ``control/take`` grants control and answers with a fresh random **control key** (32 bytes,
  in the query's reply: zenoh routes a reply to the querier only; it is never published);
* every later command, service request, release, heartbeat and frame acknowledgement of the
  controller carries a counter ``n`` and ``mac`` = HMAC-SHA256(control key, key name + the
  message's canonical JSON). The daemon refuses a message whose tag is wrong (forged) or whose
  counter is not above the last one of its stream (replayed), counts it and logs it;
* every published frame carries two 16-byte tags: HMAC(read key, frame) and HMAC(control key,
  frame) (the key of the current or last controller: one that lost control by the watchdog
  still reads; zeros before anyone took control). The **read key** is drawn when the daemon starts and
  handed on ``PREFIX/info``: monitors check it. The controller checks the control tag, which
  only the daemon and the controller can compute, also on frames it queued before its take
  (a frame forged with the read key before then is never read as the box's). A client drops
  a frame whose tag is wrong, whose sequence number does not increase, or whose sequence
  number is further ahead than the box can have sampled since the client connected (the
  ``seq`` of ``info``, the box's rate, 2 s of slack: one forged frame far ahead cannot make
  every real frame look replayed), counts it and says so (a warning).

What this protects against, and what not (docs/hardware.md):

* a process on the link that did not take control cannot command the valves, release or take
  over the box, keep the watchdog quiet, acknowledge frames, or feed the controller frames,
  even knowing the controller's id; replayed commands and frames are refused;
* the read tag stops stray or replayed publications on ``PREFIX/frames`` (another daemon, an
  old recording played back, a process that never asked ``info``) from reaching monitors; a
  participant that queried ``info`` can still forge frames for *monitors* (not for the
  controller): on a shared network, keep untrusted parties off the link with its own
  authentication (mutual TLS or user/password, :func:`softpad.box._link.session_config`);
* every queryable on a key gets each query and a client believes only the box it pinned at
  connection (its zenoh id on ``info``; two boxes answering within 0.5 s then is refused), so
  an impostor's queryable neither swallows commands nor fakes answers; a client waits only for
  the pinned box's answer (a queryable that never answers delays nothing); an impostor
  answering *alone* while the daemon is down is believed: the link's authentication keeps such
  a participant out.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import secrets
import threading
from typing import Any

#: Bytes of a key (control and read keys).
KEY_BYTES = 32
#: Bytes of one frame tag (HMAC-SHA256 truncated).
TAG_BYTES = 16
#: Both tags of a frame: read tag, then control tag.
FRAME_TAGS_BYTES = 2 * TAG_BYTES
_NO_TAG = bytes(TAG_BYTES)

#: The streams of a controller's messages, each with its own counter: queries (commands,
#: services, release; sent one at a time), heartbeats and frame acknowledgements.
STREAMS = ("query", "heartbeat", "ack")


def new_key() -> bytes:
    """A fresh random key (``secrets``)."""
    return secrets.token_bytes(KEY_BYTES)


def _canonical(key: str, msg: dict[str, Any]) -> bytes:
    body = {k: v for k, v in msg.items() if k not in ("mac", "_key")}
    text = json.dumps(body, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return f"{key}\n{text}".encode()


def message_tag(secret: bytes, key: str, msg: dict[str, Any]) -> str:
    """The hex HMAC-SHA256 of ``msg`` (without ``mac``) sent on ``key`` (the key name under
    the prefix, e.g. ``valves``): a tag for one key cannot be replayed on another."""
    return hmac.new(secret, _canonical(key, msg), hashlib.sha256).hexdigest()


def frame_tag(secret: bytes | None, data: bytes) -> bytes:
    """The frame tag of ``data`` under ``secret`` (zeros without a key)."""
    if secret is None:
        return _NO_TAG
    return hmac.digest(secret, data, "sha256")[:TAG_BYTES]


def seal_frame(data: bytes, read_key: bytes, control_key: bytes | None) -> bytes:
    """``data`` with its read tag and control tag appended."""
    return data + frame_tag(read_key, data) + frame_tag(control_key, data)


def split_frame(data: bytes) -> tuple[bytes, bytes, bytes]:
    """``(frame, read tag, control tag)`` of a sealed frame (tags empty when absent)."""
    if len(data) < FRAME_TAGS_BYTES:
        return data, b"", b""
    body = data[:-FRAME_TAGS_BYTES]
    return body, data[-FRAME_TAGS_BYTES:-TAG_BYTES], data[-TAG_BYTES:]


def tag_ok(secret: bytes | None, data: bytes, tag: bytes) -> bool:
    """True when ``tag`` is ``data``'s tag under ``secret`` (constant-time comparison)."""
    return secret is not None and hmac.compare_digest(frame_tag(secret, data), tag)


class Sealer:
    """The controller's side: adds ``n`` and ``mac`` to its messages (thread-safe)."""

    def __init__(self, secret: bytes) -> None:
        self.secret = secret
        self._n = dict.fromkeys(STREAMS, 0)
        self._lock = threading.Lock()

    def seal(self, stream: str, key: str, msg: dict[str, Any]) -> dict[str, Any]:
        """``msg`` with the next counter of ``stream`` and its tag for ``key``."""
        with self._lock:
            self._n[stream] += 1
            out = {**msg, "n": self._n[stream]}
        out["mac"] = message_tag(self.secret, key, out)
        return out


class Verifier:
    """The daemon's side for one controller: checks tags and counters (thread-safe)."""

    def __init__(self, client: str, secret: bytes) -> None:
        self.client = client
        self.secret = secret
        self._last = dict.fromkeys(STREAMS, 0)
        self._lock = threading.Lock()

    def check(self, stream: str, key: str, msg: dict[str, Any]) -> str | None:
        """None when ``msg`` comes from the controller and is fresh, else why not."""
        if msg.get("client") != self.client:
            return f"client {msg.get('client')!r} is not the controller"
        mac, n = msg.get("mac"), msg.get("n")
        if not isinstance(mac, str) or not mac.isascii() or type(n) is not int:
            return "no authentication tag (n, mac)"
        if not hmac.compare_digest(message_tag(self.secret, key, msg), mac):
            return "authentication tag is wrong (forged)"
        with self._lock:
            if n <= self._last[stream]:
                return f"counter {n} not above {self._last[stream]} (replayed)"
            self._last[stream] = n
        return None
