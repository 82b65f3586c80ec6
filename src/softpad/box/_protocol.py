"""The ``softpad-box`` wire protocol: line-delimited JSON over TCP (client and server share it).

One request line from the client, one reply line from the server, in order; UTF-8 JSON
objects terminated by ``\\n``, at most :data:`MAX_LINE_BYTES` each. Requests carry ``"op"``:

========================================  ===================================================
request                                   reply (``"ok": true`` plus)
========================================  ===================================================
``{"op": "hello", "protocol": 1}``        ``"protocol"``, ``"channels"``, ``"sample_rate_hz"``,
                                          ``"box"`` (the served box's class), ``"server"``,
                                          ``"extensions"`` (extra ops offered)
``{"op": "read"}``                        ``"t_s"``, ``"pressures_pa"`` (list, ``null`` = NaN:
                                          no valid reading), ``"supply_pa"``
``{"op": "valve", "channel": k,           nothing more (``channel`` 1-based; command
"command": "inflate"}``                   ``closed`` / ``inflate`` / ``deflate``)
``{"op": "close"}``                       nothing more; the server closes every valve and
                                          ends the session
========================================  ===================================================

A failed request is answered ``{"ok": false, "kind": K, "error": MESSAGE}`` with ``K`` one of
``"input"`` (bad request: the client raises :class:`~softpad.errors.InputError`),
``"hardware"`` (:class:`~softpad.errors.HardwareFault`) or ``"connection"`` (the served box
itself stopped answering: :class:`~softpad.box.ConnectionLost`). ``hello`` must come first;
a protocol version other than :data:`PROTOCOL_VERSION` is refused and the session ends.
JSON has no NaN: pressures use ``null``; the tokens ``NaN``/``Infinity`` are malformed.
Extension ops contain a dot (``robot.stop``); a server lists those it offers in ``hello``
(see :mod:`softpad.control._remote` for the simulator's world and robot).
"""

from __future__ import annotations

import json
import math
from typing import Any

from softpad.errors import HardwareFault, InputError

#: Version of the protocol spoken by this client and server.
PROTOCOL_VERSION = 1

#: Longest accepted message line, bytes (a frame of 64 channels is about 2 kB).
MAX_LINE_BYTES = 65536

#: Requests the server knows.
OPS = ("hello", "read", "valve", "close")


class ProtocolError(InputError):
    """A message that is not valid ``softpad-box`` JSON (the text says what is wrong)."""


def _no_constants(token: str) -> Any:
    raise ProtocolError(f"{token} is not a valid JSON number (use null for a missing reading)")


def encode(message: dict[str, Any]) -> bytes:
    """One message as a line of UTF-8 JSON (NaN/inf are refused: they are not JSON)."""
    return json.dumps(message, allow_nan=False, separators=(",", ":")).encode() + b"\n"


def decode(line: bytes) -> dict[str, Any]:
    """Parse one received line into a JSON object; :class:`ProtocolError` names the problem."""
    if len(line) > MAX_LINE_BYTES:
        raise ProtocolError(f"message of {len(line)} bytes exceeds the limit of {MAX_LINE_BYTES}")
    try:
        text = line.decode("utf-8")
    except UnicodeDecodeError:
        raise ProtocolError(f"message is not UTF-8: {line[:60]!r}") from None
    try:
        msg = json.loads(text, parse_constant=_no_constants)
    except json.JSONDecodeError as exc:
        raise ProtocolError(f"malformed JSON message {text.strip()[:80]!r}: {exc.msg}") from None
    if not isinstance(msg, dict):
        raise ProtocolError(f"a message must be a JSON object, got {text.strip()[:80]!r}")
    return msg


def finite_number(msg: dict[str, Any], key: str, what: str) -> float:
    """``msg[key]`` as a finite float, else a :class:`HardwareFault` naming ``what`` and the value."""
    v = msg.get(key)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise HardwareFault(f"{what}: {key} must be a finite number, got {v!r}")
    return float(v)
