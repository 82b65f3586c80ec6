"""Argument parsing helpers shared by the sub-commands: numbers with units, lists, files."""

from __future__ import annotations

import argparse
import math

from softpad.errors import InputError


def number_list(text: str, flag: str, scale: float = 1.0, positive: bool = False) -> list[float]:
    """Parse ``"1,1.5,2"`` into floats times ``scale``, naming the flag and the bad item on error."""
    items = [s.strip() for s in str(text).replace(";", ",").split(",")]
    if items == [""]:
        raise InputError(f"{flag} needs comma-separated numbers, got an empty value")
    out = []
    for i, s in enumerate(items, 1):
        try:
            v = float(s)
        except ValueError:
            raise InputError(f"{flag}: item {i} {s!r} is not a number") from None
        if not math.isfinite(v):
            raise InputError(f"{flag}: item {i} must be finite, got {s!r}")
        if positive and v <= 0:
            raise InputError(f"{flag}: item {i} must be > 0, got {s!r}")
        out.append(v * scale)
    return out


def kpa_list(text: str, flag: str) -> list[float]:
    """Parse ``"0.1,0,0.2"`` (kPa) into pascals, naming the flag and the bad item on error."""
    return number_list(text, flag, scale=1e3)


def finite_float(name: str, lo: float | None = None, hi: float | None = None, unit: str = ""):
    """An argparse ``type=`` that accepts a finite float within [lo, hi]."""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"{name} must be finite, got {text!r}")
        u = f" {unit}" if unit else ""
        if lo is not None and v < lo:
            raise argparse.ArgumentTypeError(f"{name} must be >= {lo:g}{u}, got {v:g}{u}")
        if hi is not None and v > hi:
            raise argparse.ArgumentTypeError(f"{name} must be <= {hi:g}{u}, got {v:g}{u}")
        return v

    parse.__name__ = name
    return parse
