"""What the ``softpad`` command prints: JSON objects with a schema version, human text."""

from __future__ import annotations

import json
import math
import sys
from typing import Any

from softpad import SCHEMA_VERSION


def _clean(value: Any) -> Any:
    """``value`` with non-finite floats as None (JSON has no NaN)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    return value


def json_text(obj: dict[str, Any]) -> str:
    """One line of JSON: ``schema_version`` first, then the fields of ``obj``."""
    return json.dumps({"schema_version": SCHEMA_VERSION, **_clean(obj)}, default=str)


def emit(obj: dict[str, Any]) -> None:
    """Print ``obj`` as one line of JSON on stdout (see :func:`json_text`)."""
    print(json_text(obj), flush=True)


def say(text: str, json_mode: bool = False) -> None:
    """Print human text: on stdout normally, on stderr when stdout carries JSON."""
    print(text, file=sys.stderr if json_mode else sys.stdout, flush=True)


def error_object(kind: str, message: str, partial: dict[str, Any] | None = None) -> dict:
    """The ``{"error": {...}}`` object of a failed command, with what was gathered before."""
    err: dict[str, Any] = {"kind": kind, "message": message}
    if partial:
        err.update({k: v for k, v in partial.items() if k not in ("kind", "message")})
    return {"error": err}
