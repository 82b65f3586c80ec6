"""The box link's wire format, for tools that speak it directly (benchmarks, attack tests).

A user opens a box by URL (:func:`softpad.box.open_box`) and never needs these: they are the
frame and request encodings of :mod:`softpad.box._link` and the frame seal of
:mod:`softpad.box._auth`, kept out of :mod:`softpad.box`'s public names.
"""

from softpad.box._auth import seal_frame, split_frame
from softpad.box._link import (
    MAX_PAYLOAD_BYTES,
    decode_frame,
    decode_request,
    encode_frame,
    encode_json,
    session_config,
)

__all__ = [
    "MAX_PAYLOAD_BYTES",
    "decode_frame",
    "decode_request",
    "encode_frame",
    "encode_json",
    "seal_frame",
    "session_config",
    "split_frame",
]
